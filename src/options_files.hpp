// The -options_file chain, checked before PETSc reads it (PETSc 3.18's reader recurses without a
// bound on a file that includes itself, and drops the rest of a line after a NUL byte).
#pragma once
#include <string>

namespace burst {

// Deepest chain of -options_file includes accepted (the command line's file is depth 1).
constexpr int kMaxOptionFileDepth = 16;

// Follows every -options_file of argv, of the PETSC_OPTIONS environment variable and of the petscrc
// files PETSc reads by default, recursively. Returns an empty string when the chain is sound, else
// the reason: a file that includes itself or a file already in its chain (the chain is named), a
// chain deeper than kMaxOptionFileDepth, a NUL byte in a file (file and line), an -options_file
// with no file after it (file and line). Files that cannot be opened are left to PETSc's message.
// Needs no MPI or PETSc: call it before PetscInitialize.
std::string CheckOptionFiles(int argc, char **argv);

} // namespace burst
