// Checkpoint and restart (issue 11; petsc.md 4.7: DMSwarm has no DMLoad in 3.18, so every field
// goes out as a Vec and comes back as one).
//
// output_dir/checkpoint_<step>.h5 holds
//   /particles/<field>   every swarm field registered through RegisterSwarmField (the models' state
//                        included) and the particle id, [N] or [N][bs], integers as reals (exact
//                        below 2^53), in rank order;
//   /gas/state           the gas cell DMDA vector (natural ordering), when the scene has gas
//                        (written and read by the gas solver, src/ice/checkpoint.cxx);
//   /<part>/values, /<part>/rank_values  each component's numbers (checkpoint_values.hpp): run
//                        (time, step, ids, each rank's particle count), diagnostics, output,
//                        fragments, gas, coupling; the names as the attributes <part>_values and
//                        <part>_rank_values of /, which a restart checks. Per-rank values keep
//                        every rank's partial sums and particle count, so that a restart on the same
//                        number of ranks gives every rank its own particles in their own order and
//                        its own sums: the continuation is then bit-identical; on another number of
//                        ranks the particles are split evenly and migrated, and the sums go to rank
//                        0 (round-off);
//   /phases/state        the phases' record (src/phases.cxx), with -phases;
//   /output/records, /output/gas_records  the output series so far (particles.xmf, gas.xmf);
// and attributes on / naming the scene (scene, dim, cells, materials, gas materials, particles) that
// a restart checks. The "complete" attribute is written last, and the file is written under a
// temporary name and renamed: a run killed while writing leaves the previous checkpoint intact.
//
// Identity and integrity (attributes on /, format 3; format 2 kept every number in /run):
//   run_id           16 hex digits drawn at random when a run starts fresh; a restart continues its
//                    checkpoint's run id, so a run and its restarts are one lineage;
//   physics_options  the options that define the physics, one "-name value" a line, sorted: every
//                    option in the database except run control, output and diagnostics (see
//                    RunControlOption: -output_*, -checkpoint_*, -monitor_*, -restart*, -log*,
//                    -max_steps, -final_time, -max_wall_time, ...); physics_hash is its FNV-1a 64;
//   checksum         a sum over every dataset entry of splitmix64(splitmix64(FNV(dataset path) +
//                    entry index) ^ bits of the value), mod 2^64: independent of the number of ranks
//                    and of their order (each rank adds its entries at their global index, the gas
//                    in natural ordering), recomputed by rank 0 from the file alone;
//   written_at       seconds since 1970 when written: "newest" means written last.
// Pruning (-checkpoint_keep) counts only the current run id's checkpoints, newest written first, so
// a restart from an older checkpoint prunes the abandoned later ones of its lineage, never the ones
// it writes. Another run's checkpoints found in -output_dir at start-up are moved (renamed) to
// output_dir/other_runs/<run id>/ with a note, so that this run can neither prune nor overwrite them
// (same step numbers), and -restart on the folder sees one run. A restart refuses a
// checkpoint whose checksum fails or whose physics options differ (each named with both values)
// unless -restart_allow_option_change. Checkpoints without these attributes (format 1) are accepted
// with a note: they cannot be verified, and the restart draws a new run id.
//
// A random state is not needed: the only random draw (initial porosity) is keyed by particle id.
#include "checkpoint.hpp"
#include "../ice/ice.hpp"
#include "../coupling/coupling.hpp"
#include "checkpoint_values.hpp"
#include "../mpm/swarm_access.hpp"
#include "util.hpp"
#include "run_lock.hpp"
#include <petscviewerhdf5.h>
#include <hdf5.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cctype>
#include <map>
#include <sstream>
#include <random>
#include <cstdio>
#include <cstring>
#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>
#include <fstream>

namespace burst {

namespace {
struct CheckpointOptions {
  PetscInt                 interval      = 0; // steps
  PetscReal                wall_interval = 0; // s
  PetscInt                 keep          = 2;
  PetscReal                max_wall_time = 0; // s, 0 = none
  PetscReal                debug_delay   = 0; // s between writing the temporary file and renaming it (tests)
  std::string              restart;
  PetscBool                allow_option_change = PETSC_FALSE;
  std::string              run_id;       // 16 hex digits, this run's lineage
  uint64_t                 checksum = 0; // this rank's part of the checkpoint being written
  std::vector<std::string> written;      // names of the checkpoints this process wrote (rank 0)
  PetscLogDouble           start = 0, last_write = 0, last_step_end = 0, write_seconds = 0;
  PetscLogEvent            ev_write = 0, ev_read = 0;
} opts;

volatile std::sig_atomic_t stop_signal = 0;

void OnStopSignal(int signum) { stop_signal = signum; }

// ---- Identity and integrity --------------------------------------------------------------------

inline uint64_t Mix64(uint64_t z)
{
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

uint64_t Fnv64(const std::string &s)
{
  uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : s) h = (h ^ c) * 0x100000001b3ULL;
  return h;
}

std::string Hex(uint64_t v)
{
  char buf[20];
  std::snprintf(buf, sizeof(buf), "%016llx", (unsigned long long)v);
  return buf;
}

// Entries [offset, offset + n) of dataset `path` (no leading slash), as the checksum adds them.
uint64_t DatasetSum(const std::string &path, PetscInt64 offset, const PetscScalar *a, PetscInt64 n)
{
  const uint64_t key = Fnv64(path);
  uint64_t       sum = 0;
  for (PetscInt64 i = 0; i < n; ++i) {
    const double v = (double)PetscRealPart(a[i]);
    uint64_t     bits;
    std::memcpy(&bits, &v, sizeof(bits));
    sum += Mix64(Mix64(key + (uint64_t)(offset + i)) ^ bits);
  }
  return sum;
}

} // namespace

// Adds a Vec's local entries (held in PETSc's ordering = the file's for a plain Vec) to the checksum.
PetscErrorCode CheckpointChecksumVec(Vec v, const std::string &path)
{
  PetscInt           lo, hi;
  const PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecGetOwnershipRange(v, &lo, &hi));
  PetscCall(VecGetArrayRead(v, &a));
  opts.checksum += DatasetSum(path, lo, a, hi - lo);
  PetscCall(VecRestoreArrayRead(v, &a));
  PetscFunctionReturn(PETSC_SUCCESS);
}

namespace {

// Options that steer a run but not its physics: left out of the physics options.
bool RunControlOption(const std::string &name)
{
  // run length and stops, output, checkpoints, monitoring, diagnostics (fragment search, the Grady
  // estimate), the parallel layout (-grid_balance*, the grid DM's own options) and PETSc's own
  // clang-format off (a table laid out by hand)
  static const char *const prefixes[] = {"output_",
                                         "checkpoint_",
                                         "monitor_",
                                         "restart",
                                         "log",
                                         "options_",
                                         "progress",
                                         "help", // burst's run control
                                         "fragments",
                                         "grady", // diagnostics
                                         "grid_balance",
                                         "grid_da_",
                                         "grid_dm_",
                                         "dm_",
                                         "sf_",
                                         "vecscatter", // parallel layout
                                         "info",
                                         "history",
                                         "malloc",
                                         "viewer",
                                         "on_error",
                                         "fp_trap",
                                         "no_signal_handler",
                                         "skip_petscrc",
                                         "mpi_", // PETSc's own
                                         "check_pointer",
                                         "is_view",
                                         "device_",
                                         "root_device",
                                         "default_device",
                                         "debugger",
                                         "start_in_debugger",
                                         "stop_for_debugger",
                                         "display",
                                         "error_output",
                                         "petsc",
                                         "version",
                                         "memory_view",
                                         "objects_dump",
                                         "get_total_flops",
                                         "tmp",
                                         "shared_tmp",
                                         "not_shared_tmp",
                                         "use_gpu",
                                         "mca"};
  static const char *const exact[]    = {"max_steps",       "final_time", "max_wall_time", "max_memory", "stop_kinetic_fraction", "mpm_energy_growth_limit", "scene", "mode", "phases", "phase_mechanics_duration",
                                         "phase_checkpoint"}; // (which phases run, and how long, is run control)
  // clang-format on
  for (const char *p : prefixes)
    if (name.compare(0, std::strlen(p), p) == 0) return true;
  for (const char *e : exact)
    if (name == e) return true;
  return false;
}

// The physics options of this process's database: name (without '-', lower case) -> value.
PetscErrorCode PhysicsOptions(std::map<std::string, std::string> &out)
{
  char *all;
  PetscFunctionBeginUser;
  out.clear();
  PetscCall(PetscOptionsGetAll(nullptr, &all));
  std::istringstream       words(all);
  std::string              name;
  std::vector<std::string> value;

  auto flush = [&]() {
    if (!name.empty() && !RunControlOption(name)) {
      std::string v;
      for (const auto &w : value) v += (v.empty() ? "" : " ") + w;
      out[name] = v;
    }
    value.clear();
  };
  for (std::string w; words >> w;) {
    if (w.size() > 1 && w[0] == '-' && (std::isalpha((unsigned char)w[1]) || w[1] == '_')) {
      flush();
      name = w.substr(1);
      std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return (char)std::tolower(c); });
    } else value.push_back(w);
  }
  flush();
  PetscCall(PetscFree(all));
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::string OptionsText(const std::map<std::string, std::string> &o)
{
  std::string s;
  for (const auto &kv : o) s += "-" + kv.first + (kv.second.empty() ? "" : " " + kv.second) + "\n";
  return s;
}

std::map<std::string, std::string> ParseOptionsText(const std::string &text)
{
  std::map<std::string, std::string> o;

  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.size() < 2 || line[0] != '-') continue;
    const size_t sp                                                         = line.find(' ');
    o[line.substr(1, sp == std::string::npos ? std::string::npos : sp - 1)] = sp == std::string::npos ? "" : line.substr(sp + 1);
  }
  return o;
}

// Two values of one option that mean the same: equal text, equal numbers (each of a comma list), or
// the same truth value.
bool SameValue(std::string a, std::string b)
{
  if (a == b) return true;
  auto lower = [](std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return (char)std::tolower(c); });
    return s;
  };
  a          = lower(a);
  b          = lower(b);
  auto truth = [](const std::string &s) { return s.empty() || s == "true" || s == "yes" || s == "1" || s == "on" ? 1 : s == "false" || s == "no" || s == "0" || s == "off" ? 0 : -1; };
  if (truth(a) >= 0 && truth(a) == truth(b)) return true;
  std::istringstream sa(a), sb(b);
  std::string        ta, tb;
  bool               any = false;
  while (true) {
    const bool ga = (bool)std::getline(sa, ta, ','), gb = (bool)std::getline(sb, tb, ',');
    if (!ga && !gb) return any;
    if (ga != gb) return false;
    char        *ea, *eb;
    const double va = std::strtod(ta.c_str(), &ea), vb = std::strtod(tb.c_str(), &eb);
    if (*ea || *eb || ta.empty() || tb.empty() || !(va == vb)) return false;
    any = true;
  }
}

PetscErrorCode BcastString(MPI_Comm comm, std::string &s)
{
  PetscInt n = (PetscInt)s.size();
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Bcast(&n, 1, MPIU_INT, 0, comm));
  s.resize((size_t)n);
  if (n) PetscCallMPI(MPI_Bcast(&s[0], (int)n, MPI_CHAR, 0, comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// What rank 0 learns about a checkpoint file from HDF5 alone.
struct CheckpointInfo {
  long        step = -1;
  std::string path;
  bool        readable = false, complete = false, identified = false; // identified: has run_id and checksum
  std::string run_id, checksum, physics;
  double      written_at = 0;     // the attribute (seconds since 1970), 0 without it
  bool        mine_now   = false; // written by this process
};

bool ReadStringAttribute(hid_t f, const char name[], std::string &value)
{
  if (H5Aexists_by_name(f, "/", name, H5P_DEFAULT) <= 0) return false;
  const hid_t a = H5Aopen_by_name(f, "/", name, H5P_DEFAULT, H5P_DEFAULT);
  if (a < 0) return false;
  const hid_t t  = H5Aget_type(a);
  bool        ok = false;
  if (H5Tget_class(t) == H5T_STRING) {
    if (H5Tis_variable_str(t) > 0) {
      char *buf = nullptr;
      if (H5Aread(a, t, &buf) >= 0 && buf) {
        value = buf;
        ok    = true;
        H5free_memory(buf);
      }
    } else {
      std::vector<char> buf(H5Tget_size(t) + 1, '\0');
      if (H5Aread(a, t, buf.data()) >= 0) {
        value = std::string(buf.data());
        ok    = true;
      }
    }
  }
  H5Tclose(t);
  H5Aclose(a);
  return ok;
}

bool ReadDoubleAttribute(hid_t f, const char name[], double &value)
{
  if (H5Aexists_by_name(f, "/", name, H5P_DEFAULT) <= 0) return false;
  const hid_t a = H5Aopen_by_name(f, "/", name, H5P_DEFAULT, H5P_DEFAULT);
  if (a < 0) return false;
  const bool ok = H5Aread(a, H5T_NATIVE_DOUBLE, &value) >= 0;
  H5Aclose(a);
  return ok;
}

// HDF5's error stack printing off while rank 0 probes files on its own.
struct QuietHDF5 {
  H5E_auto2_t func;
  void       *data;
  QuietHDF5()
  {
    H5Eget_auto2(H5E_DEFAULT, &func, &data);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHDF5() { H5Eset_auto2(H5E_DEFAULT, func, data); }
};

CheckpointInfo ReadInfo(const std::string &path, long step)
{
  CheckpointInfo info;
  QuietHDF5      quiet;
  info.path     = path;
  info.step     = step;
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return info;
  info.readable     = true;
  info.complete     = H5Aexists_by_name(f, "/", "complete", H5P_DEFAULT) > 0;
  const bool has_id = ReadStringAttribute(f, "run_id", info.run_id), has_sum = ReadStringAttribute(f, "checksum", info.checksum);
  info.identified = has_id && has_sum;
  (void)ReadStringAttribute(f, "physics_options", info.physics);
  (void)ReadDoubleAttribute(f, "written_at", info.written_at);
  H5Fclose(f);
  return info;
}

#if H5_VERSION_GE(1, 12, 0)
using LinkInfo = H5L_info2_t;
#else
using LinkInfo = H5L_info_t;
#endif

struct SumVisit {
  uint64_t    sum = 0;
  std::string error;
};

herr_t SumDataset(hid_t group, const char *name, const LinkInfo *, void *op)
{
  SumVisit   *d  = (SumVisit *)op;
  const hid_t ds = H5Dopen2(group, name, H5P_DEFAULT);
  if (ds < 0) return 0; // a group
  const hid_t space = H5Dget_space(ds);
  const int   rank  = H5Sget_simple_extent_ndims(space);
  hsize_t     dims[H5S_MAX_RANK];
  if (rank < 0 || H5Sget_simple_extent_dims(space, dims, nullptr) < 0) d->error = std::string("dataset ") + name + " has no extent";
  else if (rank == 0 || H5Sget_simple_extent_npoints(space) > 0) {
    // in blocks of whole rows of the first dimension, about 2^20 values each: rank 0 verifies a
    // checkpoint of any size in bounded memory
    hsize_t row = 1;
    for (int k = 1; k < rank; ++k) row *= dims[k];
    const hsize_t       rows  = rank ? dims[0] : 1;
    const hsize_t       block = PetscMax((hsize_t)1, ((hsize_t)1 << 20) / PetscMax(row, (hsize_t)1));
    std::vector<double> buf((size_t)(PetscMin(block, rows) * row));
    for (hsize_t r0 = 0; r0 < rows && d->error.empty(); r0 += block) {
      const hsize_t nr                  = PetscMin(block, rows - r0);
      hsize_t       start[H5S_MAX_RANK] = {0}, count[H5S_MAX_RANK];
      for (int k = 0; k < rank; ++k) count[k] = dims[k];
      if (rank) {
        start[0] = r0;
        count[0] = nr;
      }
      const hid_t mem = H5Screate_simple(PetscMax(rank, 1), rank ? count : &nr, nullptr);
      if (rank) H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr);
      if (H5Dread(ds, H5T_NATIVE_DOUBLE, mem, rank ? space : H5S_ALL, H5P_DEFAULT, buf.data()) < 0) d->error = std::string("dataset ") + name + " cannot be read";
      else d->sum += DatasetSum(name, (PetscInt64)(r0 * row), buf.data(), (PetscInt64)(nr * row));
      H5Sclose(mem);
    }
  }
  H5Sclose(space);
  H5Dclose(ds);
  return d->error.empty() ? 0 : 1;
}

// Rank 0: recomputes the checksum of a file. Empty string: it matches; else what is wrong.
std::string VerifyChecksum(const CheckpointInfo &info)
{
  QuietHDF5   quiet;
  const hid_t f = H5Fopen(info.path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return "it cannot be read as HDF5 (truncated or damaged)";
  SumVisit visit;
  if (H5Lvisit(f, H5_INDEX_NAME, H5_ITER_INC, SumDataset, &visit) < 0 && visit.error.empty()) visit.error = "its datasets cannot be read (truncated or damaged)";
  H5Fclose(f);
  if (!visit.error.empty()) return visit.error;
  if (Hex(visit.sum) != info.checksum) return "it fails its checksum (stored " + info.checksum + ", computed " + Hex(visit.sum) + "): the file was altered or damaged after it was written";
  return "";
}

// Rank 0: the checkpoint_<step>.h5 files of a folder.
std::vector<CheckpointInfo> ScanFolder(const std::string &folder)
{
  std::vector<CheckpointInfo> found;
  if (DIR *dir = opendir(folder.c_str())) {
    while (dirent *e = readdir(dir)) {
      long step;
      char tail[8];
      if (std::sscanf(e->d_name, "checkpoint_%ld.%7s", &step, tail) == 2 && !std::strcmp(tail, "h5")) found.push_back(ReadInfo(folder + "/" + e->d_name, step));
    }
    closedir(dir);
  }
  return found;
}

// Newest written first (ties: the higher step).
// Newest first: what this process wrote (by step), then by the written_at attribute, then by step
// (the order for checkpoints without the attribute). A clock set back between a run and its restart
// cannot make a run prune what it has just written.
void SortNewestFirst(std::vector<CheckpointInfo> &v)
{
  std::sort(v.begin(), v.end(), [](const CheckpointInfo &a, const CheckpointInfo &b) {
    if (a.mine_now != b.mine_now) return a.mine_now;
    if (!a.mine_now && a.written_at != b.written_at) return a.written_at > b.written_at;
    return a.step > b.step;
  });
}

std::string BaseName(const std::string &path) { return path.substr(path.find_last_of('/') + 1); }

std::string RunLabel(const CheckpointInfo &c) { return c.identified ? "run " + c.run_id : "an older burst's run (no run id)"; }

std::string CheckpointName(const Simulation &sim, PetscInt step)
{
  char name[64];
  std::snprintf(name, sizeof(name), "/checkpoint_%06d.h5", (int)step);
  return sim.output.dir + name;
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
  for (const auto &m : sim.mpm.materials) names.push_back(m->Name());
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
  if (SwarmFieldNames(sim.mpm.swarm, &names) == PETSC_SUCCESS)
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

// Writes rank 0's values (the other ranks' are ignored) as /<group>/<name>; nothing when rank 0 has
// none.
PetscErrorCode WriteRootValues(const Simulation &sim, PetscViewer viewer, const std::string &group, const char name[], const std::vector<PetscReal> &values, PetscInt *count = nullptr)
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
  PetscCall(CheckpointChecksumVec(v, group + "/" + name));
  PetscCall(PetscViewerHDF5PushGroup(viewer, ("/" + group).c_str()));
  PetscCall(VecView(v, viewer));
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscCall(VecDestroy(&v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Reads a vector written by WriteRootValues and gives its n values to every rank.
PetscErrorCode ReadRootValues(const Simulation &sim, PetscViewer viewer, const std::string &file, const std::string &group, const char name[], PetscInt n, std::vector<PetscReal> &values)
{
  Vec                v;
  const PetscScalar *a;
  PetscBool          has;
  PetscFunctionBeginUser;
  values.assign(n, 0);
  if (!n) PetscFunctionReturn(PETSC_SUCCESS);
  const std::string path = "/" + group + "/" + name;
  PetscCall(PetscViewerHDF5HasDataset(viewer, path.c_str(), &has));
  PetscCheck(has, sim.comm, PETSC_ERR_FILE_UNEXPECTED, "Checkpoint %s lacks %s (truncated or not a burst checkpoint)", file.c_str(), path.c_str());
  PetscCall(CreateRootVec(sim, n, name, &v));
  PetscCall(PetscViewerHDF5PushGroup(viewer, ("/" + group).c_str()));
  PetscCall(VecLoad(v, viewer));
  PetscCall(PetscViewerHDF5PopGroup(viewer));
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
  PetscCall(DMSwarmGetLocalSize(sim.mpm.swarm, &n));
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/particles"));
  for (const std::string &name : CheckpointFields(sim)) {
    PetscInt      bs;
    PetscDataType type;
    void         *data;
    Vec           v;
    PetscScalar  *a;
    PetscCall(DMSwarmGetField(sim.mpm.swarm, name.c_str(), &bs, &type, &data));
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
    PetscCall(DMSwarmRestoreField(sim.mpm.swarm, name.c_str(), &bs, &type, &data));
    PetscCall(CheckpointChecksumVec(v, "particles/" + name));
    PetscCall(VecView(v, viewer));
    PetscCall(VecDestroy(&v));
  }
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// The components' parts of a checkpoint (checkpoint_values.hpp), each under its own group. "run"
// is the driver's: time, step and ids, and each rank's particle count (the restart's split).
struct Part {
  std::string      name;
  CheckpointValues values;
};

std::vector<Part> Parts(Simulation &sim, PetscInt64 *local_particles)
{
  std::vector<Part> parts(4);
  parts[0].name         = "run";
  CheckpointValues &run = parts[0].values;
  run.Global("time", &sim.time);
  run.Global("dt", &sim.dt);
  run.Global("step", &sim.step);
  run.Global("next_pid", &sim.mpm.next_pid);
  run.Global("particle_steps", &sim.mpm.particle_steps);
  run.Global("total_particles", &sim.mpm.total_particles);
  run.Global("wall_stepping", &sim.wall_stepping);
  run.PerRank("local_particles", local_particles);
  parts[1].name = "diagnostics";
  sim.mpm.diag.Checkpoint(parts[1].values);
  parts[2].name = "output";
  sim.output.Checkpoint(parts[2].values);
  parts[3].name = "fragments";
  sim.mpm.fragments.Checkpoint(parts[3].values);
  if (sim.ice) {
    parts.push_back({"gas", {}});
    IceCheckpointValues(*sim.ice, parts.back().values);
  }
  if (sim.coupling) {
    parts.push_back({"coupling", {}});
    CouplingCheckpointValues(*sim.coupling, parts.back().values);
  }
  return parts;
}

// A part's values to /<part>/values (rank 0's) and /<part>/rank_values (every rank's row), with the
// names as attributes of / (<part>_values, <part>_rank_values).
PetscErrorCode WritePart(Simulation &sim, PetscViewer viewer, const Part &part)
{
  const std::vector<PetscReal> mine = part.values.Pack(true);

  std::vector<PetscReal> rows(sim.rank ? 0 : mine.size() * sim.size);
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Gather(mine.data(), (int)mine.size(), MPIU_REAL, rows.data(), (int)mine.size(), MPIU_REAL, 0, sim.comm));
  const std::string names = part.values.Names(false), rank_names = part.values.Names(true);
  PetscCall(WriteRootValues(sim, viewer, part.name, "values", part.values.Pack(false)));
  PetscCall(WriteRootValues(sim, viewer, part.name, "rank_values", rows));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", (part.name + "_values").c_str(), PETSC_STRING, names.c_str()));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", (part.name + "_rank_values").c_str(), PETSC_STRING, rank_names.c_str()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// A part's values as written, checked by name against what this run's part lists.
PetscErrorCode ReadPart(Simulation &sim, PetscViewer viewer, const std::string &file, const Part &part, PetscInt saved_ranks, std::vector<PetscReal> &values, std::vector<PetscReal> &rows)
{
  PetscFunctionBeginUser;
  for (const bool per_rank : {false, true}) {
    const std::string attr = part.name + (per_rank ? "_rank_values" : "_values");
    const std::string mine = part.values.Names(per_rank);
    std::string       theirs;
    PetscBool         has;
    PetscCall(PetscViewerHDF5HasAttribute(viewer, "/", attr.c_str(), &has));
    if (has) {
      char *text = nullptr;
      PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/", attr.c_str(), PETSC_STRING, nullptr, &text));
      theirs = text;
      PetscCall(PetscFree(text));
    }
    PetscCheck(has && theirs == mine, sim.comm, PETSC_ERR_USER_INPUT,
               "Checkpoint %s does not hold this burst's %s values for /%s (it holds '%s', this burst keeps '%s'): it was written by another version of burst or another scene; restart it with the burst that wrote it", file.c_str(),
               per_rank ? "per-rank" : "run-wide", part.name.c_str(), has ? theirs.c_str() : "none", mine.c_str());
  }
  PetscCall(ReadRootValues(sim, viewer, file, part.name, "values", part.values.Count(false), values));
  PetscCall(ReadRootValues(sim, viewer, file, part.name, "rank_values", part.values.Count(true) * saved_ranks, rows));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Removes all but the newest `keep` checkpoints of this run (rank 0): newest written first, so that a
// restart from an older checkpoint keeps what it writes; other runs' checkpoints are not touched.
void PruneCheckpoints(const Simulation &sim)
{
  std::vector<CheckpointInfo> mine;
  for (CheckpointInfo &c : ScanFolder(sim.output.dir))
    if (c.identified && c.run_id == opts.run_id) {
      c.mine_now = std::find(opts.written.begin(), opts.written.end(), BaseName(c.path)) != opts.written.end();
      mine.push_back(c);
    }
  SortNewestFirst(mine);
  for (size_t i = (size_t)opts.keep; i < mine.size(); ++i) {
    std::remove(mine[i].path.c_str());
    (void)PetscInfo(nullptr, "Pruned checkpoint %s (run %s, -checkpoint_keep %d)\n", mine[i].path.c_str(), opts.run_id.c_str(), (int)opts.keep);
  }
}

// The checkpoint a -restart value names (rank 0 decides): a file, or a folder's newest valid
// checkpoint when the folder holds one run's checkpoints only. An explicit file must pass its
// checksum; in a folder an invalid newer one is skipped with a note. `error` empty: `chosen` is it.
void ResolveRestartRoot(std::string &error, std::string &notes, CheckpointInfo &chosen)
{
  struct stat        st;
  const std::string &arg = opts.restart;
  if (stat(arg.c_str(), &st) != 0) {
    error = "Option -restart " + arg + ": no such file or folder";
    return;
  }
  if (!S_ISDIR(st.st_mode)) {
    chosen = ReadInfo(arg, -1);
    if (!chosen.readable) error = "Checkpoint " + arg + " cannot be read as HDF5 (truncated or damaged); restart from an older checkpoint_<step>.h5";
    else if (!chosen.complete) error = "Checkpoint " + arg + " is incomplete (no 'complete' mark: its writer stopped early); restart from an older checkpoint_<step>.h5";
    else if (chosen.identified) {
      const std::string why = VerifyChecksum(chosen);
      if (!why.empty()) error = "Checkpoint " + arg + ": " + why + "; restart from another checkpoint_<step>.h5";
    }
    return;
  }
  std::vector<CheckpointInfo> all = ScanFolder(arg);
  if (all.empty()) {
    error = "Option -restart " + arg + ": the folder holds no checkpoint_<step>.h5 (write them with -checkpoint_interval, -checkpoint_wall_interval or -max_wall_time)";
    return;
  }
  SortNewestFirst(all);
  // one run only (unreadable files belong to nobody)
  std::vector<std::string>           runs;
  std::map<std::string, std::string> files;
  std::map<std::string, int>         count;
  for (const CheckpointInfo &c : all) {
    if (!c.readable) continue;
    const std::string label = RunLabel(c);
    if (std::find(runs.begin(), runs.end(), label) == runs.end()) runs.push_back(label);
    if (++count[label] <= 4) files[label] += (files[label].empty() ? "" : ", ") + BaseName(c.path); // the newest four
  }
  if (runs.size() > 1) {
    error = "Option -restart " + arg + ": the folder holds the checkpoints of " + std::to_string(runs.size()) + " runs:";
    for (size_t i = 0; i < runs.size() && i < 4; ++i) error += " " + runs[i] + " (" + files[runs[i]] + (count[runs[i]] > 4 ? " and " + std::to_string(count[runs[i]] - 4) + " older" : std::string()) + ");";
    if (runs.size() > 4) error += " and " + std::to_string(runs.size() - 4) + " more runs;";
    error += " name the checkpoint file to continue from, e.g. -restart " + all[0].path;
    return;
  }
  std::string skipped;
  for (const CheckpointInfo &c : all) {
    std::string why;
    if (!c.readable) why = "cannot be read as HDF5 (truncated or damaged)";
    else if (!c.complete) why = "is incomplete (its writer stopped early)";
    else if (c.identified) why = VerifyChecksum(c);
    if (why.empty()) {
      chosen = c;
      return;
    }
    notes += "Note: -restart " + arg + ": skipping " + BaseName(c.path) + ": " + why + "\n";
    skipped += (skipped.empty() ? "" : ", ") + BaseName(c.path);
  }
  error = "Option -restart " + arg + ": no valid checkpoint in the folder (" + skipped + "; see the notes above)";
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

PetscErrorCode ReadParticles(Simulation &sim, PetscViewer viewer, const std::string &file, PetscInt64 total, const std::vector<PetscInt64> &local_counts, PetscInt saved_ranks)
{
  PetscInt local;
  PetscFunctionBeginUser;
  // Same number of ranks: every rank takes back its own particles, in order (bit-identical);
  // otherwise an even split, then migration to the owners.
  if (saved_ranks == sim.size) local = (PetscInt)local_counts[sim.rank];
  else local = (PetscInt)(total / sim.size + (sim.rank < total % sim.size ? 1 : 0));
  PetscCall(DMSwarmSetLocalSizes(sim.mpm.swarm, local, 16));
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/particles"));
  for (const std::string &name : CheckpointFields(sim)) {
    PetscInt           bs;
    PetscDataType      type;
    void              *data;
    Vec                v;
    const PetscScalar *a;
    PetscBool          has;
    PetscCall(PetscViewerHDF5HasDataset(viewer, ("/particles/" + name).c_str(), &has));
    PetscCheck(has, sim.comm, PETSC_ERR_USER_INPUT, "Checkpoint %s has no particle field %s: it was written by a run with other materials or models, or by an older burst (this run: -materials %s)", file.c_str(), name.c_str(),
               SolidNames(sim).c_str());
    PetscCall(DMSwarmGetField(sim.mpm.swarm, name.c_str(), &bs, &type, &data));
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
    PetscCall(DMSwarmRestoreField(sim.mpm.swarm, name.c_str(), &bs, &type, &data));
    PetscCall(VecDestroy(&v));
  }
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  sim.mpm.total_particles = total;
  PetscCall(MigrateParticles(sim.mpm)); // owner ranks and cell ids; no particle moves on the same ranks
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

namespace {
// Another run's checkpoints in this run's -output_dir are kept apart: moved (renamed, never copied
// or removed) to output_dir/other_runs/<their run id>/ ("unidentified" for an older burst's or an
// unreadable one) before this run writes anything that could take their names, with a note.
PetscErrorCode MoveOtherRunsAside(const Simulation &sim)
{
  std::string note, error;
  PetscFunctionBeginUser;
  if (!sim.rank) {
    std::map<std::string, std::vector<CheckpointInfo>> others;
    for (const CheckpointInfo &c : ScanFolder(sim.output.dir))
      if (!(c.identified && c.run_id == opts.run_id)) others[c.identified ? c.run_id : "unidentified"].push_back(c);
    for (auto &kv : others) {
      const std::string dir = sim.output.dir + "/other_runs/" + kv.first;
      const std::string cmd = "mkdir -p '" + dir + "'";
      if (std::system(cmd.c_str()) != 0) {
        error = "Option -output_dir " + sim.output.dir + " holds checkpoints of another run (" + kv.first + ") and " + dir + " cannot be created to keep them apart; move them away or choose another -output_dir";
        break;
      }
      std::sort(kv.second.begin(), kv.second.end(), [](const CheckpointInfo &a, const CheckpointInfo &b) { return a.step < b.step; });
      std::string names;
      for (const CheckpointInfo &c : kv.second) {
        const std::string to = dir + "/" + BaseName(c.path);
        struct stat       st;
        if (stat(to.c_str(), &st) == 0 || std::rename(c.path.c_str(), to.c_str()) != 0) {
          error = "Option -output_dir " + sim.output.dir + " holds " + BaseName(c.path) + " of another run (" + kv.first + "), and it cannot be moved to " + to + (stat(to.c_str(), &st) == 0 ? " (a file of that name exists)" : "") +
                  "; move it away or choose another -output_dir";
          break;
        }
        names += (names.empty() ? "" : ", ") + BaseName(c.path);
      }
      if (!error.empty()) break;
      note += "Note: -output_dir " + sim.output.dir + " held checkpoints of another run (" + (kv.first == "unidentified" ? std::string("without a run id") : "run " + kv.first) + "): " + names + "; moved to " + dir +
              " (continue that run with -restart " + dir + "). This run (" + opts.run_id + ") writes its own snapshots, monitor.csv and summary.json in " + sim.output.dir + "\n";
    }
  }
  PetscCall(BcastString(sim.comm, error));
  PetscCheck(error.empty(), sim.comm, PETSC_ERR_FILE_WRITE, "%s", error.c_str());
  PetscCall(BcastString(sim.comm, note));
  PetscCall(PetscPrintf(sim.comm, "%s", note.c_str()));
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
  PetscCall(PetscOptionsBool("-restart_allow_option_change", "Restart even if the physics options (materials, geometry, grid, models) differ from the checkpoint's: each difference is printed as a note; default false (refused, naming the option)", "",
                             opts.allow_option_change, &opts.allow_option_change, nullptr));
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
  // This run's id (a restart replaces it by its checkpoint's): random, from rank 0
  uint64_t run = 0;
  if (!sim.rank) {
    std::random_device rd;
    run = ((uint64_t)rd() << 32) ^ (uint64_t)rd() ^ Mix64((uint64_t)std::chrono::system_clock::now().time_since_epoch().count() ^ ((uint64_t)getpid() << 20));
  }
  PetscCallMPI(MPI_Bcast(&run, 1, MPI_UINT64_T, 0, sim.comm));
  opts.run_id = Hex(run);
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::string CheckpointRunId() { return opts.run_id; }

PetscErrorCode CheckpointKeepAs(Simulation &sim, const std::string &name)
{
  PetscFunctionBeginUser;
  if (!sim.rank) {
    const std::string from = CheckpointName(sim, sim.step), to = sim.output.dir + "/" + name;
    std::remove(to.c_str());
    if (link(from.c_str(), to.c_str()) != 0) { // (a file system without hard links: a copy, under a temporary name)
      std::ifstream in(from, std::ios::binary);
      std::ofstream out(to + ".tmp", std::ios::binary);
      out << in.rdbuf();
      PetscCheck(in.good() && out.good(), PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Could not keep checkpoint %s as %s", from.c_str(), to.c_str());
      out.close();
      PetscCheck(std::rename((to + ".tmp").c_str(), to.c_str()) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Could not rename %s.tmp", to.c_str());
    }
  }
  PetscCallMPI(MPI_Barrier(sim.comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckpointWrite(Simulation &sim)
{
  PetscViewer       viewer;
  PetscLogDouble    t0, t1;
  const std::string path = CheckpointName(sim, sim.step), tmp = path + ".tmp";
  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(PetscLogEventBegin(opts.ev_write, 0, 0, 0, 0));
  PetscCall(PetscViewerHDF5Open(sim.comm, tmp.c_str(), FILE_MODE_WRITE, &viewer));
  opts.checksum = 0;
  if (sim.HasParticles()) PetscCall(WriteParticles(sim, viewer));
  if (sim.ice) PetscCall(IceCheckpointWrite(*sim.ice, viewer));
  PetscInt64 local_particles = 0;
  if (sim.HasParticles()) {
    PetscInt n;
    PetscCall(DMSwarmGetLocalSize(sim.mpm.swarm, &n));
    local_particles = n;
  }
  for (const Part &part : Parts(sim, &local_particles)) PetscCall(WritePart(sim, viewer, part));
  if (sim.phases.Enabled()) PetscCall(WriteRootValues(sim, viewer, "phases", "state", PhasesState(sim)));
  // the output series (rank 0's)
  std::vector<PetscReal> flat;
  for (const OutputRecord &r : sim.output.records) flat.insert(flat.end(), {(PetscReal)r.step, r.time, (PetscReal)r.particles});
  PetscInt nrec;
  PetscCall(WriteRootValues(sim, viewer, "output", "records", flat, &nrec));
  nrec /= 3;
  flat.clear();
  for (const GasOutputRecord &r : sim.output.gas_records) flat.insert(flat.end(), {(PetscReal)r.step, r.time});
  PetscInt ngas;
  PetscCall(WriteRootValues(sim, viewer, "output", "gas_records", flat, &ngas));
  ngas /= 2;
  // what a restart checks
  const std::string solids = SolidNames(sim), gases = GasNames(sim);
  const PetscInt    cells[3]  = {sim.mpm.grid.cells[0], sim.mpm.grid.cells[1], sim.mpm.grid.dim == 3 ? sim.mpm.grid.cells[2] : 1};
  const PetscInt    counts[2] = {nrec, ngas};
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "scene", PETSC_STRING, sim.run.scene.c_str()));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "solid_materials", PETSC_STRING, solids.c_str()));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "gas_materials", PETSC_STRING, gases.c_str()));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "dim", PETSC_INT, &sim.mpm.grid.dim));
  for (int d = 0; d < 3; ++d) PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", (std::string("cells_") + "xyz"[d]).c_str(), PETSC_INT, &cells[d]));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "ranks", PETSC_INT, &sim.size));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "output_records", PETSC_INT, &counts[0]));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "gas_records", PETSC_INT, &counts[1]));
  { // identity and integrity
    uint64_t sum = 0;
    PetscCallMPI(MPI_Allreduce(&opts.checksum, &sum, 1, MPI_UINT64_T, MPI_SUM, sim.comm));
    std::map<std::string, std::string> physics;
    PetscCall(PhysicsOptions(physics));
    std::string text = OptionsText(physics);
    PetscCall(BcastString(sim.comm, text)); // identical on every rank (collective attribute writes)
    double when = (double)std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch()).count() * 1e-6;
    PetscCallMPI(MPI_Bcast(&when, 1, MPI_DOUBLE, 0, sim.comm));
    const PetscInt    format   = 3;
    const std::string checksum = Hex(sum), hash = Hex(Fnv64(text));
    PetscReal         written_at = (PetscReal)when;
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "format", PETSC_INT, &format));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "run_id", PETSC_STRING, opts.run_id.c_str()));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "physics_hash", PETSC_STRING, hash.c_str()));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "physics_options", PETSC_STRING, text.c_str()));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "written_at", PETSC_REAL, &written_at));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "checksum", PETSC_STRING, checksum.c_str()));
  }
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "complete", PETSC_INT, &sim.step));
  PetscCall(PetscViewerDestroy(&viewer));
  if (opts.debug_delay > 0) {
    PetscCallMPI(MPI_Barrier(sim.comm));
    PetscCall(PetscPrintf(sim.comm, "Checkpoint %s written, renaming in %g s (-checkpoint_debug_delay)\n", tmp.c_str(), (double)opts.debug_delay));
    PetscCall(PetscSleep(opts.debug_delay));
  }
  PetscCall(AtomicRename(sim.comm, tmp, path));
  if (!sim.rank) {
    opts.written.push_back(BaseName(path));
    PruneCheckpoints(sim);
  }
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
  if (opts.restart.empty()) {
    PetscCall(MoveOtherRunsAside(sim));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscLogEventBegin(opts.ev_read, 0, 0, 0, 0));
  CheckpointInfo chosen;
  {
    std::string error, notes;
    if (!sim.rank) ResolveRestartRoot(error, notes, chosen);
    PetscCall(BcastString(sim.comm, error));
    PetscCall(BcastString(sim.comm, notes));
    PetscCall(PetscPrintf(sim.comm, "%s", notes.c_str()));
    PetscCheck(error.empty(), sim.comm, PETSC_ERR_USER_INPUT, "%s", error.c_str());
    PetscCall(BcastString(sim.comm, chosen.path));
    PetscCall(BcastString(sim.comm, chosen.run_id));
    PetscCall(BcastString(sim.comm, chosen.physics));
    PetscInt identified = chosen.identified ? 1 : 0;
    PetscCallMPI(MPI_Bcast(&identified, 1, MPIU_INT, 0, sim.comm));
    chosen.identified = identified;
  }
  file = chosen.path;
  PetscCall(CheckReadable(sim, file));
  PetscCall(PetscViewerHDF5Open(sim.comm, file.c_str(), FILE_MODE_READ, &viewer));
  // Same scene?
  PetscInt dim = 0, cells[3], saved_ranks = 0, nrec = 0, ngas = 0;
  PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/", "dim", PETSC_INT, nullptr, &dim));
  PetscCheck(dim == sim.mpm.grid.dim, sim.comm, PETSC_ERR_USER_INPUT, "Checkpoint %s does not match this run: it is %" PetscInt_FMT "-D, this run is %" PetscInt_FMT "-D (-dim)", file.c_str(), dim, sim.mpm.grid.dim);
  for (int d = 0; d < 3; ++d) {
    const PetscInt mine = d < sim.mpm.grid.dim ? sim.mpm.grid.cells[d] : 1;
    PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/", (std::string("cells_") + "xyz"[d]).c_str(), PETSC_INT, nullptr, &cells[d]));
    PetscCheck(cells[d] == mine, sim.comm, PETSC_ERR_USER_INPUT, "Checkpoint %s does not match this run: %" PetscInt_FMT " cells in direction %d, this run has %" PetscInt_FMT " (-grid_cells)", file.c_str(), cells[d], d, mine);
  }
  PetscCall(CheckString(sim, viewer, file, "scene", sim.run.scene, "scene (-scene)"));
  PetscCall(CheckString(sim, viewer, file, "solid_materials", SolidNames(sim), "solid material set (-materials)"));
  PetscCall(CheckString(sim, viewer, file, "gas_materials", GasNames(sim), "gas material set (-ice_materials)"));
  // Same physics options? (format 1 checkpoints do not say)
  if (chosen.identified) {
    std::map<std::string, std::string> mine, theirs = ParseOptionsText(chosen.physics);
    PetscCall(PhysicsOptions(mine));
    std::vector<std::string> differ;
    for (const auto &kv : theirs) {
      const auto it = mine.find(kv.first);
      if (it == mine.end()) differ.push_back("-" + kv.first + " is '" + kv.second + "' in the checkpoint, not given in this run");
      else if (!SameValue(kv.second, it->second)) differ.push_back("-" + kv.first + " is '" + kv.second + "' in the checkpoint, '" + it->second + "' in this run");
    }
    for (const auto &kv : mine)
      if (!theirs.count(kv.first)) differ.push_back("-" + kv.first + " is not given in the checkpoint's run, '" + kv.second + "' in this run");
    if (!differ.empty() && opts.allow_option_change) {
      for (const std::string &d : differ) PetscCall(PetscPrintf(sim.comm, "Note: restart with a changed physics option (-restart_allow_option_change): %s\n", d.c_str()));
    } else if (!differ.empty()) {
      std::string list;
      for (size_t i = 0; i < differ.size() && i < 8; ++i) list += (i ? "; " : "") + differ[i];
      if (differ.size() > 8) list += "; and " + std::to_string(differ.size() - 8) + " more";
      SETERRQ(sim.comm, PETSC_ERR_USER_INPUT, "Checkpoint %s was written with other physics options than this run's (%d differ): %s. Restart with the checkpoint's options, or pass -restart_allow_option_change to continue with this run's",
              file.c_str(), (int)differ.size(), list.c_str());
    }
    opts.run_id = chosen.run_id; // the restart continues the checkpoint's run
  } else PetscCall(PetscPrintf(sim.comm, "Note: checkpoint %s carries no run id, physics options or checksum (written by an older burst): it is not verified, and this run continues as run %s\n", file.c_str(), opts.run_id.c_str()));
  PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/", "ranks", PETSC_INT, nullptr, &saved_ranks));
  PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/", "output_records", PETSC_INT, nullptr, &nrec));
  PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/", "gas_records", PETSC_INT, nullptr, &ngas));

  // every part's values first: the particles need the run's counts, and the parts are applied
  // after the particles and the gas are read (their set-up state stays until then)
  PetscInt64                          local_particles = 0;
  std::vector<Part>                   parts           = Parts(sim, &local_particles);
  std::vector<std::vector<PetscReal>> values(parts.size()), rows(parts.size());
  for (size_t i = 0; i < parts.size(); ++i) PetscCall(ReadPart(sim, viewer, file, parts[i], saved_ranks, values[i], rows[i]));
  std::vector<PetscReal> rec, gas_rec, phases;
  PetscCall(ReadRootValues(sim, viewer, file, "output", "records", 3 * nrec, rec));
  PetscCall(ReadRootValues(sim, viewer, file, "output", "gas_records", 2 * ngas, gas_rec));
  if (sim.phases.Enabled()) {
    PetscBool has;
    PetscCall(PetscViewerHDF5HasDataset(viewer, "/phases/state", &has));
    PetscCheck(has, sim.comm, PETSC_ERR_USER_INPUT, "Option -phases: checkpoint %s was written by a run without phases; restart it without -phases", file.c_str());
    PetscCall(ReadRootValues(sim, viewer, file, "phases", "state", kPhasesStateSize, phases));
  }
  if (sim.HasParticles()) {
    const CheckpointValues &run   = parts[0].values;
    const PetscInt          width = run.Count(true), at = run.Offset(true, "local_particles");
    std::vector<PetscInt64> counts(saved_ranks);
    for (PetscInt r = 0; r < saved_ranks; ++r) counts[r] = (PetscInt64)rows[0][(size_t)width * r + at];
    PetscCall(ReadParticles(sim, viewer, file, (PetscInt64)values[0][run.Offset(false, "total_particles")], counts, saved_ranks));
  }
  if (sim.ice) PetscCall(IceCheckpointRead(*sim.ice, viewer, file));
  PetscCall(PetscViewerDestroy(&viewer));

  if (!phases.empty()) PetscCall(PhasesRestore(sim, phases));
  // Per-rank partial sums: each rank its own on the same number of ranks, else all on rank 0.
  for (size_t i = 0; i < parts.size(); ++i) {
    const PetscInt         width = parts[i].values.Count(true);
    std::vector<PetscReal> mine(width, 0);
    for (PetscInt r = 0; r < saved_ranks; ++r)
      if (saved_ranks == sim.size ? r == sim.rank : sim.rank == 0)
        for (PetscInt k = 0; k < width; ++k) mine[k] += rows[i][(size_t)width * r + k];
    parts[i].values.Unpack(false, values[i].data());
    parts[i].values.Unpack(true, mine.data());
  }
  if (!sim.rank) { // the series continue (rank 0 holds them)
    sim.output.records.clear();
    for (PetscInt i = 0; i < nrec; ++i) sim.output.records.push_back({(PetscInt)rec[3 * i], rec[3 * i + 1], (PetscInt64)rec[3 * i + 2]});
    sim.output.gas_records.clear();
    for (PetscInt i = 0; i < ngas; ++i) sim.output.gas_records.push_back({(PetscInt)gas_rec[2 * i], gas_rec[2 * i + 1]});
  }
  sim.restarted = PETSC_TRUE;
  PetscCall(MoveOtherRunsAside(sim));
  PetscCall(PetscLogEventEnd(opts.ev_read, 0, 0, 0, 0));
  PetscCall(PetscPrintf(sim.comm, "Restarted from %s (written on %" PetscInt_FMT " rank(s)): step %" PetscInt_FMT ", t = %g s, run %s\n", file.c_str(), saved_ranks, sim.step, (double)sim.time, opts.run_id.c_str()));
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
  RunLockTouch();
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
    *stop                 = PETSC_TRUE;
    const std::string why = global[0] ? std::string("signal ") + (global[0] == SIGTERM ? "SIGTERM" : global[0] == SIGUSR1 ? "SIGUSR1" : std::to_string(global[0])) + " received" : WallMessage();
    PetscCall(PetscPrintf(sim.comm, "Stopping at step %" PetscInt_FMT ", t = %g s: %s. Wrote %s; continue with -restart %s\n", sim.step, (double)sim.time, why.c_str(), CheckpointName(sim, sim.step).c_str(), sim.output.dir.c_str()));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
