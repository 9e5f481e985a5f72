// Time step and external forces.
#include "mpm/mpm.hpp"
#include "mpm/swarm_access.hpp"
#include "../../models/elastic/tensor.hpp"
#include <cmath>

namespace burst {

// dt = cfl min_p min_d h_d / (c_p + |v_p,d|), reduced over ranks; capped by -mpm_dt_max and so that
// the last step ends at -final_time. -mpm_dt fixes it instead.
PetscErrorCode ComputeTimeStep(MpmSolver &mpm, PetscReal final_time)
{
  PetscInt         n, dim = mpm.grid.dim;
  const PetscReal *v, *c;
  PetscReal        local = PETSC_MAX_REAL, global;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(mpm.ev_dt, 0, 0, 0, 0));
  PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
  SwarmAccess fields(mpm.swarm);
  PetscCall(fields.Get(field::velocity, &v));
  PetscCall(fields.Get(field::wave_speed, &c));
  PetscInt limit = -1; // the particle that sets the step (-info)
  for (PetscInt p = 0; p < n; ++p)
    for (PetscInt d = 0; d < dim; ++d) {
      const PetscReal bound = mpm.grid.h[d] / (c[p] + std::fabs(v[dim * p + d]) + 1e-300);
      if (bound < local) local = bound, limit = p;
    }
  PetscCallMPI(MPI_Allreduce(&local, &global, 1, MPIU_REAL, MPI_MIN, mpm.comm));
  PetscBool info = PETSC_FALSE;
  PetscCall(PetscInfoEnabled(DM_CLASSID, &info)); // the limiting particle is looked up only for -info
  if (info && limit >= 0 && local == global) {
    const PetscInt64 *pid;
    const PetscInt   *material;
    PetscCall(fields.Get(DMSwarmField_pid, &pid));
    PetscCall(fields.Get(field::material, &material));
    PetscReal speed = 0;
    for (PetscInt d = 0; d < dim; ++d) speed = PetscMax(speed, std::fabs(v[dim * limit + d]));
    PetscCall(PetscInfo(mpm.swarm, "Step %" PetscInt_FMT ": dt set by particle id %" PetscInt64_FMT " (%s): wave speed %g m/s, speed %g m/s\n", mpm.step, pid[limit], mpm.materials[material[limit]]->Name(), (double)c[limit], (double)speed));
  }
  PetscCall(fields.RestoreAll());
  static PetscInt warned_step = -1; // a fixed step beyond the stable one is said once per run, when first seen
  if (mpm.dt_fixed > global && warned_step < 0) {
    warned_step = mpm.step;
    PetscCall(PetscPrintf(mpm.comm,
                          "Warning: -mpm_dt = %g s is %.3g times the particles' stable step min h/(c + |v|) = %g s at step %" PetscInt_FMT " (Courant number above 1): the solids' update is unstable; give -mpm_dt 0 for the CFL rule (-mpm_cfl %g)\n",
                          (double)mpm.dt_fixed, (double)(mpm.dt_fixed / global), (double)global, mpm.step, (double)mpm.cfl));
  }
  mpm.dt = mpm.dt_fixed > 0 ? mpm.dt_fixed : PetscMin(mpm.cfl * global, mpm.dt_max);
  PetscCheck(mpm.dt > 0 && std::isfinite(mpm.dt), mpm.comm, PETSC_ERR_NOT_CONVERGED, "Step %" PetscInt_FMT ": time step %g s is not positive; check the material wave speeds", mpm.step, (double)mpm.dt);
  const PetscReal remaining = final_time - mpm.time;
  if (mpm.dt > remaining || remaining - mpm.dt < 1e-6 * mpm.dt) mpm.dt = remaining; // end exactly at the final time
  PetscCall(PetscLogEventEnd(mpm.ev_dt, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Whether any particle can carry an external force: without a load the field stays zero (seeding
// zeroes it), and the transfers leave its terms out.
bool HasExternalForces(const MpmSolver &mpm)
{
  const bool body    = static_cast<bool>(mpm.body_force);
  const bool gravity = mpm.gravity[0] != 0 || mpm.gravity[1] != 0 || mpm.gravity[2] != 0;
  return body || gravity || !mpm.load_curves.empty();
}

// External force per particle at t_n: gravity, the body force of an analytic solution, and the
// pressure of a load curve on surface particles, with the area vector carried by Nanson's formula
// n da = J F^{-T} N dA.
PetscErrorCode ComputeExternalForces(MpmSolver &mpm)
{
  PetscInt               n, dim = mpm.grid.dim;
  PetscReal             *fext;
  const PetscReal       *m, *area0, *F, *X0;
  const PetscInt        *curve;
  std::vector<PetscReal> pressure(mpm.load_curves.size());
  PetscFunctionBeginUser;
  for (size_t c = 0; c < mpm.load_curves.size(); ++c) pressure[c] = mpm.load_curves[c].Evaluate(mpm.time);
  if (!HasExternalForces(mpm)) PetscFunctionReturn(PETSC_SUCCESS); // the field stays zero: skip the pass
  const bool body = static_cast<bool>(mpm.body_force);
  PetscCall(PetscLogEventBegin(mpm.ev_loads, 0, 0, 0, 0));
  PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
  SwarmAccess fields(mpm.swarm);
  PetscCall(fields.Get(field::external_force, &fext));
  PetscCall(fields.Get(field::mass, &m));
  PetscCall(fields.Get(field::traction_area0, &area0));
  PetscCall(fields.Get(field::F, &F));
  PetscCall(fields.Get(field::position0, &X0));
  PetscCall(fields.Get(field::load_curve, &curve));
  for (PetscInt p = 0; p < n; ++p) {
    PetscReal b[3] = {0, 0, 0};
    if (body) {
      PetscReal X[3] = {0, 0, 0};
      for (PetscInt d = 0; d < dim; ++d) X[d] = X0[dim * p + d];
      mpm.body_force(X, mpm.time, b);
    }
    for (PetscInt d = 0; d < dim; ++d) fext[dim * p + d] = m[p] * (mpm.gravity[d] + b[d]);
    if (curve[p] >= 0) {
      Mat3CMap                       Fp(F + 9 * p);
      Eigen::Matrix<PetscReal, 3, 1> N0 = Eigen::Matrix<PetscReal, 3, 1>::Zero();
      for (PetscInt d = 0; d < dim; ++d) N0[d] = area0[dim * p + d];
      const Eigen::Matrix<PetscReal, 3, 1> nda = Fp.determinant() * Fp.inverse().transpose() * N0;
      for (PetscInt d = 0; d < dim; ++d) fext[dim * p + d] -= pressure[curve[p]] * nda[d]; // pressure pushes against the outward normal
    }
  }
  PetscCall(fields.RestoreAll());
  PetscCall(PetscLogEventEnd(mpm.ev_loads, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
