// What the driver (src/burst.cxx) calls to advance a run: one time step (src/step.cxx).
#pragma once
#include "petsc_compat.hpp"

namespace burst {

struct Simulation;

// The step size (the smaller of the MPM and gas limits, -mpm_dt_max or a fixed -mpm_dt, cut to end
// at -final_time), then the phases of the scene's step in order: solids only, gas only, or the
// coupled step; then time, step count and particle-steps advance.
PetscErrorCode TakeStep(Simulation &sim);
// The MPM solver's step, time and dt from the run's (the gas's clock advances with its own steps).
void SetMpmClock(Simulation &sim);

} // namespace burst
