// Small helpers for options handling shared by the components and the models.
#pragma once
#include "petsc_compat.hpp"
#include <petscoptions.h>
#include <string>

namespace burst {

// Comma-separated names in a PetscFunctionList, for error messages.
PetscErrorCode FunctionListNames(PetscFunctionList list, std::string &names);

// Reads option `opt` as one name out of `choices`; an unknown name stops with a message naming the
// option and every valid choice. `value` holds the default on entry.
PetscErrorCode OptionsChoice(PetscOptionItems *PetscOptionsObject, const char opt[], const char help[], const char *const choices[], int n, int *value, PetscBool *set);

// Reads a real array of exactly `n` entries (if given); any other count is an error.
PetscErrorCode OptionsRealVector(PetscOptionItems *PetscOptionsObject, const char opt[], const char help[], PetscReal values[], PetscInt n, PetscBool *set);

// Checks lo <= value <= hi (or lo < value with open = true) and names the option on failure.
PetscErrorCode CheckRange(MPI_Comm comm, const char opt[], PetscReal value, PetscReal lo, PetscReal hi, PetscBool open_lower, PetscBool open_upper = PETSC_FALSE);

std::string Prefixed(const char prefix[], const char opt[]);

} // namespace burst
