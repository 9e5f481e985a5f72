// Pressure update (ice.md 1.5, step 8).
//
// Explicit (default): the relative volume that the materials carry out of a cell in this step,
// D_c = sum_m sum_f theta_hat u_f A_f dt / V (theta_hat from the advection operator), changes the
// pressure by dp_dil = -D_c / sum_m theta_m kappa_m. Semi-implicit: pressure_implicit.cxx solves
// for the pressure change with KSP. Either way the end-of-step pressure and dp_dil are stored, and
// the ghost cells refreshed for the face pressure that follows.
#include "ice.hpp"

namespace burst {

PetscErrorCode IceUpdatePressure(IceSolver &ice)
{
  PetscScalar   *a;
  const PetscInt S = ice.stride;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ice.ev_pressure, 0, 0, 0, 0));
  ice.ksp_iterations   = 0;
  ice.outer_iterations = 0;
  if (ice.pressure_solver == IcePressureSolver::SemiImplicit) {
    PetscCall(IceSolvePressureSemiImplicit(ice));
  } else {
    PetscCall(IceGetLocalArray(ice, &a));
    PetscCall(IceVolumeOutflow(ice, a, ice.work_outflow));
    for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
      for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
        for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
          const PetscInt  idx  = ice.LocalIndex(i, j, k);
          PetscScalar    *c    = a + idx * S;
          const PetscReal p_eq = c[ice.CellOffset(icef::press_eq)];
          // the volume the materials carry out, and the volume that mass conversion creates
          // (ice.md 1.5: dP_massX = sum_m dm_m v_m / (V sum kappa))
          PetscReal created = 0;
          if (ice.has_mass_source)
            for (PetscInt m = 0; m < ice.nmat; ++m) created += ice.mass_source[idx * ice.nmat + m] * c[ice.Offset(m, icef::spvol)];
          const PetscReal p               = PetscMax(p_eq + (created - ice.work_outflow[idx]) / c[ice.CellOffset(icef::sum_kappa)], 1e-12); // ice.md 7.3
          c[ice.CellOffset(icef::press)]  = p;
          c[ice.CellOffset(icef::dp_dil)] = p - p_eq;
        }
    PetscCall(IceRestoreLocalArray(ice, &a));
  }
  PetscCall(IceUpdateGhosts(ice));
  PetscCall(PetscLogEventEnd(ice.ev_pressure, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
