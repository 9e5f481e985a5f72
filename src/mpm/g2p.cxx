// Grid to particles from the ghosted [v_old, v_new] nodal velocities:
//   velocity           v_p <- a (v_p + sum N (v_new - v_old)) + (1 - a) sum N v_new   (a = FLIP fraction)
//   position           x_p <- x_p + dt sum N v_new
//   kinematics         L_p = sum v_new (x) grad N; F_p <- (I + L dt) F_p (or exp(L dt) F_p); V_p = V0 det F
//                      (fused here so F, L and the volumes are streamed once per step)
// The work of the external forces, f_ext . (v_p^n + v_p^{n+1})/2 dt, is accumulated here.
//
// Axisymmetric (x = r): the hoop rate L_tt = v_r(x_p)/r_p goes into the zz entry of L, with r_p the
// radius before the position update, so that F_tt <- (1 + L_tt dt) F_tt stays exactly r/R.
// XPIC(m) (-mpm_transfer xpic -mpm_xpic_order m): see XPICExtrapolate below.
// APIC (-mpm_transfer apic; Jiang et al., JCP 2017): v_p = sum N v_new and the affine matrix
// C_p = B_p D_p^-1, B_p = sum N v_new (x_I - x_p)^T, D_p = sum N (x_I - x_p)(x_I - x_p)^T, computed
// from the stencil itself (so the extrapolated wall weights keep it exact); for linear shape functions
// B_p D_p^-1 = sum v_new grad N^T, which stays defined when a particle sits on a node line.
#include "grid_index.hpp"
#include "mpm/swarm_access.hpp"
#include "expm.hpp"

namespace burst {

namespace {
struct G2PKernel {
  MpmSolver         &mpm;
  G2PRequest         what;
  const PetscScalar *vel;
  const PetscScalar *star; // XPIC: ghosted v* per velocity field, laid out as vel (first DIM of each 2 DIM)
  template <int DIM, ShapeType S>
  PetscErrorCode operator()()
  {
    PetscFunctionBeginUser;
    const Transfer tr = what.velocity ? mpm.transfer : Transfer::FlipPic;
    if constexpr (DIM == 2) {
      if (mpm.axisymmetric) {
        PetscCall(ByTransfer<DIM, S, true>(tr));
        PetscFunctionReturn(PETSC_SUCCESS);
      }
    }
    PetscCall(ByTransfer<DIM, S, false>(tr));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  template <int DIM, ShapeType S, bool AXI>
  PetscErrorCode ByTransfer(Transfer tr)
  {
    PetscFunctionBeginUser;
    switch (tr) {
    case Transfer::FlipPic: PetscCall((BySums<DIM, S, AXI, Transfer::FlipPic>())); break;
    case Transfer::APIC: PetscCall((BySums<DIM, S, AXI, Transfer::APIC>())); break;
    case Transfer::XPIC: PetscCall((BySums<DIM, S, AXI, Transfer::XPIC>())); break;
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  // Only the nodal sums this call uses: the velocity increment (FLIP, XPIC) and the velocity
  // gradient (kinematics; APIC with linear weights) are template switches, so MUSL's velocity-only
  // pass skips the gradient and its position-and-F pass the increment.
  template <int DIM, ShapeType S, bool AXI, Transfer TR>
  PetscErrorCode BySums()
  {
    PetscFunctionBeginUser;
    const bool dv   = what.velocity && TR != Transfer::APIC;
    const bool grad = what.kinematics || (TR == Transfer::APIC && S == ShapeType::Linear);
    if (dv && grad) PetscCall((Loop<DIM, S, AXI, TR, true, true>()));
    else if (dv) PetscCall((Loop<DIM, S, AXI, TR, true, false>()));
    else if (grad) PetscCall((Loop<DIM, S, AXI, TR, false, true>()));
    else PetscCall((Loop<DIM, S, AXI, TR, false, false>()));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  template <int DIM, ShapeType S, bool AXI, Transfer TR, bool DV, bool GRAD>
  PetscErrorCode Loop()
  {
    constexpr bool       APIC = TR == Transfer::APIC, XPIC = TR == Transfer::XPIC;
    const Grid          &g    = mpm.grid;
    const PetscInt       vdof = g.num_velocity_fields * 2 * DIM;
    const LocalNodeIndex index(g);
    const PetscReal      flip = mpm.flip_fraction, dt = mpm.dt;
    PetscInt             n;
    PetscReal           *x, *v, *L, *F, *vol, *affine = nullptr;
    const PetscReal     *hw, *fext, *vol0;
    const PetscInt      *failed = nullptr, *material = nullptr;
    const bool           exponential = mpm.f_update == FUpdate::Exponential, external = HasExternalForces(mpm);
    PetscReal            work = 0;
    PetscFunctionBeginUser;
    PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
    SwarmAccess fields(mpm.swarm);
    PetscCall(fields.Get(DMSwarmPICField_coor, &x));
    PetscCall(fields.Get(field::velocity, &v));
    PetscCall(fields.Get(field::L, &L));
    PetscCall(fields.Get(field::half_width0, &hw));
    PetscCall(fields.Get(field::F, &F));
    PetscCall(fields.Get(field::external_force, &fext));
    PetscCall(fields.Get(field::volume, &vol));
    PetscCall(fields.Get(field::volume0, &vol0));
    if constexpr (APIC) PetscCall(fields.Get(field::affine, &affine));
    if (g.num_velocity_fields > 1) PetscCall(fields.Get(field::material, &material));
    if (g.num_velocity_fields > 1 && mpm.convert_failed) PetscCall(fields.Get(state_field::failed, &failed));
    bool             fill;
    Stencil<DIM, S> *stencils = mpm.stencil_cache.Prepare<DIM, S>(n, mpm.step, &fill);
    for (PetscInt p = 0; p < n; ++p) {
      const Stencil<DIM, S> &st = stencils[p];
      if (fill) stencils[p].Evaluate(g.axes, x + DIM * p, hw + DIM * p, F + 9 * p);
      if (material && material[p] == mpm.rigid_material) {
        // A rigid particle moves with the body's prescribed velocity (its field's nodal velocity):
        // no gather; L = 0 and F, V stay as they are.
        const PetscReal *v_r = mpm.rigid_velocity;
        if (what.velocity) {
          SetParticleVelocity<DIM>(v + DIM * p, v_r, external ? fext + DIM * p : nullptr, dt, work);
          if constexpr (APIC)
            for (int a = 0; a < 9; ++a) affine[9 * p + a] = 0;
        }
        if (what.position)
          for (int a = 0; a < DIM; ++a) x[DIM * p + a] += dt * v_r[a];
        if (what.kinematics)
          for (int a = 0; a < 9; ++a) L[9 * p + a] = 0;
        continue;
      }
      PetscReal       dv[DIM] = {}, vnew[DIM] = {}, grad[DIM][DIM] = {}, B[DIM][DIM] = {}, D[DIM][DIM] = {}, vs[DIM] = {};
      const PetscReal r_old = x[DIM * p];                                                                             // axisymmetric: the radius the weights were evaluated at
      const PetscInt  vf    = g.num_velocity_fields > 1 ? mpm.VelocityField(material[p], failed ? failed[p] : 0) : 0; // converted and rigid particles read their own fields
      // grad[a][0..1] as one pair of doubles per row: the same products and sums, lane by lane (the
      // scalar form keeps 12 accumulators live in 3-D and spills)
      Pair grad01[DIM] = {};
      auto gather      = [&](PetscInt at, PetscInt i, PetscInt j, PetscInt k, PetscReal N, const PetscReal dN[]) {
        (void)i, (void)j, (void)k; // APIC only: the node position
        const PetscScalar *nv  = vel + at + vf * 2 * DIM;
        const Pair         d01 = {dN[0], dN[1]};
        for (int a = 0; a < DIM; ++a) {
          if constexpr (DV) dv[a] += N * (nv[DIM + a] - nv[a]);
          vnew[a] += N * nv[DIM + a];
          if constexpr (GRAD) {
            grad01[a] += nv[DIM + a] * d01;
            for (int b = 2; b < DIM; ++b) grad[a][b] += nv[DIM + a] * dN[b];
          }
        }
        if constexpr (XPIC) {
          const PetscScalar *sv = star + at + vf * 2 * DIM;
          for (int a = 0; a < DIM; ++a) vs[a] += N * sv[a];
        }
        if constexpr (APIC && S != ShapeType::Linear) {
          const PetscInt I[3]  = {i, j, k};
          PetscReal      dx[3] = {0, 0, 0};
          for (int b = 0; b < DIM; ++b) dx[b] = g.axes[b].origin + I[b] * g.axes[b].h - x[DIM * p + b];
          for (int a = 0; a < DIM; ++a)
            for (int b = 0; b < DIM; ++b) {
              B[a][b] += N * nv[DIM + a] * dx[b];
              D[a][b] += N * dx[a] * dx[b];
            }
        }
      };
      if constexpr (APIC && S != ShapeType::Linear) ForEachNode(st, [&](PetscInt i, PetscInt j, PetscInt k, PetscReal N, const PetscReal dN[]) { gather(index(i, j, k) * vdof, i, j, k, N, dN); });
      else ForEachLocalNode(st, index, vdof, [&](PetscInt at, PetscReal N, const PetscReal dN[]) { gather(at, 0, 0, 0, N, dN); });
      if constexpr (GRAD)
        for (int a = 0; a < DIM; ++a) grad[a][0] = grad01[a][0], grad[a][1] = grad01[a][1];
      (void)B;
      (void)D;
      (void)vs;
      if constexpr (APIC) {
        PetscReal *C = affine + 9 * p;
        for (int a = 0; a < 9; ++a) C[a] = 0;
        if constexpr (S == ShapeType::Linear) {
          for (int a = 0; a < DIM; ++a)
            for (int b = 0; b < DIM; ++b) C[3 * a + b] = grad[a][b];
        } else {
          Eigen::Matrix<PetscReal, DIM, DIM> Bm, Dm;
          for (int a = 0; a < DIM; ++a)
            for (int b = 0; b < DIM; ++b) {
              Bm(a, b) = B[a][b];
              Dm(a, b) = D[a][b];
            }
          const Eigen::Matrix<PetscReal, DIM, DIM> Cm = Bm * Dm.inverse();
          for (int a = 0; a < DIM; ++a)
            for (int b = 0; b < DIM; ++b) C[3 * a + b] = Cm(a, b);
        }
      }
      if (what.velocity) {
        PetscReal *vp = v + DIM * p;
        PetscReal  v_new[DIM];
        // XPIC(m): v_p = S v* + S (v_new - v_old), v* = [I - (I - S+S)^m] v_old on the grid
        for (int a = 0; a < DIM; ++a) v_new[a] = APIC ? vnew[a] : (XPIC ? vs[a] + dv[a] : FlipBlend(flip, vp[a], dv[a], vnew[a]));
        SetParticleVelocity<DIM>(vp, v_new, external ? fext + DIM * p : nullptr, dt, work);
      }
      if (what.position)
        for (int a = 0; a < DIM; ++a) x[DIM * p + a] += dt * vnew[a];
      if (what.kinematics) {
        PetscReal *Lp = L + 9 * p;
        for (int a = 0; a < 9; ++a) Lp[a] = 0;
        for (int a = 0; a < DIM; ++a)
          for (int b = 0; b < DIM; ++b) Lp[3 * a + b] = grad[a][b];
        if constexpr (AXI) Lp[8] = vnew[0] / r_old; // hoop rate v_r/r
        PetscReal *Fq = F + 9 * p;
        if constexpr (DIM == 2 && !AXI) {
          if (!exponential && Fq[2] == 0 && Fq[5] == 0 && Fq[6] == 0 && Fq[7] == 0) {
            // plane strain, F without out-of-plane shear: only the 2x2 block of (I + L dt) F changes
            // and F_zz stays; the products and the determinant are Eigen's 3x3 ones below with their
            // zero terms left out (the same bits)
            const PetscReal i00 = 1 + Lp[0] * dt, i01 = Lp[1] * dt, i10 = Lp[3] * dt, i11 = 1 + Lp[4] * dt;
            const PetscReal f00 = Fq[0], f01 = Fq[1], f10 = Fq[3], f11 = Fq[4];
            Fq[0]  = i00 * f00 + i01 * f10;
            Fq[1]  = i00 * f01 + i01 * f11;
            Fq[3]  = i10 * f00 + i11 * f10;
            Fq[4]  = i10 * f01 + i11 * f11;
            vol[p] = vol0[p] * (Fq[0] * (Fq[4] * Fq[8]) - Fq[1] * (Fq[3] * Fq[8]));
            continue;
          }
        }
        const Mat3 increment = exponential ? Expm(Mat3CMap(Lp) * dt) : Mat3(Mat3::Identity() + Mat3CMap(Lp) * dt);
        // F <- increment F written out: Eigen's product was a call per particle; its sums are
        // a_i0 b_0j + (a_i1 b_1j + a_i2 b_2j), kept here (the same bits)
        const PetscReal f[9] = {Fq[0], Fq[1], Fq[2], Fq[3], Fq[4], Fq[5], Fq[6], Fq[7], Fq[8]};
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) Fq[3 * a + b] = increment(a, 0) * f[b] + (increment(a, 1) * f[3 + b] + increment(a, 2) * f[6 + b]);
        vol[p] = vol0[p] * Mat3CMap(Fq).determinant();
      }
    }
    mpm.diag.external_work += work;
    // the particles moved, or their cpGIMP widths changed with F: the stencils are stale
    if (what.position || (what.kinematics && S == ShapeType::CpGimp)) mpm.stencil_cache.Invalidate();
    PetscCall(fields.RestoreAll());
    PetscFunctionReturn(PETSC_SUCCESS);
  }
};
// One application of S+ S to a grid field w (ghosted, layout of the velocity vector, first DIM entries
// of each field): u_p = sum N w_I, then sum_p N m_p u_p summed into `sum` (ghosted, zeroed here).
struct XPICKernel {
  MpmSolver         &mpm;
  const PetscScalar *w;
  PetscScalar       *sum;
  template <int DIM, ShapeType S>
  PetscErrorCode operator()()
  {
    const Grid          &g    = mpm.grid;
    const PetscInt       vdof = g.num_velocity_fields * 2 * DIM;
    const LocalNodeIndex index(g);
    PetscInt             n;
    const PetscReal     *x, *hw, *F, *m;
    const PetscInt      *failed = nullptr, *material = nullptr;
    PetscFunctionBeginUser;
    PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
    SwarmAccess fields(mpm.swarm);
    PetscCall(fields.Get(DMSwarmPICField_coor, &x));
    PetscCall(fields.Get(field::half_width0, &hw));
    PetscCall(fields.Get(field::F, &F));
    PetscCall(fields.Get(field::mass, &m));
    if (g.num_velocity_fields > 1) PetscCall(fields.Get(field::material, &material));
    if (g.num_velocity_fields > 1 && mpm.convert_failed) PetscCall(fields.Get(state_field::failed, &failed));
    bool             fill;
    Stencil<DIM, S> *stencils = mpm.stencil_cache.Prepare<DIM, S>(n, mpm.step, &fill);
    for (PetscInt p = 0; p < n; ++p) {
      const Stencil<DIM, S> &st = stencils[p];
      if (fill) stencils[p].Evaluate(g.axes, x + DIM * p, hw + DIM * p, F + 9 * p);
      const PetscInt vf     = g.num_velocity_fields > 1 ? mpm.VelocityField(material[p], failed ? failed[p] : 0) : 0;
      PetscReal      u[DIM] = {};
      ForEachNode(st, [&](PetscInt i, PetscInt j, PetscInt k, PetscReal N, const PetscReal *) {
        const PetscScalar *wv = w + index(i, j, k) * vdof + vf * 2 * DIM;
        for (int a = 0; a < DIM; ++a) u[a] += N * wv[a];
      });
      ForEachNode(st, [&](PetscInt i, PetscInt j, PetscInt k, PetscReal N, const PetscReal *) {
        PetscScalar *sv = sum + index(i, j, k) * vdof + vf * 2 * DIM;
        for (int a = 0; a < DIM; ++a) sv[a] += N * m[p] * u[a];
      });
    }
    PetscCall(fields.RestoreAll());
    PetscFunctionReturn(PETSC_SUCCESS);
  }
};
} // namespace

// XPIC(m) (Hammerquist & Nairn, CMAME 318 (2017) 724): v* = sum_{k=1..m} (-1)^{k+1} C(m,k) (S+S)^{k-1} v_old,
// the first m terms of the series for the particle velocities that FLIP keeps and PIC smooths away;
// m = 1 is PIC, m -> infinity is FLIP. S+S is one G2P then one mass-weighted P2G (m - 1 particle
// passes). Nodes under the mass cut-off stay zero; the rigid field keeps its prescribed velocity.
static PetscErrorCode XPICExtrapolate(MpmSolver &mpm)
{
  Grid          &g   = mpm.grid;
  const PetscInt dim = g.dim, nvf = g.num_velocity_fields, vdof = nvf * 2 * dim, stride = g.NodeStride(), dof = nvf * stride;
  const PetscInt m = mpm.xpic_order;
  PetscFunctionBeginUser;
  if (!g.xpic_star) {
    PetscCall(DMCreateLocalVector(g.da_velocity, &g.xpic_star));
    PetscCall(DMCreateLocalVector(g.da_velocity, &g.xpic_w));
    PetscCall(DMCreateLocalVector(g.da_velocity, &g.xpic_sum));
    PetscCall(DMCreateGlobalVector(g.da_velocity, &g.xpic_global));
  }
  // w = v_old, v* = m w
  PetscCall(VecCopy(g.velocity_local, g.xpic_w));
  PetscCall(VecCopy(g.velocity_local, g.xpic_star));
  PetscCall(VecScale(g.xpic_star, (PetscScalar)m));
  PetscReal coefficient = m; // (-1)^{k+1} C(m, k)
  for (PetscInt k = 2; k <= m; ++k) {
    coefficient *= -(PetscReal)(m - k + 1) / k;
    const PetscScalar *w;
    PetscScalar       *sum, *glob;
    const PetscScalar *nodal;
    PetscCall(VecZeroEntries(g.xpic_sum));
    PetscCall(VecGetArrayRead(g.xpic_w, &w));
    PetscCall(VecGetArray(g.xpic_sum, &sum));
    XPICKernel kernel{mpm, w, sum};
    PetscCall(DispatchShape(dim, mpm.shape, kernel));
    PetscCall(VecRestoreArray(g.xpic_sum, &sum));
    PetscCall(VecRestoreArrayRead(g.xpic_w, &w));
    PetscCall(VecZeroEntries(g.xpic_global));
    PetscCall(DMLocalToGlobal(g.da_velocity, g.xpic_sum, ADD_VALUES, g.xpic_global));
    // divide by the nodal mass; the rigid field keeps its velocity
    PetscInt nlocal;
    PetscCall(VecGetLocalSize(g.xpic_global, &nlocal));
    PetscCall(VecGetArray(g.xpic_global, &glob));
    PetscCall(VecGetArrayRead(g.nodal, &nodal));
    const PetscInt rigid = mpm.rigid_material >= 0 ? nvf - 1 : -1;
    for (PetscInt node = 0; node < nlocal / vdof; ++node)
      for (PetscInt vf = 0; vf < nvf; ++vf) {
        const PetscReal mass = nodal[node * dof + vf * stride];
        PetscScalar    *v    = glob + node * vdof + vf * 2 * dim;
        for (PetscInt a = 0; a < dim; ++a) v[a] = vf == rigid ? mpm.rigid_velocity[a] : (mass > mpm.mass_cutoff ? v[a] / mass : 0);
      }
    PetscCall(VecRestoreArrayRead(g.nodal, &nodal));
    PetscCall(VecRestoreArray(g.xpic_global, &glob));
    PetscCall(DMGlobalToLocal(g.da_velocity, g.xpic_global, INSERT_VALUES, g.xpic_w));
    PetscCall(VecAXPY(g.xpic_star, coefficient, g.xpic_w));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GridToParticles(MpmSolver &mpm, G2PRequest what)
{
  const PetscScalar *vel, *star = nullptr;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(mpm.ev_g2p, 0, 0, 0, 0));
  const bool xpic = what.velocity && mpm.transfer == Transfer::XPIC;
  if (xpic) {
    PetscCall(PetscLogEventBegin(mpm.ev_xpic, 0, 0, 0, 0));
    PetscCall(XPICExtrapolate(mpm));
    PetscCall(PetscLogEventEnd(mpm.ev_xpic, 0, 0, 0, 0));
    PetscCall(VecGetArrayRead(mpm.grid.xpic_star, &star));
  }
  PetscCall(VecGetArrayRead(mpm.grid.velocity_local, &vel));
  G2PKernel kernel{mpm, what, vel, star};
  PetscCall(DispatchShape(mpm.grid.dim, mpm.shape, kernel));
  PetscCall(VecRestoreArrayRead(mpm.grid.velocity_local, &vel));
  if (xpic) PetscCall(VecRestoreArrayRead(mpm.grid.xpic_star, &star));
  PetscCall(PetscLogEventEnd(mpm.ev_g2p, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
