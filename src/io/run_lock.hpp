// One run per output folder: output_dir/.burst.lock (src/io/run_lock.cxx).
#pragma once
#include "../simulation.hpp"

namespace burst {

// Reads -output_lock_stale_time (also under -help). Call during set-up.
PetscErrorCode RunLockSetUp(Simulation &sim);

// Rank 0 creates output_dir/.burst.lock exclusively (host, pid, start time inside) and broadcasts the
// outcome. A lock held by a live run stops this one with the holder's host and pid named; a stale
// lock (its pid gone on this host, or another host's lock untouched for -output_lock_stale_time s) is
// taken over with a note. Call before anything is written to the folder.
PetscErrorCode RunLockAcquire(Simulation &sim);

// Refreshes the lock's time stamp (at most once a minute; rank 0), so that another host can tell a
// live holder from a dead one. Cheap: call after every step.
void RunLockTouch();

// Removes the lock if this process holds it. Called at the end of a run and at exit (also after an
// error that returns from main); a killed run leaves a stale lock that the next run takes over.
void RunLockRelease();

} // namespace burst
