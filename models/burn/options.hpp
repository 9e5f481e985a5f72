// Options helpers shared by the burn models (models/burn/*.cxx); not part of the interface.
#pragma once
#include "burn.hpp"
#include "../../src/util.hpp"

namespace burst {

// Reads the real option `opt` (e.g. "-burn_simple_A", under the reactant's prefix of the
// PetscOptionsBegin block) with `help` (which states the unit and valid range) and checks
// lo < value (open_lower) or lo <= value, value <= hi; an out-of-range value stops with a message
// naming the full option (-pbx_burn_simple_A).
PetscErrorCode BurnOptionsReal(PetscOptionItems *PetscOptionsObject, const char opt[], const char help[], PetscReal *value, PetscReal lo, PetscReal hi, PetscBool open_lower);

} // namespace burst
