// The Eulerian background grid: a node DMDA over a box, with the ghost width of the interpolator.
//
// Cells are [x_i, x_{i+1}]; a cell belongs to the rank that owns its lower node (petsc.md 3), so
// particle owner ranks follow from the DMDA ownership ranges alone. Non-periodic directions use
// DM_BOUNDARY_GHOSTED so the wider supports can address nodes beyond a wall; the kernels fold those
// onto the wall node (shape.hpp). BOX stencils everywhere: STAR drops corner ghosts in
// DMLocalToGlobal(ADD_VALUES) (petsc.md 4.4).
#include "simulation.hpp"
#include "util.hpp"

namespace burst {

PetscErrorCode CreateGrid(Simulation &sim)
{
  Grid     &g = sim.grid;
  PetscBool set_cells = PETSC_FALSE, set_h = PETSC_FALSE;
  PetscReal cell_size[3] = {0, 0, 0};
  PetscInt  cells[3] = {g.cells[0], g.cells[1], g.cells[2]};
  int       bc[3][2];
  PetscFunctionBeginUser;
  PetscOptionsBegin(sim.comm, "", "Background grid", "Grid");
  PetscCall(PetscOptionsInt("-dim", "Spatial dimension: 2 (plane strain) or 3", "", g.dim, &g.dim, nullptr));
  PetscCheck(g.dim == 2 || g.dim == 3, sim.comm, PETSC_ERR_USER_INPUT, "Option -dim = %" PetscInt_FMT " is not supported: valid choices are 2 and 3", g.dim);
  PetscCall(OptionsRealVector(PetscOptionsObject, "-grid_lower", "Lower corner of the domain (m), one value per dimension", g.lower, g.dim, nullptr));
  PetscCall(OptionsRealVector(PetscOptionsObject, "-grid_upper", "Upper corner of the domain (m), one value per dimension", g.upper, g.dim, nullptr));
  {
    PetscInt n = 3;
    PetscCall(PetscOptionsIntArray("-grid_cells", "Number of cells per direction (one value per dimension, each >= 1)", "", cells, &n, &set_cells));
    PetscCheck(!set_cells || n == g.dim, sim.comm, PETSC_ERR_USER_INPUT, "Option -grid_cells needs %" PetscInt_FMT " values, got %" PetscInt_FMT, g.dim, n);
  }
  PetscCall(OptionsRealVector(PetscOptionsObject, "-grid_cell_size", "Cell size per direction (m), instead of -grid_cells; rounded to fit the box", cell_size, g.dim, &set_h));
  const char *face_opt[3][2] = {{"-bc_xmin", "-bc_xmax"}, {"-bc_ymin", "-bc_ymax"}, {"-bc_zmin", "-bc_zmax"}};
  for (PetscInt d = 0; d < g.dim; ++d)
    for (int s = 0; s < 2; ++s) {
      bc[d][s] = (int)g.bc[d][s];
      PetscCall(OptionsChoice(PetscOptionsObject, face_opt[d][s], "Boundary condition on this domain face: free, fixed (no-slip wall) or symmetry (roller, zero normal velocity)", FaceBCNames, 3, &bc[d][s], nullptr));
      g.bc[d][s] = (FaceBC)bc[d][s];
    }
  PetscOptionsEnd();

  for (PetscInt d = 0; d < g.dim; ++d) {
    PetscCheck(g.upper[d] > g.lower[d], sim.comm, PETSC_ERR_USER_INPUT, "Options -grid_lower/-grid_upper: upper corner must exceed lower corner in direction %" PetscInt_FMT " (got %g, %g)", d, (double)g.lower[d], (double)g.upper[d]);
    if (set_h && !set_cells) {
      PetscCheck(cell_size[d] > 0, sim.comm, PETSC_ERR_USER_INPUT, "Option -grid_cell_size = %g is out of range: it must be > 0", (double)cell_size[d]);
      cells[d] = (PetscInt)PetscMax(1, (PetscInt)std::lround((g.upper[d] - g.lower[d]) / cell_size[d]));
    }
    PetscCheck(cells[d] >= 1, sim.comm, PETSC_ERR_USER_INPUT, "Option -grid_cells: the cell count in direction %" PetscInt_FMT " is %" PetscInt_FMT "; it must be >= 1", d, cells[d]);
    g.cells[d]        = cells[d];
    g.h[d]            = (g.upper[d] - g.lower[d]) / cells[d];
    g.axes[d].origin  = g.lower[d];
    g.axes[d].h       = g.h[d];
    g.axes[d].nodes   = cells[d] + 1;
  }
  if (g.dim == 2) {
    g.cells[2] = 1;
    g.h[2]     = 1.0; // unit thickness: 2-D volumes and masses are per metre
    g.lower[2] = 0;
    g.upper[2] = 1;
  }

  sim.mass_cutoff = sim.mass_cutoff_fraction * sim.densest * g.CellVolume();
  const PetscInt width = ShapeGhostWidth(sim.shape);
  const DMBoundaryType bt = DM_BOUNDARY_GHOSTED;
  if (g.dim == 2) {
    PetscCall(DMDACreate2d(sim.comm, bt, bt, DMDA_STENCIL_BOX, g.cells[0] + 1, g.cells[1] + 1, PETSC_DECIDE, PETSC_DECIDE, g.num_velocity_fields * g.NodeStride(), width, nullptr, nullptr, &g.da_nodes));
  } else {
    PetscCall(DMDACreate3d(sim.comm, bt, bt, bt, DMDA_STENCIL_BOX, g.cells[0] + 1, g.cells[1] + 1, g.cells[2] + 1, PETSC_DECIDE, PETSC_DECIDE, PETSC_DECIDE, g.num_velocity_fields * g.NodeStride(), width, nullptr, nullptr, nullptr, &g.da_nodes));
  }
  PetscCall(PetscObjectSetOptionsPrefix((PetscObject)g.da_nodes, "grid_"));
  PetscCall(DMSetFromOptions(g.da_nodes));
  PetscCall(DMSetUp(g.da_nodes));
  PetscCall(DMDASetUniformCoordinates(g.da_nodes, g.lower[0], g.upper[0], g.lower[1], g.upper[1], g.lower[2], g.upper[2]));
  PetscCall(DMDACreateCompatibleDMDA(g.da_nodes, g.num_velocity_fields * 2 * g.dim, &g.da_velocity));

  // Ownership ranges for the owner-rank computation.
  PetscInt        m, n, p;
  const PetscInt *l[3] = {nullptr, nullptr, nullptr};
  PetscCall(DMDAGetInfo(g.da_nodes, nullptr, nullptr, nullptr, nullptr, &m, &n, &p, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr));
  PetscCall(DMDAGetOwnershipRanges(g.da_nodes, &l[0], &l[1], &l[2]));
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
  PetscCall(PetscObjectSetName((PetscObject)g.nodal, "nodal"));
  PetscCall(PetscObjectSetName((PetscObject)g.velocity, "grid_velocity"));
  PetscCall(PetscInfo(g.da_nodes, "Grid %" PetscInt_FMT "-D, %" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT " cells, h = %g %g %g m, ghost width %" PetscInt_FMT ", %d x %d x %d ranks\n", g.dim, g.cells[0], g.cells[1], g.cells[2], (double)g.h[0], (double)g.h[1], (double)g.h[2], width, g.procs[0], g.procs[1], g.procs[2]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
