// Checkpoint and restart (issue 11; petsc.md 4.7: DMSwarm has no DMLoad in 3.18, so every field
// goes out as a Vec and comes back as one).
//
// output_dir/checkpoint_<step>.h5 holds
//   /particles/<field>   every swarm field registered through RegisterSwarmField (the models' state
//                        included) and the particle id, [N] or [N][bs], integers as reals (exact
//                        below 2^53), in rank order;
//   /gas/state           the gas cell DMDA vector (natural ordering), when the scene has gas;
//   /run/scalars         time, step, dt, ids, energy accumulators and what the monitor, the fragment
//                        search and the gas solver remember between steps;
//   /run/rank_values     per-rank accumulators and particle counts, so that a restart on the same
//                        number of ranks gives every rank its own particles in their own order and its
//                        own partial sums: the continuation is then bit-identical; on another number
//                        of ranks the particles are split evenly and migrated, and the partial sums
//                        go to rank 0 (round-off);
//   /run/output_records, /run/gas_records  the output series so far (particles.xmf, gas.xmf);
// and attributes on / naming the scene (scene, dim, cells, materials, gas materials, particles) that
// a restart checks. The "complete" attribute is written last, and the file is written under a
// temporary name and renamed: a run killed while writing leaves the previous checkpoint intact.
//
// A random state is not needed: the only random draw (initial porosity) is keyed by particle id.
#include "checkpoint.hpp"
#include "../ice/ice.hpp"
#include "../coupling/coupling_impl.hpp"
#include "../mpm/swarm_access.hpp"
#include "../util.hpp"
#include <petscviewerhdf5.h>
#include <hdf5.h>
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

namespace burst {

namespace {
struct CheckpointOptions {
  PetscInt       interval      = 0;   // steps
  PetscReal      wall_interval = 0;   // s
  PetscInt       keep          = 2;
  PetscReal      max_wall_time = 0;   // s, 0 = none
  PetscReal      debug_delay   = 0;   // s between writing the temporary file and renaming it (tests)
  std::string    restart;
  PetscLogDouble start = 0, last_write = 0, last_step_end = 0, write_seconds = 0;
  PetscLogEvent  ev_write = 0, ev_read = 0;
} opts;

volatile std::sig_atomic_t stop_signal = 0;
void OnStopSignal(int signum) { stop_signal = signum; }

// Scalars of /run/scalars, in this order.
enum Scalar : int {
  kTime, kDt, kStep, kNextPid, kParticleSteps, kTotalParticles, kInitialEnergy, kMaxErrorDisplacement, kLastErrorDisplacement, kEnergyScale, kTrackPid, kWallStepping,
  kFragments, // 6 values
  kIceTime = kFragments + 6, kIceStep, kIceDt, kIceKspTotal, kIcePressureSolves, kIceKsp, kIceOuter,
  kIceInitial, // mass, momentum (3), internal, kinetic
  kBurntParticles = kIceInitial + 6,
  kIcePeakPressure, kIcePeakPressureTime, kInitialKinetic,
  kBudgetInitial,                   // the budgets' initial sums: mass, momentum (3), energy
  kBudgetScale = kBudgetInitial + 5, // their largest terms: mass, momentum, energy
  kNumScalars = kBudgetScale + 3
};
// Per-rank values of /run/rank_values, in this order.
enum RankValue : int {
  kExternalWork, kRemovedEnergy, kViscousWork, kRemovedMass, kRemovedParticles, kBurntMass, kEnergyFallbacks, kLocalParticles,
  kBoundaryBudget,                      // the gas's IceBoundaryBudget: mass, momentum (3), energy, work, impulse (3)
  kRemovedMomentum = kBoundaryBudget + 9, // 3
  kBcImpulse = kRemovedMomentum + 3,      // 3
  kDragEnergyChange = kBcImpulse + 3,     // the gas's energy diagnostics, IceSolver::EnergyDiagnostics order
  kCouplingCounters = kDragEnergyChange + IceSolver::kEnergyDiagnostics, // the coupling's budget counters
  kNumRankValues = kCouplingCounters + kNumCouplingCounters
};

std::string CheckpointName(const Simulation &sim, PetscInt step)
{
  char name[64];
  std::snprintf(name, sizeof(name), "/checkpoint_%06d.h5", (int)step);
  return sim.output_dir + name;
}

std::string Join(const std::vector<std::string> &names)
{
  std::string s;
  for (const auto &n : names) s += (s.empty() ? "" : ",") + n;
  return s;
}

std::string SolidNames(const Simulation &sim)
{
  std::vector<std::string> names;
  for (const auto &m : sim.materials) names.push_back(m->Name());
  return Join(names);
}

std::string GasNames(const Simulation &sim)
{
  std::vector<std::string> names;
  if (sim.ice)
    for (const auto &m : sim.ice->materials) names.push_back(m.name);
  return Join(names);
}

// Fields of the checkpoint: every registered swarm field that exists in this swarm, plus the id.
std::vector<std::string> CheckpointFields(const Simulation &sim)
{
  std::vector<std::string>  out;
  std::vector<std::string> *names = nullptr;
  if (SwarmFieldNames(sim.swarm, &names) == PETSC_SUCCESS)
    for (const std::string &n : *names)
      if (std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
  out.push_back(DMSwarmField_pid);
  return out;
}

// A vector held entirely by rank 0 (n entries there, none elsewhere), for the small run data.
PetscErrorCode CreateRootVec(const Simulation &sim, PetscInt n, const char name[], Vec *v)
{
  PetscFunctionBeginUser;
  PetscCall(VecCreate(sim.comm, v));
  PetscCall(VecSetSizes(*v, sim.rank ? 0 : n, n));
  PetscCall(VecSetType(*v, VECSTANDARD));
  PetscCall(PetscObjectSetName((PetscObject)*v, name));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Writes rank 0's values (the other ranks' are ignored); nothing when rank 0 has none.
PetscErrorCode WriteRootValues(const Simulation &sim, PetscViewer viewer, const char name[], const std::vector<PetscReal> &values, PetscInt *count = nullptr)
{
  Vec          v;
  PetscScalar *a;
  PetscInt     n = (PetscInt)values.size();
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Bcast(&n, 1, MPIU_INT, 0, sim.comm)); // only rank 0 holds the records
  if (count) *count = n;
  if (!n) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(CreateRootVec(sim, n, name, &v));
  PetscCall(VecGetArray(v, &a));
  if (!sim.rank)
    for (size_t i = 0; i < values.size(); ++i) a[i] = values[i];
  PetscCall(VecRestoreArray(v, &a));
  PetscCall(VecView(v, viewer));
  PetscCall(VecDestroy(&v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Reads a vector written by WriteRootValues and gives its n values to every rank.
PetscErrorCode ReadRootValues(const Simulation &sim, PetscViewer viewer, const std::string &file, const char name[], PetscInt n, std::vector<PetscReal> &values)
{
  Vec                v;
  const PetscScalar *a;
  PetscBool          has;
  PetscFunctionBeginUser;
  values.assign(n, 0);
  if (!n) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscViewerHDF5HasDataset(viewer, (std::string("/run/") + name).c_str(), &has));
  PetscCheck(has, sim.comm, PETSC_ERR_FILE_UNEXPECTED, "Checkpoint %s lacks /run/%s (truncated or not a burst checkpoint)", file.c_str(), name);
  PetscCall(CreateRootVec(sim, n, name, &v));
  PetscCall(VecLoad(v, viewer));
  PetscCall(VecGetArrayRead(v, &a));
  if (!sim.rank)
    for (PetscInt i = 0; i < n; ++i) values[i] = a[i];
  PetscCall(VecRestoreArrayRead(v, &a));
  PetscCall(VecDestroy(&v));
  PetscCallMPI(MPI_Bcast(values.data(), (int)n, MPIU_REAL, 0, sim.comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode WriteParticles(Simulation &sim, PetscViewer viewer)
{
  PetscInt n;
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(sim.swarm, &n));
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/particles"));
  for (const std::string &name : CheckpointFields(sim)) {
    PetscInt      bs;
    PetscDataType type;
    void         *data;
    Vec           v;
    PetscScalar  *a;
    PetscCall(DMSwarmGetField(sim.swarm, name.c_str(), &bs, &type, &data));
    PetscCall(VecCreateMPI(sim.comm, n * bs, PETSC_DETERMINE, &v));
    PetscCall(VecSetBlockSize(v, bs));
    PetscCall(PetscObjectSetName((PetscObject)v, name.c_str()));
    PetscCall(VecGetArray(v, &a));
    for (PetscInt i = 0; i < n * bs; ++i) {
      switch (type) {
      case PETSC_REAL: a[i] = ((PetscReal *)data)[i]; break;
      case PETSC_INT: a[i] = (PetscReal)((PetscInt *)data)[i]; break;
      case PETSC_INT64: a[i] = (PetscReal)((PetscInt64 *)data)[i]; break;
      default: SETERRQ(sim.comm, PETSC_ERR_SUP, "Checkpoint: swarm field %s has a type the checkpoint does not handle", name.c_str());
      }
    }
    PetscCall(VecRestoreArray(v, &a));
    PetscCall(DMSwarmRestoreField(sim.swarm, name.c_str(), &bs, &type, &data));
    PetscCall(VecView(v, viewer));
    PetscCall(VecDestroy(&v));
  }
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode WriteGas(Simulation &sim, PetscViewer viewer)
{
  Vec v;
  PetscFunctionBeginUser;
  PetscCall(IceSyncGlobal(*sim.ice)); // the local vector is the gas solver's working copy
  PetscCall(VecDuplicate(sim.ice->state, &v));
  PetscCall(VecCopy(sim.ice->state, v));
  PetscCall(PetscObjectSetName((PetscObject)v, "state"));
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/gas"));
  PetscCall(VecView(v, viewer));
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscCall(VecDestroy(&v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RankValues(Simulation &sim, std::vector<PetscReal> &all)
{
  PetscReal mine[kNumRankValues] = {0};
  PetscInt  n                    = 0;
  PetscFunctionBeginUser;
  if (sim.HasParticles()) PetscCall(DMSwarmGetLocalSize(sim.swarm, &n));
  mine[kExternalWork]      = sim.diag.external_work;
  mine[kRemovedEnergy]     = sim.diag.removed_energy;
  mine[kViscousWork]       = sim.diag.viscous_work;
  mine[kRemovedMass]       = sim.diag.removed_mass;
  mine[kRemovedParticles]  = (PetscReal)sim.diag.removed_particles;
  mine[kBurntMass]         = sim.coupling ? sim.coupling->burnt_mass : 0;
  mine[kEnergyFallbacks]   = sim.ice ? (PetscReal)sim.ice->energy_fallbacks : 0;
  mine[kLocalParticles]    = (PetscReal)n;
  if (sim.ice) {
    const IceBoundaryBudget &f = sim.ice->boundary;
    const PetscReal          values[9] = {f.mass, f.momentum[0], f.momentum[1], f.momentum[2], f.energy, f.work, f.impulse[0], f.impulse[1], f.impulse[2]};
    for (int k = 0; k < 9; ++k) mine[kBoundaryBudget + k] = values[k];
    const auto diagnostics = sim.ice->EnergyDiagnostics();
    for (int k = 0; k < IceSolver::kEnergyDiagnostics; ++k) mine[kDragEnergyChange + k] = *diagnostics[k];
  }
  for (int d = 0; d < 3; ++d) {
    mine[kRemovedMomentum + d] = sim.diag.removed_momentum[d];
    mine[kBcImpulse + d]       = sim.diag.bc_impulse[d];
  }
  if (sim.coupling)
    for (int k = 0; k < kNumCouplingCounters; ++k) mine[kCouplingCounters + k] = sim.coupling->counters[k];
  all.assign(sim.rank ? 0 : (size_t)kNumRankValues * sim.size, 0);
  PetscCallMPI(MPI_Gather(mine, kNumRankValues, MPIU_REAL, all.data(), kNumRankValues, MPIU_REAL, 0, sim.comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::vector<PetscReal> Scalars(const Simulation &sim)
{
  std::vector<PetscReal> s(kNumScalars, 0);
  s[kTime]                  = sim.time;
  s[kDt]                    = sim.dt;
  s[kStep]                  = (PetscReal)sim.step;
  s[kNextPid]               = (PetscReal)sim.next_pid;
  s[kParticleSteps]         = (PetscReal)sim.particle_steps;
  s[kTotalParticles]        = (PetscReal)sim.total_particles;
  s[kInitialEnergy]         = sim.diag.initial_energy;
  s[kMaxErrorDisplacement]  = sim.diag.max_error_displacement;
  s[kLastErrorDisplacement] = sim.diag.last_error_displacement;
  s[kEnergyScale]           = MonitorEnergyScale();
  s[kTrackPid]              = (PetscReal)sim.track_pid;
  s[kWallStepping]          = sim.wall_stepping;
  FragmentsGetState(&s[kFragments]);
  s[kInitialKinetic] = sim.diag.initial_kinetic;
  for (int k = 0; k < 5; ++k) s[kBudgetInitial + k] = sim.diag.budget_initial[k];
  for (int k = 0; k < 3; ++k) s[kBudgetScale + k] = sim.diag.budget_scale[k];
  if (sim.ice) {
    const IceSolver &ice = *sim.ice;
    s[kIceTime]           = ice.time;
    s[kIceStep]           = (PetscReal)ice.step;
    s[kIceDt]             = ice.dt;
    s[kIceKspTotal]       = (PetscReal)ice.ksp_iterations_total;
    s[kIcePressureSolves] = (PetscReal)ice.pressure_solves;
    s[kIceKsp]            = (PetscReal)ice.ksp_iterations;
    s[kIceOuter]          = (PetscReal)ice.outer_iterations;
    s[kIceInitial]        = ice.initial.mass;
    for (int d = 0; d < 3; ++d) s[kIceInitial + 1 + d] = ice.initial.momentum[d];
    s[kIceInitial + 4] = ice.initial.internal_energy;
    s[kIceInitial + 5] = ice.initial.kinetic_energy;
    s[kIcePeakPressure]     = ice.peak_pressure;
    s[kIcePeakPressureTime] = ice.peak_pressure_time;
  }
  if (sim.coupling) s[kBurntParticles] = (PetscReal)sim.coupling->burnt_particles;
  return s;
}

// Removes all but the newest `keep` checkpoints (rank 0).
void PruneCheckpoints(const Simulation &sim)
{
  std::vector<std::pair<long, std::string>> found;
  if (DIR *dir = opendir(sim.output_dir.c_str())) {
    while (dirent *e = readdir(dir)) {
      long step;
      char tail[8];
      if (std::sscanf(e->d_name, "checkpoint_%ld.%7s", &step, tail) == 2 && !std::strcmp(tail, "h5")) found.push_back({step, sim.output_dir + "/" + e->d_name});
    }
    closedir(dir);
  }
  std::sort(found.begin(), found.end());
  for (size_t i = 0; i + opts.keep < found.size(); ++i) std::remove(found[i].second.c_str());
}

// The checkpoint a -restart value names: a file, or the newest checkpoint_*.h5 in a folder.
PetscErrorCode ResolveRestart(const Simulation &sim, std::string &file)
{
  struct stat st;
  PetscFunctionBeginUser;
  file = opts.restart;
  PetscCheck(stat(file.c_str(), &st) == 0, sim.comm, PETSC_ERR_FILE_OPEN, "Option -restart %s: no such file or folder", file.c_str());
  if (S_ISDIR(st.st_mode)) {
    long best = -1;
    if (DIR *dir = opendir(opts.restart.c_str())) {
      while (dirent *e = readdir(dir)) {
        long step;
        char tail[8];
        if (std::sscanf(e->d_name, "checkpoint_%ld.%7s", &step, tail) == 2 && !std::strcmp(tail, "h5") && step > best) {
          best = step;
          file = opts.restart + "/" + e->d_name;
        }
      }
      closedir(dir);
    }
    PetscCheck(best >= 0, sim.comm, PETSC_ERR_FILE_OPEN, "Option -restart %s: the folder holds no checkpoint_<step>.h5 (write them with -checkpoint_interval, -checkpoint_wall_interval or -max_wall_time)", opts.restart.c_str());
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Rank 0 opens the file with HDF5 alone first, so that a truncated or damaged file gives a message
// naming it rather than an HDF5 error trace.
PetscErrorCode CheckReadable(const Simulation &sim, const std::string &file)
{
  PetscInt ok = 1;
  PetscFunctionBeginUser;
  if (!sim.rank) {
    H5E_auto2_t func;
    void       *data;
    H5Eget_auto2(H5E_DEFAULT, &func, &data);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0) ok = 0;
    else {
      ok = H5Aexists_by_name(f, "/", "complete", H5P_DEFAULT) > 0 ? 1 : 2;
      H5Fclose(f);
    }
    H5Eset_auto2(H5E_DEFAULT, func, data);
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPIU_INT, 0, sim.comm));
  PetscCheck(ok != 0, sim.comm, PETSC_ERR_FILE_READ, "Checkpoint %s cannot be read as HDF5 (truncated or damaged); restart from an older checkpoint_<step>.h5", file.c_str());
  PetscCheck(ok != 2, sim.comm, PETSC_ERR_FILE_READ, "Checkpoint %s is incomplete (no 'complete' mark: its writer stopped early); restart from an older checkpoint_<step>.h5", file.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckString(const Simulation &sim, PetscViewer viewer, const std::string &file, const char attr[], const std::string &mine, const char what[])
{
  char *theirs = nullptr;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/", attr, PETSC_STRING, nullptr, &theirs));
  const std::string t = theirs ? theirs : "";
  PetscCall(PetscFree(theirs));
  PetscCheck(t == mine, sim.comm, PETSC_ERR_USER_INPUT, "Checkpoint %s does not match this run: its %s is '%s', this run's is '%s'", file.c_str(), what, t.c_str(), mine.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ReadParticles(Simulation &sim, PetscViewer viewer, const std::string &file, PetscInt64 total, const std::vector<PetscReal> &rank_values, PetscInt saved_ranks)
{
  PetscInt local;
  PetscFunctionBeginUser;
  // Same number of ranks: every rank takes back its own particles, in order (bit-identical);
  // otherwise an even split, then migration to the owners.
  if (saved_ranks == sim.size) local = (PetscInt)rank_values[(size_t)kNumRankValues * sim.rank + kLocalParticles];
  else local = (PetscInt)(total / sim.size + (sim.rank < total % sim.size ? 1 : 0));
  PetscCall(DMSwarmSetLocalSizes(sim.swarm, local, 16));
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/particles"));
  for (const std::string &name : CheckpointFields(sim)) {
    PetscInt           bs;
    PetscDataType      type;
    void              *data;
    Vec                v;
    const PetscScalar *a;
    PetscBool          has;
    PetscCall(PetscViewerHDF5HasDataset(viewer, ("/particles/" + name).c_str(), &has));
    PetscCheck(has, sim.comm, PETSC_ERR_USER_INPUT, "Checkpoint %s has no particle field %s: it was written by a run with other materials or models (this run: -materials %s)", file.c_str(), name.c_str(), SolidNames(sim).c_str());
    PetscCall(DMSwarmGetField(sim.swarm, name.c_str(), &bs, &type, &data));
    PetscCall(VecCreate(sim.comm, &v));
    PetscCall(VecSetBlockSize(v, bs));
    PetscCall(VecSetSizes(v, local * bs, PETSC_DETERMINE));
    PetscCall(VecSetType(v, VECSTANDARD));
    PetscCall(PetscObjectSetName((PetscObject)v, name.c_str()));
    PetscCall(VecLoad(v, viewer));
    PetscCall(VecGetArrayRead(v, &a));
    for (PetscInt i = 0; i < local * bs; ++i) {
      switch (type) {
      case PETSC_REAL: ((PetscReal *)data)[i] = PetscRealPart(a[i]); break;
      case PETSC_INT: ((PetscInt *)data)[i] = (PetscInt)PetscRealPart(a[i]); break;
      case PETSC_INT64: ((PetscInt64 *)data)[i] = (PetscInt64)PetscRealPart(a[i]); break;
      default: break;
      }
    }
    PetscCall(VecRestoreArrayRead(v, &a));
    PetscCall(DMSwarmRestoreField(sim.swarm, name.c_str(), &bs, &type, &data));
    PetscCall(VecDestroy(&v));
  }
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  sim.total_particles = total;
  PetscCall(MigrateParticles(sim)); // owner ranks and cell ids; no particle moves on the same ranks
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ReadGas(Simulation &sim, PetscViewer viewer, const std::string &file)
{
  IceSolver &ice = *sim.ice;
  Vec        v;
  PetscBool  has;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5HasDataset(viewer, "/gas/state", &has));
  PetscCheck(has, sim.comm, PETSC_ERR_USER_INPUT, "Checkpoint %s has no gas state, but this run has gas (-ice_materials %s)", file.c_str(), GasNames(sim).c_str());
  PetscCall(VecDuplicate(ice.state, &v));
  PetscCall(PetscObjectSetName((PetscObject)v, "state"));
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/gas"));
  PetscCall(VecLoad(v, viewer));
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscCall(VecCopy(v, ice.state));
  PetscCall(VecDestroy(&v));
  PetscCall(DMGlobalToLocal(ice.da, ice.state, INSERT_VALUES, ice.local));
  PetscCall(IceUpdateGhosts(ice));
  PetscFunctionReturn(PETSC_SUCCESS);
}
} // namespace

PetscErrorCode CheckpointSetUp(Simulation &sim)
{
  char      buf[PETSC_MAX_PATH_LEN] = "";
  PetscBool set;
  PetscFunctionBeginUser;
  PetscOptionsBegin(sim.comm, "", "Checkpoint, restart and wall-clock limits", "Checkpoint");
  PetscCall(PetscOptionsInt("-checkpoint_interval", "Steps between checkpoints (output_dir/checkpoint_<step>.h5); 0 = none", "", opts.interval, &opts.interval, nullptr));
  PetscCheck(opts.interval >= 0, sim.comm, PETSC_ERR_USER_INPUT, "Option -checkpoint_interval = %" PetscInt_FMT " is out of range: it must be >= 0", opts.interval);
  PetscCall(PetscOptionsReal("-checkpoint_wall_interval", "Wall-clock time between checkpoints (s); 0 = none", "", opts.wall_interval, &opts.wall_interval, nullptr));
  PetscCall(CheckRange(sim.comm, "-checkpoint_wall_interval", opts.wall_interval, 0, PETSC_MAX_REAL, PETSC_FALSE));
  PetscCall(PetscOptionsInt("-checkpoint_keep", "How many of the newest checkpoints to keep, >= 1", "", opts.keep, &opts.keep, nullptr));
  PetscCheck(opts.keep >= 1, sim.comm, PETSC_ERR_USER_INPUT, "Option -checkpoint_keep = %" PetscInt_FMT " is out of range: it must be >= 1", opts.keep);
  PetscCall(PetscOptionsReal("-max_wall_time", "Wall-clock budget of the run (s): before it runs out, write a checkpoint and stop; 0 = none", "", opts.max_wall_time, &opts.max_wall_time, nullptr));
  PetscCall(CheckRange(sim.comm, "-max_wall_time", opts.max_wall_time, 0, PETSC_MAX_REAL, PETSC_FALSE));
  PetscCall(PetscOptionsString("-restart", "Continue from a checkpoint: a checkpoint_<step>.h5 file, or a folder (its newest checkpoint)", "", buf, buf, sizeof(buf), &set));
  PetscCheck(!set || buf[0], sim.comm, PETSC_ERR_USER_INPUT, "Option -restart needs a checkpoint file or a folder");
  opts.restart = buf;
  PetscCall(PetscOptionsReal("-checkpoint_debug_delay", "Testing only: seconds to wait between writing a checkpoint's temporary file and renaming it", "", opts.debug_delay, &opts.debug_delay, nullptr));
  PetscCall(CheckRange(sim.comm, "-checkpoint_debug_delay", opts.debug_delay, 0, 3600, PETSC_FALSE));
  PetscOptionsEnd();
  if (sim.help) PetscFunctionReturn(PETSC_SUCCESS);
  PetscClassId id;
  PetscCall(PetscClassIdRegister("burst checkpoint", &id));
  PetscCall(PetscLogEventRegister("CheckpointWrite", id, &opts.ev_write));
  PetscCall(PetscLogEventRegister("CheckpointRead", id, &opts.ev_read));
  // Batch schedulers send SIGTERM or SIGUSR1 before the end of an allocation: finish the step,
  // write a checkpoint and stop (replaces PETSc's handler, which would abort).
  struct sigaction action;
  std::memset(&action, 0, sizeof(action));
  action.sa_handler = OnStopSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGUSR1, &action, nullptr);
  PetscCall(PetscTime(&opts.start));
  opts.last_write = opts.last_step_end = opts.start;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckpointWrite(Simulation &sim)
{
  PetscViewer    viewer;
  PetscLogDouble t0, t1;
  const std::string path = CheckpointName(sim, sim.step), tmp = path + ".tmp";
  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(PetscLogEventBegin(opts.ev_write, 0, 0, 0, 0));
  PetscCall(PetscViewerHDF5Open(sim.comm, tmp.c_str(), FILE_MODE_WRITE, &viewer));
  if (sim.HasParticles()) PetscCall(WriteParticles(sim, viewer));
  if (sim.ice) PetscCall(WriteGas(sim, viewer));
  std::vector<PetscReal> ranks;
  PetscCall(RankValues(sim, ranks));
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/run"));
  PetscCall(WriteRootValues(sim, viewer, "scalars", Scalars(sim)));
  PetscCall(WriteRootValues(sim, viewer, "rank_values", ranks));
  std::vector<PetscReal> flat;
  for (const auto &r : OutputRecords()) flat.insert(flat.end(), r.begin(), r.end());
  PetscInt nrec;
  PetscCall(WriteRootValues(sim, viewer, "output_records", flat, &nrec));
  nrec /= 3;
  flat.clear();
  for (const auto &r : GasOutputRecords()) flat.insert(flat.end(), r.begin(), r.end());
  PetscInt ngas;
  PetscCall(WriteRootValues(sim, viewer, "gas_records", flat, &ngas));
  ngas /= 2;
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  // what a restart checks
  const std::string solids = SolidNames(sim), gases = GasNames(sim);
  const PetscInt    cells[3] = {sim.grid.cells[0], sim.grid.cells[1], sim.grid.dim == 3 ? sim.grid.cells[2] : 1};
  const PetscInt    counts[2] = {nrec, ngas};
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "scene", PETSC_STRING, sim.scene.c_str()));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "solid_materials", PETSC_STRING, solids.c_str()));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "gas_materials", PETSC_STRING, gases.c_str()));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "dim", PETSC_INT, &sim.grid.dim));
  for (int d = 0; d < 3; ++d) PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", (std::string("cells_") + "xyz"[d]).c_str(), PETSC_INT, &cells[d]));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "ranks", PETSC_INT, &sim.size));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "output_records", PETSC_INT, &counts[0]));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "gas_records", PETSC_INT, &counts[1]));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "complete", PETSC_INT, &sim.step));
  PetscCall(PetscViewerDestroy(&viewer));
  if (opts.debug_delay > 0) {
    PetscCallMPI(MPI_Barrier(sim.comm));
    PetscCall(PetscPrintf(sim.comm, "Checkpoint %s written, renaming in %g s (-checkpoint_debug_delay)\n", tmp.c_str(), (double)opts.debug_delay));
    PetscCall(PetscSleep(opts.debug_delay));
  }
  PetscCall(AtomicRename(sim.comm, tmp, path));
  if (!sim.rank) PruneCheckpoints(sim);
  PetscCall(PetscLogEventEnd(opts.ev_write, 0, 0, 0, 0));
  PetscCall(PetscTime(&t1));
  opts.write_seconds = PetscMax(opts.write_seconds, t1 - t0);
  opts.last_write    = t1;
  PetscCall(PetscInfo(nullptr, "Checkpoint %s written in %g s\n", path.c_str(), (double)(t1 - t0)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckpointRestore(Simulation &sim)
{
  std::string file;
  PetscViewer viewer;
  PetscFunctionBeginUser;
  if (opts.restart.empty()) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogEventBegin(opts.ev_read, 0, 0, 0, 0));
  PetscCall(ResolveRestart(sim, file));
  PetscCall(CheckReadable(sim, file));
  PetscCall(PetscViewerHDF5Open(sim.comm, file.c_str(), FILE_MODE_READ, &viewer));
  // Same scene?
  PetscInt dim = 0, cells[3], saved_ranks = 0, nrec = 0, ngas = 0;
  PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/", "dim", PETSC_INT, nullptr, &dim));
  PetscCheck(dim == sim.grid.dim, sim.comm, PETSC_ERR_USER_INPUT, "Checkpoint %s does not match this run: it is %" PetscInt_FMT "-D, this run is %" PetscInt_FMT "-D (-dim)", file.c_str(), dim, sim.grid.dim);
  for (int d = 0; d < 3; ++d) {
    const PetscInt mine = d < sim.grid.dim ? sim.grid.cells[d] : 1;
    PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/", (std::string("cells_") + "xyz"[d]).c_str(), PETSC_INT, nullptr, &cells[d]));
    PetscCheck(cells[d] == mine, sim.comm, PETSC_ERR_USER_INPUT, "Checkpoint %s does not match this run: %" PetscInt_FMT " cells in direction %d, this run has %" PetscInt_FMT " (-grid_cells)", file.c_str(), cells[d], d, mine);
  }
  PetscCall(CheckString(sim, viewer, file, "scene", sim.scene, "scene (-scene)"));
  PetscCall(CheckString(sim, viewer, file, "solid_materials", SolidNames(sim), "solid material set (-materials)"));
  PetscCall(CheckString(sim, viewer, file, "gas_materials", GasNames(sim), "gas material set (-ice_materials)"));
  PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/", "ranks", PETSC_INT, nullptr, &saved_ranks));
  PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/", "output_records", PETSC_INT, nullptr, &nrec));
  PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/", "gas_records", PETSC_INT, nullptr, &ngas));

  std::vector<PetscReal> s, ranks, rec, gas_rec;
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/run"));
  PetscCall(ReadRootValues(sim, viewer, file, "scalars", kNumScalars, s));
  PetscCall(ReadRootValues(sim, viewer, file, "rank_values", (PetscInt)kNumRankValues * saved_ranks, ranks));
  PetscCall(ReadRootValues(sim, viewer, file, "output_records", 3 * nrec, rec));
  PetscCall(ReadRootValues(sim, viewer, file, "gas_records", 2 * ngas, gas_rec));
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  if (sim.HasParticles()) PetscCall(ReadParticles(sim, viewer, file, (PetscInt64)s[kTotalParticles], ranks, saved_ranks));
  if (sim.ice) PetscCall(ReadGas(sim, viewer, file));
  PetscCall(PetscViewerDestroy(&viewer));

  sim.time                         = s[kTime];
  sim.dt                           = s[kDt];
  sim.step                         = (PetscInt)s[kStep];
  sim.next_pid                     = (PetscInt64)s[kNextPid];
  sim.particle_steps               = (PetscInt64)s[kParticleSteps];
  sim.diag.initial_energy          = s[kInitialEnergy];
  sim.diag.max_error_displacement  = s[kMaxErrorDisplacement];
  sim.diag.last_error_displacement = s[kLastErrorDisplacement];
  sim.track_pid                    = (PetscInt)s[kTrackPid];
  sim.wall_stepping                = s[kWallStepping];
  MonitorSetEnergyScale(s[kEnergyScale]);
  FragmentsSetState(&s[kFragments]);
  sim.diag.initial_kinetic = s[kInitialKinetic];
  for (int k = 0; k < 5; ++k) sim.diag.budget_initial[k] = s[kBudgetInitial + k];
  for (int k = 0; k < 3; ++k) sim.diag.budget_scale[k] = s[kBudgetScale + k];
  if (sim.ice) {
    IceSolver &ice           = *sim.ice;
    ice.time                 = s[kIceTime];
    ice.step                 = (PetscInt)s[kIceStep];
    ice.dt                   = s[kIceDt];
    ice.ksp_iterations_total = (PetscInt64)s[kIceKspTotal];
    ice.pressure_solves      = (PetscInt64)s[kIcePressureSolves];
    ice.ksp_iterations       = (PetscInt)s[kIceKsp];
    ice.outer_iterations     = (PetscInt)s[kIceOuter];
    ice.initial.mass         = s[kIceInitial];
    for (int d = 0; d < 3; ++d) ice.initial.momentum[d] = s[kIceInitial + 1 + d];
    ice.initial.internal_energy = s[kIceInitial + 4];
    ice.initial.kinetic_energy  = s[kIceInitial + 5];
    ice.peak_pressure           = s[kIcePeakPressure];
    ice.peak_pressure_time      = s[kIcePeakPressureTime];
  }
  if (sim.coupling) sim.coupling->burnt_particles = (PetscInt64)s[kBurntParticles];
  // Per-rank partial sums: each rank its own on the same number of ranks, else all on rank 0.
  PetscReal mine[kNumRankValues] = {0};
  for (PetscInt r = 0; r < saved_ranks; ++r)
    if (saved_ranks == sim.size ? r == sim.rank : sim.rank == 0)
      for (int k = 0; k < kNumRankValues; ++k) mine[k] += ranks[(size_t)kNumRankValues * r + k];
  sim.diag.external_work     = mine[kExternalWork];
  sim.diag.removed_energy    = mine[kRemovedEnergy];
  sim.diag.viscous_work      = mine[kViscousWork];
  sim.diag.removed_mass      = mine[kRemovedMass];
  sim.diag.removed_particles = (PetscInt)mine[kRemovedParticles];
  if (sim.coupling) sim.coupling->burnt_mass = mine[kBurntMass];
  if (sim.ice) sim.ice->energy_fallbacks = (PetscInt64)mine[kEnergyFallbacks];
  if (sim.ice) {
    IceBoundaryBudget &f = sim.ice->boundary;
    f.mass               = mine[kBoundaryBudget];
    for (int d = 0; d < 3; ++d) f.momentum[d] = mine[kBoundaryBudget + 1 + d];
    f.energy = mine[kBoundaryBudget + 4];
    f.work   = mine[kBoundaryBudget + 5];
    for (int d = 0; d < 3; ++d) f.impulse[d] = mine[kBoundaryBudget + 6 + d];
    const auto diagnostics = sim.ice->EnergyDiagnostics();
    for (int k = 0; k < IceSolver::kEnergyDiagnostics; ++k) *diagnostics[k] = mine[kDragEnergyChange + k];
  }
  for (int d = 0; d < 3; ++d) {
    sim.diag.removed_momentum[d] = mine[kRemovedMomentum + d];
    sim.diag.bc_impulse[d]       = mine[kBcImpulse + d];
  }
  if (sim.coupling)
    for (int k = 0; k < kNumCouplingCounters; ++k) sim.coupling->counters[k] = mine[kCouplingCounters + k];
  std::vector<std::array<PetscReal, 3>> records(nrec);
  for (PetscInt i = 0; i < nrec; ++i) records[i] = {rec[3 * i], rec[3 * i + 1], rec[3 * i + 2]};
  std::vector<std::array<PetscReal, 2>> gas_records(ngas);
  for (PetscInt i = 0; i < ngas; ++i) gas_records[i] = {gas_rec[2 * i], gas_rec[2 * i + 1]};
  if (!sim.rank) {
    OutputSetRecords(records);
    GasOutputSetRecords(gas_records);
  }
  sim.restarted = PETSC_TRUE;
  PetscCall(PetscLogEventEnd(opts.ev_read, 0, 0, 0, 0));
  PetscCall(PetscPrintf(sim.comm, "Restarted from %s (written on %" PetscInt_FMT " rank(s)): step %" PetscInt_FMT ", t = %g s\n", file.c_str(), saved_ranks, sim.step, (double)sim.time));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static std::string WallMessage()
{
  char text[128];
  std::snprintf(text, sizeof(text), "the wall-clock budget -max_wall_time %g s is nearly spent", (double)opts.max_wall_time);
  return text;
}

PetscErrorCode CheckpointAfterStep(Simulation &sim, PetscBool *stop)
{
  PetscLogDouble now;
  PetscFunctionBeginUser;
  *stop = PETSC_FALSE;
  PetscCall(PetscTime(&now));
  const PetscLogDouble step_seconds = now - opts.last_step_end;
  opts.last_step_end                = now;
  // Any rank's reason counts: [signal, budget nearly spent, wall interval due]
  PetscInt local[3] = {(PetscInt)stop_signal, 0, 0}, global[3];
  // stop while two more steps and a checkpoint still fit in the budget
  if (opts.max_wall_time > 0 && now - opts.start + 2 * step_seconds + 2 * opts.write_seconds + 1.0 > opts.max_wall_time) local[1] = 1;
  if (opts.wall_interval > 0 && now - opts.last_write >= opts.wall_interval) local[2] = 1;
  PetscCallMPI(MPI_Allreduce(local, global, 3, MPIU_INT, MPI_MAX, sim.comm));
  const bool due = (opts.interval > 0 && sim.step % opts.interval == 0) || global[2];
  if (due || global[0] || global[1]) PetscCall(CheckpointWrite(sim));
  if (global[0] || global[1]) {
    *stop = PETSC_TRUE;
    const std::string why = global[0] ? std::string("signal ") + (global[0] == SIGTERM ? "SIGTERM" : global[0] == SIGUSR1 ? "SIGUSR1" : std::to_string(global[0])) + " received" : WallMessage();
    PetscCall(PetscPrintf(sim.comm, "Stopping at step %" PetscInt_FMT ", t = %g s: %s. Wrote %s; continue with -restart %s\n", sim.step, (double)sim.time, why.c_str(), CheckpointName(sim, sim.step).c_str(), sim.output_dir.c_str()));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
