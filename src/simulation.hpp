// The state of one burst run: the MPI context, run control, output, the stages, and the solvers it
// owns (MPM, the gas, their coupling) with the scenes' own parts. Each phase of the time step
// (src/step.cxx) is a function of the solvers it uses.
#pragma once
#include "petsc_compat.hpp"
#include "mpm/mpm.hpp"
#include "io/output.hpp"
#include "ice/ice_fwd.hpp"
#include "coupling/coupling_fwd.hpp"
#include "run_control.hpp"
#include "phases.hpp"
#include <memory>
#include <ostream>
#include <string>

namespace burst {

// The gas solver (src/ice/): its own state, null when the scene has no gas materials.
struct IceSolver;
// The coupling of gas and particles (src/coupling/), null unless the scene has both.
struct Coupling;

// The analytic solutions used for verification (bar mode, manufactured solutions; src/scenes/).
class AnalyticSolution;

// The Taylor impact scene (src/scenes/taylor.cxx), null unless -taylor.
struct TaylorScene;

// Simulation owns the optional components one way, a std::unique_ptr; those only declared here
// are deleted by their own files (so this header needs no more than their names).
struct TaylorSceneDeleter {
  void operator()(TaylorScene *taylor) const; // src/scenes/taylor.cxx
};

struct Simulation {
  MPI_Comm    comm = PETSC_COMM_WORLD;
  PetscMPIInt rank = 0, size = 1;
  PetscBool   help = PETSC_FALSE; // -help: read and list every option, then stop

  RunControl run;    // the scene's name, final time, step cap and stops
  Phases     phases; // heat-up, heat only, mechanics (src/phases.cxx); mechanics alone unless -phases
  Output     output; // options, file series and monitor (src/io/)

  // The solvers and the scenes' parts
  MpmSolver                                        mpm;      // the particles and the grid's nodes (its swarm null without solids)
  std::unique_ptr<IceSolver, IceSolverDeleter>     ice;      // null without gas materials
  std::unique_ptr<Coupling, CouplingDeleter>       coupling; // null unless solids and gases
  std::unique_ptr<AnalyticSolution>                analytic; // null unless -analytic
  std::unique_ptr<TaylorScene, TaylorSceneDeleter> taylor;   // null unless -taylor

  bool HasParticles() const { return mpm.HasParticles(); }

  // The clock (the solvers' copies are set from it at every step)
  PetscInt       step = 0;
  PetscReal      time = 0, dt = 0;
  PetscBool      restarted  = PETSC_FALSE; // state loaded from a checkpoint (-restart; src/io/checkpoint.cxx)
  PetscLogDouble wall_start = 0, wall_stepping = 0;

  // Stages for -log_view
  PetscLogStage stage_setup, stage_step, stage_output;
};

// Phases and components of a run (one file each in src/).
PetscErrorCode ReadRunOptions(Simulation &sim);
PetscErrorCode CreateAnalyticSolution(Simulation &sim);
PetscErrorCode ApplyAnalyticInitialCondition(Simulation &sim);

// The Taylor impact scene (src/scenes/taylor.cxx): -taylor_* options become grid, material and geometry
// options (before anything reads them); at the end Lf, Df, the profile and the PNG data.
PetscErrorCode TaylorSceneOptions(Simulation &sim);
PetscErrorCode TaylorFinish(Simulation &sim);
PetscErrorCode TaylorSummary(const Simulation &sim, std::ostream &out);
PetscErrorCode RunPointDriver(Simulation &sim);

// Output and diagnostics (src/io/)
PetscErrorCode OutputSetUp(Simulation &sim);
// From here on a failed write names the partial files it removes and a full disk (src/io/output.cxx).
PetscErrorCode OutputPushWriteErrorHandler(const Simulation &sim);
PetscErrorCode WriteOutput(Simulation &sim);
PetscErrorCode WriteGasOutput(Simulation &sim); // gas cells (gas_NNNNNN.h5, gas.xmf)
PetscErrorCode MonitorSetUp(Simulation &sim);
PetscErrorCode Monitor(Simulation &sim, PetscBool force);
PetscErrorCode WriteSummary(Simulation &sim);
struct EnergyReport {
  PetscReal kinetic, internal, external_work, removed, total, balance_error;
  PetscReal failure_energy;                   // elastic energy released by failure responses (part of internal)
  PetscReal plastic_work, heat, viscous_work; // parts of internal, J
  PetscReal stored_elastic;                   // stored elastic energy (models that report it; else the whole internal energy), J
  PetscReal unaccounted;                      // internal - stored elastic - plastic work - viscous work - failure energy, J
  PetscReal momentum[3];
  PetscReal mass;
};
PetscErrorCode ComputeEnergies(Simulation &sim, EnergyReport &r);

// Atomic file writes: write to a temporary name, then rename (rank 0).
PetscErrorCode AtomicRename(MPI_Comm comm, const std::string &tmp, const std::string &final_name);

} // namespace burst
