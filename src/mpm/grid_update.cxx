// Grid update on owned nodes: v_old = p/m, v_new = v_old + dt f/m, then the boundary conditions of
// each domain face (fixed: v = 0; symmetry: normal component 0). Nodes lighter than the mass cut-off
// are empty (v = 0). Results go to the velocity vector [v_old, v_new] and its ghosted copy.
#include "grid_index.hpp"

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

static PetscErrorCode UpdateNodes(Simulation &sim, bool integrate)
{
  Grid          &g   = sim.grid;
  const PetscInt dim = g.dim, dof = g.num_velocity_fields * g.NodeStride(), vdof = g.num_velocity_fields * 2 * dim;
  PetscInt       xs[3], xm[3];
  const PetscScalar *nodal;
  PetscScalar       *vel;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(sim.ev_grid, 0, 0, 0, 0));
  PetscCall(DMDAGetCorners(g.da_nodes, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(VecGetArrayRead(g.nodal, &nodal));
  PetscCall(VecGetArray(g.velocity, &vel));
  PetscInt l = 0;
  for (PetscInt k = xs[2]; k < xs[2] + xm[2]; ++k)
    for (PetscInt j = xs[1]; j < xs[1] + xm[1]; ++j)
      for (PetscInt i = xs[0]; i < xs[0] + xm[0]; ++i, ++l) {
        const PetscScalar *nd   = nodal + l * dof;
        PetscScalar       *vn   = vel + l * vdof;
        const PetscInt     node[3] = {i, j, k};
        const PetscReal    mass = nd[0];
        PetscReal          v_old[3] = {0, 0, 0}, v_new[3] = {0, 0, 0};
        if (mass > sim.mass_cutoff) {
          for (PetscInt a = 0; a < dim; ++a) {
            v_old[a] = nd[1 + a] / mass;
            v_new[a] = integrate ? v_old[a] + sim.dt * nd[1 + dim + a] / mass : v_old[a];
          }
        }
        ApplyBoundaryConditions(g, node, v_new);
        if (!integrate) ApplyBoundaryConditions(g, node, v_old);
        for (PetscInt a = 0; a < dim; ++a) {
          vn[a]       = v_old[a];
          vn[dim + a] = v_new[a];
        }
      }
  PetscCall(VecRestoreArray(g.velocity, &vel));
  PetscCall(VecRestoreArrayRead(g.nodal, &nodal));
  PetscCall(DMGlobalToLocal(g.da_velocity, g.velocity, INSERT_VALUES, g.velocity_local));
  PetscCall(PetscLogEventEnd(sim.ev_grid, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GridUpdate(Simulation &sim) { return UpdateNodes(sim, true); }
PetscErrorCode GridVelocityFromMomentum(Simulation &sim) { return UpdateNodes(sim, false); }

} // namespace burst
