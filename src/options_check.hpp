// Options that nothing reads are an error (issue 11): a misspelled option must not cost a run.
#pragma once
#include "petsc_compat.hpp"
#include <petscsys.h>
#include <string>
#include <vector>

namespace burst {

// Starts recording the name of every option queried through PetscOptionsBegin/End from now on
// (the candidates of "did you mean"). Call after PetscInitialize, before any set-up; does nothing
// with -help (help mode reads everything and stops anyway).
PetscErrorCode OptionsCheckBegin(MPI_Comm comm);

// Stops recording and checks: every option given (command line, option files, PETSC_OPTIONS) that
// nothing has read stops the run, naming each with the nearest known names by edit distance;
// -options_allow_unused turns the error into a warning. PETSc's own run-time options that are only
// read at the end (-log_view, -options_view, ...) are not reported. Call after set-up, before the
// first step.
//
// Options of a feature that is off in this run (point-driver options in a scene, heat-conduction
// constants without -mpm_heat_conduction, gas options without gas, ...) are legitimately present in
// shared files: they are listed in `features` and only noted, naming the switch that would read them.
struct OptionsFeature {
  std::string prefix, contains, suffix; // an option matches: starts with prefix, contains, ends with suffix
  std::string needs;                    // the switch that turns the feature on, for the note
  bool        on;
  bool        read_when_off = false; // set-up reads these even when the feature is off: noted when given
};
PetscErrorCode OptionsCheckEnd(MPI_Comm comm, const std::vector<OptionsFeature> &features);

struct Simulation;
// The switched-off features of a scene run (mode mpm) or of the point driver (point_mode).
std::vector<OptionsFeature> RunFeatures(const Simulation &sim, bool point_mode);

} // namespace burst
