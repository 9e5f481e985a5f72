// Options helper shared by the gas EOS models (models/gas_eos/*.cxx); not part of the interface.
#pragma once
#include "gas_eos.hpp"
#include "../pointwise_registry.hpp"

namespace burst {

// -<material>_<opt> as a real with its range checked (pointwise_registry.hpp).
inline PetscErrorCode GasEOSOptionsReal(PetscOptionItems *PetscOptionsObject, const char opt[], const char help[], PetscReal *value, PetscReal lo, PetscReal hi, PetscBool open_lower)
{
  return PointwiseOptionsReal(PetscOptionsObject, opt, help, value, lo, hi, open_lower);
}

} // namespace burst
