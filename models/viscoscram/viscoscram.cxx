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
  if (c > 0 && speeds.tension + speeds.compression > 0) {
    // crack growth per sub-step <= r c, with the rate at the start and at an elastic prediction of
    // the end (a tension step may begin in compression), and the change of K_I per sub-step
    // <= r max(K_I, K'): the growth law switches branch at K_I = K' and is steep below it (m = 10),
    // so a step that loads a crack from rest is resolved (r = max_crack_growth_per_substep)
    PetscReal sum[kSym] = {0, 0, 0, 0, 0, 0}, end[kSym];
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < kSym; ++k) sum[k] += S[i][k];
    for (int k = 0; k < kSym; ++k) end[k] = sum[k] + Ddev2G[k] * dt;
    const PetscReal mean_end = mean_stress_old + mean_rate * dt;
    const PetscReal rate0 = Rate(p, speeds, Contract(sum, sum), mean_stress_old, c), rate1 = Rate(p, speeds, Contract(end, end), mean_end, c);
    const PetscReal growth = std::fmax(rate0, rate1) * dt / (p.max_crack_growth_per_substep * c);
    if (growth > substeps) substeps = std::ceil(growth);
    const PetscReal K_I0 = StressIntensity(Contract(sum, sum), mean_stress_old, c), K_I1 = StressIntensity(Contract(end, end), mean_end, c);
    const PetscReal K_ref   = std::fmax(std::fmin(K_I0, K_I1), ThresholdIntensity(p, std::fmin(mean_stress_old, mean_end), c));
    const PetscReal loading = std::fabs(K_I1 - K_I0) / (p.max_crack_growth_per_substep * K_ref);
    if (loading > substeps) substeps = std::ceil(loading);
  }
  const int nsub = substeps > p.max_substeps ? p.max_substeps : (int)substeps;
  const PetscReal h = dt / nsub;

  PetscReal viscous = 0, crack = 0;
  Rates     k1, k2, k3, k4;
  PetscReal Y[kMaxElements][kSym];
  for (int step = 0; step < nsub; ++step) {
    const PetscReal m0 = mean_stress_old + mean_rate * step * h;
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
