// The gas time step (ice.md 1.11): dt = cfl min over cells, materials and directions of
// h_d / (k c + |u_d|), with k the sound-speed knob (1 explicit; 0.5 semi-implicit, whose pressure
// is implicit in the acoustic waves). -ice_dt fixes it instead.
#include "ice.hpp"
#include <cmath>

namespace burst {

PetscErrorCode IceComputeTimeStep(IceSolver &ice, PetscReal *dt)
{
  PetscScalar *a;
  PetscReal    local = PETSC_MAX_REAL, limit_sound = 0, limit_speed = 0, limit_theta = 0, limit_T = 0;
  PetscInt     limit[4] = {-1, -1, -1, -1}; // the cell and gas that set the step (-info)
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
          if (IceIsTrace(ice, c, m)) continue; // a trace does not set the step
          // a minor gas (a pocket in a solid's cell) sets it through its speed only: its sound speed
          // is not the cell's (sum theta kappa is the solid's there, ice.md 7.5)
          const PetscReal rho_micro = 1 / c[ice.Offset(m, icef::spvol)];
          const PetscReal sound     = theta < ice.cfl_min_fraction ? 0 : std::sqrt(ice.materials[m].eos->SoundSpeed2(rho_micro, c[ice.Offset(m, icef::temp)]));
          for (PetscInt d = 0; d < ice.dim; ++d) {
            const PetscReal speed = std::fabs(c[ice.Offset(m, icef::vel + d)]), bound = ice.h[d] / (ice.sound_speed_knob * sound + speed + 1e-300);
            if (bound < local) {
              local    = bound;
              limit[0] = i, limit[1] = j, limit[2] = k, limit[3] = m;
              limit_sound = sound, limit_speed = speed, limit_theta = theta, limit_T = c[ice.Offset(m, icef::temp)];
            }
          }
        }
      }
  PetscCall(IceRestoreLocalArray(ice, &a));
  PetscCallMPI(MPI_Allreduce(&local, dt, 1, MPIU_REAL, MPI_MIN, ice.comm));
  if (local == *dt && limit[3] >= 0)
    PetscCall(PetscInfo(nullptr,
                        "Gas step %" PetscInt_FMT ": dt set by %s in cell (%" PetscInt_FMT ", %" PetscInt_FMT ", %" PetscInt_FMT "): volume fraction %g, sound speed %g m/s (0: a pocket under -ice_cfl_min_fraction), speed %g m/s, temperature %g K\n",
                        ice.step, ice.materials[limit[3]].name.c_str(), limit[0], limit[1], limit[2], (double)limit_theta, (double)limit_sound, (double)limit_speed, (double)limit_T));
  *dt *= ice.cfl;
  PetscCall(PetscLogEventEnd(ice.ev_dt, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
