// The output of a run (src/io/): its options, the file series written so far, the monitor's file and
// its events. Simulation owns one; the checkpoint saves the series so that a restart continues them.
#pragma once
#include "petsc_compat.hpp"
#include <cstdio>
#include <string>
#include <vector>

namespace burst {

struct OutputRecord { // one entry of particles.xmf
  PetscInt   step;
  PetscReal  time;
  PetscInt64 particles;
};
struct GasOutputRecord { // one entry of gas.xmf
  PetscInt  step;
  PetscReal time;
};

class CheckpointValues; // src/io/checkpoint_values.hpp

struct Output {
  // options (src/options.cxx)
  std::string dir              = "output"; // -output_dir
  PetscInt    interval         = 0;        // steps between HDF5 outputs (0: first and last only)
  PetscInt    monitor_interval = 10;
  PetscBool   write_grid       = PETSC_TRUE;
  PetscBool   progress         = PETSC_TRUE;
  PetscInt    track_pid        = -1; // particle id to trace in the monitor, -1 = none
  PetscReal   track_point[3]   = {0, 0, 0};
  PetscBool   track_by_point   = PETSC_FALSE; // trace the particle nearest to track_point at the start

  // state (rank 0 holds the series and the monitor file)
  std::vector<OutputRecord>    records;
  std::vector<GasOutputRecord> gas_records;
  FILE                        *monitor_csv   = nullptr;
  PetscReal                    energy_scale  = 0; // the monitor's scale of the energy balance error, J (the largest energy seen)
  PetscLogDouble               last_progress = 0; // wall time of the last progress line

  PetscLogEvent ev_output = 0, ev_monitor = 0;

  bool IntervalDue(PetscInt step) const { return interval > 0 && step % interval == 0; } // an output step of -output_interval
  void Checkpoint(CheckpointValues &values);                                             // its numbers' part of a checkpoint (output.cxx; the series are the checkpoint's own)
};

} // namespace burst
