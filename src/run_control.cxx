// The run's stops (src/run_control.hpp).
#include "simulation.hpp"

namespace burst {

PetscErrorCode CheckRunStops(Simulation &sim, PetscBool *stop)
{
  EnergyReport r;
  PetscFunctionBeginUser;
  *stop = PETSC_FALSE;
  if ((sim.run.stop_kinetic_fraction <= 0 && sim.run.energy_growth_limit <= 0) || sim.step % sim.output.monitor_interval) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(ComputeEnergies(sim, r));
  // balance_error = (E - W_ext - E0) / (largest energy seen): positive growth is energy from nowhere
  PetscCheck(sim.run.energy_growth_limit <= 0 || r.balance_error <= sim.run.energy_growth_limit, sim.comm, PETSC_ERR_NOT_CONVERGED,
             "Step %" PetscInt_FMT ", t = %g s: unstable: the total energy grew by %.3g of the largest energy seen (kinetic %g J, internal %g J), beyond -mpm_energy_growth_limit %g; likely cause: a time step above the stability limit of this "
             "interpolator, transfer and step order (reduce -mpm_cfl)",
             sim.step, (double)sim.time, (double)r.balance_error, (double)r.kinetic, (double)r.internal, (double)sim.run.energy_growth_limit);
  if (sim.run.stop_kinetic_fraction <= 0) PetscFunctionReturn(PETSC_SUCCESS);
  if (r.kinetic < sim.run.stop_kinetic_fraction * sim.mpm.diag.initial_kinetic) {
    *stop                     = PETSC_TRUE;
    sim.mpm.diag.kinetic_stop = PETSC_TRUE;
    PetscCall(PetscPrintf(sim.comm, "Stopping at step %" PetscInt_FMT ", t = %g s: kinetic energy %g J is below -stop_kinetic_fraction %g of its initial %g J\n", sim.step, (double)sim.time, (double)r.kinetic, (double)sim.run.stop_kinetic_fraction,
                          (double)sim.mpm.diag.initial_kinetic));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
