// Options helper shared by the gas EOS models (models/gas_eos/*.cxx); not part of the interface.
#pragma once
#include "gas_eos.hpp"
#include "../../src/util.hpp"

namespace burst {

// Reads the real option `opt` (e.g. "-gamma", under the prefix of the PetscOptionsBegin block) with
// `help` (which states the unit and valid range) and checks lo < value (open_lower) or lo <= value,
// value <= hi; an out-of-range value stops with a message naming the full option (-<material>_gamma).
PetscErrorCode GasEOSOptionsReal(PetscOptionItems *PetscOptionsObject, const char opt[], const char help[], PetscReal *value, PetscReal lo, PetscReal hi, PetscBool open_lower);

} // namespace burst
