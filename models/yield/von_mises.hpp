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
#include <type_traits>

namespace burst {

// The flow-model arguments of point k after a plastic strain increment de over dt.
template <class Flow>
inline FlowPoint MakeFlowPoint(const Flow &flow, const Chunk &c, int k, PetscReal de)
{
  (void)flow;
  return FlowPoint{c.plastic_strain[k] + de, de, de / c.dt, c.temperature[k], c.melt_temperature[k], c.shear_modulus[k], c.density[k], c.history[k]};
}

// A flow model's per-chain scratch: Flow::Lane if it declares one (Johnson-Cook's series anchors and
// thermal cache), else nothing; EvaluateFlow calls the model with it.
struct NoLane {};
template <class Flow, class = void>
struct LaneOf {
  using type = NoLane;
};
template <class Flow>
struct LaneOf<Flow, std::void_t<typename Flow::Lane>> {
  using type = typename Flow::Lane;
};
template <class Flow>
inline void EvaluateFlow(const Flow &flow, const FlowPoint &x, FlowValue &y, typename LaneOf<Flow>::type &lane)
{
  if constexpr (std::is_same_v<typename LaneOf<Flow>::type, NoLane>) (void)lane, flow.Evaluate(x, y);
  else flow.Evaluate(x, y, lane);
}

// One point's radial return: its yield test (Begin), then one safeguarded Newton iteration per
// Iterate call. The return runs two of these at once (VonMisesReturn), so that one point's Newton
// chain (each iterate waits on the flow stress of the last) overlaps the other's.
template <class Flow>
struct RadialReturn {
  typename LaneOf<Flow>::type lane;
  FlowValue                   y;
  int                         k       = 0;
  PetscInt                    it      = 0;
  PetscReal                   q_trial = 0, mu = 0, eps0 = 0, de = 0, g = 0, lo = 0, hi = 0, guess = 0;

  // The yield test of point k: an elastic point (or one with no strength left: the failure check
  // reads sigma_f <= 0) is finished here (returns false); a plastic one starts its Newton iterations.
  bool Begin(const Flow &flow, Chunk &c, int point)
  {
    k                   = point;
    const PetscReal *s  = c.deviator[k];
    PetscReal        ss = 0;
    for (int a = 0; a < 9; ++a) ss += s[a] * s[a];
    q_trial = std::sqrt(1.5 * ss), mu = c.shear_modulus[k], eps0 = c.plastic_strain[k];
    EvaluateFlow(flow, MakeFlowPoint(flow, c, k, 0.0), y, lane);
    c.plastic[k]              = 0;
    c.delta_plastic_strain[k] = 0;
    c.trace_plastic_strain[k] = 0;
    if (q_trial <= y.sigma || y.sigma <= 0 || mu <= 0) {
      c.flow_stress[k]         = y.sigma;
      c.hardening[k]           = y.d_strain;
      c.rate_hardening[k]      = 0;
      c.thermal_softening[k]   = y.d_temperature;
      c.equivalent_stress[k]   = q_trial;
      c.plastic_strain_rate[k] = 0;
      return false;
    }
    // Safeguarded Newton on de: g decreases monotonically from g(0) > 0 to g(q_trial/(3 mu)) < 0,
    // so a bracket [lo, hi] is kept and a step leaving it is replaced by bisection (the rate term of
    // JC/MTS has a kink at the rate floor, where plain Newton can cycle).
    de = 0, g = q_trial - y.sigma, lo = 0, hi = q_trial / (3 * mu), it = 0;
    // Warm start: the increment the point's previous plastic rate gives over this step (a steady
    // plastic flow keeps its rate; the bracket catches a poor guess). The first Newton step from
    // de = 0 sees no rate hardening (the smooth floor's slope vanishes there) and overshoots.
    guess = c.plastic_strain_rate[k] * c.dt;
    return true;
  }

  // One Newton iteration; returns 1 when the point has converged (its results written), 0 to go on,
  // -1 if it cannot converge (c.failed_point set).
  int Iterate(const Flow &flow, Chunk &c, PetscReal tolerance, PetscInt max_iterations)
  {
    const PetscReal dt = c.dt;
    if (it < max_iterations) {
      const PetscReal slope = 3 * mu + y.d_strain + y.d_rate / dt;
      PetscReal       next  = slope > 0 ? de + g / slope : -1;
      if (guess > 0) next = guess, guess = 0;
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      de = next;
      EvaluateFlow(flow, MakeFlowPoint(flow, c, k, de), y, lane);
      g = q_trial - 3 * mu * de - y.sigma;
      if (g > 0) lo = de;
      else hi = de;
      const bool done = std::fabs(g) <= tolerance * y.sigma || hi - lo <= 1e-15 * hi;
      if (!done) {
        ++it;
        if (it < max_iterations) return 0;
      }
    }
    if (it == max_iterations || !std::isfinite(de)) {
      c.failed_point = k;
      return -1;
    }
    const PetscReal scale = 1 - 3 * mu * de / q_trial;
    PetscReal      *s     = c.deviator[k];
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
    return 1;
  }
};

// Returns the deviatoric stress of every point of the chunk onto the yield surface. Two points are
// in flight at a time, each in its own RadialReturn (and flow-model Lane): when one finishes, it
// takes the next point of the chunk. Each point's arithmetic is that of a return on its own, so the
// results do not depend on the pairing.
template <class Flow>
PetscErrorCode VonMisesReturn(const Flow &flow, Chunk &c, PetscReal tolerance, PetscInt max_iterations)
{
  RadialReturn<Flow> lanes[2];
  bool               busy[2] = {false, false};
  int                next    = 0;
  for (;;) {
    for (int l = 0; l < 2; ++l)
      while (!busy[l] && next < c.n) busy[l] = lanes[l].Begin(flow, c, next++);
    if (!busy[0] && !busy[1]) break;
    for (int l = 0; l < 2; ++l)
      if (busy[l]) {
        const int state = lanes[l].Iterate(flow, c, tolerance, max_iterations);
        if (state < 0) return PETSC_ERR_NOT_CONVERGED;
        busy[l] = state == 0;
      }
  }
  return PETSC_SUCCESS;
}

} // namespace burst
