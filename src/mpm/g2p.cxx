// Grid to particles from the ghosted [v_old, v_new] nodal velocities:
//   velocity           v_p <- a (v_p + sum N (v_new - v_old)) + (1 - a) sum N v_new   (a = FLIP fraction)
//   position           x_p <- x_p + dt sum N v_new
//   kinematics         L_p = sum v_new (x) grad N; F_p <- (I + L dt) F_p (or exp(L dt) F_p); V_p = V0 det F
//                      (fused here so F, L and the volumes are streamed once per step)
// The work of the external forces, f_ext . (v_p^n + v_p^{n+1})/2 dt, is accumulated here.
//
// Axisymmetric (x = r): the hoop rate L_tt = v_r(x_p)/r_p goes into the zz entry of L, with r_p the
// radius before the position update, so that F_tt <- (1 + L_tt dt) F_tt stays exactly r/R.
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
  Simulation        &sim;
  G2PRequest         what;
  const PetscScalar *vel;
  template <int DIM, ShapeType S>
  PetscErrorCode operator()()
  {
    PetscFunctionBeginUser;
    const bool apic = sim.transfer == Transfer::APIC && what.velocity;
    if constexpr (DIM == 2) {
      if (sim.axisymmetric) {
        if (apic) PetscCall((Loop<DIM, S, true, true>()));
        else PetscCall((Loop<DIM, S, true, false>()));
        PetscFunctionReturn(PETSC_SUCCESS);
      }
    }
    if (apic) PetscCall((Loop<DIM, S, false, true>()));
    else PetscCall((Loop<DIM, S, false, false>()));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  template <int DIM, ShapeType S, bool AXI, bool APIC>
  PetscErrorCode Loop()
  {
    const Grid          &g = sim.grid;
    const PetscInt       vdof = g.num_velocity_fields * 2 * DIM;
    const LocalNodeIndex index(g);
    const PetscReal      flip = sim.flip_fraction, dt = sim.dt;
    PetscInt             n;
    PetscReal           *x, *v, *L, *F, *vol, *affine = nullptr;
    const PetscReal     *hw, *fext, *vol0;
    const PetscInt      *failed = nullptr, *material = nullptr;
    const bool           exponential = sim.f_update == FUpdate::Exponential;
    PetscReal            work = 0;
    PetscFunctionBeginUser;
    PetscCall(DMSwarmGetLocalSize(sim.swarm, &n));
    SwarmAccess fields(sim.swarm);
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
    if (g.num_velocity_fields > 1 && sim.convert_failed) PetscCall(fields.Get("failed", &failed));
    Stencil<DIM, S> st;
    for (PetscInt p = 0; p < n; ++p) {
      st.Evaluate(g.axes, x + DIM * p, hw + DIM * p, F + 9 * p);
      PetscReal      dv[DIM] = {}, vnew[DIM] = {}, grad[DIM][DIM] = {}, B[DIM][DIM] = {}, D[DIM][DIM] = {};
      const PetscReal r_old = x[DIM * p]; // axisymmetric: the radius the weights were evaluated at
      const PetscInt vf = g.num_velocity_fields > 1 ? sim.VelocityField(material[p], failed ? failed[p] : 0) : 0; // converted and rigid particles read their own fields
      ForEachNode(st, [&](PetscInt i, PetscInt j, PetscInt k, PetscReal N, const PetscReal dN[]) {
        const PetscScalar *nv = vel + index(i, j, k) * vdof + vf * 2 * DIM;
        for (int a = 0; a < DIM; ++a) {
          dv[a] += N * (nv[DIM + a] - nv[a]);
          vnew[a] += N * nv[DIM + a];
          for (int b = 0; b < DIM; ++b) grad[a][b] += nv[DIM + a] * dN[b];
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
      });
      (void)B;
      (void)D;
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
        for (int a = 0; a < DIM; ++a) {
          const PetscReal v_new = APIC ? vnew[a] : flip * (vp[a] + dv[a]) + (1 - flip) * vnew[a];
          work += 0.5 * dt * fext[DIM * p + a] * (vp[a] + v_new);
          vp[a] = v_new;
        }
      }
      if (what.position)
        for (int a = 0; a < DIM; ++a) x[DIM * p + a] += dt * vnew[a];
      if (what.kinematics) {
        PetscReal *Lp = L + 9 * p;
        for (int a = 0; a < 9; ++a) Lp[a] = 0;
        for (int a = 0; a < DIM; ++a)
          for (int b = 0; b < DIM; ++b) Lp[3 * a + b] = grad[a][b];
        if constexpr (AXI) Lp[8] = vnew[0] / r_old; // hoop rate v_r/r
        Mat3Map    Fp(F + 9 * p);
        const Mat3 increment = exponential ? Expm(Mat3CMap(Lp) * dt) : Mat3(Mat3::Identity() + Mat3CMap(Lp) * dt);
        Fp                   = increment * Mat3(Fp);
        vol[p]               = vol0[p] * Fp.determinant();
      }
    }
    sim.diag.external_work += work;
    PetscCall(fields.RestoreAll());
    PetscFunctionReturn(PETSC_SUCCESS);
  }
};
} // namespace

PetscErrorCode GridToParticles(Simulation &sim, G2PRequest what)
{
  const PetscScalar *vel;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(sim.ev_g2p, 0, 0, 0, 0));
  PetscCall(VecGetArrayRead(sim.grid.velocity_local, &vel));
  G2PKernel kernel{sim, what, vel};
  PetscCall(DispatchShape(sim.grid.dim, sim.shape, kernel));
  PetscCall(VecRestoreArrayRead(sim.grid.velocity_local, &vel));
  PetscCall(PetscLogEventEnd(sim.ev_g2p, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
