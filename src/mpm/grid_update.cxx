// Grid update on owned nodes: v_old = p/m, v_new = v_old + dt f/m per velocity field, contact
// between the fields, then the boundary conditions of each domain face (fixed: v = 0; symmetry: normal component 0). Nodes lighter than the mass cut-off
// are empty (v = 0). Results go to the velocity vector [v_old, v_new] and its ghosted copy.
#include "grid_index.hpp"
#include <cmath>

namespace burst {

// Applies the face conditions to the velocity v (dim components) of node (i, j, k).
static inline void ApplyBoundaryConditions(const Grid &g, const PetscInt node[], PetscReal v[])
{
  for (PetscInt d = 0; d < g.dim; ++d) {
    for (int side = 0; side < 2; ++side) {
      const bool on_face = side == 0 ? node[d] == 0 : node[d] == g.cells[d];
      if (!on_face) continue;
      const FaceBC bc = g.bc[d][side];
      if (bc == FaceBC::Fixed)
        for (PetscInt a = 0; a < g.dim; ++a) v[a] = 0;
      else if (bc == FaceBC::Symmetry) v[d] = 0;
    }
  }
}

// Contact between the two deformable velocity fields of a node (intact and converted particles, or
// the material of -mpm_contact_material and the rest), Bardenhagen
// et al., CMES 2 (2001) 509: no_slip gives both the centre-of-mass velocity; friction acts only while
// the fields approach along the common normal n (from field 0 towards field 1, from the difference
// of the nodal mass gradients, which point out of each body), removes the approaching normal velocity and limits the tangential slip by Coulomb
// friction mu |dv.n|. Momentum is conserved: the two corrections are equal and opposite.
static inline void Contact(const MpmSolver &mpm, PetscInt dim, const PetscReal m[2], const PetscReal grad0[], const PetscReal grad1[], PetscReal v0[], PetscReal v1[])
{
  PetscReal vcm[3], n[3] = {0, 0, 0}, norm = 0;
  for (PetscInt a = 0; a < dim; ++a) {
    vcm[a] = (m[0] * v0[a] + m[1] * v1[a]) / (m[0] + m[1]);
    n[a]   = grad0[a] - grad1[a]; // the nodal sums m_p grad N_I(x_p) point out of each body
    norm += n[a] * n[a];
  }
  norm = std::sqrt(norm);
  if (mpm.contact == ContactType::NoSlip || norm == 0) {
    for (PetscInt a = 0; a < dim; ++a) v0[a] = v1[a] = vcm[a];
    return;
  }
  for (PetscInt a = 0; a < dim; ++a) n[a] /= norm;
  PetscReal *v[2] = {v0, v1};
  for (int f = 0; f < 2; ++f) {
    const PetscReal sign = f == 0 ? 1.0 : -1.0; // outward normal of field f
    PetscReal       dv[3], dn = 0, dt[3], tnorm = 0;
    for (PetscInt a = 0; a < dim; ++a) {
      dv[a] = v[f][a] - vcm[a];
      dn += dv[a] * sign * n[a];
    }
    if (dn <= 0) return; // separating: the fields move independently
    for (PetscInt a = 0; a < dim; ++a) {
      dt[a] = dv[a] - dn * sign * n[a];
      tnorm += dt[a] * dt[a];
    }
    tnorm = std::sqrt(tnorm);
    if (mpm.friction * dn >= tnorm) {
      for (PetscInt a = 0; a < dim; ++a) v[f][a] = vcm[a]; // stick
    } else {
      for (PetscInt a = 0; a < dim; ++a) v[f][a] -= dn * sign * n[a] + (tnorm > 0 ? mpm.friction * dn * dt[a] / tnorm : 0);
    }
  }
}

// Contact of a deformable field with the rigid body (prescribed velocity v_r, infinite mass): where
// the field moves into the body along its outward normal n (the rigid field's nodal mass gradient,
// which points out of it), the normal part of the relative velocity is removed and the tangential
// slip is limited by Coulomb friction; no_slip gives the field the rigid velocity.
static inline void RigidContact(const MpmSolver &mpm, PetscInt dim, const PetscReal grad_rigid[], const PetscReal v_r[], PetscReal v[])
{
  PetscReal n[3] = {0, 0, 0}, norm = 0, dv[3], dn = 0;
  for (PetscInt a = 0; a < dim; ++a) {
    n[a] = grad_rigid[a];
    norm += n[a] * n[a];
  }
  norm = std::sqrt(norm);
  if (mpm.contact == ContactType::NoSlip || norm == 0) {
    for (PetscInt a = 0; a < dim; ++a) v[a] = v_r[a];
    return;
  }
  for (PetscInt a = 0; a < dim; ++a) {
    n[a] /= norm;
    dv[a] = v[a] - v_r[a];
    dn += dv[a] * n[a];
  }
  if (dn >= 0) return; // moving away from the body
  PetscReal dt[3], tnorm = 0;
  for (PetscInt a = 0; a < dim; ++a) {
    dt[a] = dv[a] - dn * n[a];
    tnorm += dt[a] * dt[a];
  }
  tnorm = std::sqrt(tnorm);
  if (mpm.friction * -dn >= tnorm) {
    for (PetscInt a = 0; a < dim; ++a) v[a] = v_r[a];
  } else {
    for (PetscInt a = 0; a < dim; ++a) v[a] -= dn * n[a] + (tnorm > 0 ? mpm.friction * -dn * dt[a] / tnorm : 0);
  }
}

static PetscErrorCode UpdateNodes(MpmSolver &mpm, bool integrate)
{
  Grid              &g   = mpm.grid;
  const PetscInt     dim = g.dim, dof = g.num_velocity_fields * g.NodeStride(), vdof = g.num_velocity_fields * 2 * dim;
  const PetscInt     stride = g.NodeStride(), nvf = g.num_velocity_fields;
  PetscInt           xs[3], xm[3];
  const PetscScalar *nodal;
  PetscScalar       *vel;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(mpm.ev_grid, 0, 0, 0, 0));
  PetscCall(DMDAGetCorners(g.da_nodes, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(VecGetArrayRead(g.nodal, &nodal));
  PetscCall(VecGetArray(g.velocity, &vel));
  // With ghost nodes the owned velocities go into both vectors here, and only the ghost nodes are
  // scattered after (GridVelocityGhosts): DMGlobalToLocal would copy every owned entry, a pass over
  // the whole grid per update that a second rank does not shrink.
  PetscScalar *vel_local = nullptr;
  if (g.velocity_local != g.velocity) PetscCall(VecGetArray(g.velocity_local, &vel_local));
  // the nodes no particle reaches this step (p2g.cxx) are empty without a look at their sums
  const unsigned char *reached = g.reached_step == mpm.step && !g.reached.empty() ? g.reached.data() : nullptr;
  const LocalNodeIndex index(g);
  const PetscInt       owned = xm[0] * xm[1] * xm[2];
  if ((PetscInt)g.velocity_written.size() != owned) g.velocity_written.assign(owned, 1); // (a new layout: write every node once)
  unsigned char *written       = g.velocity_written.data();
  PetscReal      bc_impulse[3] = {0, 0, 0}; // what the face conditions take from the new nodal momenta (the budgets with gas)
  // node (i, j, k), owned index l: its velocities from its sums
  auto update = [&](PetscInt i, PetscInt j, PetscInt k, PetscInt l) {
    PetscScalar *vout = vel + l * vdof, *vout_local = vel_local ? vel_local + index(i, j, k) * vdof : nullptr;
    { // an empty node (every field under the mass cut-off) has zero velocities: skip the rest
      bool empty = true;
      if (!reached || reached[index(i, j, k)])
        for (PetscInt vf = 0; vf < nvf; ++vf) empty = empty && !(nodal[l * dof + vf * stride] > mpm.mass_cutoff);
      if (empty) {
        if (written[l]) { // (else both vectors hold zeros here already)
          for (PetscInt a = 0; a < vdof; ++a) vout[a] = 0;
          if (vout_local)
            for (PetscInt a = 0; a < vdof; ++a) vout_local[a] = 0;
          written[l] = 0;
        }
        return;
      }
    }
    written[l]                 = 1;
    const PetscInt node[3]     = {i, j, k};
    PetscReal      v_old[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, v_new[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, mass[3] = {0, 0, 0};
    for (PetscInt vf = 0; vf < nvf; ++vf) {
      const PetscScalar *nd = nodal + l * dof + vf * stride;
      mass[vf]              = nd[0];
      if (mass[vf] > mpm.mass_cutoff) {
        for (PetscInt a = 0; a < dim; ++a) {
          v_old[vf][a] = nd[1 + a] / mass[vf];
          v_new[vf][a] = integrate ? v_old[vf][a] + mpm.dt * nd[1 + dim + a] / mass[vf] : v_old[vf][a];
        }
      }
    }
    // Mass gradients for the contact normals. On a symmetry face the component normal to it is
    // zero by symmetry (the body does not end there, it is mirrored), so it is dropped.
    PetscReal grads[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    if (nvf > 1)
      for (PetscInt vf = 0; vf < nvf; ++vf)
        for (PetscInt a = 0; a < dim; ++a) {
          const bool mirrored = (node[a] == 0 && g.bc[a][0] == FaceBC::Symmetry) || (node[a] == g.cells[a] && g.bc[a][1] == FaceBC::Symmetry);
          grads[vf][a]        = mirrored ? 0 : nodal[l * dof + vf * stride + 1 + 2 * dim + a];
        }
    const PetscInt rigid = mpm.rigid_material >= 0 ? nvf - 1 : -1;
    if (rigid >= 0 && mass[rigid] > mpm.mass_cutoff) {
      const PetscReal *gr = grads[rigid];
      for (PetscInt a = 0; a < dim; ++a) v_old[rigid][a] = v_new[rigid][a] = mpm.rigid_velocity[a];
      for (PetscInt vf = 0; vf < rigid; ++vf)
        if (mass[vf] > mpm.mass_cutoff) {
          RigidContact(mpm, dim, gr, mpm.rigid_velocity, v_old[vf]);
          RigidContact(mpm, dim, gr, mpm.rigid_velocity, v_new[vf]);
        }
    }
    if (mpm.TwoDeformableFields() && mass[0] > mpm.mass_cutoff && mass[1] > mpm.mass_cutoff) {
      const PetscReal *g0 = grads[0], *g1 = grads[1];
      Contact(mpm, dim, mass, g0, g1, v_old[0], v_old[1]);
      Contact(mpm, dim, mass, g0, g1, v_new[0], v_new[1]);
    }
    for (PetscInt vf = 0; vf < nvf; ++vf) {
      if (vf != rigid) { // the rigid velocity is prescribed
        const PetscReal before[3] = {v_new[vf][0], v_new[vf][1], v_new[vf][2]};
        ApplyBoundaryConditions(g, node, v_new[vf]);
        if (!integrate) ApplyBoundaryConditions(g, node, v_old[vf]);
        else // the particles' momentum changes by m_I (v_new - v_old) summed over the nodes: this is the faces' part
          for (PetscInt a = 0; a < dim; ++a) bc_impulse[a] += mass[vf] * (v_new[vf][a] - before[a]);
      }
      PetscScalar *vn = vout + vf * 2 * dim;
      for (PetscInt a = 0; a < dim; ++a) {
        vn[a]       = v_old[vf][a];
        vn[dim + a] = v_new[vf][a];
      }
    }
    if (vout_local)
      for (PetscInt a = 0; a < vdof; ++a) vout_local[a] = vout[a];
  };
  // With this step's marks, a node neither reached nor written is zero and stays so: only the others
  // are visited (most of a grid is empty: the cylinder's ring covers a few per cent of its nodes, the
  // Taylor rod about a tenth).
  ForEachMarkedRun(
    g, reached, xs, xm,
    [&](PetscInt l, PetscInt, PetscInt count, PetscInt i, PetscInt j, PetscInt k) {
      for (PetscInt n = 0; n < count; ++n) update(i + n, j, k, l + n);
    },
    written);
  for (PetscInt a = 0; a < dim; ++a) mpm.diag.bc_impulse[a] += bc_impulse[a];
  if (vel_local) PetscCall(VecRestoreArray(g.velocity_local, &vel_local));
  PetscCall(VecRestoreArray(g.velocity, &vel));
  PetscCall(VecRestoreArrayRead(g.nodal, &nodal));
  PetscCall(GridVelocityGhosts(g));
  PetscCall(PetscLogEventEnd(mpm.ev_grid, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GridUpdate(MpmSolver &mpm) { return UpdateNodes(mpm, true); }
PetscErrorCode GridVelocityFromMomentum(MpmSolver &mpm) { return UpdateNodes(mpm, false); }

} // namespace burst
