// Unit tests of the material models (models/elastic/*.cxx) created through the registry
// (models/registry.cxx): stresses against hand-computed values, objectivity, and the input checks.
// main() is in unit_main.cxx: it initialises PETSc (the registry reads PETSc options).
//
// Every test prints the figure it measured ("[ measured ]" lines) and the source of the expected value.
//
// Elastic constants used throughout: E = 1000 Pa, nu = 0.3, rho = 2000 kg/m^3, so
//   mu     = E / (2 (1 + nu))              = 384.615384615384615 Pa
//   lambda = E nu / ((1 + nu)(1 - 2 nu))   = 576.923076923076923 Pa
//   c      = sqrt((lambda + 2 mu) / rho)   = 0.820412654142366990 m/s
// (evaluated with 30-digit arithmetic).
#include "material.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <random>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>
#include "unit_helpers.hpp"

using namespace burst;

namespace {

constexpr double kMu = 384.615384615384615, kLambda = 576.923076923076923, kRho = 2000.0;
constexpr double kWaveSpeed = 0.820412654142366990;

using M3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

void Report(const std::string &what, double measured, double tol, const char *source)
{
  std::printf("[ measured ] %-62s %.3e (tolerance %.1e; source: %s)\n", what.c_str(), measured, tol, source);
  std::fflush(stdout);
}

void ReportCode(const std::string &what, PetscErrorCode measured, PetscErrorCode expected, const char *source)
{
  std::printf("[ measured ] %-62s %d (expected %d; source: %s)\n", what.c_str(), (int)measured, (int)expected, source);
  std::fflush(stdout);
}

// Owns the arrays of a few material points and hands them out as MaterialPointFields.
struct Points {
  explicit Points(PetscInt n) : n(n), material(n, 0), L(9 * n, 0.0), F(9 * n, 0.0), stress(9 * n, 0.0), mass(n, 2e-3), volume(n, 1e-6), temperature(n, 293.0), wave_speed(n, -1.0), energy(n, 0.0)
  {
    for (PetscInt p = 0; p < n; ++p) { SetF(p, M3::Identity()); }
  }
  MaterialPointFields Fields()
  {
    MaterialPointFields f;
    f.n               = n;
    f.material        = material.data();
    f.L               = L.data();
    f.F               = F.data();
    f.stress          = stress.data();
    f.mass            = mass.data();
    f.volume          = volume.data();
    f.temperature     = temperature.data();
    f.wave_speed      = wave_speed.data();
    f.internal_energy = energy.data();
    return f;
  }
  void SetF(PetscInt p, const M3 &m) { Eigen::Map<M3>(F.data() + 9 * p) = m; }
  void SetL(PetscInt p, const M3 &m) { Eigen::Map<M3>(L.data() + 9 * p) = m; }
  void SetStress(PetscInt p, const M3 &m) { Eigen::Map<M3>(stress.data() + 9 * p) = m; }
  M3   Stress(PetscInt p) const { return Eigen::Map<const M3>(stress.data() + 9 * p); }

  PetscInt               n;
  std::vector<PetscInt>  material;
  std::vector<PetscReal> L, F, stress, mass, volume, temperature, wave_speed, energy;
};

// Creates material `name` with E = 1000, nu = 0.3, rho = 2000 and the given model.
Material *CreateReference(ScopedOptions &opt, const std::string &name, const std::string &model)
{
  opt.Material(name, model, "2000", "1000", "0.3");
  Material *m = nullptr;
  EXPECT_EQ(MaterialCreate(PETSC_COMM_WORLD, name.c_str(), &m), 0);
  return m;
}

M3 M3of(double a00, double a01, double a02, double a10, double a11, double a12, double a20, double a21, double a22)
{
  M3 m;
  m << a00, a01, a02, a10, a11, a12, a20, a21, a22;
  return m;
}

M3 Rotation(double angle, Eigen::Vector3d axis) { return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(); }

double MaxAbs(const M3 &m) { return m.cwiseAbs().maxCoeff(); }

// Calls the error-returning handler around a call that is expected to fail, so PETSc returns the
// error code instead of aborting (and prints nothing).
PetscErrorCode CreateExpectingError(const std::string &name, Material **m)
{
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  const PetscErrorCode rc = MaterialCreate(PETSC_COMM_WORLD, name.c_str(), m);
  PetscPopErrorHandler();
  return rc;
}

} // namespace

// ---------------------------------------------------------------------------------------------------
// neo_hookean: sigma = (lambda ln J / J) I + (mu / J)(B - I), B = F F^T (Simo & Pister; the header of
// neo_hookean.cxx). Expected values evaluated by hand (30-digit arithmetic):
//   F = diag(1.1, 1, 1): J = 1.1, ln J = 0.0953101798043248600
//     sigma_xx = lambda ln J / J + mu (1.21 - 1) / J = 123.414429967303248 Pa
//     sigma_yy = sigma_zz = lambda ln J / J          =  49.987856540729822 Pa
//   simple shear F = I + 0.2 e_x (x) e_y: J = 1, B - I = [[0.04, 0.2, 0], [0.2, 0, 0], [0, 0, 0]]
//     sigma_xx = 0.04 mu = 15.384615384615385 Pa, sigma_xy = sigma_yx = 0.2 mu = 76.923076923076923 Pa
TEST(NeoHookean, HandComputedStress)
{
  ScopedOptions opt;
  Material     *m = CreateReference(opt, "nh_hand", "neo_hookean");
  ASSERT_NE(m, nullptr);
  EXPECT_STREQ(m->Model(), "neo_hookean");
  EXPECT_EQ(m->Density(), 2000.0);

  Points pts(3);
  pts.SetF(0, M3of(1.1, 0, 0, 0, 1, 0, 0, 0, 1));
  pts.SetF(1, M3of(1, 0.2, 0, 0, 1, 0, 0, 0, 1));
  pts.SetF(2, M3of(1.1, 0, 0, 0, 1, 0, 0, 0, 1));
  pts.material[2] = 1; // another material: must be left alone
  pts.SetStress(2, M3::Constant(7.0));
  ASSERT_EQ(m->UpdateStress(pts.Fields(), 0, 1e-3), 0);

  const M3     expect0 = M3of(123.414429967303248, 0, 0, 0, 49.987856540729822, 0, 0, 0, 49.987856540729822);
  const M3     expect1 = M3of(15.384615384615385, 76.923076923076923, 0, 76.923076923076923, 0, 0, 0, 0, 0);
  const double err0 = MaxAbs(pts.Stress(0) - expect0) / kMu, err1 = MaxAbs(pts.Stress(1) - expect1) / kMu;
  std::printf("  F = diag(1.1,1,1): sigma_xx = %.15g, sigma_yy = %.15g Pa\n", pts.Stress(0)(0, 0), pts.Stress(0)(1, 1));
  std::printf("  simple shear 0.2:  sigma_xx = %.15g, sigma_xy = %.15g Pa\n", pts.Stress(1)(0, 0), pts.Stress(1)(0, 1));
  Report("neo-Hookean F=diag(1.1,1,1): max |sigma - hand| / mu", err0, 1e-13, "hand: Simo-Pister neo-Hookean");
  Report("neo-Hookean simple shear 0.2: max |sigma - hand| / mu", err1, 1e-13, "hand: Simo-Pister neo-Hookean");
  EXPECT_LE(err0, 1e-13);
  EXPECT_LE(err1, 1e-13);
  EXPECT_EQ(MaxAbs(pts.Stress(2) - M3::Constant(7.0)), 0.0) << "particle of material 1 was changed";
  EXPECT_EQ(pts.wave_speed[2], -1.0);
  delete m;
}

// Objectivity: sigma(R F) = R sigma(F) R^T for rotations R, for a general F (det F = 1.16...).
TEST(NeoHookean, Objectivity)
{
  ScopedOptions opt;
  Material     *m = CreateReference(opt, "nh_obj", "neo_hookean");
  ASSERT_NE(m, nullptr);
  const M3 F    = M3of(1.08, 0.13, -0.05, 0.02, 0.95, 0.21, -0.07, 0.04, 1.12);
  const M3 R[3] = {Rotation(0.7, {1, 2, 3}), Rotation(2.9, {-1, 0.5, 0.2}), Rotation(M_PI / 2, {0, 0, 1})};

  Points pts(4);
  pts.SetF(0, F);
  for (int r = 0; r < 3; ++r) pts.SetF(1 + r, R[r] * F);
  ASSERT_EQ(m->UpdateStress(pts.Fields(), 0, 1e-3), 0);
  const M3 s   = pts.Stress(0);
  double   err = 0, asym = 0;
  for (int r = 0; r < 3; ++r) err = std::max(err, MaxAbs(pts.Stress(1 + r) - R[r] * s * R[r].transpose()) / MaxAbs(s));
  for (int p = 0; p < 4; ++p) asym = std::max(asym, MaxAbs(pts.Stress(p) - pts.Stress(p).transpose()) / MaxAbs(s));
  Report("neo-Hookean: max |sigma(RF) - R sigma(F) R^T| / |sigma|", err, 1e-13, "objectivity of hyperelasticity");
  Report("neo-Hookean: max |sigma - sigma^T| / |sigma|", asym, 1e-14, "balance of angular momentum");
  EXPECT_LE(err, 1e-13);
  EXPECT_LE(asym, 1e-14);
  delete m;
}

// The stress is the one derived from the stored energy stated in neo_hookean.cxx,
//   W(F) = mu/2 (tr B - 3) - mu ln J + lambda/2 (ln J)^2,  sigma = (1/J) (dW/dF) F^T,
// with dW/dF by central differences (step 1e-6): checks the stress formula independently of the
// closed form above.
TEST(NeoHookean, StressDerivesFromEnergy)
{
  ScopedOptions opt;
  Material     *m = CreateReference(opt, "nh_energy", "neo_hookean");
  ASSERT_NE(m, nullptr);
  auto W = [](const M3 &F) {
    const double lnJ = std::log(F.determinant());
    return 0.5 * kMu * ((F * F.transpose()).trace() - 3) - kMu * lnJ + 0.5 * kLambda * lnJ * lnJ;
  };
  const M3 Fs[2] = {M3of(1.08, 0.13, -0.05, 0.02, 0.95, 0.21, -0.07, 0.04, 1.12), M3of(0.7, 0.3, 0, -0.2, 0.9, 0.1, 0.05, 0, 0.6)};

  Points pts(2);
  for (int p = 0; p < 2; ++p) pts.SetF(p, Fs[p]);
  ASSERT_EQ(m->UpdateStress(pts.Fields(), 0, 1e-3), 0);
  double err = 0;
  for (int p = 0; p < 2; ++p) {
    M3           P;
    const double step = 1e-6;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        M3 Fp = Fs[p], Fm = Fs[p];
        Fp(i, j) += step;
        Fm(i, j) -= step;
        P(i, j) = (W(Fp) - W(Fm)) / (2 * step);
      }
    const M3 sigma = P * Fs[p].transpose() / Fs[p].determinant();
    err            = std::max(err, MaxAbs(pts.Stress(p) - sigma) / kMu);
  }
  Report("neo-Hookean: max |sigma - (1/J) dW/dF F^T| / mu (FD)", err, 1e-7, "energy in neo_hookean.cxx");
  EXPECT_LE(err, 1e-7);
  delete m;
}

// Undeformed: zero stress and the longitudinal wave speed sqrt((lambda + 2 mu)/rho).
TEST(NeoHookean, ReferenceStateAndWaveSpeed)
{
  ScopedOptions opt;
  Material     *m = CreateReference(opt, "nh_ref", "neo_hookean");
  ASSERT_NE(m, nullptr);
  Points pts(1);
  ASSERT_EQ(m->ComputeWaveSpeed(pts.Fields(), 0), 0);
  const double c0 = pts.wave_speed[0];
  ASSERT_EQ(m->UpdateStress(pts.Fields(), 0, 1e-3), 0);
  const double err_c = std::max(std::fabs(c0 - kWaveSpeed), std::fabs(pts.wave_speed[0] - kWaveSpeed)) / kWaveSpeed;
  std::printf("  wave speed: ComputeWaveSpeed %.15g, UpdateStress %.15g m/s (hand 0.820412654142367)\n", c0, pts.wave_speed[0]);
  Report("neo-Hookean F=I: max |sigma| / mu", MaxAbs(pts.Stress(0)) / kMu, 1e-15, "stress-free reference state");
  Report("neo-Hookean F=I: |c - sqrt((lambda+2mu)/rho)| / c", err_c, 1e-14, "hand: linearised elasticity");
  EXPECT_LE(MaxAbs(pts.Stress(0)) / kMu, 1e-15);
  EXPECT_LE(err_c, 1e-14);
  delete m;
}

// ---------------------------------------------------------------------------------------------------
// linear_elastic (hypoelastic, Jaumann rate): sigma += dt [lambda tr(D) I + 2 mu D + W sigma - sigma W].

// Uniaxial strain rate L = diag(e, 0, 0), e = 2 /s, dt = 1e-4 s, from zero stress:
//   sigma_xx = (lambda + 2 mu) e dt = 1346.153846153846 * 2e-4 = 0.26923076923076923 Pa
//   sigma_yy = sigma_zz = lambda e dt = 576.923076923077 * 2e-4 = 0.11538461538461538 Pa
// stress work 0.5 (0 + sigma_xx) e dt V_mid with V_mid = V (1 - tr(D) dt/2) (StressWork in material.hpp).
TEST(LinearElastic, UniaxialStrain)
{
  ScopedOptions opt;
  Material     *m = CreateReference(opt, "le_uni", "linear_elastic");
  ASSERT_NE(m, nullptr);
  const double e = 2.0, dt = 1e-4;

  Points pts(2);
  for (int p = 0; p < 2; ++p) {
    pts.SetL(p, M3of(e, 0, 0, 0, 0, 0, 0, 0, 0));
    pts.SetF(p, M3of(1 + e * dt, 0, 0, 0, 1, 0, 0, 0, 1));
  }
  pts.material[1] = 3; // another material: untouched
  ASSERT_EQ(m->UpdateStress(pts.Fields(), 0, dt), 0);
  const M3     expect = M3of(0.26923076923076923, 0, 0, 0, 0.11538461538461538, 0, 0, 0, 0.11538461538461538);
  const double err    = MaxAbs(pts.Stress(0) - expect) / 0.26923076923076923;
  const double V_mid = 1e-6 * (1 - 0.5 * e * dt), dE = 0.5 * 0.26923076923076923 * e * dt * V_mid;
  const double err_E = std::fabs(pts.energy[0] - dE) / dE;
  std::printf("  sigma_xx = %.15g, sigma_yy = %.15g Pa; work = %.6e J (hand %.6e)\n", pts.Stress(0)(0, 0), pts.Stress(0)(1, 1), pts.energy[0], dE);
  Report("linear elastic uniaxial strain: max |sigma - hand| / sigma_xx", err, 1e-13, "hand: Hooke's law, (lambda+2mu) e dt, lambda e dt");
  Report("linear elastic uniaxial strain: |work - hand| / work", err_E, 1e-12, "hand: midpoint stress power (material.hpp)");
  EXPECT_LE(err, 1e-13);
  EXPECT_LE(err_E, 1e-12);
  EXPECT_EQ(MaxAbs(pts.Stress(1)), 0.0);
  EXPECT_EQ(pts.energy[1], 0.0);
  EXPECT_EQ(pts.wave_speed[1], -1.0);
  delete m;
}

// Pure spin L = [[0, w, 0], [-w, 0, 0], [0, 0, 0]] (D = 0):
//  - from zero stress the stress stays exactly zero (200 steps) and no work is done;
//  - from sigma = diag(s, 0, 0) one step rotates the stress by the Hughes-Winget (Cayley) rotation
//    Q = (I - W dt/2)^{-1} (I + W dt/2): a rotation by phi = 2 atan(w dt/2) about z, so
//    sigma = s [[cos^2 phi, -sin phi cos phi], [-sin phi cos phi, sin^2 phi]]; s = 100 Pa, w = 3 /s,
//    dt = 1e-3 s: sigma_xy = -0.299999550... Pa (first order: -s w dt = -0.3, the Jaumann rate), and
//    the invariants (trace, Frobenius norm) are unchanged to round-off because Q is orthogonal.
TEST(LinearElastic, PureSpin)
{
  ScopedOptions opt;
  Material     *m = CreateReference(opt, "le_spin", "linear_elastic");
  ASSERT_NE(m, nullptr);
  const double w = 3.0, dt = 1e-3;

  Points pts(2);
  for (int p = 0; p < 2; ++p) pts.SetL(p, M3of(0, w, 0, -w, 0, 0, 0, 0, 0));
  pts.SetStress(1, M3of(100, 0, 0, 0, 0, 0, 0, 0, 0));
  ASSERT_EQ(m->UpdateStress(pts.Fields(), 0, dt), 0);
  const double phi = 2 * std::atan(0.5 * w * dt), c = std::cos(phi), sn = std::sin(phi);
  const M3     expect1 = M3of(100 * c * c, -100 * sn * c, 0, -100 * sn * c, 100 * sn * sn, 0, 0, 0, 0);
  const M3     s1      = pts.Stress(1);
  const double err1    = MaxAbs(s1 - expect1) / 100;
  for (int step = 1; step < 200; ++step) ASSERT_EQ(m->UpdateStress(pts.Fields(), 0, dt), 0);
  std::printf("  prestressed, one step: sigma_xy = %.15g, sigma_yx = %.15g Pa (hand %.15g; Jaumann first order -0.3)\n", s1(0, 1), s1(1, 0), -100 * sn * c);
  const double err_norm = std::fabs(s1.norm() - 100) / 100;
  Report("linear elastic spin of diag(100,0,0): | |sigma| - 100 | / 100", err_norm, 1e-14, "Q orthogonal: invariants kept");
  EXPECT_LE(err_norm, 1e-14);
  Report("linear elastic spin from zero stress (200 steps): max |sigma|", MaxAbs(pts.Stress(0)), 0.0, "D = 0: no stress rate");
  Report("linear elastic spin from zero stress: |work|", std::fabs(pts.energy[0]), 0.0, "D = 0: no stress power");
  Report("linear elastic spin of diag(100,0,0): max |sigma - hand| / 100", err1, 1e-14, "hand: Hughes-Winget rotation by 2 atan(w dt/2)");
  EXPECT_EQ(MaxAbs(pts.Stress(0)), 0.0);
  EXPECT_EQ(pts.energy[0], 0.0);
  EXPECT_LE(err1, 1e-14);
  delete m;
}

// The plane path of linear_elastic (a point without out-of-plane shear, 2-D plane strain) is the
// general update with its zero terms left out: the same bits. Point 0 has a plane state and takes that
// path; point 1 has the same state plus sigma_xz = sigma_zx = 1e-300 Pa, which sends it through the
// general path while changing no in-plane value (every product with it meets an exactly zero rotation
// or rate entry). Over 50 steps of random plane L (stretch, shear and spin), the in-plane stresses,
// sigma_zz, the work and the wave speed must agree bit for bit.
TEST(LinearElastic, PlaneMatchesGeneral)
{
  ScopedOptions opt;
  Material     *m = CreateReference(opt, "le_plane", "linear_elastic");
  ASSERT_NE(m, nullptr);
  std::mt19937_64                        rng(2026);
  std::uniform_real_distribution<double> u(-50.0, 50.0);
  const double                           dt = 1e-4;

  Points pts(2);
  pts.SetStress(0, M3of(3, 1.5, 0, 1.5, -2, 0, 0, 0, 0.7));
  pts.SetStress(1, M3of(3, 1.5, 1e-300, 1.5, -2, 0, 1e-300, 0, 0.7));
  long differing = 0;
  for (int step = 0; step < 50; ++step) {
    const M3 L = M3of(u(rng), u(rng), 0, u(rng), u(rng), 0, 0, 0, 0);
    pts.SetL(0, L);
    pts.SetL(1, L);
    ASSERT_EQ(m->UpdateStress(pts.Fields(), 0, dt), 0);
    for (int e : {0, 1, 3, 4, 8}) differing += pts.stress[e] != pts.stress[9 + e];
    differing += pts.energy[0] != pts.energy[1];
    differing += pts.wave_speed[0] != pts.wave_speed[1];
  }
  std::printf("  after 50 steps: sigma_xx %.17g, sigma_xy %.17g, sigma_zz %.17g Pa, sigma_xz of the general point %.3g Pa\n", pts.stress[0], pts.stress[1], pts.stress[8], pts.stress[9 + 2]);
  Report("linear elastic plane path against the general one: differing values", (double)differing, 0.0, "the same expressions without their zero terms");
  EXPECT_EQ(differing, 0);
  EXPECT_NE(pts.stress[0], 3.0); // the state did change
  delete m;
}

// Wave speed sqrt((lambda + 2 mu)/rho) = 0.820412654142367 m/s at F = I.
TEST(LinearElastic, WaveSpeed)
{
  ScopedOptions opt;
  Material     *m = CreateReference(opt, "le_wave", "linear_elastic");
  ASSERT_NE(m, nullptr);
  Points pts(1);
  ASSERT_EQ(m->ComputeWaveSpeed(pts.Fields(), 0), 0);
  const double c0 = pts.wave_speed[0];
  ASSERT_EQ(m->UpdateStress(pts.Fields(), 0, 1e-4), 0); // L = 0, F = I
  const double err = std::max(std::fabs(c0 - kWaveSpeed), std::fabs(pts.wave_speed[0] - kWaveSpeed)) / kWaveSpeed;
  std::printf("  wave speed: ComputeWaveSpeed %.15g, UpdateStress %.15g m/s (hand 0.820412654142367)\n", c0, pts.wave_speed[0]);
  Report("linear elastic: |c - sqrt((lambda+2mu)/rho)| / c", err, 1e-14, "hand: P-wave speed");
  EXPECT_LE(err, 1e-14);
  delete m;
}

// ---------------------------------------------------------------------------------------------------
// Bad input must return an error code (not abort, not succeed). Each case has a valid control that
// differs only in the bad option, so a test cannot pass because of an unrelated mistake. The code
// must be PETSC_ERR_USER_INPUT (95), the one every input check in models/ raises; any other non-zero
// code would mean the call failed somewhere else (e.g. option parsing) before the check was reached.

namespace {
// Tries to create `name`; returns the error code and deletes whatever was allocated.
PetscErrorCode TryCreate(const std::string &name, bool expect_error)
{
  Material      *m  = nullptr;
  PetscErrorCode rc = expect_error ? CreateExpectingError(name, &m) : MaterialCreate(PETSC_COMM_WORLD, name.c_str(), &m);
  delete m; // null on error: MaterialCreate frees what it allocated
  return rc;
}
} // namespace

TEST(MaterialInput, ValidControl)
{
  ScopedOptions opt;
  opt.Material("in_ok_le", "linear_elastic", "7850", "200e9", "0.29");
  opt.Material("in_ok_nh", "neo_hookean", "1000", "1e6", "0.4999");
  const PetscErrorCode a = TryCreate("in_ok_le", false), b = TryCreate("in_ok_nh", false);
  ReportCode("valid linear_elastic: error code", a, 0, "control");
  ReportCode("valid neo_hookean (nu = 0.4999): error code", b, 0, "control");
  EXPECT_EQ(a, 0);
  EXPECT_EQ(b, 0);
}

TEST(MaterialInput, MissingOrBadDensity)
{
  ScopedOptions opt;
  opt.Material("in_noden", "linear_elastic", "", "1000", "0.3");
  opt.Material("in_zeroden", "neo_hookean", "0", "1000", "0.3");
  opt.Material("in_negden", "linear_elastic", "-5", "1000", "0.3");
  opt.Material("in_nanden", "linear_elastic", "nan", "1000", "0.3");
  const PetscErrorCode a = TryCreate("in_noden", true), b = TryCreate("in_zeroden", true), c = TryCreate("in_negden", true), d = TryCreate("in_nanden", true);
  ReportCode("missing -<name>_density: error code", a, PETSC_ERR_USER_INPUT, "material.hpp: density required");
  ReportCode("density = 0: error code", b, PETSC_ERR_USER_INPUT, "material.hpp: density > 0");
  ReportCode("density = -5: error code", c, PETSC_ERR_USER_INPUT, "material.hpp: density > 0");
  ReportCode("density = nan: error code", d, PETSC_ERR_USER_INPUT, "registry.cxx: density finite");
  EXPECT_EQ(a, PETSC_ERR_USER_INPUT);
  EXPECT_EQ(b, PETSC_ERR_USER_INPUT);
  EXPECT_EQ(c, PETSC_ERR_USER_INPUT);
  EXPECT_EQ(d, PETSC_ERR_USER_INPUT);
}

TEST(MaterialInput, UnknownOrMissingModel)
{
  ScopedOptions opt;
  opt.Material("in_badmodel", "neo_hooke", "1000", "1000", "0.3");
  opt.Material("in_nomodel", "", "1000", "1000", "0.3");
  const PetscErrorCode a = TryCreate("in_badmodel", true), b = TryCreate("in_nomodel", true);
  ReportCode("unknown -<name>_model neo_hooke: error code", a, PETSC_ERR_USER_INPUT, "registry.cxx: unknown model");
  ReportCode("missing -<name>_model: error code", b, PETSC_ERR_USER_INPUT, "registry.cxx: model required");
  EXPECT_EQ(a, PETSC_ERR_USER_INPUT);
  EXPECT_EQ(b, PETSC_ERR_USER_INPUT);
}

TEST(MaterialInput, BadElasticConstants)
{
  ScopedOptions opt;
  opt.Material("in_nu05", "linear_elastic", "1000", "1000", "0.5");
  opt.Material("in_nu05nh", "neo_hookean", "1000", "1000", "0.5");
  opt.Material("in_num1", "linear_elastic", "1000", "1000", "-1");
  opt.Material("in_noE", "neo_hookean", "1000", "", "0.3");
  opt.Material("in_negE", "linear_elastic", "1000", "-3", "0.3");
  const PetscErrorCode a = TryCreate("in_nu05", true), b = TryCreate("in_nu05nh", true), c = TryCreate("in_num1", true), d = TryCreate("in_noE", true), e = TryCreate("in_negE", true);
  ReportCode("poisson_ratio = 0.5 (linear_elastic): error code", a, PETSC_ERR_USER_INPUT, "elastic_parameters.cxx: nu in (-1, 0.5)");
  ReportCode("poisson_ratio = 0.5 (neo_hookean): error code", b, PETSC_ERR_USER_INPUT, "elastic_parameters.cxx: nu in (-1, 0.5)");
  ReportCode("poisson_ratio = -1: error code", c, PETSC_ERR_USER_INPUT, "elastic_parameters.cxx: nu in (-1, 0.5)");
  ReportCode("missing youngs_modulus: error code", d, PETSC_ERR_USER_INPUT, "elastic_parameters.cxx: E required");
  ReportCode("youngs_modulus = -3: error code", e, PETSC_ERR_USER_INPUT, "elastic_parameters.cxx: E > 0");
  EXPECT_EQ(a, PETSC_ERR_USER_INPUT);
  EXPECT_EQ(b, PETSC_ERR_USER_INPUT);
  EXPECT_EQ(c, PETSC_ERR_USER_INPUT);
  EXPECT_EQ(d, PETSC_ERR_USER_INPUT);
  EXPECT_EQ(e, PETSC_ERR_USER_INPUT);
}
