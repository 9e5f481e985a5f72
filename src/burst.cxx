static const char help[] = "burst: material point method (MPM) for metal containers that deform, fail and fragment under\n"
                           "high-rate loading, and multi-material ICE for the gases on the same grid. Configure a run with PETSc options, usually an option file:\n"
                           "  build/burst -options_file options/scenes/colliding_disks.opts\n"
                           "Units are SI throughout (m, kg, s, Pa, K).\n\n";

// Sample runs:
//   build/burst -options_file options/scenes/colliding_disks.opts
//   mpiexec -n 2 build/burst -options_file options/scenes/block3d.opts -log_view
//   build/burst -options_file tests/decks/bar_vibration.opts -mpm_shape_type ugimp
//
// The flow of one run: options -> grid -> materials -> particles -> [step, monitor, output]* ->
// summary. One time step is src/step.cxx.
#include "simulation.hpp"
#include "step.hpp"
#include "mpm/geometry.hpp"
#include "scenes/analytic.hpp"
#include "util.hpp"
#include "options_check.hpp"
#include "options_files.hpp"
#include "io/checkpoint.hpp"
#include "io/run_lock.hpp"
#include "ice/ice.hpp"
#include "coupling/coupling.hpp"
#include "../models/burn/burn.hpp"
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <new>

using namespace burst;

static const char *const ModeNames[] = {"mpm", "point"};

static PetscErrorCode RegisterLogging(Simulation &sim)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogStageRegister("Setup", &sim.stage_setup));
  PetscCall(PetscLogStageRegister("Stepping", &sim.stage_step));
  PetscCall(PetscLogStageRegister("Output", &sim.stage_output));
  PetscClassId id;
  PetscCall(PetscClassIdRegister("burst", &id));
  PetscCall(PetscLogEventRegister("MPM_P2G", id, &sim.mpm.ev_p2g));
  PetscCall(PetscLogEventRegister("MPM_GhostSums", id, &sim.mpm.ev_ghost_sums)); // (inside MPM_P2G and MPM_Remap, several ranks: the sums onto the owners, with the wait for the other ranks)
  PetscCall(PetscLogEventRegister("MPM_GridUpdate", id, &sim.mpm.ev_grid));
  PetscCall(PetscLogEventRegister("MPM_G2P", id, &sim.mpm.ev_g2p));
  PetscCall(PetscLogEventRegister("MPM_XPIC", id, &sim.mpm.ev_xpic));
  PetscCall(PetscLogEventRegister("MPM_Remap", id, &sim.mpm.ev_remap));
  PetscCall(PetscLogEventRegister("MPM_Stress", id, &sim.mpm.ev_stress));
  PetscCall(PetscLogEventRegister("MPM_Migrate", id, &sim.mpm.ev_migrate));
  PetscCall(PetscLogEventRegister("MPM_TimeStep", id, &sim.mpm.ev_dt));
  PetscCall(PetscLogEventRegister("MPM_Monitor", id, &sim.output.ev_monitor));
  PetscCall(PetscLogEventRegister("MPM_Loads", id, &sim.mpm.ev_loads));
  PetscCall(PetscLogEventRegister("MPM_Output", id, &sim.output.ev_output));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode SetUp(Simulation &sim)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogStagePush(sim.stage_setup));
  // 0. A scene built from a few physical options (-taylor) writes the options the steps below read
  PetscCall(TaylorSceneOptions(sim));
  // 1. Run control and the background grid
  PetscCall(ReadRunOptions(sim));
  PetscCall(CheckpointSetUp(sim));
  PetscCall(RunLockSetUp(sim)); // the lock itself is taken when the output folder is set up
  // 2. Materials (they decide the velocity fields of the grid), the grid, load curves and the
  //    geometry objects that seed particles
  PetscCall(CreateMaterials(sim.mpm));
  PetscCall(CreateGrid(sim.mpm));
  PetscCall(AxisymmetricSetUp(sim.mpm));
  PetscCall(FragmentsSetUp(sim.mpm));
  PetscCall(ReadLoadCurves(sim.mpm));
  PetscCall(ReadGeometries(sim.mpm));
  PetscCall(HeatConductionSetUp(sim.mpm));
  PetscCall(PhasesSetUp(sim)); // before the swarm: the heat-up's measurement has fields of its own
  PetscCall(CreateAnalyticSolution(sim));
  sim.mpm.surface_heat_fields = sim.phases.Enabled() ? PETSC_TRUE : PETSC_FALSE;
  if (sim.analytic && sim.analytic->HasBodyForce()) {
    const AnalyticSolution *analytic = sim.analytic.get();
    sim.mpm.body_force               = [analytic](const PetscReal X[], PetscReal t, PetscReal b[]) { analytic->BodyForce(X, t, b); };
  }
  // a last picture of the particles when a check finds them invalid, named after the failed step
  sim.mpm.write_snapshot = [&sim](PetscInt step) -> PetscErrorCode {
    const PetscInt saved = sim.step;
    PetscFunctionBeginUser;
    sim.step = step;
    PetscCall(WriteOutput(sim));
    sim.step = saved;
    PetscCall(PetscPrintf(sim.comm, "Wrote the particles as they are to %s/particles_%06d.h5 (particles.xmf)\n", sim.output.dir.c_str(), (int)step));
    PetscFunctionReturn(PETSC_SUCCESS);
  };
  PetscCheck(sim.help || !sim.mpm.convert_failed || SwarmHasModelField(sim.mpm, state_field::failed), sim.comm, PETSC_ERR_USER_INPUT,
             "Option -mpm_convert_failed needs a material that tags failed particles (model elastic_plastic with -<name>_failure_criteria)");
  // 3. The gas's view of the solids (the coupling's equations of state); the swarm registers the
  //    ambient pressure that the coupling asks for
  const Grid &g   = sim.mpm.grid;
  const bool  gas = IceMaterialsRequested(sim.comm);
  IceGridSpec spec{g.dim, {g.cells[0], g.cells[1], g.cells[2]}, {g.lower[0], g.lower[1], g.lower[2]}, {g.h[0], g.h[1], g.h[2]}, {sim.mpm.gravity[0], sim.mpm.gravity[1], sim.mpm.gravity[2]}, g.da_nodes, {}, sim.mpm.axisymmetric == PETSC_TRUE};
  if (!sim.mpm.materials.empty() && gas) {
    Coupling *coupling = nullptr;
    PetscCall(CouplingSolidMaterials(sim.mpm, spec.solids, &coupling));
    sim.coupling.reset(coupling);
  }
  // the gas grid copies the node ranges when it is created, after the start-up balance
  PetscCheck(!gas || !g.balance || g.balance_interval == 0, sim.comm, PETSC_ERR_SUP,
             "Option -grid_balance_interval = %" PetscInt_FMT " is not available with gases (-ice_materials): the gas grid is balanced at start-up only; use -grid_balance_interval 0", g.balance_interval);
  sim.mpm.grid.balance_with_gas = gas;
  PetscCheck(sim.help || !sim.mpm.materials.empty() || gas, sim.comm, PETSC_ERR_USER_INPUT, "No materials: give -materials name1,... (solids, each with -<name>_model) and/or -ice_materials name1,... (gases, each with -<name>_eos_type)");
  // 4. Particles, when the scene has solids (-grid_balance sets the node ranges from their work here)
  if (sim.help) PetscCall(SwarmSetFromOptions(sim.mpm));
  if (!sim.help && !sim.mpm.materials.empty()) {
    PetscCall(CreateSwarm(sim.mpm));
    PetscCall(SeedParticles(sim.mpm));
    PetscCall(ApplyAnalyticInitialCondition(sim));
    PetscCall(MigrateParticles(sim.mpm));
    PetscCall(ComputeInitialWaveSpeed(sim.mpm));
    PetscCall(CheckParticleState(sim.mpm, "seeding"));
  }
  // 5. The gas, on cells of the same grid and the same ranks' ranges (null without -ice_materials)
  {
    spec.nodes     = g.da_nodes; // (re-created by a start-up balance)
    IceSolver *ice = nullptr;
    PetscCall(IceCreate(sim.comm, spec, sim.help, &ice));
    sim.ice.reset(ice);
    sim.mpm.grid.ranges_copied = sim.ice != nullptr;
    if (sim.help && sim.coupling) PetscCall(CouplingBurnHelp(*sim.coupling));
    if (!sim.ice) sim.coupling.reset();
    if (sim.ice) PetscCall(IceApplyPerturbation(*sim.ice));
  }
  if (sim.help) {
    PetscCall(PetscLogStagePop());
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  // 6. Gas and particles meet (src/coupling/)
  if (sim.coupling) PetscCall(CouplingSetUp(*sim.coupling, *sim.ice));
  PetscCall(OutputSetUp(sim));
  PetscCall(CheckpointRestore(sim)); // -restart: the checkpoint's particles, gas and accumulators replace the seeded ones
  SetMpmClock(sim);
  PetscCall(PhasesCheck(sim)); // the phase the run starts in (a checkpoint's, or the first of -phases)
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode View(Simulation &sim)
{
  PetscViewer viewer = PETSC_VIEWER_STDOUT_(sim.comm);
  const Grid &g      = sim.mpm.grid;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "burst: scene %s, %" PetscInt_FMT "-D, %d rank(s)\n", sim.run.scene.c_str(), g.dim, sim.size));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  grid %" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT " cells of %g x %g x %g m, %d x %d x %d ranks\n", g.cells[0], g.cells[1], g.dim == 3 ? g.cells[2] : 1, (double)g.h[0], (double)g.h[1],
                                   g.dim == 3 ? (double)g.h[2] : 0.0, g.procs[0], g.procs[1], g.procs[2]));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  shape %s, scheme %s, FLIP fraction %g, F update %s, cfl %g, final time %g s\n", ShapeTypeNames[(int)sim.mpm.shape], StepSchemeNames[(int)sim.mpm.scheme], (double)sim.mpm.flip_fraction,
                                   FUpdateNames[(int)sim.mpm.f_update], (double)sim.mpm.cfl, (double)sim.run.final_time));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  %lld particles\n", (long long)sim.mpm.total_particles));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  run %s%s\n", CheckpointRunId().c_str(), sim.restarted ? " (continued from its checkpoint)" : ""));
  for (auto &m : sim.mpm.materials) PetscCall(m->View(viewer));
  if (sim.ice) PetscCall(IceView(*sim.ice, viewer));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Particles and gas cells (HDF5/XDMF) and, for a gas run along x (one cell in the other directions), the gas
// profile: profile_<step>.csv at every output and profile.csv at the end.
static PetscErrorCode WriteAllOutput(Simulation &sim, bool last)
{
  PetscFunctionBeginUser;
  if (sim.HasParticles()) PetscCall(WriteOutput(sim));
  if (sim.ice) PetscCall(WriteGasOutput(sim));
  if (sim.ice && sim.mpm.grid.cells[1] == 1 && (sim.mpm.grid.dim == 2 || sim.mpm.grid.cells[2] == 1)) {
    char name[64];
    PetscCall(PetscSNPrintf(name, sizeof(name), "/profile_%06" PetscInt_FMT ".csv", sim.step));
    PetscCall(IceWriteProfile(*sim.ice, sim.output.dir + name, sim.time, sim.step));
    if (last) PetscCall(IceWriteProfile(*sim.ice, sim.output.dir + "/profile.csv", sim.time, sim.step));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Run(Simulation &sim)
{
  PetscLogDouble t0, t1;
  PetscFunctionBeginUser;
  PetscCall(MonitorSetUp(sim));
  if (sim.HasParticles() && sim.mpm.fragments.options.enabled && sim.mpm.fragments.initial_mass < 0) { // a restart reads it from its checkpoint
    PetscCall(FragmentsRecordInitialMass(sim.mpm));
    if (sim.restarted) // a checkpoint written with -fragments off
      PetscCall(PetscPrintf(sim.comm, "Note: the checkpoint holds no initial mass for -fragments_min_mass_fraction; taking the mass at t = %g s, %g kg\n", (double)sim.mpm.time, (double)sim.mpm.fragments.initial_mass));
  }
  if (!sim.restarted) { // a restart continues monitor.csv and the output series
    PetscCall(Monitor(sim, PETSC_TRUE));
    PetscCall(PetscLogStagePush(sim.stage_output));
    PetscCall(WriteAllOutput(sim, false));
    PetscCall(PetscLogStagePop());
  }
  PetscCall(PetscTime(&sim.wall_start));
  for (bool done = false; !done && !sim.run.Reached(sim.time, sim.step);) {
    PetscCall(PetscTime(&t0));
    PetscCall(PetscLogStagePush(sim.stage_step));
    PetscCall(TakeStep(sim));
    PetscCall(PetscLogStagePop());
    PetscCall(PetscTime(&t1));
    sim.wall_stepping += t1 - t0;
    PetscBool stop = PETSC_FALSE, phases_done = PETSC_FALSE;
    PetscCall(PhasesAfterStep(sim, &phases_done)); // a switch prints, checkpoints and changes the next step
    PetscCall(CheckRunStops(sim, &stop));
    stop            = (PetscBool)(stop || phases_done);
    const bool last = stop || sim.run.Reached(sim.time, sim.step);
    PetscCall(Monitor(sim, last ? PETSC_TRUE : PETSC_FALSE));
    if (sim.HasParticles()) PetscCall(FragmentsMonitor(sim.mpm));
    if (last || sim.phases.switched || sim.output.IntervalDue(sim.step)) { // (and the state a phase ended with)
      PetscCall(PetscLogStagePush(sim.stage_output));
      if (sim.HasParticles()) PetscCall(FindFragments(sim.mpm, last ? (sim.output.dir + "/fragments.csv").c_str() : nullptr));
      PetscCall(WriteAllOutput(sim, last));
      PetscCall(PetscLogStagePop());
    }
    PetscBool halt; // a checkpoint when due; stop on SIGTERM/SIGUSR1 or near -max_wall_time
    PetscCall(CheckpointAfterStep(sim, &halt));
    done = last || halt;
  }
  if (sim.taylor) PetscCall(TaylorFinish(sim));
  PetscCall(WriteSummary(sim));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Before PetscInitialize: an -options_file chain that PETSc's reader would crash on (a cycle) or read
// wrongly (a NUL byte, a dangling -options_file) stops here with the file, line and chain named.
// MPI is not up yet: the message comes from the first process of the job only (as PETSc's would).
static int RefuseOptionFiles(int argc, char **argv)
{
  const std::string error = CheckOptionFiles(argc, argv);
  if (error.empty()) return 0;
  const char *rank = nullptr;
  for (const char *v : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"})
    if (!rank) rank = std::getenv(v);
  if (!rank || !std::strcmp(rank, "0"))
    std::fprintf(stderr,
                 "[0]PETSC ERROR: --------------------- Error Message --------------------------------------------------------------\n"
                 "[0]PETSC ERROR: %s\n",
                 error.c_str());
  return PETSC_ERR_USER_INPUT;
}

// One run, between PetscInitialize and PetscFinalize.
static const char *main_phase = "set-up"; // what main's exception handler names

static PetscErrorCode Main(Simulation &sim)
{
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(sim.comm, &sim.rank));
  PetscCallMPI(MPI_Comm_size(sim.comm, &sim.size));
  PetscCall(PetscOptionsHasHelp(nullptr, &sim.help));
  sim.mpm.comm = sim.comm;
  sim.mpm.rank = sim.rank;
  sim.mpm.size = sim.size;
  sim.mpm.help = sim.help;
  PetscCall(OptionsCheckBegin(sim.comm)); // records what set-up reads, for the unused-option check
  int mode = 0;
  PetscOptionsBegin(sim.comm, "", "burst", "Mode");
  PetscCall(OptionsChoice(PetscOptionsObject, "-mode", "What to run: mpm (a scene) or point (one material point through a prescribed path)", ModeNames, 2, &mode, nullptr));
  PetscOptionsEnd();
  PetscCall(RegisterLogging(sim));
  if (mode == 1) {
    main_phase = "the point driver";
    PetscCall(RunPointDriver(sim));
  } else {
    PetscCall(SetUp(sim));
    if (!sim.help) {
      PetscCall(OptionsCheckEnd(sim.comm, RunFeatures(sim, false))); // before the first step: a misspelled option must not cost a run
      PetscCall(View(sim));
      PetscCall(OutputPushWriteErrorHandler(sim));
      main_phase = "the run";
      PetscCall(Run(sim));
      RunLockRelease(); // the run is complete: the folder is free
    }
    main_phase = "clean-up";
    sim.coupling.reset(); // before the gas it couples
    sim.ice.reset();
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  if (int rc = RefuseOptionFiles(argc, argv)) return rc;
  PetscCall(PetscInitialize(&argc, &argv, nullptr, help));
  try { // an exception our code lets through is said, with the phase, instead of std::terminate
    Simulation           sim;
    const PetscErrorCode ierr = Main(sim);
    if (ierr) RunLockRelease(); // an error reaching main aborts (no exit handlers): free the output folder first
    PetscCall(ierr);
  } catch (const std::bad_alloc &) {
    PetscMPIInt rank = 0;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    RunLockRelease();
    std::fprintf(stderr, "burst: out of memory on rank %d during %s (std::bad_alloc); the set-up's estimate did not foresee it: give fewer particles or cells, more ranks, or a smaller -max_memory so that the set-up refuses such a run\n", (int)rank,
                 main_phase);
    MPI_Abort(PETSC_COMM_WORLD, PETSC_ERR_MEM);
  } catch (const std::exception &e) {
    PetscMPIInt rank = 0;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    RunLockRelease();
    std::fprintf(stderr, "burst: unexpected exception on rank %d during %s: %s\n", (int)rank, main_phase, e.what());
    MPI_Abort(PETSC_COMM_WORLD, PETSC_ERR_LIB);
  }
  PetscCall(MaterialRegistryDestroy());
  PetscCall(GasEOSRegistryDestroy());
  PetscCall(BurnModelRegistryDestroy());
  PetscCall(PetscFinalize());
  return 0;
}
