// Unit tests of the sub-models of the elastic_plastic material (models/flow_stress, shear_modulus,
// melt, specific_heat), created through their registries with SubModelCreate and options set by
// PetscOptionsSetValue, exactly as ElasticPlastic::SetUp creates them. Flow models are evaluated
// through FlowStress::Return (the von Mises return the material runs), on a hand-filled one-point Chunk:
//  - sigma_f at (eps_p, rate, T): zero trial deviator (elastic branch, which reports sigma_f at de = 0)
//    with -MAT_flow_stress_min_rate set to the wanted rate, since the rate fed is max(de/dt, min_rate);
//  - MTS hardening paths: plastic steps with a huge dt, so the rate fed stays min_rate (constant).
// Reference values: models.md section 7 (7.1 JC, 7.2 MTS copper, 7.3 MTS HY-100, 7.4 steel Cp),
// and hand computations written next to each test. Every test prints "[ measured ]" lines.
#include "plasticity/families.hpp"
#include "flow_stress/flow_stress.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>
#include "unit_helpers.hpp"

using namespace burst;

namespace {

void Report(const std::string &what, double measured, double expected, double tol, const char *source)
{
  std::printf("[ measured ] %-58s %.6g (expected %.6g, tolerance %.1e; %s)\n", what.c_str(), measured, expected, tol, source);
  std::fflush(stdout);
}

MaterialConstants Constants(const std::string &name, double rho, double mu)
{
  MaterialConstants mc;
  mc.name          = name;
  mc.density       = rho;
  mc.shear_modulus = mu;
  mc.bulk_modulus  = 150e9;
  return mc;
}

// Creates the sub-model of `family` through its registry (returns null on error).
template <class T>
std::unique_ptr<T> Create(PetscErrorCode (*list_fn)(PetscFunctionList *), const MaterialConstants &mc, const char family[], const char default_type[])
{
  PetscFunctionList list = nullptr;
  SubModel         *m    = nullptr;
  EXPECT_EQ(list_fn(&list), 0);
  EXPECT_EQ(SubModelCreate(PETSC_COMM_WORLD, list, mc, family, default_type, "unit test", &m), 0);
  return std::unique_ptr<T>(static_cast<T *>(m));
}

// Captures the first error message (PetscPushErrorHandler), so a test can read what the user sees.
PetscErrorCode CaptureHandler(MPI_Comm, int, const char *, const char *, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  if (p == PETSC_ERROR_INITIAL && mess) *static_cast<std::string *>(ctx) += mess;
  return n;
}

// Tries to create a sub-model expecting failure; returns the error code and the message.
PetscErrorCode CreateExpectingError(PetscErrorCode (*list_fn)(PetscFunctionList *), const MaterialConstants &mc, const char family[], const char default_type[], std::string &message)
{
  PetscFunctionList list = nullptr;
  SubModel         *m    = nullptr;
  EXPECT_EQ(list_fn(&list), 0);
  PetscPushErrorHandler(CaptureHandler, &message);
  const PetscErrorCode rc = SubModelCreate(PETSC_COMM_WORLD, list, mc, family, default_type, "unit test", &m);
  PetscPopErrorHandler();
  delete m;
  return rc;
}

// One-point chunk at temperature T (K), melt Tm (K), shear modulus mu (Pa), density rho.
Chunk OnePoint(double T, double Tm, double mu, double rho)
{
  Chunk c{};
  c.n                   = 1;
  c.dt                  = 1;
  c.density0            = rho;
  c.density[0]          = rho;
  c.temperature[0]      = T;
  c.melt_temperature[0] = Tm;
  c.shear_modulus[0]    = mu;
  return c;
}

// Trial deviator of equivalent stress q: s = q diag(2/3, -1/3, -1/3).
void SetTrial(Chunk &c, double q)
{
  for (int a = 0; a < 9; ++a) c.deviator[0][a] = 0;
  c.deviator[0][0] = 2.0 / 3.0 * q;
  c.deviator[0][4] = c.deviator[0][8] = -1.0 / 3.0 * q;
}

// sigma_f of `flow` at (eps_p, history, T) and the rate min_rate: the elastic branch of the return.
double FlowAt(const FlowStress &flow, Chunk c, double eps, double history)
{
  c.plastic_strain[0] = eps;
  c.history[0][0]     = history;
  SetTrial(c, 0);
  EXPECT_EQ(flow.Return(c, ReturnSettings()), 0);
  EXPECT_EQ(c.plastic[0], 0);
  return c.flow_stress[0];
}

// d sigma_f/d eps_p reported by the elastic branch at (eps_p 0, history): (mu/mu0) S_e theta(history) for MTS.
double HardeningAt(const FlowStress &flow, Chunk c, double history)
{
  c.history[0][0] = history;
  SetTrial(c, 0);
  EXPECT_EQ(flow.Return(c, ReturnSettings()), 0);
  return c.hardening[0];
}

// A shear or other chunk model evaluated at one state.
template <class Model>
Chunk Evaluated(const Model &m, Chunk c)
{
  m.Evaluate(c);
  return c;
}

// ---------------------------------------------------------------------------------------------------
// Johnson-Cook, models.md 7.1 (every row; MPa). Tolerance 0.05 MPa: the table is rounded to 0.1 MPa.
struct JCRow {
  double eps, rate, T, expected;
};

void CheckJC(const std::string &mat, const std::vector<std::pair<std::string, std::string>> &params, double Tm, const std::vector<JCRow> &rows)
{
  ScopedOptions opt;
  opt.Set("-" + mat + "_flow_stress_type", "johnson_cook");
  opt.Family(mat, "flow_stress", params);
  for (const JCRow &r : rows) {
    opt.Set("-" + mat + "_flow_stress_min_rate", std::to_string(r.rate));
    auto flow = Create<FlowStress>(FlowStressList, Constants(mat, 7800, 80e9), "flow_stress", "johnson_cook");
    ASSERT_TRUE(flow);
    const double s = FlowAt(*flow, OnePoint(r.T, Tm, 80e9, 7800), r.eps, 0) / 1e6;
    char         what[128];
    std::snprintf(what, sizeof(what), "JC %s sigma_f(%g, %g/s, %g K) MPa", mat.c_str(), r.eps, r.rate, r.T);
    Report(what, s, r.expected, 0.05, "models.md 7.1");
    EXPECT_NEAR(s, r.expected, 0.05) << what;
  }
}

} // namespace

TEST(JohnsonCook, Table71_4340)
{
  CheckJC("jc4340", {{"A", "792e6"}, {"B", "510e6"}, {"n", "0.26"}, {"C", "0.014"}, {"m", "1.03"}}, 1793, {{0.1, 1, 298, 1072.3}, {0.1, 1e3, 298, 1176.0}, {0.5, 1e4, 298, 1374.9}, {0.2, 1e3, 600, 998.6}, {0.2, 1e3, 1000, 669.0}});
}

TEST(JohnsonCook, Table71_OFHCCopper) { CheckJC("jccu", {{"A", "90e6"}, {"B", "292e6"}, {"n", "0.31"}, {"C", "0.025"}, {"m", "1.09"}}, 1356, {{0.1, 1, 298, 233.0}, {0.5, 1e3, 298, 381.8}, {1.0, 1e4, 298, 470.0}, {0.5, 1e3, 700, 248.8}}); }

TEST(JohnsonCook, Table71_ArmcoIron)
{
  // m = 0.55 (Johnson & Cook 1983) and the Uintah file's 1.44 (models.md 6.5): equal at 298 K.
  CheckJC("jcarmco", {{"A", "175e6"}, {"B", "380e6"}, {"n", "0.32"}, {"C", "0.060"}, {"m", "0.55"}}, 1811, {{0.1, 1, 298, 356.9}, {0.5, 1e3, 298, 678.1}, {0.2, 1e3, 600, 334.3}});
  CheckJC("jcarmcou", {{"A", "175e6"}, {"B", "380e6"}, {"n", "0.32"}, {"C", "0.060"}, {"m", "1.44"}}, 1811, {{0.1, 1, 298, 356.9}, {0.5, 1e3, 298, 678.1}, {0.2, 1e3, 600, 512.8}});
}

TEST(JohnsonCook, Table71_HY100) { CheckJC("jchy", {{"A", "316e6"}, {"B", "1067e6"}, {"n", "0.107"}, {"C", "0.0277"}, {"m", "0.7"}, {"reference_rate", "3300"}, {"room_temperature", "300"}}, 1500, {{0.1, 3300, 300, 1150.0}}); }

// ---------------------------------------------------------------------------------------------------
// MTS, annealed copper (models.md 6.4, 7.2), with the MTS shear modulus (mu0 47.7, D 3.0 GPa, T0 180 K).
namespace {
void SetCopperMTS(ScopedOptions &opt, const std::string &mat)
{
  opt.Set("-" + mat + "_shear_modulus_type", "mts");
  opt.Family(mat, "shear_modulus", {{"mu0", "47.7e9"}, {"D", "3.0e9"}, {"T0", "180"}});
  opt.Set("-" + mat + "_flow_stress_type", "mts");
  opt.Family(mat, "flow_stress",
             {{"sigma_a", "40e6"},
              {"k_over_b3", "0.823e6"},
              {"g0e", "1.6"},
              {"edot0e", "1e7"},
              {"p_e", "0.666666666666667"},
              {"q_e", "1"},
              {"a0", "2390e6"},
              {"a1", "12e6"},
              {"a2", "1.696e6"},
              {"a3", "0"},
              {"theta_IV", "0"},
              {"alpha", "2"},
              {"edot_es0", "1e7"},
              {"g0es", "0.2625"},
              {"sigma_es0", "770e6"}});
}
} // namespace

TEST(MTS, Table72_AnnealedCopper)
{
  struct Case {
    double rate, T, mu, Se, ses, theta0, sigma[6];
  };
  const Case    cases[]        = {{1e-3, 298, 44.08, 0.8823, 472.7, 2307.2, {40.0, 114.27, 162.09, 221.08, 257.55, 302.45}},
                                  {1e3, 298, 44.08, 0.9523, 633.5, 2526.5, {40.0, 131.39, 194.35, 276.07, 328.38, 394.39}},
                                  {4e3, 696, 37.54, 0.8902, 488.6, 2596.8, {40.0, 110.46, 154.44, 207.57, 239.95, 279.44}}};
  const double  eps_targets[6] = {0, 0.05, 0.1, 0.2, 0.3, 0.5};
  const double  rho = 8930, Tm = 1356, sigma_a = 40e6;
  ScopedOptions opt;
  SetCopperMTS(opt, "mtscu");
  for (const Case &k : cases) {
    opt.Set("-mtscu_flow_stress_min_rate", std::to_string(k.rate));
    MaterialConstants mc    = Constants("mtscu", rho, 45.45e9);
    auto              shear = Create<ShearModulusModel>(ShearModulusList, mc, "shear_modulus", "constant");
    ASSERT_TRUE(shear);
    mc.shear_modulus = shear->ReferenceShearModulus(); // as ElasticPlastic::SetUp
    auto flow        = Create<FlowStress>(FlowStressList, mc, "flow_stress", "johnson_cook");
    ASSERT_TRUE(flow);
    char what[128];
    // mu(T) from the shear model (table rounded to 0.01 GPa)
    const double mu = Evaluated(*shear, OnePoint(k.T, Tm, 0, rho)).shear_modulus[0];
    std::snprintf(what, sizeof(what), "MTS Cu mu(%g K) GPa", k.T);
    Report(what, mu / 1e9, k.mu, 0.005, "models.md 7.2");
    EXPECT_NEAR(mu / 1e9, k.mu, 0.005);
    const double ratio = mu / 47.7e9;
    Chunk        c     = OnePoint(k.T, Tm, mu, rho);
    // S_e from sigma_f = sigma_a + (mu/mu0) S_e h at a history h = 100 MPa < sigma_hat_es, de = 0
    const double Se = (FlowAt(*flow, c, 0, 100e6) - sigma_a) / (ratio * 100e6);
    std::snprintf(what, sizeof(what), "MTS Cu S_e(%g/s, %g K)", k.rate, k.T);
    Report(what, Se, k.Se, 5e-5, "models.md 7.2");
    EXPECT_NEAR(Se, k.Se, 5e-5);
    // sigma_hat_es: where theta falls to theta_IV = 0 (F(1) = 1; the elastic branch reports the
    // hardening (mu/mu0) S_e theta(sigma_hat_e)), found by bisection on the history
    double lo = 1e6, hi = 2e9;
    for (int it = 0; it < 100; ++it) {
      const double mid                           = 0.5 * (lo + hi);
      (HardeningAt(*flow, c, mid) > 0 ? lo : hi) = mid;
    }
    const double ses = 0.5 * (lo + hi) / 1e6;
    std::snprintf(what, sizeof(what), "MTS Cu sigma_hat_es(%g/s, %g K) MPa", k.rate, k.T);
    Report(what, ses, k.ses, 0.05, "models.md 7.2");
    EXPECT_NEAR(ses, k.ses, 0.05);
    // theta0: the elastic branch reports d sigma_f/d eps_p = (mu/mu0) S_e theta(0) = (mu/mu0) S_e theta0
    {
      Chunk e = c;
      SetTrial(e, 0);
      ASSERT_EQ(flow->Return(e, ReturnSettings()), 0);
      const double theta0 = e.hardening[0] / (ratio * Se) / 1e6;
      std::snprintf(what, sizeof(what), "MTS Cu theta0(%g/s, %g K) MPa", k.rate, k.T);
      Report(what, theta0, k.theta0, 0.05, "models.md 7.2");
      EXPECT_NEAR(theta0, k.theta0, 0.05);
    }
    // sigma_f along eps_p at constant rate: plastic steps of ~1e-4 with dt = 1e6 s (rate fed = min_rate)
    std::vector<double> eps{0}, sig{FlowAt(*flow, c, 0, 0)};
    c.dt = 1e6;
    while (eps.back() < 0.5) {
      SetTrial(c, sig.back() + 3 * mu * 1e-4);
      ASSERT_EQ(flow->Return(c, ReturnSettings()), 0);
      ASSERT_EQ(c.plastic[0], 1);
      eps.push_back(c.plastic_strain[0]);
      sig.push_back(c.flow_stress[0]);
    }
    for (int t = 0; t < 6; ++t) {
      size_t j = 0;
      while (j + 1 < eps.size() && eps[j + 1] < eps_targets[t]) ++j;
      const double w = eps_targets[t] > 0 ? (eps_targets[t] - eps[j]) / (eps[j + 1] - eps[j]) : 0;
      const double s = ((1 - w) * sig[j] + w * sig[std::min(j + 1, eps.size() - 1)]) / 1e6;
      std::snprintf(what, sizeof(what), "MTS Cu sigma_f(eps %g, %g/s, %g K) MPa", eps_targets[t], k.rate, k.T);
      Report(what, s, k.sigma[t], 0.2, "models.md 7.2 (tolerance stated there)");
      EXPECT_NEAR(s, k.sigma[t], 0.2) << what;
    }
    // the history variable holds sigma_hat_e: sigma_f = sigma_a + (mu/mu0) S_e sigma_hat_e
    EXPECT_NEAR(c.flow_stress[0], sigma_a + ratio * Se * c.history[0][0], 1.0);
  }
}

// ---------------------------------------------------------------------------------------------------
// MTS, HY-100 (models.md 6.2, 7.3): initial yield sigma_f = sigma_a + (mu/mu0) S_i sigma_hat_i at eps_p 0.
namespace {
void SetHY100MTS(ScopedOptions &opt, const std::string &mat)
{
  opt.Set("-" + mat + "_shear_modulus_type", "mts");
  opt.Family(mat, "shear_modulus", {{"mu0", "71.46e9"}, {"D", "2.9e9"}, {"T0", "204"}});
  opt.Set("-" + mat + "_flow_stress_type", "mts");
  opt.Family(mat, "flow_stress", {{"sigma_a", "40e6"}, {"k_over_b3", "0.905e6"}, {"sigma_i", "1341e6"}, {"g0i", "1.161"}, {"edot0i", "1e13"}, {"p_i", "0.5"},        {"q_i", "1.5"}, {"g0e", "1.6"},      {"edot0e", "1e7"}, {"p_e", "0.666666666666667"},
                                  {"q_e", "1"},        {"a0", "6.0e9"},          {"a1", "0"},           {"a2", "0"},      {"a3", "2.0758e6"}, {"theta_IV", "200e6"}, {"alpha", "3"}, {"edot_es0", "1e7"}, {"g0es", "0.112"}, {"sigma_es0", "822e6"}});
}

// The HY-100 MTS flow model of material `mat` with the rate floor min_rate (1/s), created with the
// reference shear modulus mu0 = 71.46 GPa.
std::unique_ptr<FlowStress> HY100MTSFlow(ScopedOptions &opt, const std::string &mat, const char min_rate[])
{
  SetHY100MTS(opt, mat);
  opt.Set("-" + mat + "_flow_stress_min_rate", min_rate);
  MaterialConstants mc = Constants(mat, 7860, 69e9);
  mc.shear_modulus     = 71.46e9;
  return Create<FlowStress>(FlowStressList, mc, "flow_stress", "johnson_cook");
}
} // namespace

TEST(MTS, Table73_HY100InitialYield)
{
  struct Case {
    double rate, T, mu, Si, sigma;
  };
  const Case    cases[] = {{1e-3, 298, 68.51, 0.5627, 763.4}, {3000, 298, 68.51, 0.6776, 911.2}, {3000, 573, 64.68, 0.5125, 662.1}, {1e4, 600, 64.30, 0.5137, 659.9}};
  const double  rho = 7860, Tm = 2000;
  ScopedOptions opt;
  SetHY100MTS(opt, "mtshy");
  for (const Case &k : cases) {
    opt.Set("-mtshy_flow_stress_min_rate", std::to_string(k.rate));
    MaterialConstants mc    = Constants("mtshy", rho, 69e9);
    auto              shear = Create<ShearModulusModel>(ShearModulusList, mc, "shear_modulus", "constant");
    ASSERT_TRUE(shear);
    mc.shear_modulus = shear->ReferenceShearModulus();
    auto flow        = Create<FlowStress>(FlowStressList, mc, "flow_stress", "johnson_cook");
    ASSERT_TRUE(flow);
    char         what[128];
    const double mu = Evaluated(*shear, OnePoint(k.T, Tm, 0, rho)).shear_modulus[0];
    std::snprintf(what, sizeof(what), "MTS HY-100 mu(%g K) GPa", k.T);
    Report(what, mu / 1e9, k.mu, 0.005, "models.md 7.3");
    EXPECT_NEAR(mu / 1e9, k.mu, 0.005);
    const double s  = FlowAt(*flow, OnePoint(k.T, Tm, mu, rho), 0, 0);
    const double Si = (s - 40e6) / (mu / 71.46e9 * 1341e6);
    std::snprintf(what, sizeof(what), "MTS HY-100 S_i(%g/s, %g K)", k.rate, k.T);
    Report(what, Si, k.Si, 5e-5, "models.md 7.3");
    EXPECT_NEAR(Si, k.Si, 5e-5);
    std::snprintf(what, sizeof(what), "MTS HY-100 sigma_f(0, %g/s, %g K) MPa", k.rate, k.T);
    Report(what, s / 1e6, k.sigma, 0.05, "models.md 7.3");
    EXPECT_NEAR(s / 1e6, k.sigma, 0.05);
  }
}

// Derivatives of the MTS flow stress seen through the return: the reported hardening (d_strain, plus
// d_rate/dt when the rate is not floored) against a finite difference of sigma_f along the return
// (two trial stresses), and the thermal softening d_temperature against a finite difference in T
// (along the return, dsigma/dT = d_temperature 3 mu/(3 mu + H)). HY-100 with theta_IV, sigma_hat_e
// = 100 MPa at t_n (below sigma_hat_es = 200 MPa at 1e-3 /s and 500 K, so the hardening is active)
// and 450 MPa (above it: stage IV, theta of the same formula), eps_p 0.1, 500 K.
TEST(MTS, DerivativesAlongReturn)
{
  ScopedOptions opt;
  auto          flow = HY100MTSFlow(opt, "mtsder", "1e-3");
  ASSERT_TRUE(flow);
  ReturnSettings settings;
  settings.tolerance = 1e-14;
  const double mu = 66e9, T = 500;
  double       history = 0;

  auto Run = [&](double q, double dt, double temperature) {
    Chunk c             = OnePoint(temperature, 2000, mu, 7860);
    c.dt                = dt;
    c.plastic_strain[0] = 0.1;
    c.history[0][0]     = history;
    SetTrial(c, q);
    EXPECT_EQ(flow->Return(c, settings), 0);
    EXPECT_EQ(c.plastic[0], 1);
    return c;
  };
  for (double h : {100e6, 450e6})   // below and above saturation (X = 2.25: theta from the same formula, stage IV)
    for (double dt : {1e6, 1e-5}) { // rate floored (d_strain alone) / rate 1e3-1e4 /s (d_strain + d_rate/dt)
      history        = h;
      const double q = 1.5e9;
      const Chunk  a = Run(q, dt, T), b = Run(q + 1e5, dt, T);
      const double fd = (b.flow_stress[0] - a.flow_stress[0]) / (b.delta_plastic_strain[0] - a.delta_plastic_strain[0]);
      // the total slope along the return is strain hardening plus the rate term (rate_hardening)
      const double an = 0.5 * (a.hardening[0] + a.rate_hardening[0] + b.hardening[0] + b.rate_hardening[0]);
      char         what[128];
      std::snprintf(what, sizeof(what), "MTS hardening rel. error vs FD (h %g, dt %g s, H %.3g Pa)", h, dt, an);
      Report(what, std::fabs(an - fd) / std::fabs(fd), 0, 1e-4, "central difference along the return");
      EXPECT_GT(an, 1e8); // not at saturation: the check is not vacuous
      EXPECT_NEAR(an, fd, 1e-4 * std::fabs(fd));
      const Chunk  hot = Run(q, dt, T + 0.01), cold = Run(q, dt, T - 0.01);
      const double dT = (hot.flow_stress[0] - cold.flow_stress[0]) / 0.02 * (3 * mu + a.hardening[0] + a.rate_hardening[0]) / (3 * mu);
      std::snprintf(what, sizeof(what), "MTS d sigma/dT rel. error vs FD (h %g, dt %g s, %.4g Pa/K)", h, dt, a.thermal_softening[0]);
      Report(what, std::fabs(a.thermal_softening[0] - dT) / std::fabs(dT), 0, 1e-4, "central difference in T along the return");
      EXPECT_NEAR(a.thermal_softening[0], dT, 1e-4 * std::fabs(dT));
      EXPECT_LT(a.thermal_softening[0], 0);
    }
}

// sigma_hat_e is a structure variable of eq. 11 (sigma_hat_e^{n+1} = sigma_hat_e^n + theta Delta eps):
// it changes only with plastic strain. HY-100 at 622 K, hardened at ~1e4 /s to sigma_hat_e = 450 MPa
// (sigma_hat_es(1e4 /s) = 472 MPa), then a plastic step of ~1e-9 at 3 /s, where sigma_hat_es =
// 822 MPa (3/1e7)^(k T/(mu b^3 g0es)) = 255 MPa: sigma_hat_e moves by at most |theta| Delta eps
// (< 10 Pa) and sigma_f is continuous. (Issue 12: a cap at the current sigma_hat_es dropped it to
// 255 MPa in one step of no strain, and with the adiabatic thermal softening that made the Drucker
// check fail 44 % of the HY-100 cylinder's particles as they unloaded, at plastic rates of 0.01-100 /s.)
TEST(MTS, HistoryChangesOnlyWithPlasticStrain)
{
  ScopedOptions opt;
  auto          flow = HY100MTSFlow(opt, "mtshist", "3");
  ASSERT_TRUE(flow);
  const double T = 622, mu = 71.46e9 - 2.9e9 / (std::exp(204.0 / T) - 1), h = 450e6;
  Chunk        c      = OnePoint(T, 2000, mu, 7860);
  c.dt                = 1e6; // the rate fed stays at min_rate
  c.plastic_strain[0] = 0.17;
  const double sigma0 = FlowAt(*flow, c, 0.17, h);
  c.history[0][0]     = h;
  SetTrial(c, sigma0 + 3 * mu * 1e-9);
  ASSERT_EQ(flow->Return(c, ReturnSettings()), 0);
  ASSERT_EQ(c.plastic[0], 1);
  const double de = c.delta_plastic_strain[0];
  char         what[128];
  std::snprintf(what, sizeof(what), "MTS sigma_hat_e change after de %.2g at 3/s (Pa)", de);
  Report(what, c.history[0][0] - h, 0, 10, "eq. 11: |theta| de < 6e9 de");
  EXPECT_GT(de, 0);
  EXPECT_LT(de, 1e-8);
  EXPECT_NEAR(c.history[0][0], h, 10);
  std::snprintf(what, sizeof(what), "MTS sigma_f jump over the step (Pa)");
  Report(what, c.flow_stress[0] - sigma0, 0, 100, "continuity: (3 mu + H) de");
  EXPECT_NEAR(c.flow_stress[0], sigma0, 100);
  EXPECT_GT(c.hardening[0], 0); // stage IV above saturation: theta ~ theta_IV
}

// ---------------------------------------------------------------------------------------------------
// SCG shear modulus (eq. 8) and melt temperature (eq. 9) with the 4340 constants of models.md 6.1
// (mu0 81.8 GPa, A 20.6e-12 /Pa, B 0.16e-3 /K; Tm0 2310 K, Gamma0 3.0, a 1.67), rho0 7830. By hand
// (30-digit arithmetic):
//   eta = 1, T = 300 K, p = 0:        mu = mu0 = 81.8 GPa;       Tm = Tm0 = 2310 K
//   eta = 1, T = 600 K, p = 0:        mu = 81.8 (1 - 0.16e-3 * 300) = 77.8736 GPa (B > 0: softer when hot)
//   eta = 1.1, T = 800 K, p = 10 GPa: eta^-1/3 = 0.968729306151464,
//                                     mu = 81.8 [1 + 0.206 * 0.968729306 - 0.08] = 91.5798637920971 GPa
//                                     Tm = 2310 exp(3.34 (1 - 1/1.1)) 1.1^(2 (3 - 1.67 - 1/3))
//                                        = 2310 * 1.354776320572 * 1.209231408757 = 3784.32996174259 K
//   eta = 0.95 (tension):             Tm = 1749.29599315636 K
//   T >= Tm:                          mu = 0
TEST(SCG, ShearAndMeltByHand)
{
  ScopedOptions opt;
  opt.Set("-scg_shear_modulus_type", "scg");
  opt.Family("scg", "shear_modulus", {{"A", "20.6e-12"}, {"B", "0.16e-3"}});
  opt.Set("-scg_melt_type", "scg");
  opt.Family("scg", "melt", {{"Tm0", "2310"}, {"Gamma0", "3.0"}, {"a", "1.67"}});
  const double      rho0  = 7830;
  MaterialConstants mc    = Constants("scg", rho0, 81.8e9); // mu0 defaults to the material's modulus
  auto              shear = Create<ShearModulusModel>(ShearModulusList, mc, "shear_modulus", "constant");
  auto              melt  = Create<MeltModel>(MeltList, mc, "melt", "constant");
  ASSERT_TRUE(shear && melt);
  EXPECT_EQ(shear->ReferenceShearModulus(), 81.8e9);
  struct Case {
    double eta, T, p, mu, Tm;
  };
  const Case cases[] = {{1, 300, 0, 81.8e9, 2310}, {1, 600, 0, 77.8736e9, 2310}, {1.1, 800, 10e9, 91.5798637920971e9, 3784.32996174259}, {0.95, 300, 0, 81.8e9, 1749.29599315636}};
  for (const Case &k : cases) {
    Chunk c       = OnePoint(k.T, 0, 0, rho0 * k.eta);
    c.pressure[0] = k.p;
    melt->Evaluate(c);
    shear->Evaluate(c);
    char what[128];
    std::snprintf(what, sizeof(what), "SCG Tm(eta %g) K", k.eta);
    Report(what, c.melt_temperature[0], k.Tm, 1e-9 * k.Tm, "hand computation, eq. 9");
    EXPECT_NEAR(c.melt_temperature[0], k.Tm, 1e-9 * k.Tm);
    const double mu_expected = k.mu; // with p = 0, eta does not enter
    std::snprintf(what, sizeof(what), "SCG mu(eta %g, T %g K, p %g Pa) Pa", k.eta, k.T, k.p);
    Report(what, c.shear_modulus[0], mu_expected, 1e-9 * mu_expected, "hand computation, eq. 8");
    EXPECT_NEAR(c.shear_modulus[0], mu_expected, 1e-9 * mu_expected);
  }
  Chunk c = OnePoint(2400, 2310, 0, rho0);
  shear->Evaluate(c);
  Report("SCG mu at T > Tm (Pa)", c.shear_modulus[0], 0, 0, "eq. 8 with melt: zero");
  EXPECT_EQ(c.shear_modulus[0], 0);
}

// MTS shear modulus at and above melt.
TEST(MTS, ShearZeroAtMelt)
{
  ScopedOptions opt;
  opt.Set("-mtsmelt_shear_modulus_type", "mts");
  opt.Family("mtsmelt", "shear_modulus", {{"mu0", "47.7e9"}, {"D", "3.0e9"}, {"T0", "180"}});
  auto shear = Create<ShearModulusModel>(ShearModulusList, Constants("mtsmelt", 8930, 45e9), "shear_modulus", "constant");
  ASSERT_TRUE(shear);
  const double mu = Evaluated(*shear, OnePoint(1356, 1356, 0, 8930)).shear_modulus[0];
  Report("MTS mu at T = Tm (Pa)", mu, 0, 0, "zero at melt");
  EXPECT_EQ(mu, 0);
}

// ---------------------------------------------------------------------------------------------------
// Specific heat: the two-branch steel law and eq. 19 against models.md 7.4 (table rounded to 0.1), the
// smoothing of the Curie singularity, and the copper law (Uintah CopperCp) by hand:
//   300 K: 0.1009 * 300 + 358.4 = 388.67;  1000 K: 459.3;
//   200 K: 4.16e-5 * 8e6 - 0.027 * 4e4 + 6.21 * 200 - 142.6 = 332.8 - 1080 + 1242 - 142.6 = 352.2
TEST(SpecificHeat, Table74AndCopper)
{
  ScopedOptions opt;
  opt.Set("-cps_specific_heat_type", "steel");
  opt.Set("-cpg_specific_heat_type", "goto");
  opt.Set("-cpc_specific_heat_type", "copper");
  auto steel  = Create<SpecificHeatModel>(SpecificHeatList, Constants("cps", 7830, 80e9), "specific_heat", "constant");
  auto goto19 = Create<SpecificHeatModel>(SpecificHeatList, Constants("cpg", 7860, 69e9), "specific_heat", "constant");
  auto copper = Create<SpecificHeatModel>(SpecificHeatList, Constants("cpc", 8930, 45e9), "specific_heat", "constant");
  ASSERT_TRUE(steel && goto19 && copper);
  const double T[]    = {298, 400, 500, 600, 800, 1000, 1100, 1300};
  const double two[]  = {442.4, 482.6, 524.9, 571.1, 687.8, 982.2, 638.5, 626.6};
  const double eq19[] = {454.6, 468.5, 515.1, 574.5, 708.5, 850.6, 923.0, 1069.1};

  auto Cp = [](const SpecificHeatModel &m, double temperature) { return Evaluated(m, OnePoint(temperature, 3000, 0, 7830)).specific_heat[0]; };
  for (int i = 0; i < 8; ++i) {
    char what[96];
    std::snprintf(what, sizeof(what), "steel Cp two-branch (%g K) J/(kg K)", T[i]);
    Report(what, Cp(*steel, T[i]), two[i], 0.05, "models.md 7.4");
    EXPECT_NEAR(Cp(*steel, T[i]), two[i], 0.05);
    std::snprintf(what, sizeof(what), "steel Cp eq. 19 (%g K) J/(kg K)", T[i]);
    Report(what, Cp(*goto19, T[i]), eq19[i], 0.05, "models.md 7.4");
    EXPECT_NEAR(Cp(*goto19, T[i]), eq19[i], 0.05);
  }
  // Curie band (T_c 1040 K, half-width 10 K): finite and continuous; midpoint of the branch values at
  // 1030 K (1246.504) and 1050 K (763.302) at T_c.
  const double at_c = Cp(*steel, 1040), mid = 0.5 * (Cp(*steel, 1030) + Cp(*steel, 1050));
  Report("steel Cp at T_c (J/(kg K))", at_c, mid, 1e-9, "linear in the Curie band");
  EXPECT_NEAR(at_c, mid, 1e-9);
  EXPECT_NEAR(mid, 1004.903, 0.01);
  const double jump = std::max(std::fabs(Cp(*steel, 1030 - 1e-9) - Cp(*steel, 1030 + 1e-9)), std::fabs(Cp(*steel, 1050 - 1e-9) - Cp(*steel, 1050 + 1e-9)));
  Report("steel Cp jump at the band edges (J/(kg K))", jump, 0, 1e-3, "continuity");
  EXPECT_LT(jump, 1e-3);
  const double cu_T[] = {200, 300, 1000}, cu_cp[] = {352.2, 388.67, 459.3};
  for (int i = 0; i < 3; ++i) {
    char what[96];
    std::snprintf(what, sizeof(what), "copper Cp (%g K) J/(kg K)", cu_T[i]);
    Report(what, Cp(*copper, cu_T[i]), cu_cp[i], 1e-9, "hand computation, Uintah CopperCp");
    EXPECT_NEAR(Cp(*copper, cu_T[i]), cu_cp[i], 1e-9);
  }
  EXPECT_GT(Cp(*copper, 10), 0);
}

// ---------------------------------------------------------------------------------------------------
// Bad input: an unknown type lists the valid names; a missing or out-of-range parameter names the option.
TEST(SubModelInput, UnknownFlowTypeListsValidNames)
{
  ScopedOptions opt;
  opt.Set("-steel_flow_stress_type", "bogus");
  std::string          message;
  const PetscErrorCode rc = CreateExpectingError(FlowStressList, Constants("steel", 7830, 80e9), "flow_stress", "johnson_cook", message);
  std::printf("[ measured ] error %d, message: %s\n", (int)rc, message.c_str());
  EXPECT_NE(rc, 0);
  for (const char *name : {"-steel_flow_stress_type", "bogus", "johnson_cook", "linear_hardening", "mts"}) EXPECT_NE(message.find(name), std::string::npos) << name;
}

TEST(SubModelInput, MissingOrBadParameterNamesOption)
{
  struct Case {
    const char *family, *type, *drop, *bad_key, *bad_value, *expect;
  };
  // copper MTS without -sigma_es0; HY-100 MTS with a3 < 0 (the signed +a3 T convention); SCG shear
  // without -B; SCG melt without -Tm0; steel Cp with a negative Curie width.
  const Case cases[] = {{"flow_stress", "mts", "sigma_es0", "", "", "-mi0_flow_stress_sigma_es0"},
                        {"flow_stress", "mts", "", "a3", "-2.0758e6", "-mi1_flow_stress_a3"},
                        {"shear_modulus", "scg", "B", "", "", "-mi2_shear_modulus_B"},
                        {"melt", "scg", "Tm0", "", "", "-mi3_melt_Tm0"},
                        {"specific_heat", "steel", "", "curie_width", "-5", "-mi4_specific_heat_curie_width"}};
  int        i       = 0;
  for (const Case &k : cases) {
    const std::string mat = "mi" + std::to_string(i++);
    ScopedOptions     opt;
    std::string       family                    = k.family;
    PetscErrorCode (*list)(PetscFunctionList *) = family == "flow_stress" ? FlowStressList : family == "shear_modulus" ? ShearModulusList : family == "melt" ? MeltList : SpecificHeatList;
    if (family == "flow_stress") SetCopperMTS(opt, mat);
    opt.Set("-" + mat + "_" + family + "_type", k.type);
    if (family == "shear_modulus") opt.Family(mat, family, {{"A", "20.6e-12"}, {"B", "0.16e-3"}});
    if (family == "melt") opt.Family(mat, family, {{"Tm0", "2310"}, {"Gamma0", "3"}, {"a", "1.67"}});
    if (*k.drop) PetscOptionsClearValue(nullptr, ("-" + mat + "_" + family + "_" + k.drop).c_str());
    if (*k.bad_key) opt.Set("-" + mat + "_" + family + "_" + k.bad_key, k.bad_value);
    std::string          message;
    MaterialConstants    mc = Constants(mat, 8930, 47.7e9);
    const PetscErrorCode rc = CreateExpectingError(list, mc, k.family, "constant", message);
    std::printf("[ measured ] %s %s: error %d, message: %s\n", k.family, k.type, (int)rc, message.c_str());
    EXPECT_NE(rc, 0);
    EXPECT_NE(message.find(k.expect), std::string::npos) << k.expect;
  }
}
