// The arguments and results of a pointwise flow-stress evaluation.
#pragma once
#include <petscsys.h>

namespace burst {

struct FlowPoint {
  PetscReal        plastic_strain;      // equivalent plastic strain at t_{n+1} (= at t_n + delta_strain)
  PetscReal        delta_strain;        // plastic strain increment of this step (history models integrate with it)
  PetscReal        plastic_strain_rate; // 1/s (already floored by the caller)
  PetscReal        temperature;         // K
  PetscReal        melt_temperature;    // K
  PetscReal        shear_modulus;       // current mu, Pa
  PetscReal        density;             // kg/m^3
  const PetscReal *history;             // flow-model history at t_n
};

struct FlowValue {
  PetscReal sigma   = 0; // flow stress, Pa
  PetscReal d_strain = 0; // d sigma / d eps_p, Pa
  PetscReal d_rate  = 0; // d sigma / d eps_p_dot, Pa s
  PetscReal d_temperature = 0; // d sigma / dT, Pa/K
};

} // namespace burst
