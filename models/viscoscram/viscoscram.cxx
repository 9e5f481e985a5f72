// ViscoSCRAM point kernel: see viscoscram.hpp for the equations and their sources.
#include "viscoscram.hpp"
#include <cmath>

namespace burst {
namespace viscoscram {

void Parameters::Derive()
{
  shear_modulus       = 0;
  max_relaxation_rate = 0;
  friction_factor     = std::sqrt(45 / (2 * (3 - 2 * friction * friction))) * friction; // eq. 31
  threshold_factor    = std::sqrt(1 + 2 / crack_exponent);                              // eq. 28
  growth_factor       = std::pow(1 + crack_exponent / 2, 1 / crack_exponent);           // eq. 29
  crack_scale_cubed   = crack_scale * crack_scale * crack_scale;
  integer_exponent    = crack_exponent == std::floor(crack_exponent) && crack_exponent >= 1 && crack_exponent <= 64 ? (int)crack_exponent : 0;
  for (int i = 0; i < elements; ++i) {
    shear_modulus += shear_moduli[i];
    if (relaxation_rates[i] > max_relaxation_rate) max_relaxation_rate = relaxation_rates[i];
  }
  for (int i = 0; i < kMaxElements; ++i) {
    shear_fraction[i] = i < elements ? shear_moduli[i] / shear_modulus : 0;
    viscous_weight[i] = i < elements ? relaxation_rates[i] / (2 * shear_moduli[i]) : 0;
  }
}

namespace {

// v_r of eq. 24 for tension and compression: the reference code's empirical speed law
// (ViscoScram.cc: exp(0.90564746 ln(sqrt(3/2)|D'|) - 2.90178468)), zero below 1e-8 1/s, capped at v_max.
struct CrackSpeeds {
  PetscReal tension, compression;
};

CrackSpeeds Speeds(const Parameters &p, PetscReal deviatoric_rate_norm)
{
  const PetscReal rate = std::sqrt(1.5) * deviatoric_rate_norm;
  const PetscReal v    = rate > 1e-8 ? p.crack_speed_coefficient * std::pow(rate, p.crack_speed_exponent) : 0;
  return {std::fmin(p.tension_growth_factor * v, p.max_crack_speed), std::fmin(v, p.max_crack_speed)};
}

// x^m, by repeated squaring when m is a whole number (m = 10: four multiplications instead of pow)
inline PetscReal Power(const Parameters &p, PetscReal x)
{
  if (!p.integer_exponent) return std::pow(x, p.crack_exponent);
  PetscReal result = 1, base = x;
  for (int e = p.integer_exponent; e; e >>= 1, base *= base)
    if (e & 1) result *= base;
  return result;
}

// The crack at one state: cdot of eq. 24 and what the sub-steps need.
struct Crack {
  PetscReal rate;      // cdot, m/s
  PetscReal stiffness; // how fast the crack equations change a sub-step's answer, 1/s (see below)
  PetscReal excess;    // K_I - K', Pa m^1/2 (the growth law switches branch at 0)
  PetscReal K_prime;   // K', Pa m^1/2
};

// eqs. 24-31 at deviator norm SS = S:S, mean stress and crack radius c, with the speeds chosen.
// stiffness: the largest of d cdot/dc ((m/2) cdot/c below K', v_r (K_0m/K_I)^2/c above, from
// K_I ~ sqrt(c)) and the relaxation rate of the softening term, xdot/(1 + x) = 3 c^2 cdot/(a^3 + c^3);
// RK4 wants it times h below max_relaxation_per_substep, like the relaxation rates 1/tau_i.
template <bool with_stiffness>
inline Crack Evaluate(const Parameters &p, const CrackSpeeds &v, PetscReal SS, PetscReal mean_stress, PetscReal c)
{
  Crack           out{0, 0, 0, 0};
  const bool      tension = mean_stress > 0;
  const PetscReal K_I     = std::sqrt(1.5 * PETSC_PI * c * (SS + (tension ? 3 * mean_stress * mean_stress : 0))); // eqs. 26-27
  PetscReal       K_0m    = p.fracture_toughness;
  if (!tension && p.friction > 0) { // eqs. 30-31: crack-face friction raises the threshold in compression
    const PetscReal a_f = -p.friction_factor * mean_stress * std::sqrt(c);
    K_0m *= std::sqrt(1 + PETSC_PI * a_f * (1 + a_f / p.fracture_toughness) / p.fracture_toughness);
  }
  out.K_prime         = K_0m * p.threshold_factor; // eq. 28
  out.excess          = K_I - out.K_prime;
  const PetscReal v_r = tension ? v.tension : v.compression;
  if (c <= 0 || v_r <= 0) return out;
  const bool below = K_I < out.K_prime;
  out.rate         = below ? v_r * Power(p, K_I / (out.K_prime * p.growth_factor)) : v_r * (1 - (K_0m / K_I) * (K_0m / K_I)); // eqs. 24, 29
  if (with_stiffness) {
    const PetscReal slope = below ? 0.5 * p.crack_exponent * out.rate / c : v_r * (K_0m / K_I) * (K_0m / K_I) / c;
    out.stiffness         = std::fmax(slope, 3 * c * c * out.rate / (p.crack_scale_cubed + c * c * c));
  }
  return out;
}

PetscReal Rate(const Parameters &p, const CrackSpeeds &v, PetscReal SS, PetscReal mean_stress, PetscReal c) { return Evaluate<false>(p, v, SS, mean_stress, c).rate; }

// The right-hand side at one stage: element stress rates dS, crack rate, viscous and crack power.
struct Rates {
  PetscReal dS[kMaxElements][kSym];
  PetscReal dc, viscous, crack;
};

inline void EvaluateRates(const Parameters &p, const CrackSpeeds &v, const PetscReal (*S)[kSym], PetscReal c, PetscReal mean_stress, const PetscReal Ddev2G[kSym], Rates &r)
{
  const int n         = p.elements;
  PetscReal sum[kSym] = {0, 0, 0, 0, 0, 0}, relax[kSym] = {0, 0, 0, 0, 0, 0};
  PetscReal viscous = 0;
  for (int i = 0; i < n; ++i) {
    const PetscReal lambda = p.relaxation_rates[i];
    for (int k = 0; k < kSym; ++k) sum[k] += S[i][k], relax[k] += lambda * S[i][k];
    viscous += p.viscous_weight[i] * Contract(S[i], S[i]); // S_i:S_i/(2 G_i tau_i)
  }
  const PetscReal SS = Contract(sum, sum);
  const PetscReal a3 = p.crack_scale_cubed;
  r.dc               = c > 0 ? Rate(p, v, SS, mean_stress, c) : 0;
  const PetscReal x = c * c * c / a3, xdot = 3 * c * c * r.dc / a3;
  PetscReal       Sdot[kSym];
  const PetscReal soften = 1 / (1 + x);
  for (int k = 0; k < kSym; ++k) Sdot[k] = (Ddev2G[k] - relax[k] - xdot * sum[k]) * soften;
  PetscReal crack_rate_stress[kSym]; // (xdot S + x Sdot) = 2 G times the crack strain rate
  for (int k = 0; k < kSym; ++k) crack_rate_stress[k] = xdot * sum[k] + x * Sdot[k];
  const PetscReal G = p.shear_modulus;
  PetscReal       drive[kSym]; // 2 G D' less the crack term, shared by the elements in proportion G_i/G
  for (int k = 0; k < kSym; ++k) drive[k] = Ddev2G[k] - crack_rate_stress[k];
  for (int i = 0; i < n; ++i) {
    const PetscReal g = p.shear_fraction[i], lambda = p.relaxation_rates[i];
    for (int k = 0; k < kSym; ++k) r.dS[i][k] = g * drive[k] - lambda * S[i][k];
  }
  r.viscous = viscous;
  r.crack   = p.crack_heating == CrackHeating::CrackWork ? Contract(sum, crack_rate_stress) / (2 * G) : xdot * SS / (4 * G);
}

} // namespace

PetscReal CrackRate(const Parameters &p, const PetscReal S[kSym], PetscReal mean_stress, PetscReal c, PetscReal deviatoric_rate_norm) { return Rate(p, Speeds(p, deviatoric_rate_norm), Contract(S, S), mean_stress, c); }

PetscReal StoredEnergy(const Parameters &p, const PetscReal *S, PetscReal crack_radius)
{
  PetscReal energy = 0, sum[kSym] = {0, 0, 0, 0, 0, 0};
  for (int i = 0; i < p.elements; ++i) {
    energy += Contract(S + kSym * i, S + kSym * i) / (4 * p.shear_moduli[i]);
    for (int k = 0; k < kSym; ++k) sum[k] += S[kSym * i + k];
  }
  if (p.crack_heating == CrackHeating::Release) {
    const PetscReal x = std::pow(crack_radius / p.crack_scale, 3);
    energy += x * Contract(sum, sum) / (4 * p.shear_modulus);
  }
  return energy;
}

void Update(const Parameters &p, PetscReal *S_flat, PetscReal *crack_radius, PetscReal mean_stress_old, const PetscReal D[kSym], PetscReal dt, PetscReal density, PetscReal temperature, Result *out)
{
  const int n             = p.elements;
  PetscReal(*S)[kSym]     = reinterpret_cast<PetscReal(*)[kSym]>(S_flat);
  const PetscReal trace_D = D[0] + D[1] + D[2];
  // 2 G D', constant over the step
  PetscReal Ddev2G[kSym];
  for (int k = 0; k < kSym; ++k) Ddev2G[k] = 2 * p.shear_modulus * (D[k] - (k < 3 ? trace_D / 3 : 0));
  PetscReal Ddev[kSym];
  for (int k = 0; k < kSym; ++k) Ddev[k] = D[k] - (k < 3 ? trace_D / 3 : 0);
  const CrackSpeeds speeds    = Speeds(p, std::sqrt(Contract(Ddev, Ddev)));
  const PetscReal   mean_rate = p.bulk_modulus * trace_D;
  PetscReal         c         = *crack_radius;

  // sub-steps only when the step asks for them: relaxation (RK4 accuracy) and crack growth
  PetscReal substeps = 1;
  if (p.max_relaxation_rate * dt > p.max_relaxation_per_substep) substeps = std::ceil(p.max_relaxation_rate * dt / p.max_relaxation_per_substep);
  PetscReal t_switch = -1, switch_time_scale = 0;
  bool      loading_crack = false; // K_I rises through K' in this step (else it falls through it)
  if (c > 0 && speeds.tension + speeds.compression > 0) {
    // the crack equations' own rate (Crack::stiffness) times the sub-step below max_relaxation_per_substep,
    // at the start and at an elastic prediction of the end (a tension step may begin in compression)
    PetscReal sum[kSym] = {0, 0, 0, 0, 0, 0}, end[kSym];
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < kSym; ++k) sum[k] += S[i][k];
    for (int k = 0; k < kSym; ++k) end[k] = sum[k] + Ddev2G[k] * dt;
    const PetscReal mean_end = mean_stress_old + mean_rate * dt;
    const Crack     crack0 = Evaluate<true>(p, speeds, Contract(sum, sum), mean_stress_old, c), crack1 = Evaluate<true>(p, speeds, Contract(end, end), mean_end, c);
    const PetscReal growth = std::fmax(crack0.stiffness, crack1.stiffness) * dt / p.max_relaxation_per_substep;
    if (growth > substeps) substeps = std::ceil(growth);
    // and the crack speed, which loading changes too (through K_I), by at most r_v of itself per
    // sub-step (r_v = crack_rate_change_per_substep)
    if (crack0.rate != crack1.rate) {
      const PetscReal change = std::fabs(crack1.rate - crack0.rate) / (p.crack_rate_change_per_substep * std::fmax(crack0.rate, crack1.rate));
      if (change > substeps) substeps = std::ceil(change);
    }
    // the growth law switches branch at K_I = K' (eq. 24; steep below, m = 10): a step whose
    // predicted K_I - K' changes sign gets a sub-step boundary there (see the loop)
    const PetscReal f0 = crack0.excess, f1 = crack1.excess;
    if ((f0 < 0) != (f1 < 0) && f0 != f1) {
      t_switch          = dt * f0 / (f0 - f1);
      loading_crack     = f0 < 0;
      switch_time_scale = dt * (crack0.K_prime + (crack1.K_prime - crack0.K_prime) * t_switch / dt) / std::fabs(f1 - f0);
    }
  }
  const PetscReal h_uniform = dt / (substeps > p.max_substeps ? p.max_substeps : substeps);

  // on the sub-critical side of the switch cdot goes as (K_I/K_1)^m, a power of t: 2m sub-steps
  // there (RK4 on t^10 over 20 sub-steps: 3e-4 of that side's growth)
  // Either refinement is skipped when the crack could not grow by 1e-6 c over the part it refines
  // (below K': at most v_r/(1 + m/2) times that part over m + 1; after the rise: about v_r times the
  // time K_I takes to change by K'), as when a step loads a crack from rest far past K'.
  bool            loading = t_switch > 0 && switch_time_scale > 0 && loading_crack;
  const PetscReal v_max = std::fmax(speeds.tension, speeds.compression), m = p.crack_exponent;
  const PetscReal power_side = t_switch > 0 ? (loading ? t_switch : dt - t_switch) : 0;
  const PetscReal h_power    = v_max * power_side / ((1 + m / 2) * (m + 1)) > 1e-6 * c ? power_side / std::fmin(2 * std::ceil(m), 100.0) : dt;
  if (loading && v_max * switch_time_scale < 1e-6 * c) loading = false, t_switch = -1;
  PetscReal viscous = 0, crack = 0, t = 0, h_graded = p.crack_rate_change_per_substep * switch_time_scale;
  int       nsub = 0;
  Rates     k1, k2, k3, k4;
  PetscReal Y[kMaxElements][kSym];
  while (t < dt) {
    PetscReal h = h_uniform;
    if (t_switch > 0 && nsub < p.max_substeps) {
      if (t < t_switch - 1e-12 * dt) h = std::fmin(loading ? std::fmin(h, h_power) : h, t_switch - t); // land on the switch
      else if (loading) {
        h = std::fmin(h, h_graded);
        h_graded *= 1.5;
      } else h = std::fmin(h, h_power);
    }
    if (h >= dt - t || dt - t - h < 1e-12 * dt) h = dt - t; // the last sub-step ends on dt
    const PetscReal m0 = mean_stress_old + mean_rate * t;
    EvaluateRates(p, speeds, S, c, m0, Ddev2G, k1);
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < kSym; ++k) Y[i][k] = S[i][k] + 0.5 * h * k1.dS[i][k];
    EvaluateRates(p, speeds, Y, c + 0.5 * h * k1.dc, m0 + 0.5 * h * mean_rate, Ddev2G, k2);
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < kSym; ++k) Y[i][k] = S[i][k] + 0.5 * h * k2.dS[i][k];
    EvaluateRates(p, speeds, Y, c + 0.5 * h * k2.dc, m0 + 0.5 * h * mean_rate, Ddev2G, k3);
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < kSym; ++k) Y[i][k] = S[i][k] + h * k3.dS[i][k];
    EvaluateRates(p, speeds, Y, c + h * k3.dc, m0 + h * mean_rate, Ddev2G, k4);
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < kSym; ++k) S[i][k] += h / 6 * (k1.dS[i][k] + 2 * (k2.dS[i][k] + k3.dS[i][k]) + k4.dS[i][k]);
    c += h / 6 * (k1.dc + 2 * (k2.dc + k3.dc) + k4.dc);
    viscous += h / 6 * (k1.viscous + 2 * (k2.viscous + k3.viscous) + k4.viscous);
    crack += h / 6 * (k1.crack + 2 * (k2.crack + k3.crack) + k4.crack);
    t = h == dt - t ? dt : t + h;
    ++nsub;
  }
  *crack_radius = c;
  for (int k = 0; k < kSym; ++k) {
    out->deviator[k] = 0;
    for (int i = 0; i < n; ++i) out->deviator[k] += S[i][k];
  }
  out->mean_stress         = mean_stress_old + mean_rate * dt;
  out->viscous_dissipation = viscous;
  out->crack_dissipation   = crack;
  out->temperature_change  = (viscous + crack) / (density * p.specific_heat) - p.gruneisen * temperature * trace_D * dt;
  out->substeps            = nsub;
}

} // namespace viscoscram
} // namespace burst
