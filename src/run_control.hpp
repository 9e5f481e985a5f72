// When a run ends: the scene's name, its final time and step cap, and the stops checked at monitor
// steps (src/run_control.cxx). Simulation owns one; src/options.cxx reads its options.
#pragma once
#include "petsc_compat.hpp"
#include <string>

namespace burst {

struct Simulation;

struct RunControl {
  std::string scene                 = "unnamed";
  PetscReal   final_time            = 1.0; // s
  PetscInt    max_steps             = PETSC_MAX_INT;
  PetscReal   energy_growth_limit   = 0; // stop with an error once the energy balance error exceeds this (0: never)
  PetscReal   stop_kinetic_fraction = 0; // stop once the kinetic energy falls below this fraction of its initial value (0: never)

  // The run has reached -final_time or -max_steps.
  bool Reached(PetscReal time, PetscInt step) const { return !(time < final_time * (1 - 1e-12) && step < max_steps); }
};

// At monitor steps: *stop once the kinetic energy is below -stop_kinetic_fraction of its initial
// value; an error naming the cause once the energy has grown past -mpm_energy_growth_limit.
PetscErrorCode CheckRunStops(Simulation &sim, PetscBool *stop);

} // namespace burst
