// The gas time step (ice.md 1.11): dt = cfl min over cells, materials and directions of
// h_d / (k c + |u_d|), with k the sound-speed knob (1 explicit; 0.5 semi-implicit, whose pressure
// is implicit in the acoustic waves). -ice_dt fixes it instead.
#include "ice.hpp"
#include <cmath>

namespace burst {

PetscErrorCode IceComputeTimeStep(IceSolver &ice, PetscReal *dt)
{
  PetscScalar *a;
  PetscReal    local = PETSC_MAX_REAL;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ice.ev_dt, 0, 0, 0, 0));
  if (ice.dt_fixed > 0) {
    *dt = ice.dt_fixed;
    PetscCall(PetscLogEventEnd(ice.ev_dt, 0, 0, 0, 0));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(IceGetLocalArray(ice, &a));
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        const PetscScalar *c = a + ice.LocalIndex(i, j, k) * ice.stride;
        for (PetscInt m = 0; m < ice.ngas; ++m) { // the MPM limit covers the solids (ice.md 7.5)
          const PetscReal theta = c[ice.Offset(m, icef::theta)];
          if (theta < ice.trace_fraction) continue; // a trace does not set the step
          // a minor gas (a pocket in a solid's cell) sets it through its speed only: its sound speed
          // is not the cell's (sum theta kappa is the solid's there, ice.md 7.5)
          const PetscReal rho_micro = 1 / c[ice.Offset(m, icef::spvol)];
          const PetscReal sound     = theta < ice.cfl_min_fraction ? 0 : std::sqrt(ice.materials[m].eos->SoundSpeed2(rho_micro, c[ice.Offset(m, icef::temp)]));
          for (PetscInt d = 0; d < ice.dim; ++d) local = PetscMin(local, ice.h[d] / (ice.sound_speed_knob * sound + std::fabs(c[ice.Offset(m, icef::vel + d)]) + 1e-300));
        }
      }
  PetscCall(IceRestoreLocalArray(ice, &a));
  PetscCallMPI(MPI_Allreduce(&local, dt, 1, MPIU_REAL, MPI_MIN, ice.comm));
  *dt *= ice.cfl;
  PetscCall(PetscLogEventEnd(ice.ev_dt, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
