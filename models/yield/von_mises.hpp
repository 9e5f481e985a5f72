// Radial return for the von Mises yield condition (paper eq. 12) with a rate- and temperature-
// dependent flow stress. With q_tr = sqrt(3/2 s_tr:s_tr) and the unknown plastic strain increment
// de (= sqrt(2/3) dgamma), solve by Newton (models.md 4.7)
//   g(de) = q_tr - 3 mu de - sigma_f(eps_p + de, de/dt, T) = 0,
//   g'    = -3 mu - (d sigma_f/d eps_p + d sigma_f/d eps_p_dot / dt), safeguarded by a bracket,
// then s = s_tr (1 - 3 mu de / q_tr). The plastic rate de/dt feeds the flow stress (not the total
// rate: models.md 2.2); each model floors it smoothly (SmoothRateFloor).
#pragma once
#include "../plasticity/chunk.hpp"
#include "flow_point.hpp"
#include <cmath>

namespace burst {

// The flow-model arguments of point k after a plastic strain increment de over dt.
template <class Flow>
inline FlowPoint MakeFlowPoint(const Flow &flow, const Chunk &c, int k, PetscReal de)
{
  (void)flow;
  return FlowPoint{c.plastic_strain[k] + de, de, de / c.dt, c.temperature[k], c.melt_temperature[k], c.shear_modulus[k], c.density[k], c.history[k]};
}

// Returns the deviatoric stress of every point of the chunk onto the yield surface.
template <class Flow>
PetscErrorCode VonMisesReturn(const Flow &flow, Chunk &c, PetscReal tolerance, PetscInt max_iterations)
{
  for (int k = 0; k < c.n; ++k) {
    PetscReal *s  = c.deviator[k];
    PetscReal  ss = 0;
    for (int a = 0; a < 9; ++a) ss += s[a] * s[a];
    const PetscReal q_trial = std::sqrt(1.5 * ss), mu = c.shear_modulus[k], dt = c.dt;
    const PetscReal eps0 = c.plastic_strain[k];
    FlowValue       y;
    flow.Evaluate(MakeFlowPoint(flow, c, k, 0.0), y);
    c.plastic[k]              = 0;
    c.delta_plastic_strain[k] = 0;
    c.trace_plastic_strain[k] = 0;
    if (q_trial <= y.sigma || y.sigma <= 0 || mu <= 0) {
      // elastic (or no strength left: the failure check reads sigma_f <= 0)
      c.flow_stress[k]         = y.sigma;
      c.hardening[k]           = y.d_strain;
      c.rate_hardening[k]      = 0;
      c.thermal_softening[k]   = y.d_temperature;
      c.equivalent_stress[k]   = q_trial;
      c.plastic_strain_rate[k] = 0;
      continue;
    }
    // Safeguarded Newton on de: g decreases monotonically from g(0) > 0 to g(q_trial/(3 mu)) < 0,
    // so a bracket [lo, hi] is kept and a step leaving it is replaced by bisection (the rate term of
    // JC/MTS has a kink at the rate floor, where plain Newton can cycle).
    PetscReal de = 0, g = q_trial - y.sigma, lo = 0, hi = q_trial / (3 * mu);
    PetscInt  it = 0;
    // Warm start: the increment the point's previous plastic rate gives over this step (a steady
    // plastic flow keeps its rate; the bracket catches a poor guess). The first Newton step from
    // de = 0 sees no rate hardening (the smooth floor's slope vanishes there) and overshoots.
    PetscReal guess = c.plastic_strain_rate[k] * dt;
    for (; it < max_iterations; ++it) {
      const PetscReal slope = 3 * mu + y.d_strain + y.d_rate / dt;
      PetscReal       next  = slope > 0 ? de + g / slope : -1;
      if (guess > 0) next = guess, guess = 0;
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      de = next;
      flow.Evaluate(MakeFlowPoint(flow, c, k, de), y);
      g = q_trial - 3 * mu * de - y.sigma;
      if (g > 0) lo = de;
      else hi = de;
      if (std::fabs(g) <= tolerance * y.sigma || hi - lo <= 1e-15 * hi) break;
    }
    if (it == max_iterations || !std::isfinite(de)) {
      c.failed_point = k;
      return PETSC_ERR_NOT_CONVERGED;
    }
    const PetscReal scale = 1 - 3 * mu * de / q_trial;
    for (int a = 0; a < 9; ++a) s[a] *= scale;
    flow.UpdateHistory(MakeFlowPoint(flow, c, k, de), de, c.history[k]);
    c.plastic[k]              = 1;
    c.delta_plastic_strain[k] = de;
    c.plastic_strain[k]       = eps0 + de;
    c.plastic_strain_rate[k]  = de / dt;
    c.flow_stress[k]          = y.sigma;
    c.hardening[k]            = y.d_strain;
    c.rate_hardening[k]       = y.d_rate / dt;
    c.thermal_softening[k]    = y.d_temperature;
    c.equivalent_stress[k]    = q_trial * scale;
  }
  return PETSC_SUCCESS;
}

} // namespace burst
