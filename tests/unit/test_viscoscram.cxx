// Unit tests of the ViscoSCRAM point kernel (models/viscoscram/viscoscram.hpp) on plain arrays: no
// swarm, no grid. Each test derives its tolerance from the integrator's error and prints the figure
// it measured ("[ measured ]" lines). Parameters: the PBX 9501 set of
// options/materials/pbx9501_viscoscram.opts (G_i, 1/tau_i of Uintah's ViscoSCRAMPBX9501.xml).
//   FrozenCracks.*   cracks frozen at zero size (c = 0, v_max = 0): simple shear at constant rate from
//                    rest and a step strain against the closed-form Maxwell sums (mpmice-lessons.md
//                    ViscoSCRAM, test 1); observed order of the RK4 integrator from three dt; sub-steps
//   FrozenCrack.*    a frozen crack c = a/2, x = (c/a)^3 = 1/8: instantaneous shear modulus G/(1 + x)
//                    and relaxation rates divided by 1 + x (one element: closed form; five elements:
//                    the exact exponential of the linear system)
//   Energy.*         growing cracks in simple shear: the stress work (the Material interface's
//                    trapezoid, StressWork) equals the stored energy plus the viscous and crack
//                    dissipation, for both crack-heating choices; the temperature rise is the
//                    dissipation over rho c_v
//   ViscoScramMaterial.RigidRotationKeepsInvariants  the material (registry, state fields on plain arrays, the
//                    Green-Naghdi frame): a point loaded in uniaxial tension (cracks growing) and then
//                    spun rigidly keeps, to rounding, the stress of a twin that is not spun, rotated
//                    (so its invariants), its crack radius and its temperature
#include "viscoscram/viscoscram.hpp"
#include "material.hpp"
#include "unit_helpers.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <string>
#include <vector>

using namespace burst;
namespace vs = burst::viscoscram;

namespace {

const double kG[5]      = {3.5e8, 1.739e8, 5.212e8, 9.085e8, 6.875e8};
const double kLambda[5] = {0, 7.32e3, 7.32e4, 7.32e5, 2e6};

void Report(const std::string &what, double measured, double tol, const char *source)
{
  std::printf("[ measured ] %-66s %.3e (bound %.2e; %s)\n", what.c_str(), measured, tol, source);
  std::fflush(stdout);
}

vs::Parameters Pbx9501(bool cracks)
{
  vs::Parameters p;
  for (int i = 0; i < 5; ++i) p.shear_moduli[i] = kG[i], p.relaxation_rates[i] = kLambda[i];
  p.max_crack_speed            = cracks ? 300 : 0;
  p.max_relaxation_per_substep = 1e30; // no sub-steps unless a test asks for them
  p.Derive();
  p.bulk_modulus = 2 * p.shear_modulus * 1.3 / (3 * 0.4);
  return p;
}

// Runs nsteps of constant D from the element stresses S (in/out); returns sigma_xy after each step.
std::vector<double> Drive(const vs::Parameters &p, double *S, double c, const double D[6], double t_end, int nsteps, int *substeps = nullptr)
{
  std::vector<double> xy;
  vs::Result          r;
  for (int n = 0; n < nsteps; ++n) {
    vs::Update(p, S, &c, 0, D, t_end / nsteps, 1840, 300, &r);
    xy.push_back(r.deviator[3]);
    if (substeps) *substeps = r.substeps;
  }
  return xy;
}

// Shear at engineering rate gdot from rest: sigma_xy = gdot [G_1 t + sum_{i>=2} G_i tau_i (1 - e^{-t/tau_i})]
double ShearClosedForm(double gdot, double t)
{
  double s = 0;
  for (int i = 0; i < 5; ++i) s += kLambda[i] > 0 ? kG[i] / kLambda[i] * (1 - std::exp(-kLambda[i] * t)) : kG[i] * t;
  return gdot * s;
}

// Step strain gamma0: sigma_xy = gamma0 sum G_i e^{-t/tau_i}
double RelaxClosedForm(double gamma0, double t)
{
  double s = 0;
  for (int i = 0; i < 5; ++i) s += kG[i] * std::exp(-kLambda[i] * t);
  return gamma0 * s;
}

// The RK4 bound: for y' = -lambda y the local error is (lambda h)^5/120 of y, so over lambda t of
// relaxation the global error is below lambda t (lambda h)^4 / 120 of the fastest element's share.
double Rk4Bound(double lambda, double h, double t, double share) { return lambda * t * std::pow(lambda * h, 4) / 120 * share; }

} // namespace

TEST(ViscoScramFrozenCracks, SimpleShearAtConstantRate)
{
  const vs::Parameters p    = Pbx9501(false);
  const double         gdot = 1e3, t_end = 2e-6, D[6] = {0, 0, 0, 0.5 * gdot, 0, 0};
  const double         scale = ShearClosedForm(gdot, t_end);
  double               errors[3];
  const int            steps[3] = {8, 16, 32}; // lambda_5 dt = 0.5, 0.25, 0.125
  for (int k = 0; k < 3; ++k) {
    double S[30] = {};
    auto   xy    = Drive(p, S, 0, D, t_end, steps[k]);
    errors[k]    = 0;
    for (int n = 0; n < steps[k]; ++n) errors[k] = std::fmax(errors[k], std::fabs(xy[n] - ShearClosedForm(gdot, (n + 1) * t_end / steps[k])) / scale);
  }
  const double order1 = std::log2(errors[0] / errors[1]), order2 = std::log2(errors[1] / errors[2]);
  const double bound = Rk4Bound(2e6, t_end / 32, t_end, 1.0);
  Report("shear: max |sigma_xy - Maxwell sum| / sigma_xy(t_end), 32 steps", errors[2], bound, "RK4 bound lambda_5 t (lambda_5 h)^4/120");
  Report("shear: observed order 16 -> 32 steps (RK4: 4)", order2, 3.7, "lower bound");
  std::printf("[ measured ] errors %.3e %.3e %.3e, orders %.3f %.3f\n", errors[0], errors[1], errors[2], order1, order2);
  EXPECT_LT(errors[2], bound);
  EXPECT_GT(order1, 3.7);
  EXPECT_GT(order2, 3.7);
  EXPECT_LT(order2, 4.5);
}

TEST(ViscoScramFrozenCracks, StepStrainRelaxation)
{
  const vs::Parameters p      = Pbx9501(false);
  const double         gamma0 = 1e-3, t_end = 2e-6, D[6] = {0, 0, 0, 0, 0, 0};
  double               errors[3];
  const int            steps[3] = {8, 16, 32};
  for (int k = 0; k < 3; ++k) {
    double S[30] = {};
    for (int i = 0; i < 5; ++i) S[6 * i + 3] = kG[i] * gamma0; // the instantaneous response 2 G_i (gamma0/2)
    auto xy   = Drive(p, S, 0, D, t_end, steps[k]);
    errors[k] = 0;
    for (int n = 0; n < steps[k]; ++n) errors[k] = std::fmax(errors[k], std::fabs(xy[n] - RelaxClosedForm(gamma0, (n + 1) * t_end / steps[k])) / (p.shear_modulus * gamma0));
  }
  const double order1 = std::log2(errors[0] / errors[1]), order2 = std::log2(errors[1] / errors[2]);
  const double bound = Rk4Bound(2e6, t_end / 32, t_end, kG[4] / 2.6411e9);
  Report("step strain: max |sigma_xy - gamma0 sum G_i e^{-t/tau_i}| / (G gamma0), 32 steps", errors[2], bound, "RK4 bound, element 5's share");
  std::printf("[ measured ] errors %.3e %.3e %.3e, orders %.3f %.3f\n", errors[0], errors[1], errors[2], order1, order2);
  EXPECT_LT(errors[2], bound);
  EXPECT_GT(order1, 3.7);
  EXPECT_GT(order2, 3.7);
  EXPECT_LT(order2, 4.5);
}

// A step of lambda_5 dt = 8 is cut into sub-steps of lambda_5 h <= 0.5 (16 of them) and keeps the
// accuracy of those sub-steps; a step of lambda_5 dt = 0.16 (the exploding scenes' 8e-8 s) is not cut.
TEST(ViscoScramFrozenCracks, SubStepsOnlyWhenAsked)
{
  vs::Parameters p             = Pbx9501(false);
  p.max_relaxation_per_substep = 0.5;
  const double gdot = 1e3, D[6] = {0, 0, 0, 0.5 * gdot, 0, 0};
  double       S[30]    = {};
  int          substeps = 0;
  auto         xy       = Drive(p, S, 0, D, 4e-6, 1, &substeps);
  const double error    = std::fabs(xy[0] - ShearClosedForm(gdot, 4e-6)) / ShearClosedForm(gdot, 4e-6);
  const double bound    = Rk4Bound(2e6, 4e-6 / 16, 4e-6, 1.0);
  Report("one step of 4 us: sub-steps (lambda_5 dt / 0.5 = 16)", substeps, 16, "ceil(lambda_max dt / 0.5)");
  Report("one step of 4 us: |sigma_xy - Maxwell sum| / sigma_xy", error, bound, "RK4 bound at h = dt/16");
  EXPECT_EQ(substeps, 16);
  EXPECT_LT(error, bound);
  double S2[30] = {};
  Drive(p, S2, 0, D, 8e-8, 1, &substeps);
  EXPECT_EQ(substeps, 1);
}

// One element (G, 1/tau) with a frozen crack c = a/2: S' = (2 G D' - S/tau)/(1 + x), so the
// instantaneous modulus is G/(1 + x) and the relaxation rate 1/(tau (1 + x)):
// shear from rest sigma_xy = gdot G tau (1 - e^{-t/(tau (1 + x))}); step strain gamma0 G/(1 + x) e^{-t/(tau (1 + x))}.
TEST(ViscoScramFrozenCrack, OneElementClosedForm)
{
  vs::Parameters p  = Pbx9501(false);
  p.elements        = 1;
  p.shear_moduli[0] = 1e9, p.relaxation_rates[0] = 1e6;
  p.Derive();
  const double x = 0.125, c = 0.5 * p.crack_scale, gdot = 1e3, t_end = 4e-6, lambda_eff = 1e6 / (1 + x);
  // instantaneous modulus: a shear step of 1e-14 s (lambda dt = 1e-8)
  {
    double       S[30]   = {};
    const double D[6]    = {0, 0, 0, 0.5 * gdot, 0, 0};
    auto         xy      = Drive(p, S, c, D, 1e-14, 1);
    const double modulus = xy[0] / (gdot * 1e-14);
    const double error   = std::fabs(modulus / (1e9 / (1 + x)) - 1);
    Report("frozen crack: instantaneous modulus / (G/(1 + x)) - 1", error, 1e-7, "O(lambda dt) = 1e-8");
    EXPECT_LT(error, 1e-7);
  }
  double errors[2];
  for (int k = 0; k < 2; ++k) {
    const int    n     = 32 << k;
    double       S[30] = {};
    const double D[6]  = {0, 0, 0, 0.5 * gdot, 0, 0};
    auto         xy    = Drive(p, S, c, D, t_end, n);
    errors[k]          = 0;
    for (int j = 0; j < n; ++j) {
      const double t = (j + 1) * t_end / n;
      errors[k]      = std::fmax(errors[k], std::fabs(xy[j] - gdot * 1e9 / 1e6 * (1 - std::exp(-lambda_eff * t))) / (gdot * 1e3));
    }
  }
  const double bound = Rk4Bound(lambda_eff, t_end / 64, t_end, 1.0);
  Report("frozen crack, one element, shear: max error / (G tau gdot), 64 steps", errors[1], bound, "RK4 bound at lambda/(1 + x)");
  Report("frozen crack, one element, shear: observed order 32 -> 64", std::log2(errors[0] / errors[1]), 3.7, "RK4: 4");
  EXPECT_LT(errors[1], bound);
  EXPECT_GT(std::log2(errors[0] / errors[1]), 3.7);
  // step strain: S(0+) = G gamma0/(1 + x), then relaxation at lambda/(1 + x)
  {
    double       S[30]  = {};
    const double gamma0 = 1e-3, D[6] = {0, 0, 0, 0.5 * gamma0 / 1e-14, 0, 0}, D0[6] = {0, 0, 0, 0, 0, 0};
    Drive(p, S, c, D, 1e-14, 1);
    auto         xy    = Drive(p, S, c, D0, t_end, 64);
    const double exact = gamma0 * 1e9 / (1 + x) * std::exp(-lambda_eff * t_end), error = std::fabs(xy.back() / exact - 1);
    const double bound = Rk4Bound(lambda_eff, t_end / 64, t_end, 1.0) * std::exp(lambda_eff * t_end) + 1e-7;
    Report("frozen crack, one element, step strain: relative error at 4 us", error, bound, "RK4 bound relative to e^{-lambda t/(1+x)}, + O(lambda dt) of the step");
    EXPECT_LT(error, bound);
  }
}

// Five elements, frozen crack: a step strain gives S_i(0+) = G_i gamma0/(1 + x) and then the linear
// system S_i' = -lambda_i S_i + (G_i/G) (x/(1 + x)) sum_j lambda_j S_j, whose exact solution is the
// exponential of its 5x5 matrix (eigen-decomposition).
TEST(ViscoScramFrozenCrack, FiveElementsExactExponential)
{
  const vs::Parameters        p = Pbx9501(false);
  const double                x = 0.125, c = 0.5 * p.crack_scale, gamma0 = 1e-3, t_end = 2e-6, G = p.shear_modulus;
  Eigen::Matrix<double, 5, 5> A;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) A(i, j) = (i == j ? -kLambda[i] : 0) + kG[i] / G * x / (1 + x) * kLambda[j];
  Eigen::Matrix<double, 5, 1> y0;
  for (int i = 0; i < 5; ++i) y0(i) = kG[i] * gamma0 / (1 + x);
  Eigen::EigenSolver<Eigen::Matrix<double, 5, 5>> eig(A);
  const Eigen::Matrix<std::complex<double>, 5, 5> V    = eig.eigenvectors();
  const Eigen::Matrix<std::complex<double>, 5, 1> coef = V.fullPivLu().solve(y0.cast<std::complex<double>>());

  auto exact = [&](double t) {
    std::complex<double> s = 0;
    for (int k = 0; k < 5; ++k) s += coef(k) * std::exp(eig.eigenvalues()(k) * t) * V.col(k).sum();
    return s.real();
  };
  // instantaneous modulus
  double       S[30] = {};
  const double D[6] = {0, 0, 0, 0.5 * gamma0 / 1e-14, 0, 0}, D0[6] = {0, 0, 0, 0, 0, 0};
  auto         xy0       = Drive(p, S, c, D, 1e-14, 1);
  const double e_modulus = std::fabs(xy0[0] / (gamma0 * G / (1 + x)) - 1);
  Report("frozen crack, five elements: sigma_xy(0+) / (G gamma0/(1 + x)) - 1", e_modulus, 1e-7, "O(lambda_5 dt) = 2e-8");
  EXPECT_LT(e_modulus, 1e-7);
  // initial relaxation rate: sigma' = -sum lambda_j S_j/(1 + x)
  double rate_exact = 0;
  for (int i = 0; i < 5; ++i) rate_exact -= kLambda[i] * kG[i] * gamma0 / (1 + x) / (1 + x);
  double S1[30];
  for (int k = 0; k < 30; ++k) S1[k] = S[k];
  const double h      = 1e-12;
  auto         xy1    = Drive(p, S1, c, D0, h, 1);
  const double e_rate = std::fabs((xy1[0] - xy0[0]) / h / rate_exact - 1);
  Report("frozen crack, five elements: initial relaxation rate / closed form - 1", e_rate, 1e-5, "O(lambda_5 h) = 2e-6");
  EXPECT_LT(e_rate, 1e-5);
  // the whole relaxation curve
  auto   xy    = Drive(p, S, c, D0, t_end, 64);
  double error = 0;
  for (int n = 0; n < 64; ++n) error = std::fmax(error, std::fabs(xy[n] - exact((n + 1) * t_end / 64)) / (G * gamma0));
  const double bound = Rk4Bound(2e6, t_end / 64, t_end, 1.0) + 1e-7;
  Report("frozen crack, five elements: max |sigma_xy - exp(A t) S(0+)| / (G gamma0)", error, bound, "RK4 bound + O(lambda_5 dt) of the step");
  EXPECT_LT(error, bound);
}

// Growing cracks in simple shear at 1e4 /s for 5 us (c from 30 um to about 1 mm: x from 3e-5 to
// order 1): W = sum_n (S_n + S_{n+1})/2 : D' dt (the trapezoid of the interface's StressWork) against
// stored + viscous + crack. The trapezoid's error is dt^2/12 times the integral of S'':D'; that
// estimate, from the run's own second differences, bounds the mismatch (twice it, plus rounding),
// and the mismatch falls at second order.
TEST(ViscoScramEnergy, StressWorkEqualsStoredPlusDissipated)
{
  for (vs::CrackHeating heating : {vs::CrackHeating::CrackWork, vs::CrackHeating::Release}) {
    vs::Parameters p  = Pbx9501(true);
    p.crack_heating   = heating;
    p.gruneisen       = 1.0; // no volume change: no thermoelastic term
    const char  *name = heating == vs::CrackHeating::CrackWork ? "crack_work" : "release";
    const double gdot = 1e4, t_end = 5e-6, D[6] = {0, 0, 0, 0.5 * gdot, 0, 0}, rho = 1840;
    double       mismatch[2], estimate[2], dissipated_share = 0, crack_share = 0, c_end = 0;
    for (int k = 0; k < 2; ++k) {
      const int           n     = 1000 << k;
      const double        dt    = t_end / n;
      double              S[30] = {}, c = 3e-5, work = 0, viscous = 0, crack = 0, dT = 0, s_old = 0, d2 = 0;
      std::vector<double> s(1, 0.0);
      vs::Result          r;
      for (int j = 0; j < n; ++j) {
        vs::Update(p, S, &c, 0, D, dt, rho, 300, &r);
        work += 2 * 0.5 * (s_old + r.deviator[3]) * D[3] * dt; // S:D' = 2 S_xy D_xy
        s_old = r.deviator[3];
        s.push_back(s_old);
        viscous += r.viscous_dissipation;
        crack += r.crack_dissipation;
        dT += r.temperature_change;
      }
      for (int j = 1; j < n; ++j) d2 += (s[j + 1] - 2 * s[j] + s[j - 1]) / (dt * dt) * 2 * D[3] * dt;
      const double stored = vs::StoredEnergy(p, S, c);
      mismatch[k]         = std::fabs(work - stored - viscous - crack) / work;
      estimate[k]         = dt * dt / 12 * std::fabs(d2) / work;
      dissipated_share    = (viscous + crack) / work;
      crack_share         = crack / work;
      c_end               = c;
      const double e_T    = std::fabs(dT - (viscous + crack) / (rho * p.specific_heat)) / dT;
      Report(std::string(name) + ": |dT - dissipated/(rho c_v)| / dT", e_T, 1e-12, "rounding");
      EXPECT_LT(e_T, 1e-12);
    }
    std::printf("[ measured ] %s: c_end %.3e m, dissipated %.3f of the work (crack %.3f)\n", name, c_end, dissipated_share, crack_share);
    Report(std::string(name) + ": |W - stored - dissipated| / W at 2000 steps", mismatch[1], 2 * estimate[1] + 1e-12, "trapezoid error dt^2/12 |int S'':D'|");
    Report(std::string(name) + ": order of the mismatch 1000 -> 2000 steps", std::log2(mismatch[0] / mismatch[1]), 1.8, "trapezoid: 2");
    EXPECT_LT(mismatch[1], 2 * estimate[1] + 1e-12);
    EXPECT_GT(std::log2(mismatch[0] / mismatch[1]), 1.8);
    EXPECT_GT(c_end, 3e-4); // the cracks did grow (the test can see the crack terms)
    EXPECT_GT(crack_share, 0.01);
  }
}

// Two points on plain arrays: 20 steps of uniaxial strain at
// 1e3 /s (strain 1e-3, cracks growing in tension), then 40 steps in which point 0 spins at 1e6 rad/s
// (L = W exactly, F = R(theta) F_load exactly: 2 rad) and point 1 stands still (L = 0). With D = 0
// exactly both see the same co-rotated rate, so sigma_0 = R sigma_1 R^T to rounding: the same
// invariants, crack radius and temperature.
TEST(ViscoScramMaterial, RigidRotationKeepsInvariants)
{
  using M3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
  ScopedOptions opt;
  opt.Set("-vsr_model", "viscoscram");
  opt.Set("-vsr_density", "1840");
  Material *material = nullptr;
  ASSERT_EQ(MaterialCreate(PETSC_COMM_WORLD, "vsr", &material), 0);
  material->id_ = 0;
  // two points on plain arrays, the state in MaterialStateStorage
  const double         V0 = 1e-9;
  PetscReal            Fp[18]{}, sigma_p[18]{}, Lp[18]{}, m[2], V[2], Vr[2], T[2], c[2]{}, e[2]{};
  PetscInt             mat[2] = {0, 0};
  PetscInt64           pid[2] = {0, 1};
  MaterialStateStorage storage;
  ASSERT_EQ(storage.Allocate(material->StateFields(), 2), 0);
  for (int p = 0; p < 2; ++p) {
    for (int a = 0; a < 9; ++a) Fp[9 * p + a] = (a % 4 == 0) ? 1 : 0;
    V[p] = Vr[p] = V0;
    m[p]         = 1840 * V0;
    T[p]         = 300;
  }
  MaterialPointFields mp;
  mp.n = 2, mp.material = mat, mp.L = Lp, mp.F = Fp, mp.stress = sigma_p, mp.mass = m, mp.volume = V, mp.volume0 = Vr, mp.temperature = T, mp.wave_speed = c, mp.internal_energy = e, mp.id = pid, mp.state = &storage.State();
  ASSERT_EQ(material->InitializeState(mp, 0, 2), 0);
  const double rate = 1e3, omega = 1e6, dt = 5e-8;
  M3           F_load = M3::Identity();

  auto step = [&](const M3 L[2], const M3 F[2], double t) {
    for (int p = 0; p < 2; ++p) {
      Eigen::Map<M3>(Lp + 9 * p) = L[p];
      Eigen::Map<M3>(Fp + 9 * p) = F[p];
      V[p]                       = V0 * F[p].determinant();
    }
    mp.time = t;
    EXPECT_EQ(material->UpdateStress(mp, 0, dt), 0);
  };
  double t = 0;
  for (int n = 0; n < 20; ++n) {
    t += dt;
    F_load(0, 0)   = 1 + rate * t;
    const M3 L[2]  = {M3::Zero(), M3::Zero()};
    M3       Ls[2] = {L[0], L[1]};
    Ls[0](0, 0) = Ls[1](0, 0) = rate / F_load(0, 0); // L = Fdot F^-1 of F = diag(1 + rate t, 1, 1)
    const M3 F[2]             = {F_load, F_load};
    step(Ls, F, t);
  }
  double theta = 0;
  for (int n = 0; n < 40; ++n) {
    t += dt;
    theta += omega * dt;
    M3 W = M3::Zero(), R = M3::Identity();
    W(0, 1) = -omega, W(1, 0) = omega;
    R(0, 0) = R(1, 1) = std::cos(theta);
    R(0, 1) = -std::sin(theta), R(1, 0) = std::sin(theta);
    const M3 L[2] = {W, M3::Zero()}, F[2] = {R * F_load, F_load};
    step(L, F, t);
  }
  M3 R    = M3::Identity();
  R(0, 0) = R(1, 1) = std::cos(theta);
  R(0, 1) = -std::sin(theta), R(1, 0) = std::sin(theta);
  PetscReal *crack = nullptr;
  ASSERT_EQ(storage.State().Get("crack_radius", &crack), 0);
  const M3                          spun = Eigen::Map<M3>(sigma_p), still = Eigen::Map<M3>(sigma_p + 9);
  const double                      c_spun = crack[0], c_still = crack[1], T_spun = T[0], T_still = T[1];
  const double                      scale = still.cwiseAbs().maxCoeff();
  Eigen::SelfAdjointEigenSolver<M3> e_spun(spun), e_still(still);
  const double                      err_tensor = (R.transpose() * spun * R - still).cwiseAbs().maxCoeff() / scale;
  const double                      err_eigen  = (e_spun.eigenvalues() - e_still.eigenvalues()).cwiseAbs().maxCoeff() / scale;
  std::printf("[ measured ] loaded to sigma_xx %.4e Pa, crack %.3e m (from 3e-5), spun by %.1f rad\n", still(0, 0), c_still, theta);
  Report("rigid spin: max |R^T sigma R - sigma_still| / |sigma|", err_tensor, 1e-12, "rounding (D = 0 exactly: same kernel input)");
  Report("rigid spin: principal stresses, max difference / |sigma|", err_eigen, 1e-12, "rounding");
  Report("rigid spin: |c - c_still| / c, |T - T_still| / T", std::fmax(std::fabs(c_spun - c_still) / c_still, std::fabs(T_spun - T_still) / T_still), 1e-14, "rounding");
  EXPECT_LT(err_tensor, 1e-12);
  EXPECT_LT(err_eigen, 1e-12);
  EXPECT_LT(std::fabs(c_spun - c_still) / c_still, 1e-14);
  EXPECT_LT(std::fabs(T_spun - T_still) / T_still, 1e-14);
  EXPECT_GT(c_still, 3.5e-5); // the cracks grew: the check sees the crack state too
  delete material;
}
