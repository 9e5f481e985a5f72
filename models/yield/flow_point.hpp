// The arguments and results of a pointwise flow-stress evaluation.
#pragma once
#include <petscsys.h>
#include <cmath>

namespace burst {

// Smooth floor of a strain rate, sqrt(rate^2 + floor^2): equal to the rate well above the floor,
// equal to the floor at zero rate, and C-infinity, so the Newton iterations of the returns never meet
// a kink (a max() floor stalls them at first yield). Returns d(effective)/d(rate) in *slope.
inline PetscReal SmoothRateFloor(PetscReal rate, PetscReal floor, PetscReal *slope)
{
  const PetscReal effective = std::sqrt(rate * rate + floor * floor);
  *slope                    = rate / effective;
  return effective;
}

struct FlowPoint {
  PetscReal        plastic_strain;      // equivalent plastic strain at t_{n+1} (= at t_n + delta_strain)
  PetscReal        delta_strain;        // plastic strain increment of this step (history models integrate with it)
  PetscReal        plastic_strain_rate; // 1/s, the plastic rate de/dt (>= 0; models apply their own floor)
  PetscReal        temperature;         // K
  PetscReal        melt_temperature;    // K
  PetscReal        shear_modulus;       // current mu, Pa
  PetscReal        density;             // kg/m^3
  const PetscReal *history;             // flow-model history at t_n
};

struct FlowValue {
  PetscReal sigma         = 0; // flow stress, Pa
  PetscReal d_strain      = 0; // d sigma / d eps_p, Pa
  PetscReal d_rate        = 0; // d sigma / d eps_p_dot, Pa s
  PetscReal d_temperature = 0; // d sigma / dT, Pa/K
};

} // namespace burst
