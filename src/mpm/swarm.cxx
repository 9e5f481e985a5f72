// Material points: a DMSWARM_BASIC swarm whose owner ranks burst computes from the node DMDA's
// ownership ranges (petsc.md 3, 4.1-4.2). BASIC migration sends each point straight to its owner at
// any distance, so nothing is lost silently; burst still compares the global count before and after.
#include "mpm/mpm.hpp"
#include "mpm/material_state.hpp"
#include "util.hpp"
#include <cmath>
#include <cstring>

namespace burst {

// The swarm's options (also read under -help, where no swarm is made).
PetscErrorCode SwarmSetFromOptions(MpmSolver &mpm)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(mpm.comm, "", "Particle order", "Swarm");
  PetscCall(PetscOptionsInt("-mpm_sort_interval", "Steps between sorts of each rank's particles by cell (neighbouring particles then touch neighbouring nodes); 0: never", "", mpm.sort_interval, &mpm.sort_interval, nullptr));
  PetscOptionsEnd();
  PetscCheck(mpm.sort_interval >= 0, mpm.comm, PETSC_ERR_USER_INPUT, "Option -mpm_sort_interval = %" PetscInt_FMT " is out of range: it must be >= 0", mpm.sort_interval);
  PetscCall(StressShareSetUp(mpm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CreateSwarm(MpmSolver &mpm)
{
  const PetscInt dim = mpm.grid.dim;
  DM             sw;
  PetscFunctionBeginUser;
  PetscCall(DMCreate(mpm.comm, &sw));
  PetscCall(PetscObjectSetOptionsPrefix((PetscObject)sw, "swarm_"));
  PetscCall(DMSetType(sw, DMSWARM));
  PetscCall(DMSetDimension(sw, dim));
  PetscCall(DMSwarmSetType(sw, DMSWARM_BASIC));
  mpm.swarm_bytes = (PetscInt)(sizeof(PetscInt64) + sizeof(PetscInt)); // DMSwarm_pid and DMSwarm_rank, registered by PETSc
  // Coordinates and cell id first, under the PIC names, as DMSwarm's own viewers expect.
  PetscCall(RegisterSwarmField(sw, DMSwarmPICField_coor, dim, PETSC_REAL, &mpm.swarm_bytes));
  PetscCall(RegisterSwarmField(sw, DMSwarmPICField_cellid, 1, PETSC_INT, &mpm.swarm_bytes));
  PetscCall(RegisterSwarmField(sw, field::velocity, dim, PETSC_REAL, &mpm.swarm_bytes));
  PetscCall(RegisterSwarmField(sw, field::mass, 1, PETSC_REAL, &mpm.swarm_bytes));
  PetscCall(RegisterSwarmField(sw, field::volume, 1, PETSC_REAL, &mpm.swarm_bytes));
  PetscCall(RegisterSwarmField(sw, field::volume0, 1, PETSC_REAL, &mpm.swarm_bytes));
  PetscCall(RegisterSwarmField(sw, field::position0, dim, PETSC_REAL, &mpm.swarm_bytes));
  PetscCall(RegisterSwarmField(sw, field::half_width0, dim, PETSC_REAL, &mpm.swarm_bytes));
  PetscCall(RegisterSwarmField(sw, field::F, 9, PETSC_REAL, &mpm.swarm_bytes));
  PetscCall(RegisterSwarmField(sw, field::stress, 9, PETSC_REAL, &mpm.swarm_bytes));
  PetscCall(RegisterSwarmField(sw, field::L, 9, PETSC_REAL, &mpm.swarm_bytes));
  PetscCall(RegisterSwarmField(sw, field::temperature, 1, PETSC_REAL, &mpm.swarm_bytes));
  PetscCall(RegisterSwarmField(sw, field::wave_speed, 1, PETSC_REAL, &mpm.swarm_bytes));
  PetscCall(RegisterSwarmField(sw, field::internal_energy, 1, PETSC_REAL, &mpm.swarm_bytes));
  PetscCall(RegisterSwarmField(sw, field::external_force, dim, PETSC_REAL, &mpm.swarm_bytes));
  PetscCall(RegisterSwarmField(sw, field::traction_area0, dim, PETSC_REAL, &mpm.swarm_bytes));
  PetscCall(RegisterSwarmField(sw, field::load_curve, 1, PETSC_INT, &mpm.swarm_bytes));
  PetscCall(RegisterSwarmField(sw, field::material, 1, PETSC_INT, &mpm.swarm_bytes));
  PetscCall(RegisterSwarmField(sw, field::bulk_viscosity, 1, PETSC_REAL, &mpm.swarm_bytes));
  PetscCall(RegisterSwarmField(sw, field::fragment, 1, PETSC_INT, &mpm.swarm_bytes));
  if (mpm.ambient_pressure) PetscCall(RegisterSwarmField(sw, field::ambient_pressure, 1, PETSC_REAL, &mpm.swarm_bytes));
  if (mpm.surface_heat_fields)
    for (const char *name : {field::surface_heat, field::surface_temperature_time, field::surface_conductance, field::reacted_fraction}) PetscCall(RegisterSwarmField(sw, name, 1, PETSC_REAL, &mpm.swarm_bytes));
  if (mpm.deformation_heat) PetscCall(RegisterSwarmField(sw, field::deformation_heat, 1, PETSC_REAL, &mpm.swarm_bytes));
  if (mpm.transfer == Transfer::APIC) PetscCall(RegisterSwarmField(sw, field::affine, 9, PETSC_REAL, &mpm.swarm_bytes));
  PetscCall(RegisterMaterialState(sw, mpm.materials, &mpm.swarm_bytes));
  PetscCall(DMSwarmFinalizeFieldRegister(sw));
  PetscCall(SwarmSetFromOptions(mpm));
  if (!mpm.ev_sort) PetscCall(PetscLogEventRegister("MPM_Sort", DM_CLASSID, &mpm.ev_sort));
  // A small buffer: every removal zeroes the whole spare tail (petsc.md 4.3).
  PetscCall(DMSwarmSetLocalSizes(sw, 0, 16));
  mpm.swarm = sw;
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Slot r of sorted starts with start[r] <= i < start[r+1].
static inline PetscInt FindSlot(const std::vector<PetscInt> &start, PetscInt i)
{
  PetscInt lo = 0, hi = (PetscInt)start.size() - 2;
  while (lo < hi) {
    const PetscInt mid = (lo + hi + 1) / 2;
    if (start[mid] <= i) lo = mid;
    else hi = mid - 1;
  }
  return lo;
}

// Writes the owner rank (DMSwarm_rank) and local cell id of every particle. Particles outside the
// domain get rank -1 and are counted in num_outside; num_leaving (if given) counts those owned by
// another rank. On one rank, when the caller needs no cell ids (no sort this step), only the inside
// test runs: every rank is 0 and the cell ids keep older values.
PetscErrorCode ComputeOwnerRanks(MpmSolver &mpm, PetscInt *num_outside, bool need_cells, PetscInt *num_leaving)
{
  const Grid &g = mpm.grid;
  PetscInt    n, outside = 0, leaving = 0;
  PetscReal  *x;
  PetscInt   *rank, *cell;
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
  SwarmAccess fields(mpm.swarm);
  PetscCall(fields.Get(DMSwarmPICField_coor, &x));
  PetscCall(fields.Get(DMSwarmField_rank, &rank));
  PetscCall(fields.Get(DMSwarmPICField_cellid, &cell));
  // the grid's numbers in locals: the stores into rank[] and cell[] (PetscInt) could otherwise
  // alias the grid's PetscInt members and force a reload of each per particle
  const PetscInt  dim = g.dim, cells[3] = {g.cells[0], g.cells[1], g.cells[2]}, procs[2] = {g.procs[0], g.procs[1]};
  const PetscReal lower[3] = {g.lower[0], g.lower[1], g.lower[2]}, upper[3] = {g.upper[0], g.upper[1], g.upper[2]}, h[3] = {g.h[0], g.h[1], g.h[2]};
  const bool      one_slot[3] = {g.start[0].size() <= 2, g.start[1].size() <= 2, dim < 3 || g.start[2].size() <= 2};
  if (mpm.size == 1 && !need_cells) {
    for (PetscInt p = 0; p < n; ++p) {
      bool inside = true;
      for (PetscInt d = 0; d < dim; ++d) {
        const PetscReal xd = x[p * dim + d];
        inside             = inside && xd >= lower[d] && xd <= upper[d]; // false for NaN
      }
      rank[p] = inside ? 0 : -1;
      outside += !inside;
    }
    PetscCall(fields.RestoreAll());
    *num_outside = outside;
    if (num_leaving) *num_leaving = 0;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  for (PetscInt p = 0; p < n; ++p) {
    PetscInt slot[3] = {0, 0, 0}, c[3] = {0, 0, 0};
    bool     inside = true;
    for (PetscInt d = 0; d < dim; ++d) {
      const PetscReal xd = x[p * dim + d];
      if (!(xd >= lower[d] && xd <= upper[d])) { // also catches NaN
        inside = false;
        break;
      }
      c[d]    = PetscMin((PetscInt)std::floor((xd - lower[d]) / h[d]), cells[d] - 1);
      slot[d] = one_slot[d] ? 0 : FindSlot(g.start[d], c[d]);
    }
    if (!inside) {
      rank[p] = -1;
      cell[p] = -1;
      ++outside;
      continue;
    }
    rank[p] = slot[0] + procs[0] * (slot[1] + procs[1] * slot[2]);
    cell[p] = c[0] + cells[0] * (c[1] + cells[1] * c[2]);
    leaving += rank[p] != mpm.rank;
  }
  PetscCall(fields.RestoreAll());
  *num_outside = outside;
  if (num_leaving) *num_leaving = leaving;
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Removes the flagged particles by compaction (petsc.md 4.3), adding their mass and energy to the
// diagnostics and updating the global count.
PetscErrorCode RemoveParticles(MpmSolver &mpm, const std::vector<char> &remove, PetscInt64 *removed)
{
  PetscInt   n, dim = mpm.grid.dim;
  PetscReal *mass, *v, *energy;
  PetscInt64 local = 0;
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
  std::vector<PetscInt> survivors;
  bool                  any = false; // (burning calls this every step; most steps remove nothing)
  for (PetscInt p = 0; p < n && !any; ++p) any = remove[p];
  if (any) {
    SwarmAccess fields(mpm.swarm);
    PetscCall(fields.Get(field::mass, &mass));
    PetscCall(fields.Get(field::velocity, &v));
    PetscCall(fields.Get(field::internal_energy, &energy));
    for (PetscInt p = 0; p < n; ++p) {
      if (!remove[p]) {
        survivors.push_back(p);
        continue;
      }
      PetscReal v2 = 0;
      for (PetscInt d = 0; d < dim; ++d) v2 += v[p * dim + d] * v[p * dim + d];
      mpm.diag.removed_energy += 0.5 * mass[p] * v2 + energy[p];
      mpm.diag.removed_mass += mass[p];
      for (PetscInt d = 0; d < dim; ++d) mpm.diag.removed_momentum[d] += mass[p] * v[p * dim + d];
      mpm.diag.removed_particles++;
      ++local;
    }
    PetscCall(fields.RestoreAll());
    mpm.stencil_cache.Invalidate(); // the particles are renumbered
    const PetscInt keep = (PetscInt)survivors.size();
    for (PetscInt k = 0; k < keep; ++k)
      if (survivors[k] != k) PetscCall(DMSwarmCopyPoint(mpm.swarm, survivors[k], k));
    PetscCall(DMSwarmSetLocalSizes(mpm.swarm, keep, -1));
  }
  PetscCallMPI(MPI_Allreduce(&local, removed, 1, MPIU_INT64, MPI_SUM, mpm.comm));
  mpm.total_particles -= *removed;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MigrateParticles(MpmSolver &mpm)
{
  PetscInt   outside = 0, leaving = 0, n;
  PetscInt64 global_outside = 0, removed_before = 0, count = 0, local;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(mpm.ev_migrate, 0, 0, 0, 0));
  mpm.stencil_cache.Invalidate(); // arrivals, departures and possibly new ghost ranges
  const bool sort    = mpm.sort_interval > 0 && (mpm.step + 1) % mpm.sort_interval == 0;
  const bool balance = mpm.grid.balance && mpm.size > 1 && (mpm.grid.balanced_at < 0 || (mpm.grid.balance_interval > 0 && (mpm.step + 1) % mpm.grid.balance_interval == 0));
  PetscCall(ComputeOwnerRanks(mpm, &outside, sort || balance, &leaving));
  if (balance) {
    PetscBool changed;
    PetscCall(BalanceGrid(mpm, &changed)); // new ownership ranges from the particle work (grid.cxx)
    mpm.grid.balanced_at = mpm.step;
    if (changed) PetscCall(ComputeOwnerRanks(mpm, &outside, true, &leaving));
  }
  // particles that left the domain and particles that change rank, in one reduction
  const PetscInt64 local_counts[2] = {outside, leaving};
  PetscInt64       global_counts[2];
  PetscCallMPI(MPI_Allreduce(local_counts, global_counts, 2, MPIU_INT64, MPI_SUM, mpm.comm));
  global_outside = global_counts[0];
  if (global_outside) {
    if (mpm.outside == OutsidePolicy::Error) {
      PetscInt   np;
      PetscReal *x;
      PetscInt  *rank;
      PetscCall(DMSwarmGetLocalSize(mpm.swarm, &np));
      SwarmAccess fields(mpm.swarm);
      PetscCall(fields.Get(DMSwarmPICField_coor, &x));
      PetscCall(fields.Get(DMSwarmField_rank, &rank));
      for (PetscInt p = 0; p < np; ++p)
        if (rank[p] < 0) {
          PetscCall(PetscPrintf(PETSC_COMM_SELF, "[%d] step %" PetscInt_FMT ": particle %" PetscInt_FMT " left the domain at (%g, %g, %g) m\n", mpm.rank, mpm.step, p, (double)x[p * mpm.grid.dim], (double)x[p * mpm.grid.dim + 1],
                                mpm.grid.dim == 3 ? (double)x[p * 3 + 2] : 0.0));
          break;
        }
      PetscCall(fields.RestoreAll());
      SETERRQ(mpm.comm, PETSC_ERR_USER, "Step %" PetscInt_FMT ": %" PetscInt64_FMT " particle(s) left the domain (-mpm_outside_domain error); enlarge -grid_lower/-grid_upper or use -mpm_outside_domain remove", mpm.step, global_outside);
    }
    removed_before = mpm.diag.removed_particles;
    {
      PetscInt        np;
      const PetscInt *rank;
      PetscCall(DMSwarmGetLocalSize(mpm.swarm, &np));
      std::vector<char> remove(np);
      SwarmAccess       fields(mpm.swarm);
      PetscCall(fields.Get(DMSwarmField_rank, &rank));
      for (PetscInt p = 0; p < np; ++p) remove[p] = rank[p] < 0;
      PetscCall(fields.RestoreAll());
      PetscInt64 removed;
      PetscCall(RemoveParticles(mpm, remove, &removed));
    }
    PetscCall(PetscInfo(mpm.swarm, "Step %" PetscInt_FMT ": removed %" PetscInt_FMT " particles that left the domain on this rank\n", mpm.step, mpm.diag.removed_particles - (PetscInt)removed_before));
  }
  // DMSwarmMigrate only when a particle changes rank: a step moves particles a fraction of a cell, so
  // most steps none crosses a rank boundary, and the migration's collectives (about ten) are spared
  if (global_counts[1] > 0) {
    PetscCall(DMSwarmMigrate(mpm.swarm, PETSC_TRUE));
    PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
    local = n;
    PetscCallMPI(MPI_Allreduce(&local, &count, 1, MPIU_INT64, MPI_SUM, mpm.comm));
    PetscCheck(count == mpm.total_particles, mpm.comm, PETSC_ERR_PLIB, "Step %" PetscInt_FMT ": migration changed the particle count from %" PetscInt64_FMT " to %" PetscInt64_FMT, mpm.step, mpm.total_particles, count);
  }
  PetscCall(PetscLogEventEnd(mpm.ev_migrate, 0, 0, 0, 0));
  if (sort) PetscCall(SortParticlesByCell(mpm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

template <size_t B>
static inline void Gather(const char *src, char *dst, const std::vector<PetscInt> &order, PetscInt n)
{
  for (PetscInt p = 0; p < n; ++p) std::memcpy(dst + B * p, src + B * order[p], B);
}

// Reorders each rank's particles by cell id (a stable counting sort over the rank's cells; the cell
// ids are those ComputeOwnerRanks wrote before the migration), permuting every field. Migration
// appends arrivals at the end and fills holes from the end, and particles drift from their seeded
// order, so after a while neighbouring particles in memory touch nodes far apart; sorted, the
// transfers (P2G, G2P) walk the nodal arrays nearly in order. Cost: one gather and copy of every
// field (the swarm's bytes per particle, twice), about one streaming pass of a step.
PetscErrorCode SortParticlesByCell(MpmSolver &mpm)
{
  PetscInt                  n;
  std::vector<std::string> *names;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(mpm.ev_sort, 0, 0, 0, 0));
  PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
  std::vector<PetscInt> order(n);
  bool                  sorted = true;
  {
    const PetscInt *cell;

    SwarmAccess fields(mpm.swarm);
    PetscCall(fields.Get(DMSwarmPICField_cellid, &cell));
    PetscInt lo = PETSC_MAX_INT, hi = -1;
    for (PetscInt p = 0; p < n; ++p) {
      lo = PetscMin(lo, cell[p]);
      hi = PetscMax(hi, cell[p]);
    }
    if (n > 0) {
      std::vector<PetscInt> offset(hi - lo + 2, 0);
      for (PetscInt p = 0; p < n; ++p) offset[cell[p] - lo + 1]++;
      for (size_t c = 1; c < offset.size(); ++c) offset[c] += offset[c - 1];
      for (PetscInt p = 0; p < n; ++p) order[offset[cell[p] - lo]++] = p;
      for (PetscInt p = 0; p < n && sorted; ++p) sorted = order[p] == p;
    }
    PetscCall(fields.RestoreAll());
  }
  if (!sorted) {
    mpm.stencil_cache.Invalidate();
    PetscCall(SwarmFieldNames(mpm.swarm, &names));
    std::vector<std::string> all = {DMSwarmField_pid, DMSwarmField_rank};
    all.insert(all.end(), names->begin(), names->end());
    std::vector<char> buffer;
    for (const std::string &name : all) {
      PetscInt      bs;
      PetscDataType type;
      void         *data;
      size_t        size;
      PetscCall(DMSwarmGetField(mpm.swarm, name.c_str(), &bs, &type, &data));
      PetscCall(PetscDataTypeGetSize(type, &size));
      const size_t bytes = size * (size_t)bs;
      buffer.resize(bytes * (size_t)n);
      char *src = static_cast<char *>(data), *dst = buffer.data();
      switch (bytes) { // fixed sizes inline the copies (a call per particle and field costs more than the copy)
      case 4: Gather<4>(src, dst, order, n); break;
      case 8: Gather<8>(src, dst, order, n); break;
      case 16: Gather<16>(src, dst, order, n); break;
      case 24: Gather<24>(src, dst, order, n); break;
      case 32: Gather<32>(src, dst, order, n); break;
      case 72: Gather<72>(src, dst, order, n); break;
      default:
        for (PetscInt p = 0; p < n; ++p) std::memcpy(dst + bytes * p, src + bytes * order[p], bytes);
      }
      std::memcpy(src, dst, bytes * (size_t)n);
      PetscCall(DMSwarmRestoreField(mpm.swarm, name.c_str(), &bs, &type, &data));
    }
  }
  PetscCall(PetscLogEventEnd(mpm.ev_sort, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
