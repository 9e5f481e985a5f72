// Particles to grid: mass, momentum and force (internal -V sigma grad N plus external N f_ext) summed
// into the ghosted local nodal vector, then onto the global one (the owned nodes the particles reach
// added in place, the ghost nodes through Grid::ghost_sums: DMLocalToGlobal(ADD_VALUES) without its
// pass over the whole grid; petsc.md 5.2); on a rank without ghost nodes (one rank) straight into the
// global vector.
//
// Axisymmetric (-axisymmetric; x = r, y = z, masses and volumes per radian): the weak form of
// div sigma in cylindrical coordinates adds the hoop term to the radial force,
//   f_r,I = -sum_p V_p (sigma_rr dN/dr + sigma_rz dN/dz + sigma_tt N_I / r_p),
// with sigma_tt the zz entry of the 3x3 stress (Sulsky & Schreyer, CMAME 139 (1996) 409; Nairn &
// Guilkey, IJNME 101 (2015) 127). APIC (-mpm_transfer apic) adds the affine part of the particle
// velocity to the momentum: m_p N_I (v_p + C_p (x_I - x_p)) (Jiang et al., JCP 2017, eq. 9).
// Both are template switches, so the default path is the loop it always was.
//
// MUSL's remap (RemapMomentum): the particle velocities from the grid, v_p <- a (v_p + sum N (v_new -
// v_old)) + (1 - a) sum N v_new as in G2P, and their momentum m_p N_I v_p back onto the grid, in one
// particle pass (the same operations as G2P's velocity pass followed by a momentum P2G).
#include "grid_index.hpp"
#include "mpm/swarm_access.hpp"
#include <algorithm>
#include <type_traits>

namespace burst {

namespace {
struct P2GKernel {
  MpmSolver         &mpm;
  P2GRequest         what;
  PetscScalar       *nodal;
  const PetscScalar *vel     = nullptr; // RemapMomentum: the ghosted [v_old, v_new] nodal velocities
  unsigned char     *reached = nullptr; // the P2G of the masses: marks each particle's first stencil node
  template <int DIM, ShapeType S>
  PetscErrorCode operator()()
  {
    PetscFunctionBeginUser;
    const bool apic = mpm.transfer == Transfer::APIC && what.momentum;
    if constexpr (DIM == 2) {
      if (mpm.axisymmetric) {
        if (apic) PetscCall((ByRequest<DIM, S, true, true>()));
        else PetscCall((ByRequest<DIM, S, true, false>()));
        PetscFunctionReturn(PETSC_SUCCESS);
      }
    }
    if (apic) PetscCall((ByRequest<DIM, S, false, true>()));
    else PetscCall((ByRequest<DIM, S, false, false>()));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  // The requested sums (mass, momentum, force) as template switches: the node loop carries only
  // the sums of this call.
  template <int DIM, ShapeType S, bool AXI, bool APIC>
  PetscErrorCode ByRequest()
  {
    PetscFunctionBeginUser;
    const int request = (what.mass ? 1 : 0) | (what.momentum ? 2 : 0) | (what.force ? 4 : 0);
    if (vel) { // the remap: momentum of the velocities it updates
      PetscCall((Loop<DIM, S, AXI, false, false, true, false, true>()));
      PetscFunctionReturn(PETSC_SUCCESS);
    }
    switch (request) {
    case 1: PetscCall((Loop<DIM, S, AXI, APIC, true, false, false>())); break;
    case 2: PetscCall((Loop<DIM, S, AXI, APIC, false, true, false>())); break;
    case 3: PetscCall((Loop<DIM, S, AXI, APIC, true, true, false>())); break;
    case 4: PetscCall((Loop<DIM, S, AXI, APIC, false, false, true>())); break;
    case 5: PetscCall((Loop<DIM, S, AXI, APIC, true, false, true>())); break;
    case 6: PetscCall((Loop<DIM, S, AXI, APIC, false, true, true>())); break;
    case 7: PetscCall((Loop<DIM, S, AXI, APIC, true, true, true>())); break;
    default: break;
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  template <int DIM, ShapeType S, bool AXI, bool APIC_, bool MASS, bool MOM, bool FORCE, bool REMAP = false>
  PetscErrorCode Loop()
  {
    constexpr bool APIC = APIC_ && MOM;
    static_assert(!REMAP || (MOM && !MASS && !FORCE && !APIC), "the remap sums momentum only");
    const Grid          &g   = mpm.grid;
    const PetscInt       dof = g.num_velocity_fields * g.NodeStride();
    const LocalNodeIndex index(g);
    PetscInt             n;
    const PetscReal     *x, *m, *vol, *hw, *F, *sigma, *fext, *q, *ambient = nullptr, *affine = nullptr;
    PetscReal           *v;
    const PetscInt       vdof = g.num_velocity_fields * 2 * DIM;
    const PetscReal      flip = mpm.flip_fraction, dt = mpm.dt;
    PetscReal            work = 0; // the remap: work of the external forces (as in G2P)
    (void)vdof, (void)flip, (void)dt;
    const PetscInt *failed = nullptr, *material = nullptr;
    const PetscInt  stride = g.NodeStride(), nvf = g.num_velocity_fields;
    PetscFunctionBeginUser;
    PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
    SwarmAccess fields(mpm.swarm);
    PetscCall(fields.Get(DMSwarmPICField_coor, &x));
    PetscCall(fields.Get(field::velocity, &v));
    PetscCall(fields.Get(field::mass, &m));
    PetscCall(fields.Get(field::volume, &vol));
    PetscCall(fields.Get(field::half_width0, &hw));
    PetscCall(fields.Get(field::F, &F));
    PetscCall(fields.Get(field::stress, &sigma));
    PetscCall(fields.Get(field::external_force, &fext));
    PetscCall(fields.Get(field::bulk_viscosity, &q));
    if (mpm.ambient_pressure) PetscCall(fields.Get(field::ambient_pressure, &ambient));
    if constexpr (APIC) PetscCall(fields.Get(field::affine, &affine));
    if (nvf > 1) PetscCall(fields.Get(field::material, &material));
    if (nvf > 1 && mpm.convert_failed) PetscCall(fields.Get(state_field::failed, &failed));
    bool             fill;
    Stencil<DIM, S> *stencils = mpm.stencil_cache.Prepare<DIM, S>(n, mpm.step, &fill);
    constexpr bool   do_mass = MASS, do_mom = MOM, do_force = FORCE;
    const bool       deformable_gradients = mpm.TwoDeformableFields();
    // external forces as a compile-time switch for the whole loop: without loads (most scenes) the
    // force is the internal one alone
    auto particles = [&](auto external) {
      constexpr bool has_external = decltype(external)::value, do_external = do_force && has_external;
      for (PetscInt p = 0; p < n; ++p) {
        Stencil<DIM, S> &st = stencils[p];
        if (fill) st.Evaluate(g.axes, x + DIM * p, hw + DIM * p, F + 9 * p);
        if constexpr (MASS) reached[index(st.idx[0][0], st.idx[1][0], DIM == 3 ? st.idx[DIM - 1][0] : 0)] = 1;
        const PetscReal  mp = m[p], Vp = vol[p], qp = q[p] - (ambient ? ambient[p] : 0);            // sigma - q I + (p_gas - p_ref) I (ice.md 2.3)
        const PetscInt   vf = nvf > 1 ? mpm.VelocityField(material[p], failed ? failed[p] : 0) : 0; // converted and rigid particles: their own fields
        const PetscReal *xp = x + DIM * p;
        // The particle's values in locals: the node array's stores cannot alias them, so the scatter
        // below reads them from registers (same operations, same order).
        PetscReal vp[DIM], s[DIM][DIM], fe[DIM] = {};
        if constexpr (REMAP) RemapVelocity<DIM, S>(st, p, vf, material, index, vdof, flip, dt, has_external ? fext : nullptr, v, work);
        for (int a = 0; a < DIM; ++a) {
          vp[a] = v[DIM * p + a];
          if constexpr (do_external) fe[a] = fext[DIM * p + a];
          for (int b = 0; b < DIM; ++b) s[a][b] = sigma[9 * p + 3 * a + b];
        }
        Pair s01[DIM], fe01 = {fe[0], fe[1]}; // columns of the stress rows 0 and 1: s01[b] = (s[0][b], s[1][b])
        for (int b = 0; b < DIM; ++b) s01[b] = Pair{s[0][b], s[1][b]};
        // a rigid particle carries no stress, and its field's velocity is prescribed (the grid update
        // sets it, so its momentum is never read): mass and the mass gradient only, for the contact
        const bool deformable = !(material && material[p] == mpm.rigid_material);
        PetscReal  hoop       = 0; // axisymmetric: V_p sigma_tt / r_p
        if constexpr (AXI) hoop = Vp * sigma[9 * p + 8] / xp[0];
        (void)hoop;
        // deformable or rigid as a compile-time switch per particle (a runtime test in the node loop
        // costs the deformable particles more than the rigid ones save)
        // The mass gradients: the rigid field's gives the rigid contact's normal; a deformable field's
        // is read only by the contact between two deformable fields (grid_update.cxx)
        auto scatter = [&](auto deformable_p, auto gradient_p) {
          constexpr bool body = decltype(deformable_p)::value, do_force_p = do_force && body, do_mom_p = do_mom && body, do_gradient = decltype(gradient_p)::value;

          auto add = [&](PetscScalar *node, PetscInt i, PetscInt j, PetscInt k, PetscReal N, const PetscReal dN[]) {
            (void)i, (void)j, (void)k; // APIC only: the node position
            if constexpr (do_mass) {
              node[0] += N * mp;
              if (do_gradient && nvf > 1)
                for (int a = 0; a < DIM; ++a) node[1 + 2 * DIM + a] += mp * dN[a]; // sum m_p grad N_I(x_p): points out of the body (contact normals)
            }
            if constexpr (APIC && body) {
              PetscReal      dx[3] = {0, 0, 0};
              const PetscInt I[3]  = {i, j, k};
              for (int b = 0; b < DIM; ++b) dx[b] = g.axes[b].origin + I[b] * g.axes[b].h - xp[b];
              const PetscReal *C = affine + 9 * p;
              for (int a = 0; a < DIM; ++a) {
                PetscReal va = vp[a];
                for (int b = 0; b < DIM; ++b) va += C[3 * a + b] * dx[b];
                node[1 + a] += N * mp * va;
              }
            } else if constexpr (do_mom_p && !APIC)
              for (int a = 0; a < DIM; ++a) node[1 + a] += N * mp * vp[a];
            if constexpr (do_force_p) {
              // rows 0 and 1 as one pair of doubles (the same operations lane by lane), the rest scalar
              Pair div01 = {0, 0};
              for (int b = 0; b < DIM; ++b) div01 += s01[b] * dN[b];
              div01 -= qp * Pair{dN[0], dN[1]}; // artificial bulk viscosity: sigma - q I
              Pair f01 = -Vp * div01;
              if constexpr (do_external) f01 += N * fe01;
              node[1 + DIM] += f01[0];
              node[2 + DIM] += f01[1];
              for (int a = 2; a < DIM; ++a) {
                PetscReal div = 0;
                for (int b = 0; b < DIM; ++b) div += s[a][b] * dN[b];
                div -= qp * dN[a];
                if constexpr (do_external) node[1 + DIM + a] += -Vp * div + N * fe[a];
                else node[1 + DIM + a] += -Vp * div;
              }
            }
            if constexpr (AXI && do_force_p) node[1 + DIM] -= hoop * N; // the hoop stress pulls the radial force inwards
          };
          if constexpr (APIC && body) ForEachNode(st, [&](PetscInt i, PetscInt j, PetscInt k, PetscReal N, const PetscReal dN[]) { add(nodal + index(i, j, k) * dof + vf * stride, i, j, k, N, dN); });
          else ForEachLocalNode(st, index, dof, [&](PetscInt at, PetscReal N, const PetscReal dN[]) { add(nodal + at + vf * stride, 0, 0, 0, N, dN); });
        };
        if (!deformable) {
          if (do_mass) scatter(std::false_type{}, std::true_type{});
        } else if (deformable_gradients) scatter(std::true_type{}, std::true_type{});
        else scatter(std::true_type{}, std::false_type{});
      }
    };
    if (HasExternalForces(mpm)) particles(std::true_type{});
    else particles(std::false_type{});
    if constexpr (REMAP) mpm.diag.external_work += work;
    PetscCall(fields.RestoreAll());
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  // G2P's velocity gather and update of particle p (FlipBlend, SetParticleVelocity: the same as
  // GridToParticles' velocity pass). fext: null without loads (no external work).
  template <int DIM, ShapeType S>
  void RemapVelocity(const Stencil<DIM, S> &st, PetscInt p, PetscInt vf, const PetscInt *material, const LocalNodeIndex &index, PetscInt vdof, PetscReal flip, PetscReal dt, const PetscReal *fext, PetscReal *v, PetscReal &work) const
  {
    PetscReal       *vp     = v + DIM * p;
    const PetscReal *fext_p = fext ? fext + DIM * p : nullptr;
    if (material && material[p] == mpm.rigid_material) {
      SetParticleVelocity<DIM>(vp, mpm.rigid_velocity, fext_p, dt, work);
      return;
    }
    PetscReal dv[DIM] = {}, vnew[DIM] = {};
    ForEachLocalNode(st, index, vdof, [&](PetscInt at, PetscReal N, const PetscReal[]) {
      const PetscScalar *nv = vel + at + vf * 2 * DIM;
      for (int a = 0; a < DIM; ++a) {
        dv[a] += N * (nv[DIM + a] - nv[a]);
        vnew[a] += N * nv[DIM + a];
      }
    });
    PetscReal v_new[DIM];
    for (int a = 0; a < DIM; ++a) v_new[a] = FlipBlend(flip, vp[a], dv[a], vnew[a]);
    SetParticleVelocity<DIM>(vp, v_new, fext_p, dt, work);
  }
};
} // namespace

// From each particle's first stencil node (marked by the kernel) to every node its stencil can
// reach: the next NS - 1 nodes in each direction. Owned nodes within NS - 1 of a face with ghost
// nodes are marked whole: the neighbour's particles add to them through the ghost sum.
static PetscErrorCode SpreadReached(MpmSolver &mpm)
{
  Grid          &g      = mpm.grid;
  const PetscInt spread = ShapeGhostWidth(mpm.shape), n[3] = {g.gxm[0], g.gxm[1], g.dim == 3 ? g.gxm[2] : 1};
  const PetscInt step[3] = {1, n[0], n[0] * n[1]};
  unsigned char *r       = g.reached.data();
  PetscInt       xs[3], xm[3];
  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < g.dim; ++d) {                          // node i takes the marks of i - 1 .. i - spread: descending i reads unspread marks
    const PetscInt outer = n[0] * n[1] * n[2] / (step[d] * n[d]); // lines (d = 0) or planes above direction d
    for (PetscInt o = 0; o < outer; ++o) {
      unsigned char *base = r + o * step[d] * n[d];
      for (PetscInt i = n[d] - 1; i > 0; --i)
        for (PetscInt back = 1; back <= spread && back <= i; ++back) {
          unsigned char *to = base + i * step[d], *from = base + (i - back) * step[d];
          for (PetscInt e = 0; e < step[d]; ++e) to[e] |= from[e];
        }
    }
  }
  PetscCall(DMDAGetCorners(g.da_nodes, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  for (PetscInt d = 0; d < g.dim; ++d) {
    PetscInt       lo[3] = {0, 0, 0}, hi[3] = {n[0], n[1], n[2]};
    const PetscInt own_lo = xs[d] - g.gxs[d], own_hi = own_lo + xm[d]; // owned planes [own_lo, own_hi)
    for (int side = 0; side < 2; ++side) {
      if (side == 0 ? own_lo == 0 : own_hi == n[d]) continue; // no ghost nodes on this side
      lo[d] = side == 0 ? own_lo : PetscMax(own_hi - spread, own_lo);
      hi[d] = side == 0 ? PetscMin(own_lo + spread, own_hi) : own_hi;
      for (PetscInt k = lo[2]; k < hi[2]; ++k)
        for (PetscInt j = lo[1]; j < hi[1]; ++j)
          for (PetscInt i = lo[0]; i < hi[0]; ++i) r[i + j * step[1] + k * step[2]] = 1;
    }
  }
  g.reached_step = mpm.step;
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Zeroes the listed dofs (every dof when zero is null) of the marked nodes (every node when marks is
// null) of a nodal array over the box [xs, xs + xm).
static void ZeroNodes(const Grid &g, const unsigned char *marks, PetscScalar *array, const PetscInt xs[3], const PetscInt xm[3], PetscInt dof, const PetscInt *zero, PetscInt nzero)
{
  ForEachMarkedRun(g, marks, xs, xm, [&](PetscInt l, PetscInt, PetscInt count, PetscInt, PetscInt, PetscInt) {
    if (!zero) std::fill(array + l * dof, array + (l + count) * dof, 0.0);
    else
      for (PetscInt node = l; node < l + count; ++node)
        for (PetscInt z = 0; z < nzero; ++z) array[node * dof + zero[z]] = 0;
  });
}

// The requested sums of every particle (vel: the remap) into the nodal vector.
//
// Only the nodes the last P2G of the masses marked (g.reached) can hold non-zero sums: the vectors
// start at zero, only this function writes them, and a P2G of the masses zeroes every dof of the
// nodes marked before it (the others are zero already), so the particles' sums land on a zero
// vector and only on the nodes they mark. A P2G without the masses comes after one at the same
// positions (USF's forces, the remap, the coupled step's forces): its particles reach only the
// marked nodes, where it zeroes the requested dofs of the global vector and every dof of the local
// one (whose other dofs would be added again). Without a valid mark (the first P2G, a new grid
// layout) the whole vectors are zeroed. This spares zeroing the empty part of the grid (85 % of the
// Taylor deck's nodes) twice per step.
static PetscErrorCode NodalSums(MpmSolver &mpm, P2GRequest what, const PetscScalar *vel)
{
  Grid          &g = mpm.grid;
  PetscScalar   *nodal;
  PetscInt       nlocal, nghosted, xs[3], xm[3];
  const PetscInt dof = g.num_velocity_fields * g.NodeStride(), dim = g.dim, stride = g.NodeStride();
  PetscFunctionBeginUser;
  // The requested dofs of one node, every field
  PetscInt zero[3 * (1 + 3 * 3)], nzero = 0;
  PetscCheck(g.num_velocity_fields <= 3, mpm.comm, PETSC_ERR_PLIB, "At most 3 velocity fields, not %" PetscInt_FMT, g.num_velocity_fields);
  for (PetscInt vf = 0; vf < g.num_velocity_fields; ++vf) {
    const PetscInt base = vf * stride;
    if (what.mass) {
      zero[nzero++] = base;
      for (PetscInt a = 0; a < dim && stride > 1 + 2 * dim; ++a) zero[nzero++] = base + 1 + 2 * dim + a;
    }
    for (PetscInt a = 0; a < dim; ++a) {
      if (what.momentum) zero[nzero++] = base + 1 + a;
      if (what.force) zero[nzero++] = base + 1 + dim + a;
    }
  }
  PetscCall(VecGetLocalSize(g.nodal, &nlocal));
  PetscCall(VecGetLocalSize(g.nodal_local, &nghosted));
  PetscCall(DMDAGetCorners(g.da_nodes, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  // Without ghost nodes (one rank) the ghosted box is the owned box, in the same order: the
  // particles sum straight into the global vector (no local vector; the same sums in the same
  // order). Otherwise into the ghosted local vector, whose owned part is then added in place and
  // whose ghost nodes go to their owners through Grid::ghost_sums (DMLocalToGlobal(ADD_VALUES) in two
  // parts, petsc.md 5.2).
  const bool   direct        = nlocal == nghosted;
  const size_t ghosted_nodes = (size_t)g.gxm[0] * g.gxm[1] * g.gxm[2];
  // the nodes that can hold sums (null: any node, the whole vectors are zeroed)
  const unsigned char *old_marks = g.reached.size() == ghosted_nodes && (what.mass || g.reached_step == mpm.step) ? g.reached.data() : nullptr;
  const bool           all       = what.mass || nzero == dof; // a P2G of the masses zeroes every dof
  if (!old_marks && all) PetscCall(VecZeroEntries(g.nodal));
  else {
    PetscCall(VecGetArray(g.nodal, &nodal));
    ZeroNodes(g, old_marks, nodal, xs, xm, dof, all ? nullptr : zero, nzero);
    PetscCall(VecRestoreArray(g.nodal, &nodal));
  }
  if (!direct) { // every dof of the local vector: its other dofs would be added again
    if (!old_marks) PetscCall(VecZeroEntries(g.nodal_local));
    else {
      PetscCall(VecGetArray(g.nodal_local, &nodal));
      ZeroNodes(g, old_marks, nodal, g.gxs, g.gxm, dof, nullptr, 0);
      PetscCall(VecRestoreArray(g.nodal_local, &nodal));
    }
  }
  Vec target = direct ? g.nodal : g.nodal_local;
  PetscCall(VecGetArray(target, &nodal));
  P2GKernel kernel{mpm, what, nodal, vel};
  if (what.mass) {
    g.reached.assign(ghosted_nodes, 0);
    kernel.reached = g.reached.data();
  }
  PetscCall(DispatchShape(dim, mpm.shape, kernel));
  PetscCall(VecRestoreArray(target, &nodal));
  if (what.mass) PetscCall(SpreadReached(mpm));
  if (!direct) {
    // DMLocalToGlobal(ADD_VALUES) in two parts: the owned nodes that the particles reach added here
    // (the others hold zeros), then the ghost nodes through the scatter
    PetscCheck(g.ghost_sums, PETSC_COMM_SELF, PETSC_ERR_PLIB, "The ghost-node scatter of the nodal sums is missing");
    PetscCall(PetscLogEventBegin(mpm.ev_ghost_sums, 0, 0, 0, 0));
    const PetscScalar *local;
    PetscCall(VecGetArrayRead(g.nodal_local, &local));
    PetscCall(VecGetArray(g.nodal, &nodal));
    const unsigned char *marks = g.reached_step == mpm.step ? g.reached.data() : nullptr; // this step's marks (the mass P2G above, or the one before at the same positions)
    ForEachMarkedRun(g, marks, xs, xm, [&](PetscInt l, PetscInt at, PetscInt count, PetscInt, PetscInt, PetscInt) {
      for (PetscInt node = 0; node < count; ++node)
        for (PetscInt z = 0; z < nzero; ++z) nodal[(l + node) * dof + zero[z]] += local[(at + node) * dof + zero[z]]; // the requested dofs (the local vector's others are zero)
    });
    PetscCall(VecRestoreArray(g.nodal, &nodal));
    PetscCall(VecRestoreArrayRead(g.nodal_local, &local));
    PetscCall(VecScatterBegin(g.ghost_sums, g.nodal_local, g.nodal, ADD_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(g.ghost_sums, g.nodal_local, g.nodal, ADD_VALUES, SCATTER_FORWARD));
    PetscCall(PetscLogEventEnd(mpm.ev_ghost_sums, 0, 0, 0, 0));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ParticlesToGrid(MpmSolver &mpm, P2GRequest what)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(mpm.ev_p2g, 0, 0, 0, 0));
  PetscCall(NodalSums(mpm, what, nullptr));
  PetscCall(PetscLogEventEnd(mpm.ev_p2g, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RemapMomentum(MpmSolver &mpm)
{
  const PetscScalar *vel;
  PetscFunctionBeginUser;
  if (mpm.transfer != Transfer::FlipPic) { // APIC and XPIC: their own velocity pass, then the sums
    PetscCall(GridToParticles(mpm, {PETSC_TRUE, PETSC_FALSE, PETSC_FALSE}));
    PetscCall(ParticlesToGrid(mpm, {PETSC_FALSE, PETSC_TRUE, PETSC_FALSE}));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscLogEventBegin(mpm.ev_remap, 0, 0, 0, 0));
  PetscCall(VecGetArrayRead(mpm.grid.velocity_local, &vel));
  PetscCall(NodalSums(mpm, {PETSC_FALSE, PETSC_TRUE, PETSC_FALSE}, vel));
  PetscCall(VecRestoreArrayRead(mpm.grid.velocity_local, &vel));
  PetscCall(PetscLogEventEnd(mpm.ev_remap, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
