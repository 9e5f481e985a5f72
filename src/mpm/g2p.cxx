// Grid to particles from the ghosted [v_old, v_new] nodal velocities:
//   velocity           v_p <- a (v_p + sum N (v_new - v_old)) + (1 - a) sum N v_new   (a = FLIP fraction)
//   position           x_p <- x_p + dt sum N v_new
//   kinematics         L_p = sum v_new (x) grad N; F_p <- (I + L dt) F_p (or exp(L dt) F_p); V_p = V0 det F
//                      (fused here so F, L and the volumes are streamed once per step)
// The work of the external forces, f_ext . (v_p^n + v_p^{n+1})/2 dt, is accumulated here.
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
    const Grid          &g = sim.grid;
    const PetscInt       vdof = g.num_velocity_fields * 2 * DIM;
    const LocalNodeIndex index(g);
    const PetscReal      flip = sim.flip_fraction, dt = sim.dt;
    PetscInt             n;
    PetscReal           *x, *v, *L, *F, *vol;
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
    if (g.num_velocity_fields > 1) PetscCall(fields.Get(field::material, &material));
    if (g.num_velocity_fields > 1 && sim.convert_failed) PetscCall(fields.Get("failed", &failed));
    Stencil<DIM, S> st;
    for (PetscInt p = 0; p < n; ++p) {
      st.Evaluate(g.axes, x + DIM * p, hw + DIM * p, F + 9 * p);
      PetscReal      dv[DIM] = {}, vnew[DIM] = {}, grad[DIM][DIM] = {};
      const PetscInt vf = g.num_velocity_fields > 1 ? sim.VelocityField(material[p], failed ? failed[p] : 0) : 0; // converted and rigid particles read their own fields
      ForEachNode(st, [&](PetscInt i, PetscInt j, PetscInt k, PetscReal N, const PetscReal dN[]) {
        const PetscScalar *nv = vel + index(i, j, k) * vdof + vf * 2 * DIM;
        for (int a = 0; a < DIM; ++a) {
          dv[a] += N * (nv[DIM + a] - nv[a]);
          vnew[a] += N * nv[DIM + a];
          for (int b = 0; b < DIM; ++b) grad[a][b] += nv[DIM + a] * dN[b];
        }
      });
      if (what.velocity) {
        PetscReal *vp = v + DIM * p;
        for (int a = 0; a < DIM; ++a) {
          const PetscReal v_new = flip * (vp[a] + dv[a]) + (1 - flip) * vnew[a];
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
