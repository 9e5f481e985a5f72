// Particle and grid output as HDF5 + XDMF that ParaView opens as is (petsc.md 4.5-4.6, 8).
//
// Each output step writes particles_NNNNNN.h5 (datasets /particles/<field>, [N][bs]) and, with
// -output_grid, grid_NNNNNN.h5: one dataset per node field, /nodes/<field> in natural ordering,
// scalars [Nz][Ny][Nx] and vectors [Nz][Ny][Nx][3] (padded to 3 in 2-D): mass, velocity, force, and
// mass_1, velocity_1, force_1 for the converted field (grid_output.hpp, also for cell-centred data).
// The XDMF points at each dataset directly (no HyperSlab: ParaView's XDMF readers print HDF5 error
// traces or drop the arrays for those). The files are written under a temporary name and renamed
// when complete; particles.xmf and grid.xmf list every step written so far as a temporal collection
// and are replaced atomically too.
#include "../simulation.hpp"
#include "grid_output.hpp"
#include "run_lock.hpp"
#include "checkpoint_values.hpp"
#include <petscviewerhdf5.h>
#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <cerrno>
#include <cstring>
#include <dirent.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

namespace burst {

namespace {
// One particle field to write: swarm field name, components written, and how to read them.
struct ParticleOutputField {
  const char *swarm_name; // field in the swarm
  const char *out_name;   // dataset name
  PetscInt    bs;         // components in the swarm
  PetscInt    out_bs;     // components written (vectors padded to 3 for ParaView)
  bool        is_int;
  bool        displacement; // x - X0
  bool        is_int64 = false;
};
} // namespace

PetscErrorCode AtomicRename(MPI_Comm comm, const std::string &tmp, const std::string &final_name)
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Barrier(comm));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) PetscCheck(std::rename(tmp.c_str(), final_name.c_str()) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Could not rename %s to %s", tmp.c_str(), final_name.c_str());
  PetscCallMPI(MPI_Barrier(comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// A write that fails (HDF5, a rename, a text file) stops the run with PETSc's message; this handler
// adds what the user needs: the files that were being written (the *.tmp of -output_dir, removed so
// that no partial file is left) and whether the disk is full, then hands over to PETSc's traceback.
namespace {
std::string    disk_full_dir; // -output_dir, set by OutputPushWriteErrorHandler
PetscErrorCode WriteErrorHandler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  const bool write_error = p == PETSC_ERROR_INITIAL && (n == PETSC_ERR_FILE_WRITE || n == PETSC_ERR_FILE_OPEN || (n == PETSC_ERR_LIB && mess && std::strstr(mess, "HDF5")));
  if (write_error && !disk_full_dir.empty()) {
    const int      saved = errno;
    struct statvfs fs;
    std::string    partial;
    if (DIR *d = opendir(disk_full_dir.c_str())) {
      while (dirent *e = readdir(d)) {
        const std::string name = e->d_name;
        if (name.size() > 4 && name.compare(name.size() - 4, 4, ".tmp") == 0) {
          partial += " " + name;
          unlink((disk_full_dir + "/" + name).c_str()); // (each rank tries; the first one removes it)
        }
      }
      closedir(d);
    }
    const bool   stat_ok = statvfs(disk_full_dir.c_str(), &fs) == 0;
    const double free_b  = stat_ok ? (double)fs.f_bavail * (double)fs.f_frsize : -1;
    const bool   full    = saved == ENOSPC || (stat_ok && free_b < 1 << 20);
    std::fprintf(stderr, "burst: writing to %s failed%s%s%s%s\n", disk_full_dir.c_str(), partial.empty() ? "" : " (partial files removed:", partial.c_str(), partial.empty() ? "" : ")",
                 full ? (std::string(": the disk is full (") + std::to_string((long long)free_b) + " bytes free); free space or give another -output_dir").c_str() : (saved ? (std::string(": ") + std::strerror(saved)).c_str() : ""));
  }
  return PetscTraceBackErrorHandler(comm, line, fun, file, n, p, mess, ctx);
}
} // namespace

PetscErrorCode OutputPushWriteErrorHandler(const Simulation &sim)
{
  PetscFunctionBeginUser;
  disk_full_dir = sim.output.dir;
  PetscCall(PetscPushErrorHandler(WriteErrorHandler, nullptr));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode OutputSetUp(Simulation &sim)
{
  PetscFunctionBeginUser;
  if (!sim.rank) {
    struct stat st;
    if (stat(sim.output.dir.c_str(), &st) != 0) {
      std::string cmd = "mkdir -p '" + sim.output.dir + "'";
      PetscCheck(std::system(cmd.c_str()) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Could not create -output_dir %s", sim.output.dir.c_str());
    }
  }
  // One run per folder: a second run into it stops here, before it writes anything there.
  PetscCall(RunLockAcquire(sim));
  // An output folder that cannot be written is an error now, not after hours of computing.
  PetscInt ok = 1;
  if (!sim.rank) {
    const std::string probe = sim.output.dir + "/.burst_write_test";
    FILE             *f     = std::fopen(probe.c_str(), "w");
    ok                      = f && std::fputs("burst\n", f) >= 0 ? 1 : 0;
    if (f) ok = (std::fclose(f) == 0 && ok) ? 1 : 0;
    std::remove(probe.c_str());
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPIU_INT, 0, sim.comm));
  PetscCheck(ok, sim.comm, PETSC_ERR_FILE_WRITE, "Option -output_dir %s: the folder cannot be written (permissions, a file of that name, or a full disk)", sim.output.dir.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode WriteParticleField(Simulation &sim, PetscViewer viewer, const ParticleOutputField &f, PetscInt n)
{
  Vec          vec;
  PetscScalar *out;
  void        *data, *x = nullptr;
  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(sim.comm, n * f.out_bs, PETSC_DETERMINE, &vec));
  PetscCall(VecSetBlockSize(vec, f.out_bs));
  PetscCall(PetscObjectSetName((PetscObject)vec, f.out_name));
  PetscCall(VecGetArray(vec, &out));
  PetscCall(DMSwarmGetField(sim.mpm.swarm, f.swarm_name, nullptr, nullptr, &data));
  if (f.displacement) PetscCall(DMSwarmGetField(sim.mpm.swarm, DMSwarmPICField_coor, nullptr, nullptr, &x));
  for (PetscInt p = 0; p < n; ++p)
    for (PetscInt c = 0; c < f.out_bs; ++c) {
      PetscReal value = 0;
      if (c < f.bs) {
        if (f.is_int64) value = (PetscReal)((PetscInt64 *)data)[p * f.bs + c]; // exact below 2^53
        else if (f.is_int) value = (PetscReal)((PetscInt *)data)[p * f.bs + c];
        else value = ((PetscReal *)data)[p * f.bs + c];
        if (f.displacement) value = ((PetscReal *)x)[p * f.bs + c] - value;
      }
      out[p * f.out_bs + c] = value;
    }
  if (f.displacement) PetscCall(DMSwarmRestoreField(sim.mpm.swarm, DMSwarmPICField_coor, nullptr, nullptr, &x));
  PetscCall(DMSwarmRestoreField(sim.mpm.swarm, f.swarm_name, nullptr, nullptr, &data));
  PetscCall(VecRestoreArray(vec, &out));
  PetscCall(VecView(vec, viewer));
  PetscCall(VecDestroy(&vec));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Model fields declared by the materials (each once).
static std::vector<ParticleOutputField> ModelFields(const Simulation &sim)
{
  std::vector<ParticleOutputField> out;
  for (const auto &m : sim.mpm.materials)
    for (const OutputField &f : m->OutputFields()) {
      bool seen = false;
      for (const auto &o : out) seen = seen || std::string(o.out_name) == f.name;
      if (!seen) out.push_back({f.name, f.name, f.bs, f.bs, f.is_int, false});
    }
  return out;
}

static std::vector<ParticleOutputField> ParticleFields(const Simulation &sim)
{
  const PetscInt                   dim    = sim.mpm.grid.dim;
  std::vector<ParticleOutputField> fields = {
    {DMSwarmPICField_coor, "coordinates", dim, dim, false, false},
    {field::velocity, "velocity", dim, 3, false, false},
    {field::position0, "displacement", dim, 3, false, true},
    {field::mass, "mass", 1, 1, false, false},
    {field::volume, "volume", 1, 1, false, false},
    {field::stress, "stress", 9, 9, false, false},
    {field::F, "deformation_gradient", 9, 9, false, false},
    {field::temperature, "temperature", 1, 1, false, false},
    {field::internal_energy, "internal_energy", 1, 1, false, false},
    {field::material, "material", 1, 1, true, false},
    {DMSwarmField_pid, "id", 1, 1, true, false, true},
    {field::fragment, "fragment", 1, 1, true, false},
  };
  for (const auto &f : ModelFields(sim)) fields.push_back(f);
  if (sim.phases.Enabled()) {
    fields.push_back({field::surface_conductance, "surface_conductance", 1, 1, false, false});
    fields.push_back({field::reacted_fraction, "reacted_fraction", 1, 1, false, false});
  }
  return fields;
}

static std::string XdmfParticleGrid(const Simulation &sim, const std::string &file, PetscInt64 n, PetscReal time)
{
  const PetscInt     dim = sim.mpm.grid.dim;
  std::ostringstream s;
  s << "    <Grid Name=\"particles\" GridType=\"Uniform\">\n      <Time Value=\"" << time << "\"/>\n";
  s << "      <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n << "\" NodesPerElement=\"1\"/>\n";
  s << "      <Geometry GeometryType=\"" << (dim == 2 ? "XY" : "XYZ") << "\">\n        <DataItem Dimensions=\"" << n << " " << dim << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << file
    << ":/particles/coordinates</DataItem>\n      </Geometry>\n";
  for (const auto &f : ParticleFields(sim)) {
    if (f.swarm_name == DMSwarmPICField_coor) continue;
    const char *type = f.out_bs == 1 ? "Scalar" : (f.out_bs == 3 ? "Vector" : "Tensor");
    s << "      <Attribute Name=\"" << f.out_name << "\" AttributeType=\"" << type << "\" Center=\"Node\">\n        <DataItem Dimensions=\"" << n;
    if (f.out_bs > 1) s << " " << f.out_bs;
    s << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << file << ":/particles/" << f.out_name << "</DataItem>\n      </Attribute>\n";
  }
  s << "    </Grid>\n";
  return s.str();
}

// Node grid fields per velocity field f (nodal layout [mass, momentum(dim), force(dim)(, mass
// gradient(dim))] stacked per field; velocity layout [v_old(dim), v_new(dim)] per field): mass, the
// updated velocity and the force; the converted field's (f = 1, -mpm_convert_failed) with a suffix.
static std::vector<GridField> NodalFields(const Grid &g)
{
  std::vector<GridField> out;
  for (PetscInt f = 0; f < g.num_velocity_fields; ++f) {
    const std::string suffix = f ? "_" + std::to_string(f) : "";
    out.push_back({"mass" + suffix, f * g.NodeStride(), 1});
    out.push_back({"force" + suffix, f * g.NodeStride() + 1 + g.dim, g.dim});
  }
  return out;
}

static std::vector<GridField> VelocityFields(const Grid &g)
{
  std::vector<GridField> out;
  for (PetscInt f = 0; f < g.num_velocity_fields; ++f) out.push_back({"velocity" + (f ? "_" + std::to_string(f) : std::string()), f * 2 * g.dim + g.dim, g.dim});
  return out;
}

static const char grid_group[] = "/nodes";

static std::string XdmfNodeGrid(const Simulation &sim, const std::string &file, PetscReal time)
{
  const Grid            &g      = sim.mpm.grid;
  std::vector<GridField> fields = NodalFields(g), velocity = VelocityFields(g);
  fields.insert(fields.begin() + 1, velocity.begin(), velocity.end());
  return XdmfGridBlock(file, grid_group, g.dim, g.cells, g.lower, g.h, false, fields, time);
}

static PetscErrorCode WriteCollection(Simulation &sim, const char name[], bool grid)
{
  PetscFunctionBeginUser;
  if (sim.rank) PetscFunctionReturn(PETSC_SUCCESS);
  const std::string path = sim.output.dir + "/" + name, tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"2.0\">\n <Domain>\n  <Grid Name=\"TimeSeries\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (const auto &r : sim.output.records) {
      char file[64];
      std::snprintf(file, sizeof(file), "%s_%06d.h5", grid ? "grid" : "particles", (int)r.step);
      out << (grid ? XdmfNodeGrid(sim, file, r.time) : XdmfParticleGrid(sim, file, r.particles, r.time));
    }
    out << "  </Grid>\n </Domain>\n</Xdmf>\n";
    PetscCheck(out.good(), PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Could not write %s", tmp.c_str());
  }
  PetscCheck(std::rename(tmp.c_str(), path.c_str()) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Could not rename %s", tmp.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode WriteOutput(Simulation &sim)
{
  PetscViewer viewer;
  PetscInt    n;
  char        name[64];
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(sim.output.ev_output, 0, 0, 0, 0));
  PetscCall(DMSwarmGetLocalSize(sim.mpm.swarm, &n));
  std::snprintf(name, sizeof(name), "particles_%06d.h5", (int)sim.step);
  std::string path = sim.output.dir + "/" + name, tmp = path + ".tmp";
  PetscCall(PetscViewerHDF5Open(sim.comm, tmp.c_str(), FILE_MODE_WRITE, &viewer));
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/particles"));
  for (const auto &f : ParticleFields(sim)) PetscCall(WriteParticleField(sim, viewer, f, n));
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/particles", "time", PETSC_REAL, &sim.time));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/particles", "step", PETSC_INT, &sim.step));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscCall(AtomicRename(sim.comm, tmp, path));

  if (sim.output.write_grid) {
    std::snprintf(name, sizeof(name), "grid_%06d.h5", (int)sim.step);
    path = sim.output.dir + "/" + name;
    tmp  = path + ".tmp";
    PetscCall(PetscViewerHDF5Open(sim.comm, tmp.c_str(), FILE_MODE_WRITE, &viewer));
    PetscCall(WriteGridFields(viewer, sim.mpm.grid.da_nodes, sim.mpm.grid.nodal, grid_group, NodalFields(sim.mpm.grid)));
    PetscCall(WriteGridFields(viewer, sim.mpm.grid.da_velocity, sim.mpm.grid.velocity, grid_group, VelocityFields(sim.mpm.grid)));
    PetscCall(PetscViewerDestroy(&viewer));
    PetscCall(AtomicRename(sim.comm, tmp, path));
  }
  if (!sim.rank) sim.output.records.push_back({sim.step, sim.time, sim.mpm.total_particles});
  PetscCall(WriteCollection(sim, "particles.xmf", false));
  if (sim.output.write_grid) PetscCall(WriteCollection(sim, "grid.xmf", true));
  PetscCall(PetscLogEventEnd(sim.output.ev_output, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

void Output::Checkpoint(CheckpointValues &values)
{
  values.Global("energy_scale", &energy_scale);
  values.Global("track_pid", &track_pid); // (-monitor_track_point picks it at the start)
}

} // namespace burst
