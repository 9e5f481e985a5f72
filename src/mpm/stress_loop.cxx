// The constitutive call: each material updates the stress of its own particles in one flat loop
// (models/). F and V were updated with L in the G2P pass (g2p.cxx).
#include "mpm/mpm.hpp"
#include "mpm/material_state.hpp"
#include "../../models/elastic/tensor.hpp"
#include <cmath>

namespace burst {

PetscErrorCode UpdateStress(MpmSolver &mpm)
{
  MaterialPointFields f;
  MaterialState       state;

  SwarmAccess fields(mpm.swarm);
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(mpm.ev_stress, 0, 0, 0, 0));
  PetscCall(GetMaterialPointFields(fields, mpm.swarm, state, f));
  f.time      = mpm.time + mpm.dt;
  f.cell_size = mpm.grid.h[0];
  // A burning solid's products take its internal energy; the part of its stress work that the
  // update turned into temperature (dissipation, thermoelastic heating) is counted once
  // (coupling/burn.cxx), so the temperature change of the update is kept per particle.
  const bool track_heat = !mpm.deformation_heat_cv.empty();
  if (track_heat) mpm.temperature_before.assign(f.temperature, f.temperature + f.n);
  PetscCall(UpdateStressShared(mpm, f));
  if (track_heat) {
    PetscReal *heat;
    PetscCall(fields.Get(field::deformation_heat, &heat));
    for (PetscInt p = 0; p < f.n; ++p) heat[p] += f.mass[p] * mpm.deformation_heat_cv[f.material[p]] * (f.temperature[p] - mpm.temperature_before[p]);
  }
  if (mpm.viscosity[0] > 0 || mpm.viscosity[1] > 0) {
    // Artificial bulk viscosity (models.md 5.5; von Neumann-Richtmyer with a linear term): acts in
    // compression only, enters the internal force as -q I (p2g.cxx), and its work is dissipated:
    // added to the internal energy so the balance closes.
    PetscReal *q;
    PetscCall(fields.Get(field::bulk_viscosity, &q));
    PetscReal dx = 0;
    for (PetscInt d = 0; d < mpm.grid.dim; ++d) dx += mpm.grid.h[d] / mpm.grid.dim;
    for (PetscInt p = 0; p < f.n; ++p) {
      const PetscReal *L = f.L + 9 * p, trace_D = L[0] + L[4] + L[8];
      if (trace_D >= 0) {
        q[p] = 0;
        continue;
      }
      const PetscReal rho = f.mass[p] / f.volume[p];
      q[p]                = rho * (mpm.viscosity[0] * f.wave_speed[p] * -trace_D * dx + mpm.viscosity[1] * trace_D * trace_D * dx * dx);
      f.internal_energy[p] += -q[p] * trace_D * f.volume[p] * mpm.dt;
      mpm.diag.viscous_work += -q[p] * trace_D * f.volume[p] * mpm.dt;
    }
  }
  PetscCall(fields.RestoreAll());
  PetscCall(PetscLogEventEnd(mpm.ev_stress, 0, 0, 0, 0));
  PetscCall(CheckParticleState(mpm, "stress update"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Initial stress (hyperelastic models compute it from F; hypoelastic keep zero) and wave speeds.
PetscErrorCode ComputeInitialWaveSpeed(MpmSolver &mpm)
{
  MaterialPointFields f;
  MaterialState       state;

  SwarmAccess fields(mpm.swarm);
  PetscFunctionBeginUser;
  PetscCall(GetMaterialPointFields(fields, mpm.swarm, state, f));
  f.time      = mpm.time;
  f.cell_size = mpm.grid.h[0];
  for (PetscInt id = 0; id < (PetscInt)mpm.materials.size(); ++id) {
    PetscCall(mpm.materials[id]->UpdateStress(f, id, 0.0));
    PetscCall(mpm.materials[id]->ComputeWaveSpeed(f, id));
  }
  PetscCall(fields.RestoreAll());
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Stops the run on a NaN or non-positive density, naming the phase, step, particle and field.
PetscErrorCode CheckParticleState(MpmSolver &mpm, const char phase[])
{
  PetscInt          n, dim = mpm.grid.dim, bad = -1;
  const PetscReal  *x, *v, *sigma, *vol, *m;
  const PetscInt64 *pid;
  const char       *what    = "";
  PetscInt64        bad_pid = -1;
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
  SwarmAccess fields(mpm.swarm);
  PetscCall(fields.Get(DMSwarmPICField_coor, &x));
  PetscCall(fields.Get(field::velocity, &v));
  PetscCall(fields.Get(field::stress, &sigma));
  PetscCall(fields.Get(field::volume, &vol));
  PetscCall(fields.Get(field::mass, &m));
  PetscCall(fields.Get(DMSwarmField_pid, &pid));
  for (PetscInt p = 0; p < n && bad < 0; ++p) {
    PetscReal sum = 0;
    for (PetscInt a = 0; a < dim; ++a) sum += x[dim * p + a] + v[dim * p + a];
    for (int a = 0; a < 9; ++a) sum += sigma[9 * p + a];
    if (!std::isfinite(sum)) {
      bad  = p;
      what = "position/velocity/stress is not finite";
    } else if (!(vol[p] > 0) || !(m[p] / vol[p] > 0)) {
      bad  = p;
      what = "density is negative or zero (det F <= 0)";
    }
  }
  if (bad >= 0) bad_pid = pid[bad];
  PetscCall(fields.RestoreAll());
  PetscMPIInt local_bad = bad >= 0, any_bad = 0;
  PetscCallMPI(MPI_Allreduce(&local_bad, &any_bad, 1, MPI_INT, MPI_MAX, mpm.comm));
  if (local_bad) PetscCall(PetscPrintf(PETSC_COMM_SELF, "[%d] after %s, step %" PetscInt_FMT ", t = %g s: particle id %" PetscInt64_FMT ": %s\n", mpm.rank, phase, mpm.step, (double)mpm.time, bad_pid, what));
  if (any_bad && mpm.step > 0 && mpm.write_snapshot) PetscCall(mpm.write_snapshot(mpm.step + 1)); // named after the step that failed, not over the last good output
  PetscCheck(!any_bad, mpm.comm, PETSC_ERR_NOT_CONVERGED, "Step %" PetscInt_FMT ": invalid particle state after %s (see the line above: step, particle id and field); reduce -mpm_cfl or check the material parameters", mpm.step, phase);
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
