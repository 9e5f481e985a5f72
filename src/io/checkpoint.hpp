// Checkpoint and restart, wall-clock limits and stop signals (issue 11; petsc.md 4.7).
#pragma once
#include "../simulation.hpp"

namespace burst {

// Reads -checkpoint_interval, -checkpoint_wall_interval, -checkpoint_keep, -restart, -max_wall_time
// and installs the SIGTERM/SIGUSR1 handlers. Call during set-up (before the unused-option check).
PetscErrorCode CheckpointSetUp(Simulation &sim);

// This run's id: 16 hex digits drawn at random at start-up, or the checkpoint's after a restart (a
// run and its restarts are one lineage: -checkpoint_keep prunes only its checkpoints).
std::string CheckpointRunId();

// With -restart: replaces the seeded particles, the gas state and every accumulator by the
// checkpoint's, after checking that it belongs to this scene (dimension, grid, materials). Call at
// the end of set-up. Sets sim.restarted.
PetscErrorCode CheckpointRestore(Simulation &sim);

// After a step (and its output): writes a checkpoint when one is due (step interval, wall interval,
// a stop signal, the wall-clock budget) and sets *stop when the run must end now.
PetscErrorCode CheckpointAfterStep(Simulation &sim, PetscBool *stop);

// Writes output_dir/checkpoint_<step>.h5 (temporary name, then rename) with this run's id, its
// physics options and a checksum of every dataset, and keeps the newest -checkpoint_keep of this
// run's checkpoints (other runs' in the folder are never removed).
PetscErrorCode CheckpointWrite(Simulation &sim);

// Keeps the checkpoint of the current step also as output_dir/name, which pruning (-checkpoint_keep)
// does not touch (a hard link, or a copy); -restart takes it like any checkpoint file.
PetscErrorCode CheckpointKeepAs(Simulation &sim, const std::string &name);

} // namespace burst
