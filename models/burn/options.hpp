// Options helper shared by the burn models (models/burn/*.cxx); not part of the interface.
#pragma once
#include "burn.hpp"
#include "../pointwise_registry.hpp"

namespace burst {

// -<material>_<opt> as a real with its range checked (pointwise_registry.hpp).
inline PetscErrorCode BurnOptionsReal(PetscOptionItems *PetscOptionsObject, const char opt[], const char help[], PetscReal *value, PetscReal lo, PetscReal hi, PetscBool open_lower, PetscBool open_upper = PETSC_FALSE)
{
  return PointwiseOptionsReal(PetscOptionsObject, opt, help, value, lo, hi, open_lower, open_upper);
}

} // namespace burst
