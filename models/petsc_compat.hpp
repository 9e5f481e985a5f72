// Shims so the code reads like current PETSc while building against Debian's 3.18.
#pragma once
#include <petscsys.h>
#include <petscversion.h>

#if PETSC_VERSION_LT(3, 19, 0)
  #define PETSC_SUCCESS 0
#endif
