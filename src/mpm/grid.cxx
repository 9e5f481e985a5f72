// The Eulerian background grid: a node DMDA over a box, with the ghost width of the interpolator.
//
// Cells are [x_i, x_{i+1}]; a cell belongs to the rank that owns its lower node (petsc.md 3), so
// particle owner ranks follow from the DMDA ownership ranges alone. DM_BOUNDARY_NONE: the kernels fold
// a support node beyond a wall onto the inside nodes (shape.hpp), so no node outside the domain is
// addressed, and a rank without neighbours has no ghost nodes (its local vectors are its global
// ones). BOX stencils everywhere: STAR drops corner ghosts in DMLocalToGlobal(ADD_VALUES) (petsc.md 4.4).
#include "mpm/mpm.hpp"
#include "memory.hpp"
#include "util.hpp"
#include "mpm/swarm_access.hpp"
#include <string>
#include <vector>

namespace burst {

static std::string RangesString(const std::vector<PetscInt> &r)
{
  std::string s;
  for (size_t i = 0; i < r.size(); ++i) s += (i ? "," : "") + std::to_string(r[i]);
  return s;
}

// The scatter between the ghost nodes of a local vector of `da` and their owners' entries of the
// global one: forward, ADD_VALUES, it is the ghost part of DMLocalToGlobal (the nodal sums: the P2G
// adds the owned part itself, only at the nodes its particles reach, p2g.cxx, where DMLocalToGlobal
// would add every owned entry of the local vector, a pass over the whole grid per transfer);
// reverse, INSERT_VALUES, the ghost part of DMGlobalToLocal (the grid velocities: the grid update
// writes the owned part of both vectors itself, grid_update.cxx). Null without ghost nodes.
static PetscErrorCode CreateGhostScatter(const Grid &g, DM da, Vec local_vec, Vec global_vec, VecScatter *scatter)
{
  PetscInt               xs[3], xm[3], dof;
  ISLocalToGlobalMapping ltog;
  std::vector<PetscInt>  local, global;
  IS                     from, to;
  PetscFunctionBeginUser;
  PetscCall(VecScatterDestroy(scatter));
  PetscCall(DMDAGetCorners(da, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(DMDAGetInfo(da, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, &dof, nullptr, nullptr, nullptr, nullptr, nullptr));
  PetscInt l = 0;
  for (PetscInt k = g.gxs[2]; k < g.gxs[2] + g.gxm[2]; ++k)
    for (PetscInt j = g.gxs[1]; j < g.gxs[1] + g.gxm[1]; ++j)
      for (PetscInt i = g.gxs[0]; i < g.gxs[0] + g.gxm[0]; ++i, ++l) {
        const bool owned = i >= xs[0] && i < xs[0] + xm[0] && j >= xs[1] && j < xs[1] + xm[1] && k >= xs[2] && k < xs[2] + xm[2];
        if (!owned) local.push_back(l);
      }
  if (local.empty()) PetscFunctionReturn(PETSC_SUCCESS); // one rank: the local vectors are the global ones
  global.resize(local.size());
  PetscCall(DMGetLocalToGlobalMapping(da, &ltog));
  PetscCall(ISLocalToGlobalMappingApplyBlock(ltog, (PetscInt)local.size(), local.data(), global.data()));
  PetscCall(ISCreateBlock(PETSC_COMM_SELF, dof, (PetscInt)local.size(), local.data(), PETSC_COPY_VALUES, &from));
  PetscCall(ISCreateBlock(PETSC_COMM_SELF, dof, (PetscInt)global.size(), global.data(), PETSC_COPY_VALUES, &to));
  PetscCall(VecScatterCreate(local_vec, from, global_vec, to, scatter));
  PetscCall(ISDestroy(&from));
  PetscCall(ISDestroy(&to));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// The node DMDA, its velocity twin, the vectors and the ownership tables; with ranges (one vector of
// node counts per direction), on the same process grid with those ownership ranges.
static PetscErrorCode CreateNodeDMDA(MpmSolver &mpm, const std::vector<PetscInt> *ranges)
{
  Grid &g = mpm.grid;
  PetscFunctionBeginUser;
  g.reached.clear(); // the marks of another layout (p2g.cxx): the new vectors are zeroed whole first
  g.reached_step = -1;
  g.velocity_written.clear(); // (grid_update.cxx: the first update writes every node)
  const PetscInt width = ShapeGhostWidth(mpm.shape);
  // No ghost nodes outside the domain: every support stays inside [0, M-1] (shape.hpp moves the
  // weight of a node beyond a wall onto the inside nodes), so on one rank the local vectors are the
  // global ones and P2G sums straight into them.
  const DMBoundaryType bt        = DM_BOUNDARY_NONE;
  const PetscInt       procs0[3] = {ranges ? (PetscInt)g.procs[0] : PETSC_DECIDE, ranges ? (PetscInt)g.procs[1] : PETSC_DECIDE, ranges ? (PetscInt)g.procs[2] : PETSC_DECIDE};
  const PetscInt      *l[3]      = {ranges ? ranges[0].data() : nullptr, ranges ? ranges[1].data() : nullptr, ranges ? ranges[2].data() : nullptr};
  if (!ranges && !mpm.materials.empty()) { // (without solids the node vectors are not allocated: the gas has its own)
    const PetscReal nodes = (PetscReal)(g.cells[0] + 1) * (g.cells[1] + 1) * (g.dim == 3 ? g.cells[2] + 1 : 1);
    const PetscReal bytes = nodes / mpm.size * g.num_velocity_fields * (g.dim == 3 ? kMemoryNodeBytes3d : kMemoryNodeBytes2d);
    PetscCall(MemoryCheck(mpm.comm, "The background grid (-grid_cells)", bytes, "use fewer cells (-grid_cells, -grid_cell_size) or more ranks"));
  }
  if (g.dim == 2) {
    PetscCall(DMDACreate2d(mpm.comm, bt, bt, DMDA_STENCIL_BOX, g.cells[0] + 1, g.cells[1] + 1, procs0[0], procs0[1], g.num_velocity_fields * g.NodeStride(), width, l[0], l[1], &g.da_nodes));
  } else {
    PetscCall(DMDACreate3d(mpm.comm, bt, bt, bt, DMDA_STENCIL_BOX, g.cells[0] + 1, g.cells[1] + 1, g.cells[2] + 1, procs0[0], procs0[1], procs0[2], g.num_velocity_fields * g.NodeStride(), width, l[0], l[1], l[2], &g.da_nodes));
  }
  PetscCall(PetscObjectSetOptionsPrefix((PetscObject)g.da_nodes, "grid_"));
  if (!ranges) PetscCall(DMSetFromOptions(g.da_nodes)); // (a re-balance keeps the process grid and sets the ranges)
  PetscCall(DMSetUp(g.da_nodes));
  PetscCall(DMDASetUniformCoordinates(g.da_nodes, g.lower[0], g.upper[0], g.lower[1], g.upper[1], g.lower[2], g.upper[2]));
  PetscCall(DMDACreateCompatibleDMDA(g.da_nodes, g.num_velocity_fields * 2 * g.dim, &g.da_velocity));

  // Ownership ranges for the owner-rank computation.
  PetscInt m, n, p;
  PetscCall(DMDAGetInfo(g.da_nodes, nullptr, nullptr, nullptr, nullptr, &m, &n, &p, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr));
  PetscCall(DMDAGetOwnershipRanges(g.da_nodes, &l[0], &l[1], &l[2]));
  if (ranges) PetscCheck(m == g.procs[0] && n == g.procs[1] && (g.dim == 2 || p == g.procs[2]), mpm.comm, PETSC_ERR_PLIB, "The re-balanced grid changed the process grid");
  const PetscInt procs[3] = {m, n, g.dim == 3 ? p : 1};
  for (PetscInt d = 0; d < 3; ++d) {
    g.procs[d] = (PetscMPIInt)procs[d];
    g.start[d].assign(procs[d] + 1, 0);
    for (PetscInt r = 0; r < procs[d]; ++r) g.start[d][r + 1] = g.start[d][r] + (d < g.dim ? l[d][r] : 1);
  }
  PetscInt gxs[3], gxm[3];
  PetscCall(DMDAGetGhostCorners(g.da_nodes, &gxs[0], &gxs[1], &gxs[2], &gxm[0], &gxm[1], &gxm[2]));
  for (int d = 0; d < 3; ++d) {
    g.gxs[d] = gxs[d];
    g.gxm[d] = gxm[d];
  }
  PetscCall(DMCreateGlobalVector(g.da_nodes, &g.nodal));
  PetscCall(DMCreateLocalVector(g.da_nodes, &g.nodal_local));
  PetscCall(DMCreateGlobalVector(g.da_velocity, &g.velocity));
  PetscCall(DMCreateLocalVector(g.da_velocity, &g.velocity_local));
  {
    // Without ghost nodes (one rank) the ghosted box is the owned box: the local velocity vector is
    // the global one (no copy per grid update)
    PetscInt n_owned, n_ghosted;
    PetscCall(VecGetLocalSize(g.velocity, &n_owned));
    PetscCall(VecGetLocalSize(g.velocity_local, &n_ghosted));
    if (n_owned == n_ghosted) {
      PetscCall(VecDestroy(&g.velocity_local));
      PetscCall(PetscObjectReference((PetscObject)g.velocity));
      g.velocity_local = g.velocity;
    }
  }
  PetscCall(PetscObjectSetName((PetscObject)g.nodal, "nodal"));
  PetscCall(PetscObjectSetName((PetscObject)g.velocity, "grid_velocity"));
  PetscCall(CreateGhostScatter(g, g.da_nodes, g.nodal_local, g.nodal, &g.ghost_sums));
  if (g.velocity_local != g.velocity) PetscCall(CreateGhostScatter(g, g.da_velocity, g.velocity_local, g.velocity, &g.velocity_ghosts));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GridVelocityToLocal(Grid &g)
{
  PetscFunctionBeginUser;
  if (g.velocity_local != g.velocity) PetscCall(DMGlobalToLocal(g.da_velocity, g.velocity, INSERT_VALUES, g.velocity_local));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GridVelocityGhosts(Grid &g)
{
  PetscFunctionBeginUser;
  if (g.velocity_local == g.velocity) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(g.velocity_ghosts, PETSC_COMM_SELF, PETSC_ERR_PLIB, "The ghost-node scatter of the grid velocities is missing");
  PetscCall(VecScatterBegin(g.velocity_ghosts, g.velocity, g.velocity_local, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(g.velocity_ghosts, g.velocity, g.velocity_local, INSERT_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CreateGrid(MpmSolver &mpm)
{
  Grid     &g         = mpm.grid;
  PetscBool set_cells = PETSC_FALSE, set_h = PETSC_FALSE;
  PetscReal cell_size[3] = {0, 0, 0};
  PetscInt  cells[3]     = {g.cells[0], g.cells[1], g.cells[2]};
  int       bc[3][2];
  PetscFunctionBeginUser;
  PetscOptionsBegin(mpm.comm, "", "Background grid", "Grid");
  PetscCall(PetscOptionsInt("-dim", "Spatial dimension: 2 (plane strain) or 3", "", g.dim, &g.dim, nullptr));
  PetscCheck(g.dim == 2 || g.dim == 3, mpm.comm, PETSC_ERR_USER_INPUT, "Option -dim = %" PetscInt_FMT " is not supported: valid choices are 2 and 3", g.dim);
  PetscCall(OptionsRealVector(PetscOptionsObject, "-grid_lower", "Lower corner of the domain (m), one value per dimension", g.lower, g.dim, nullptr));
  PetscCall(OptionsRealVector(PetscOptionsObject, "-grid_upper", "Upper corner of the domain (m), one value per dimension", g.upper, g.dim, nullptr));
  {
    PetscInt n = 3;
    PetscCall(PetscOptionsIntArray("-grid_cells", "Number of cells per direction (one value per dimension, each >= 1)", "", cells, &n, &set_cells));
    PetscCheck(!set_cells || n == g.dim, mpm.comm, PETSC_ERR_USER_INPUT, "Option -grid_cells needs %" PetscInt_FMT " values, got %" PetscInt_FMT, g.dim, n);
    if (set_cells) { // PETSc's integer parsing wraps a count beyond the index type: read the values again as reals
      PetscReal as_real[3] = {0, 0, 0};
      PetscInt  nr         = 3;
      PetscCall(PetscOptionsGetRealArray(nullptr, nullptr, "-grid_cells", as_real, &nr, nullptr));
      for (PetscInt d = 0; d < PetscMin(n, nr); ++d)
        PetscCheck(as_real[d] == (PetscReal)cells[d], mpm.comm, PETSC_ERR_USER_INPUT, "Option -grid_cells: %g cells in direction %" PetscInt_FMT " is not a count this build can index (whole numbers from 1 to %g)", (double)as_real[d], d,
                   (double)(PETSC_MAX_INT / 4));
    }
  }
  PetscCall(OptionsRealVector(PetscOptionsObject, "-grid_cell_size", "Cell size per direction (m), rounded to fit the box; overrides -grid_cells (which the scene files set)", cell_size, g.dim, &set_h));
  const char *face_opt[3][2] = {{"-bc_xmin", "-bc_xmax"}, {"-bc_ymin", "-bc_ymax"}, {"-bc_zmin", "-bc_zmax"}};
  for (PetscInt d = 0; d < g.dim; ++d)
    for (int s = 0; s < 2; ++s) {
      bc[d][s] = (int)g.bc[d][s];
      PetscCall(OptionsChoice(PetscOptionsObject, face_opt[d][s], "Boundary condition on this domain face: free, fixed (no-slip wall) or symmetry (roller, zero normal velocity)", FaceBCNames, 3, &bc[d][s], nullptr));
      g.bc[d][s] = (FaceBC)bc[d][s];
    }
  PetscCall(PetscOptionsBool("-grid_balance", "Set the ranks' node ownership ranges from the particle work at start-up (instead of equal node counts)", "", g.balance, &g.balance, nullptr));
  PetscCall(PetscOptionsInt("-grid_balance_interval", "With -grid_balance: steps between re-balances (new ranges, particles migrated); 0: at start-up only", "", g.balance_interval, &g.balance_interval, nullptr));
  PetscCall(PetscOptionsReal("-grid_balance_rigid_weight", "With -grid_balance: work of a rigid particle relative to a deformable one (-), in [0, 1] (no stress update)", "", g.balance_rigid_weight, &g.balance_rigid_weight, nullptr));
  PetscCall(PetscOptionsReal("-grid_balance_node_weight", "With -grid_balance: work of a grid node relative to a particle (-), >= 0 (grid update, ghost exchange)", "", g.balance_node_weight, &g.balance_node_weight, nullptr));
  PetscCall(PetscOptionsReal("-grid_balance_gas_weight", "With -grid_balance and gases (-ice_materials): work of a gas cell's step relative to a particle's (-), >= 0; the gas grid takes the balanced ranges", "", g.balance_gas_weight,
                             &g.balance_gas_weight, nullptr));
  PetscCall(PetscOptionsReal("-grid_balance_plastic_weight",
                             "With -grid_balance: work of a particle that yielded in the last step relative to an elastic one (-), >= 1 (its return mapping); with -grid_balance_interval the ranges follow the plastic zone", "",
                             g.balance_plastic_weight, &g.balance_plastic_weight, nullptr));
  PetscOptionsEnd();
  PetscCheck(g.balance_interval >= 0, mpm.comm, PETSC_ERR_USER_INPUT, "Option -grid_balance_interval = %" PetscInt_FMT " is out of range: it must be >= 0", g.balance_interval);
  PetscCall(CheckRange(mpm.comm, "-grid_balance_rigid_weight", g.balance_rigid_weight, 0, 1, PETSC_FALSE));
  PetscCall(CheckRange(mpm.comm, "-grid_balance_node_weight", g.balance_node_weight, 0, PETSC_MAX_REAL, PETSC_FALSE));
  PetscCall(CheckRange(mpm.comm, "-grid_balance_plastic_weight", g.balance_plastic_weight, 1, PETSC_MAX_REAL, PETSC_FALSE));
  PetscCall(CheckRange(mpm.comm, "-grid_balance_gas_weight", g.balance_gas_weight, 0, PETSC_MAX_REAL, PETSC_FALSE));
  if (!mpm.ev_balance) PetscCall(PetscLogEventRegister("MPM_Balance", DM_CLASSID, &mpm.ev_balance));

  if (set_h && set_cells) PetscCall(PetscPrintf(mpm.comm, "Note: -grid_cell_size overrides -grid_cells\n"));
  for (PetscInt d = 0; d < g.dim; ++d) {
    PetscCheck(g.upper[d] > g.lower[d], mpm.comm, PETSC_ERR_USER_INPUT, "Options -grid_lower/-grid_upper: upper corner must exceed lower corner in direction %" PetscInt_FMT " (got %g, %g)", d, (double)g.lower[d], (double)g.upper[d]);
    if (set_h) {
      PetscCheck(cell_size[d] > 0, mpm.comm, PETSC_ERR_USER_INPUT, "Option -grid_cell_size = %g is out of range: it must be > 0", (double)cell_size[d]);
      const PetscReal count = std::round((g.upper[d] - g.lower[d]) / cell_size[d]);
      PetscCheck(count <= (PetscReal)PETSC_MAX_INT / 4, mpm.comm, PETSC_ERR_USER_INPUT, "Option -grid_cell_size = %g gives %g cells in direction %" PetscInt_FMT "; at most %g fit a PetscInt index", (double)cell_size[d], (double)count, d,
                 (double)(PETSC_MAX_INT / 4));
      cells[d] = (PetscInt)PetscMax(1, (PetscInt)count);
    }
    PetscCheck(cells[d] >= 1, mpm.comm, PETSC_ERR_USER_INPUT, "Option -grid_cells: the cell count in direction %" PetscInt_FMT " is %" PetscInt_FMT "; it must be >= 1", d, cells[d]);
    g.cells[d]       = cells[d];
    g.h[d]           = (g.upper[d] - g.lower[d]) / cells[d];
    g.axes[d].origin = g.lower[d];
    g.axes[d].h      = g.h[d];
    g.axes[d].nodes  = cells[d] + 1;
  }
  if (g.dim == 2) {
    g.cells[2] = 1;
    g.h[2]     = 1.0; // unit thickness: 2-D volumes and masses are per metre
    g.lower[2] = 0;
    g.upper[2] = 1;
  }

  mpm.mass_cutoff = mpm.mass_cutoff_fraction * mpm.densest * g.CellVolume();
  PetscCall(CreateNodeDMDA(mpm, nullptr));
  PetscCall(PetscInfo(g.da_nodes, "Grid %" PetscInt_FMT "-D, %" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT " cells, h = %g %g %g m, ghost width %" PetscInt_FMT ", %d x %d x %d ranks\n", g.dim, g.cells[0], g.cells[1], g.cells[2],
                      (double)g.h[0], (double)g.h[1], (double)g.h[2], ShapeGhostWidth(mpm.shape), g.procs[0], g.procs[1], g.procs[2]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Load balance: new node ownership ranges from the particle work, on the same process grid. The
// work along each direction is the sum over the slabs of cells (one cell index, all of the others) of
// the particles' weights (1 for a deformable particle, -grid_balance_rigid_weight for a rigid one,
// times -grid_balance_plastic_weight for a particle that yielded in the last step) plus
// -grid_balance_node_weight per node; each direction's ranges cut that profile into equal parts
// (a cell goes with its lower node, petsc.md 3). Every rank keeps at least the ghost width plus one
// nodes per direction (DMDA's minimum). The particles must carry their cell ids (ComputeOwnerRanks);
// the caller recomputes the owner ranks and migrates when the ranges changed. The grid vectors are
// created anew (their values are rebuilt by the next step's P2G). Not with gas or heat conduction,
// whose grids copy the node DMDA's ranges at set-up.
PetscErrorCode BalanceGrid(MpmSolver &mpm, PetscBool *changed)
{
  Grid &g = mpm.grid;
  PetscFunctionBeginUser;
  *changed = PETSC_FALSE;
  if (mpm.size == 1) PetscFunctionReturn(PETSC_SUCCESS);
  mpm.stencil_cache.Invalidate(); // new ghost ranges
  // the gas grid is created after this start-up balance and copies its ranges; conduction's before it
  PetscCheck(!mpm.grid.ranges_copied && !mpm.heat, mpm.comm, PETSC_ERR_SUP,
             "Option -grid_balance is not available with -mpm_heat_conduction, nor with -grid_balance_interval > 0 and gases (-ice_materials): their grids keep the node ranges they were created with");
  PetscCall(PetscLogEventBegin(mpm.ev_balance, 0, 0, 0, 0));
  const PetscInt         dim = g.dim, nc[3] = {g.cells[0], g.cells[1], dim == 3 ? g.cells[2] : 1};
  const PetscInt         offset[3] = {0, nc[0], nc[0] + nc[1]};
  std::vector<PetscReal> work(nc[0] + nc[1] + nc[2], 0), total(work.size(), 0);
  {
    std::vector<PetscReal> weight(mpm.materials.size());
    for (size_t m = 0; m < mpm.materials.size(); ++m) {
      PetscReal v[3];
      weight[m] = mpm.materials[m]->IsRigid(v) ? g.balance_rigid_weight : 1.0;
    }
    // the plastic rate of the metal models (models/plasticity), when a material carries it
    bool plastic_field = false;
    for (const auto &m : mpm.materials)
      for (const OutputField &of : m->OutputFields()) plastic_field = plastic_field || std::string(of.name) == state_field::plastic_strain_rate;
    PetscInt         n;
    const PetscInt  *cell, *material;
    const PetscReal *rate = nullptr;
    PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
    SwarmAccess fields(mpm.swarm);
    PetscCall(fields.Get(DMSwarmPICField_cellid, &cell));
    PetscCall(fields.Get(field::material, &material));
    if (plastic_field && g.balance_plastic_weight != 1) PetscCall(fields.Get(state_field::plastic_strain_rate, &rate));
    for (PetscInt p = 0; p < n; ++p) {
      if (cell[p] < 0) continue;
      const PetscInt  c[3] = {cell[p] % nc[0], (cell[p] / nc[0]) % nc[1], cell[p] / (nc[0] * nc[1])};
      const PetscReal w    = weight[material[p]] * (rate && rate[p] > 0 ? g.balance_plastic_weight : 1.0);
      for (PetscInt d = 0; d < dim; ++d) work[offset[d] + c[d]] += w;
    }
    PetscCall(fields.RestoreAll());
  }
  PetscCallMPI(MPI_Allreduce(work.data(), total.data(), (PetscMPIInt)work.size(), MPIU_REAL, MPI_SUM, mpm.comm));
  const PetscInt        min_nodes = ShapeGhostWidth(mpm.shape) + 1;
  std::vector<PetscInt> ranges[3];
  bool                  same = true;
  for (PetscInt d = 0; d < 3; ++d) {
    const PetscInt P = g.procs[d], nodes = d < dim ? g.cells[d] + 1 : 1;
    ranges[d].assign(P, 0);
    if (P == 1) {
      ranges[d][0] = nodes;
      continue;
    }
    // cumulative work up to the lower node of each cell index (nodes per slab: the product of the others)
    PetscReal slab_nodes = 1;
    for (PetscInt e = 0; e < dim; ++e)
      if (e != d) slab_nodes *= g.cells[e] + 1;
    std::vector<PetscReal> cumulative(nodes + 1, 0); // cumulative[i]: work of nodes (and their cells) < i
    // and with gases, the gas cells of each slab (a cell goes with its lower node)
    PetscReal slab_cells = 1;
    for (PetscInt e = 0; e < dim; ++e)
      if (e != d) slab_cells *= g.cells[e];
    const PetscReal cell_work = g.balance_with_gas ? g.balance_gas_weight * slab_cells : 0;
    for (PetscInt i = 0; i < nodes; ++i) cumulative[i + 1] = cumulative[i] + (i < nc[d] ? total[offset[d] + i] + cell_work : 0) + g.balance_node_weight * slab_nodes;
    PetscInt begin = 0;
    for (PetscInt r = 0; r < P - 1; ++r) {
      const PetscReal target = cumulative[nodes] * (r + 1) / P;
      PetscInt        end    = begin + min_nodes;
      while (end < nodes && cumulative[end] < target) ++end;
      if (end > begin + min_nodes && target - cumulative[end - 1] < cumulative[end] - target) --end; // the nearer cut
      end          = PetscMin(end, nodes - min_nodes * (P - 1 - r));                                 // room for the others
      ranges[d][r] = end - begin;
      begin        = end;
    }
    ranges[d][P - 1] = nodes - begin;
    for (PetscInt r = 0; r < P; ++r) same = same && ranges[d][r] == g.start[d][r + 1] - g.start[d][r];
  }
  if (!same) {
    PetscCall(VecDestroy(&g.nodal));
    PetscCall(VecDestroy(&g.nodal_local));
    PetscCall(VecScatterDestroy(&g.ghost_sums));
    PetscCall(VecScatterDestroy(&g.velocity_ghosts));
    PetscCall(VecDestroy(&g.velocity));
    PetscCall(VecDestroy(&g.velocity_local));
    PetscCall(DMDestroy(&g.da_velocity));
    PetscCall(DMDestroy(&g.da_nodes));
    PetscCall(CreateNodeDMDA(mpm, ranges));
    *changed = PETSC_TRUE;
    if (g.balanced_at < 0 || g.balance_interval == 0)
      PetscCall(PetscPrintf(mpm.comm, "  grid balanced from the particle work: node ranges x %s, y %s, z %s\n", RangesString(ranges[0]).c_str(), RangesString(ranges[1]).c_str(), RangesString(ranges[2]).c_str()));
    else PetscCall(PetscInfo(g.da_nodes, "Step %" PetscInt_FMT ": balanced node ranges x %s, y %s, z %s\n", mpm.step, RangesString(ranges[0]).c_str(), RangesString(ranges[1]).c_str(), RangesString(ranges[2]).c_str()));
  }
  PetscCall(PetscLogEventEnd(mpm.ev_balance, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
