// ViscoSCRAM point kernel: see viscoscram.hpp for the equations and their sources.
#include "viscoscram.hpp"
#include <cmath>

namespace burst {
namespace viscoscram {

void Parameters::Derive()
{
  shear_modulus       = 0;
  max_relaxation_rate = 0;
  for (int i = 0; i < elements; ++i) {
    shear_modulus += shear_moduli[i];
    if (relaxation_rates[i] > max_relaxation_rate) max_relaxation_rate = relaxation_rates[i];
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

// K_I of eqs. 26-27: sqrt(3/2) sqrt(pi c) sigma_e, sigma_e = sqrt(S:S + 3 f sigma_m^2)
inline PetscReal StressIntensity(PetscReal SS, PetscReal mean_stress, PetscReal c)
{
  return std::sqrt(1.5 * PETSC_PI * c * (SS + (mean_stress > 0 ? 3 * mean_stress * mean_stress : 0)));
}

// K_0m of eq. 30 (crack-face friction raises the threshold in compression, eq. 31 for mu')
inline PetscReal FrictionThreshold(const Parameters &p, PetscReal mean_stress, PetscReal c)
{
  const PetscReal mu  = mean_stress > 0 ? 0 : std::sqrt(45 / (2 * (3 - 2 * p.friction * p.friction))) * p.friction;
  const PetscReal a_f = -mu * mean_stress * std::sqrt(c);
  return p.fracture_toughness * std::sqrt(1 + PETSC_PI * a_f * (1 + a_f / p.fracture_toughness) / p.fracture_toughness);
}

// K' of eq. 28, where the growth law switches branch
inline PetscReal ThresholdIntensity(const Parameters &p, PetscReal mean_stress, PetscReal c) { return FrictionThreshold(p, mean_stress, c) * std::sqrt(1 + 2 / p.crack_exponent); }

// eq. 24 with the speed already chosen
PetscReal Rate(const Parameters &p, const CrackSpeeds &v, PetscReal SS, PetscReal mean_stress, PetscReal c)
{
  if (c <= 0) return 0;
  const bool      tension = mean_stress > 0;
  const PetscReal v_r     = tension ? v.tension : v.compression;
  if (v_r <= 0) return 0;
  const PetscReal K_I     = StressIntensity(SS, mean_stress, c); // eqs. 26-27
  const PetscReal K_0m    = FrictionThreshold(p, mean_stress, c); // eqs. 30-31
  const PetscReal m       = p.crack_exponent;
  const PetscReal K_prime = K_0m * std::sqrt(1 + 2 / m);          // eq. 28
  if (K_I < K_prime) {
    const PetscReal K_1 = K_prime * std::pow(1 + m / 2, 1 / m);       // eq. 29
    return v_r * std::pow(K_I / K_1, m);
  }
  return v_r * (1 - (K_0m / K_I) * (K_0m / K_I));
}

// The rate at which the crack equations change a sub-step's answer (1/s), the largest of d cdot/dc
// (eq. 24: (m/2) cdot/c below K', v_r (K_0m/K_I)^2/c above, from K_I ~ sqrt(c)) and the relaxation
// rate of the softening term, xdot/(1 + x) = 3 c^2 cdot/(a^3 + c^3); RK4 wants it times h below
// max_relaxation_per_substep, like the relaxation rates 1/tau_i.
PetscReal CrackStiffness(const Parameters &p, const CrackSpeeds &v, PetscReal SS, PetscReal mean_stress, PetscReal c)
{
  const PetscReal cdot = Rate(p, v, SS, mean_stress, c);
  if (cdot <= 0) return 0;
  const PetscReal K_I = StressIntensity(SS, mean_stress, c), K_0m = FrictionThreshold(p, mean_stress, c);
  const PetscReal slope = K_I < K_0m * std::sqrt(1 + 2 / p.crack_exponent) ? 0.5 * p.crack_exponent * cdot / c : (mean_stress > 0 ? v.tension : v.compression) * (K_0m / K_I) * (K_0m / K_I) / c;
  const PetscReal a3 = p.crack_scale * p.crack_scale * p.crack_scale;
  return std::fmax(slope, 3 * c * c * cdot / (a3 + c * c * c));
}

// The right-hand side at one stage: element stress rates dS, crack rate, viscous and crack power.
struct Rates {
  PetscReal dS[kMaxElements][kSym];
  PetscReal dc, viscous, crack;
};

inline void Evaluate(const Parameters &p, const CrackSpeeds &v, const PetscReal (*S)[kSym], PetscReal c, PetscReal mean_stress, const PetscReal Ddev2G[kSym], Rates &r)
{
  const int       n = p.elements;
  PetscReal       sum[kSym] = {0, 0, 0, 0, 0, 0}, relax[kSym] = {0, 0, 0, 0, 0, 0};
  PetscReal       viscous = 0;
  for (int i = 0; i < n; ++i) {
    const PetscReal lambda = p.relaxation_rates[i];
    for (int k = 0; k < kSym; ++k) sum[k] += S[i][k], relax[k] += lambda * S[i][k];
    if (lambda > 0) viscous += lambda * Contract(S[i], S[i]) / (2 * p.shear_moduli[i]);
  }
  const PetscReal SS = Contract(sum, sum);
  const PetscReal a3 = p.crack_scale * p.crack_scale * p.crack_scale;
  r.dc               = Rate(p, v, SS, mean_stress, c);
  const PetscReal x = c * c * c / a3, xdot = 3 * c * c * r.dc / a3;
  PetscReal       Sdot[kSym];
  for (int k = 0; k < kSym; ++k) Sdot[k] = (Ddev2G[k] - relax[k] - xdot * sum[k]) / (1 + x);
  PetscReal crack_rate_stress[kSym]; // (xdot S + x Sdot) = 2 G times the crack strain rate
  for (int k = 0; k < kSym; ++k) crack_rate_stress[k] = xdot * sum[k] + x * Sdot[k];
  const PetscReal G = p.shear_modulus;
  for (int i = 0; i < n; ++i) {
    const PetscReal g = p.shear_moduli[i] / G, lambda = p.relaxation_rates[i];
    for (int k = 0; k < kSym; ++k) r.dS[i][k] = g * Ddev2G[k] - lambda * S[i][k] - g * crack_rate_stress[k];
  }
  r.viscous = viscous;
  r.crack   = p.crack_heating == CrackHeating::CrackWork ? Contract(sum, crack_rate_stress) / (2 * G) : xdot * SS / (4 * G);
}

} // namespace

PetscReal CrackRate(const Parameters &p, const PetscReal S[kSym], PetscReal mean_stress, PetscReal c, PetscReal deviatoric_rate_norm)
{
  return Rate(p, Speeds(p, deviatoric_rate_norm), Contract(S, S), mean_stress, c);
}

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
  const int n      = p.elements;
  PetscReal (*S)[kSym] = reinterpret_cast<PetscReal (*)[kSym]>(S_flat);
  const PetscReal trace_D = D[0] + D[1] + D[2];
  // 2 G D', constant over the step
  PetscReal Ddev2G[kSym];
  for (int k = 0; k < kSym; ++k) Ddev2G[k] = 2 * p.shear_modulus * (D[k] - (k < 3 ? trace_D / 3 : 0));
  PetscReal Ddev[kSym];
  for (int k = 0; k < kSym; ++k) Ddev[k] = D[k] - (k < 3 ? trace_D / 3 : 0);
  const CrackSpeeds speeds = Speeds(p, std::sqrt(Contract(Ddev, Ddev)));
  const PetscReal   mean_rate = p.bulk_modulus * trace_D;
  PetscReal         c = *crack_radius;

  // sub-steps only when the step asks for them: relaxation (RK4 accuracy) and crack growth
  PetscReal substeps = 1;
  if (p.max_relaxation_rate * dt > p.max_relaxation_per_substep) substeps = std::ceil(p.max_relaxation_rate * dt / p.max_relaxation_per_substep);
  PetscReal t_switch = -1, switch_time_scale = 0;
  bool      loading_crack = false; // K_I rises through K' in this step (else it falls through it)
  if (c > 0 && speeds.tension + speeds.compression > 0) {
    // the crack equations' own rate (CrackStiffness) times the sub-step below max_relaxation_per_substep,
    // at the start and at an elastic prediction of the end (a tension step may begin in compression)
    PetscReal sum[kSym] = {0, 0, 0, 0, 0, 0}, end[kSym];
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < kSym; ++k) sum[k] += S[i][k];
    for (int k = 0; k < kSym; ++k) end[k] = sum[k] + Ddev2G[k] * dt;
    const PetscReal mean_end  = mean_stress_old + mean_rate * dt;
    const PetscReal stiffness = std::fmax(CrackStiffness(p, speeds, Contract(sum, sum), mean_stress_old, c), CrackStiffness(p, speeds, Contract(end, end), mean_end, c));
    const PetscReal growth    = stiffness * dt / p.max_relaxation_per_substep;
    if (growth > substeps) substeps = std::ceil(growth);
    // and the crack speed, which loading changes too (through K_I), by at most r_v of itself per
    // sub-step (r_v = crack_rate_change_per_substep)
    const PetscReal rate0 = Rate(p, speeds, Contract(sum, sum), mean_stress_old, c), rate1 = Rate(p, speeds, Contract(end, end), mean_end, c);
    if (rate0 != rate1) {
      const PetscReal change = std::fabs(rate1 - rate0) / (p.crack_rate_change_per_substep * std::fmax(rate0, rate1));
      if (change > substeps) substeps = std::ceil(change);
    }
    // the growth law switches branch at K_I = K' (eq. 24; steep below, m = 10): a step whose
    // predicted K_I - K' changes sign gets a sub-step boundary there, and after it sub-steps that
    // start at r times the time K_I takes to change by K' and grow by half each (graded)
    const PetscReal f0 = StressIntensity(Contract(sum, sum), mean_stress_old, c) - ThresholdIntensity(p, mean_stress_old, c);
    const PetscReal f1 = StressIntensity(Contract(end, end), mean_end, c) - ThresholdIntensity(p, mean_end, c);
    if ((f0 < 0) != (f1 < 0) && f0 != f1) {
      t_switch          = dt * f0 / (f0 - f1);
      loading_crack     = f0 < 0;
      switch_time_scale = dt * ThresholdIntensity(p, mean_stress_old + mean_rate * t_switch, c) / std::fabs(f1 - f0);
    }
  }
  const PetscReal h_uniform = dt / (substeps > p.max_substeps ? p.max_substeps : substeps);

  // on the sub-critical side of the switch cdot goes as (K_I/K_1)^m, a power of t: 2m sub-steps
  // there (RK4 on t^10 over 20 sub-steps: 3e-4 of that side's growth)
  // Either refinement is skipped when the crack could not grow by 1e-6 c over the part it refines
  // (below K': at most v_r/(1 + m/2) times that part over m + 1; after the rise: about v_r times the
  // time K_I takes to change by K'), as when a step loads a crack from rest far past K'.
  bool            loading = t_switch > 0 && switch_time_scale > 0 && loading_crack;
  const PetscReal v_max   = std::fmax(speeds.tension, speeds.compression), m = p.crack_exponent;
  const PetscReal power_side = t_switch > 0 ? (loading ? t_switch : dt - t_switch) : 0;
  const PetscReal h_power = v_max * power_side / ((1 + m / 2) * (m + 1)) > 1e-6 * c ? power_side / std::fmin(2 * std::ceil(m), 100.0) : dt;
  if (loading && v_max * switch_time_scale < 1e-6 * c) loading = false, t_switch = -1;
  PetscReal       viscous = 0, crack = 0, t = 0, h_graded = p.crack_rate_change_per_substep * switch_time_scale;
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
    Evaluate(p, speeds, S, c, m0, Ddev2G, k1);
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < kSym; ++k) Y[i][k] = S[i][k] + 0.5 * h * k1.dS[i][k];
    Evaluate(p, speeds, Y, c + 0.5 * h * k1.dc, m0 + 0.5 * h * mean_rate, Ddev2G, k2);
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < kSym; ++k) Y[i][k] = S[i][k] + 0.5 * h * k2.dS[i][k];
    Evaluate(p, speeds, Y, c + 0.5 * h * k2.dc, m0 + 0.5 * h * mean_rate, Ddev2G, k3);
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < kSym; ++k) Y[i][k] = S[i][k] + h * k3.dS[i][k];
    Evaluate(p, speeds, Y, c + h * k3.dc, m0 + h * mean_rate, Ddev2G, k4);
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
  out->crack_rate          = Rate(p, speeds, Contract(out->deviator, out->deviator), out->mean_stress, c);
  out->substeps            = nsub;
}

} // namespace viscoscram
} // namespace burst
