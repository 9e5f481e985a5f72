// Axisymmetric MPM (-dim 2 -axisymmetric): x is the radius r, y the axis z, theta the third
// direction (the zz entries of the 3x3 tensors). The formulation lives in the kernels it changes:
//   seed.cxx   particle volume and mass per radian: V_p = A_p r_p, m_p = rho V_p;
//   g2p.cxx    hoop rate L_tt = v_r/r_p, so F_tt tracks r/R and V = V0 det F includes the hoop stretch;
//   p2g.cxx    hoop stress in the radial internal force, -V_p sigma_tt N_I / r_p.
// Everything else (grid update, contact, energies, loads through Nanson's formula with per-radian
// areas) is unchanged. Here: the checks on the grid and on the features that do not support it.
//
// The axis: the face r = 0 carries v_r = 0 (a symmetry face). Supports that reach beyond it use the
// wall extrapolation of shape.hpp, which for v_r (zero on the axis) is the odd reflection
// v_r(-h) = -v_r(h) that the axis requires. Particles never reach r = 0: v_r vanishes linearly there.
// Every interpolator is defined (linear, uGIMP, cpGIMP, B-spline): their weights are the Cartesian
// ones in (r, z), as in Uintah and NairnMPM; the GIMP weights are not re-derived for the r-weighted
// particle domain, which costs first order only in the cells next to the axis.
#include "mpm/mpm.hpp"

namespace burst {

PetscErrorCode AxisymmetricSetUp(MpmSolver &mpm)
{
  Grid &g = mpm.grid;
  PetscFunctionBeginUser;
  if (!mpm.axisymmetric) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(g.dim == 2, mpm.comm, PETSC_ERR_USER_INPUT, "Option -axisymmetric needs -dim 2 (x is the radius, y the axis); got -dim %" PetscInt_FMT, g.dim);
  PetscCheck(g.lower[0] >= 0, mpm.comm, PETSC_ERR_USER_INPUT, "Option -axisymmetric: the radius x must be >= 0, but -grid_lower gives x = %g m", (double)g.lower[0]);
  if (g.lower[0] == 0) {
    PetscCheck(g.bc[0][0] != FaceBC::Fixed || mpm.help, mpm.comm, PETSC_ERR_USER_INPUT, "Option -axisymmetric: the axis (x = 0) is a symmetry face; -bc_xmin fixed would also hold the axial velocity there (use symmetry or free)");
    g.bc[0][0] = FaceBC::Symmetry; // v_r = 0 on the axis
  }
  PetscBool heat = PETSC_FALSE;
  PetscCall(PetscOptionsGetBool(nullptr, nullptr, "-mpm_heat_conduction", &heat, nullptr));
  PetscCheck(!heat, mpm.comm, PETSC_ERR_SUP, "Option -axisymmetric does not support -mpm_heat_conduction yet (its Laplacian is Cartesian)");
  // The empty-node cut-off is a fraction of a full cell's mass: per radian, a cell at r = h.
  mpm.mass_cutoff *= g.h[0];
  PetscCall(PetscInfo(nullptr, "Axisymmetric: r in [%g, %g] m, z in [%g, %g] m, mass cut-off %g kg/rad\n", (double)g.lower[0], (double)g.upper[0], (double)g.lower[1], (double)g.upper[1], (double)mpm.mass_cutoff));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
