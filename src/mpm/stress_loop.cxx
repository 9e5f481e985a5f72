// The constitutive call: each material updates the stress of its own particles in one flat loop
// (models/). F and V were updated with L in the G2P pass (g2p.cxx).
#include "../simulation.hpp"
#include "../../models/elastic/tensor.hpp"
#include <cmath>

namespace burst {

// Gathers the field views a material needs; must be matched by RestorePointFields.
static PetscErrorCode GetPointFields(Simulation &sim, MaterialPointFields &f)
{
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(sim.swarm, &f.n));
  PetscCall(DMSwarmGetField(sim.swarm, field::material, nullptr, nullptr, (void **)&f.material));
  PetscCall(DMSwarmGetField(sim.swarm, field::L, nullptr, nullptr, (void **)&f.L));
  PetscCall(DMSwarmGetField(sim.swarm, field::F, nullptr, nullptr, (void **)&f.F));
  PetscCall(DMSwarmGetField(sim.swarm, field::stress, nullptr, nullptr, (void **)&f.stress));
  PetscCall(DMSwarmGetField(sim.swarm, field::mass, nullptr, nullptr, (void **)&f.mass));
  PetscCall(DMSwarmGetField(sim.swarm, field::volume, nullptr, nullptr, (void **)&f.volume));
  PetscCall(DMSwarmGetField(sim.swarm, field::temperature, nullptr, nullptr, (void **)&f.temperature));
  PetscCall(DMSwarmGetField(sim.swarm, field::wave_speed, nullptr, nullptr, (void **)&f.wave_speed));
  PetscCall(DMSwarmGetField(sim.swarm, field::internal_energy, nullptr, nullptr, (void **)&f.internal_energy));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode RestorePointFields(Simulation &sim, MaterialPointFields &f)
{
  PetscFunctionBeginUser;
  PetscCall(DMSwarmRestoreField(sim.swarm, field::internal_energy, nullptr, nullptr, (void **)&f.internal_energy));
  PetscCall(DMSwarmRestoreField(sim.swarm, field::wave_speed, nullptr, nullptr, (void **)&f.wave_speed));
  PetscCall(DMSwarmRestoreField(sim.swarm, field::temperature, nullptr, nullptr, (void **)&f.temperature));
  PetscCall(DMSwarmRestoreField(sim.swarm, field::volume, nullptr, nullptr, (void **)&f.volume));
  PetscCall(DMSwarmRestoreField(sim.swarm, field::mass, nullptr, nullptr, (void **)&f.mass));
  PetscCall(DMSwarmRestoreField(sim.swarm, field::stress, nullptr, nullptr, (void **)&f.stress));
  PetscCall(DMSwarmRestoreField(sim.swarm, field::F, nullptr, nullptr, (void **)&f.F));
  PetscCall(DMSwarmRestoreField(sim.swarm, field::L, nullptr, nullptr, (void **)&f.L));
  PetscCall(DMSwarmRestoreField(sim.swarm, field::material, nullptr, nullptr, (void **)&f.material));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode UpdateStress(Simulation &sim)
{
  MaterialPointFields f;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(sim.ev_stress, 0, 0, 0, 0));
  PetscCall(GetPointFields(sim, f));
  for (PetscInt id = 0; id < (PetscInt)sim.materials.size(); ++id) PetscCall(sim.materials[id]->UpdateStress(f, id, sim.dt));
  PetscCall(RestorePointFields(sim, f));
  PetscCall(PetscLogEventEnd(sim.ev_stress, 0, 0, 0, 0));
  PetscCall(CheckParticleState(sim, "stress update"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Initial stress (hyperelastic models compute it from F; hypoelastic keep zero) and wave speeds.
PetscErrorCode ComputeInitialWaveSpeed(Simulation &sim)
{
  MaterialPointFields f;
  PetscFunctionBeginUser;
  PetscCall(GetPointFields(sim, f));
  for (PetscInt id = 0; id < (PetscInt)sim.materials.size(); ++id) {
    PetscCall(sim.materials[id]->UpdateStress(f, id, 0.0));
    PetscCall(sim.materials[id]->ComputeWaveSpeed(f, id));
  }
  PetscCall(RestorePointFields(sim, f));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Stops the run on a NaN or non-positive density, naming the phase, step, particle and field.
PetscErrorCode CheckParticleState(Simulation &sim, const char phase[])
{
  PetscInt         n, dim = sim.grid.dim, bad = -1;
  const PetscReal *x, *v, *sigma, *vol, *m;
  const PetscInt64 *pid;
  const char      *what = "";
  PetscInt64       bad_pid = -1;
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(sim.swarm, &n));
  PetscCall(DMSwarmGetField(sim.swarm, DMSwarmPICField_coor, nullptr, nullptr, (void **)&x));
  PetscCall(DMSwarmGetField(sim.swarm, field::velocity, nullptr, nullptr, (void **)&v));
  PetscCall(DMSwarmGetField(sim.swarm, field::stress, nullptr, nullptr, (void **)&sigma));
  PetscCall(DMSwarmGetField(sim.swarm, field::volume, nullptr, nullptr, (void **)&vol));
  PetscCall(DMSwarmGetField(sim.swarm, field::mass, nullptr, nullptr, (void **)&m));
  PetscCall(DMSwarmGetField(sim.swarm, DMSwarmField_pid, nullptr, nullptr, (void **)&pid));
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
  PetscCall(DMSwarmRestoreField(sim.swarm, DMSwarmField_pid, nullptr, nullptr, (void **)&pid));
  PetscCall(DMSwarmRestoreField(sim.swarm, field::mass, nullptr, nullptr, (void **)&m));
  PetscCall(DMSwarmRestoreField(sim.swarm, field::volume, nullptr, nullptr, (void **)&vol));
  PetscCall(DMSwarmRestoreField(sim.swarm, field::stress, nullptr, nullptr, (void **)&sigma));
  PetscCall(DMSwarmRestoreField(sim.swarm, field::velocity, nullptr, nullptr, (void **)&v));
  PetscCall(DMSwarmRestoreField(sim.swarm, DMSwarmPICField_coor, nullptr, nullptr, (void **)&x));
  PetscMPIInt local_bad = bad >= 0, any_bad = 0;
  PetscCallMPI(MPI_Allreduce(&local_bad, &any_bad, 1, MPI_INT, MPI_MAX, sim.comm));
  if (local_bad) PetscCall(PetscPrintf(PETSC_COMM_SELF, "[%d] after %s, step %" PetscInt_FMT ", t = %g s: particle id %" PetscInt64_FMT ": %s\n", sim.rank, phase, sim.step, (double)sim.time, bad_pid, what));
  PetscCheck(!any_bad, sim.comm, PETSC_ERR_NOT_CONVERGED, "Step %" PetscInt_FMT ": invalid particle state after %s (see the line above: step, particle id and field); reduce -mpm_cfl or check the material parameters", sim.step, phase);
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
