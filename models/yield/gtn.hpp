// Gurson-Tvergaard-Needleman yield condition (paper eqs. 13-14) and its return mapping.
//   Phi = (q/sigma_f)^2 + 2 q1 f* cosh(3 q2 sigma_m / (2 sigma_f)) - (1 + q3 f*^2)
//   f* = f (f <= f_c), f_c + k (f - f_c) (f > f_c)
#pragma once
#include "../plasticity/chunk.hpp"
#include "flow_point.hpp"

namespace burst {

struct GTNParameters {
  PetscReal q1 = 1.5, q2 = 1.0, q3 = 2.25;
  PetscReal critical_porosity = 0.05; // f_c of eq. 14 (acceleration threshold)
  PetscReal acceleration = 4.0;       // k of eq. 14
};

// Full GTN return (models.md 4.7). Not yet implemented: selecting -MAT_yield_type gtn stops the run.
template <class Flow>
PetscErrorCode GTNReturn(const Flow &, Chunk &, const GTNParameters &, PetscReal, PetscInt)
{
  return PETSC_ERR_SUP;
}

} // namespace burst
