// Unit tests (suite burn: ctest -R burn) of the burn models (models/burn): the burning-surface area,
// Simple Burn, Steady Burn (WSB) and the CVODE thermal-decomposition kinetics. Models are created
// through the registry with BurnModelCreate and options set by PetscOptionsSetValue.
//  - BurnSurfaceArea: axis-aligned normals give the face area; a diagonal 2-D normal by hand; 0 for g = 0.
//  - Simple Burn (ice.md 3.2): the rate at 1 atm and 10 MPa by hand and against ice.md's regression
//    (4.1 and 146 cm/s at rho 1840); no burn at or below each ignition threshold; dm capped at M_s - M_tiny.
//  - Steady Burn (ice.md 3.3): the oracle table (T_s, mdot, r = mdot/rho_c at four pressures) to half a
//    unit of the table's last printed digit; ignition thresholds; the T0 clamp.
//  - Thermal decomposition: the CVODE ignition delay against the high-activation-energy closed form
//    t_ad = c T0^2/(Q Z T_a) exp(T_a/T0) within its asymptotic correction, and against an independent
//    RK4 integration (rel 1e-6), adiabatic and with cook-off heating; Advance against RK4 in time.
// Every test prints "[ measured ]" lines.
#include "burn/burn.hpp"
#include "burn/thermal_decomposition.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include "unit_helpers.hpp"

using namespace burst;

namespace {

// Frees the burn registry's list before PetscFinalize (unit_main.cxx only destroys the material registry).
class BurnEnvironment : public ::testing::Environment {
public:
  void TearDown() override { EXPECT_EQ(BurnModelRegistryDestroy(), 0); }
};
::testing::Environment *const burn_env = ::testing::AddGlobalTestEnvironment(new BurnEnvironment);

void Report(const std::string &what, double measured, double expected, double tol, const char *source)
{
  std::printf("[ measured ] %-62s %.10g (expected %.10g, tolerance %.2e; %s)\n", what.c_str(), measured, expected, tol, source);
  std::fflush(stdout);
}

// |a - b| <= rel |b|, printed.
void ExpectRel(const std::string &what, double measured, double expected, double rel, const char *source)
{
  Report(what + " [rel]", measured, expected, rel, source);
  EXPECT_LE(std::fabs(measured - expected), rel * std::fabs(expected)) << what;
}

// |a - b| <= abs, printed.
void ExpectAbs(const std::string &what, double measured, double expected, double abs, const char *source)
{
  Report(what + " [abs]", measured, expected, abs, source);
  EXPECT_LE(std::fabs(measured - expected), abs) << what;
}

std::unique_ptr<BurnModel> Create(const char material[])
{
  BurnModel *model = nullptr;
  EXPECT_EQ(BurnModelCreate(PETSC_COMM_WORLD, material, &model), 0);
  EXPECT_NE(model, nullptr);
  return std::unique_ptr<BurnModel>(model);
}

PetscErrorCode CaptureHandler(MPI_Comm, int, const char *, const char *, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  if (p == PETSC_ERROR_INITIAL && mess) *static_cast<std::string *>(ctx) += mess;
  return n;
}

PetscErrorCode CreateExpectingError(const char material[], std::string &message)
{
  BurnModel *model = nullptr;
  PetscPushErrorHandler(CaptureHandler, &message);
  const PetscErrorCode rc = BurnModelCreate(PETSC_COMM_WORLD, material, &model);
  PetscPopErrorHandler();
  delete model;
  std::printf("[ measured ] error %d: %s\n", (int)rc, message.c_str());
  return rc;
}

// A surface cell of PBX that every model ignites with defaults: 1 MPa, 600 K, contrast 0.5.
BurnInput BurningCell()
{
  BurnInput in;
  in.p             = 1e6;
  in.T_s           = 300;
  in.T_g           = 600;
  in.rho_s         = 1840;
  in.area          = 1e-6; // 1 mm^2
  in.dt            = 1e-6; // 1 us
  in.M_s           = 1e-6; // kg (a 1 mm cell full of PBX holds 1.84e-6 kg)
  in.M_tiny        = 1e-15;
  in.mass_contrast = 0.5;
  in.T_hot         = 600;
  in.n_particles   = 4;
  return in;
}

} // namespace

// ---------------------------------------------------------------------------------------------
// Burning-surface area, A = V (max_i |n_i|)^(1/3) / sum_i h_i |n_i| (ice.md 3.1)

TEST(burn, SurfaceAreaAxisAligned)
{
  const PetscReal h[3] = {1e-3, 2e-3, 3e-3}, V = 1e-3 * 2e-3 * 3e-3;
  // n = (1, 0, 0): max 1, sum h_x -> A = V/h_x = h_y h_z = 6e-6 m^2; the gradient's size and sign do not matter
  const PetscReal gx[3] = {-42.0, 0, 0}, gy[3] = {0, 1e-9, 0}, gz[3] = {0, 0, 7};
  ExpectRel("3-D normal along x: h_y h_z", BurnSurfaceArea(3, h, gx, V), 2e-3 * 3e-3, 1e-14, "by hand");
  ExpectRel("3-D normal along y: h_x h_z", BurnSurfaceArea(3, h, gy, V), 1e-3 * 3e-3, 1e-14, "by hand");
  ExpectRel("3-D normal along z: h_x h_y", BurnSurfaceArea(3, h, gz, V), 1e-3 * 2e-3, 1e-14, "by hand");
  // 2-D (depth h_z in V): normal along y -> V/h_y = h_x h_z
  ExpectRel("2-D normal along y: h_x h_z", BurnSurfaceArea(2, h, gy, V), 1e-3 * 3e-3, 1e-14, "by hand");
  const PetscReal g0[3] = {0, 0, 0};
  Report("zero gradient", BurnSurfaceArea(3, h, g0, V), 0, 0, "A = 0 by definition");
  EXPECT_EQ(BurnSurfaceArea(3, h, g0, V), 0.0);
}

TEST(burn, SurfaceAreaDiagonal2D)
{
  // n = (1, 1)/sqrt(2): max |n_i| = 2^(-1/2), (max)^(1/3) = 2^(-1/6), sum h_i |n_i| = (h_x + h_y)/sqrt(2)
  //   A = V 2^(-1/6) sqrt(2)/(h_x + h_y) = V 2^(1/3)/(h_x + h_y).
  // Square cell h_x = h_y = 1 mm, depth h_z = 1 mm, V = 1e-9 m^3: A = 2^(1/3)/2 mm^2 = 2^(-2/3) mm^2 = 0.6299605249e-6 m^2.
  const PetscReal hs[3] = {1e-3, 1e-3, 1e-3}, g[3] = {3, -3, 0};
  ExpectRel("square cell, diagonal normal: 2^(-2/3) h h_z", BurnSurfaceArea(2, hs, g, 1e-9), 0.6299605249474366e-6, 1e-14, "by hand");
  // The 3-D call with g_z = 0 gives the same (Uintah's 2-D runs are one cell thick).
  ExpectRel("same in 3-D with g_z = 0", BurnSurfaceArea(3, hs, g, 1e-9), 0.6299605249474366e-6, 1e-14, "by hand");
  // h_x = 1 mm, h_y = 2 mm, h_z = 1 mm, V = 2e-9 m^3: A = 2e-9 2^(1/3)/3e-3 = 8.399473666e-7 m^2.
  const PetscReal hr[3] = {1e-3, 2e-3, 1e-3};
  ExpectRel("1x2 mm cell, diagonal normal: V 2^(1/3)/(h_x+h_y)", BurnSurfaceArea(2, hr, g, 2e-9), 8.399473665965821e-07, 1e-14, "by hand");
}

// ---------------------------------------------------------------------------------------------
// Registry

TEST(burn, DefaultIsNone)
{
  auto       m  = Create("pbx");
  BurnInput  in = BurningCell();
  BurnOutput out;
  EXPECT_EQ(m->name_, "none");
  EXPECT_FALSE(m->Ignites(in));
  EXPECT_EQ(m->Evaluate(in, &out), 0);
  Report("none: dm of a hot surface cell", out.dm, 0, 0, "never burns");
  EXPECT_EQ(out.burning, PETSC_FALSE);
  EXPECT_EQ(out.dm, 0.0);
}

TEST(burn, UnknownTypeIsAnError)
{
  ScopedOptions o;
  o.Set("-pbx_burn_type", "fast_burn");
  std::string msg;
  EXPECT_NE(CreateExpectingError("pbx", msg), 0);
  EXPECT_NE(msg.find("-pbx_burn_type"), std::string::npos) << msg;
  EXPECT_NE(msg.find("none, simple_burn, steady_burn"), std::string::npos) << msg;
}

TEST(burn, OutOfRangeIsAnError)
{
  const char *cases[][3] = {
    {"simple_burn", "-bad_burn_simple_A", "-1"}, {"simple_burn", "-bad_burn_simple_surface_contrast", "1"}, {"steady_burn", "-bad_burn_steady_C_p", "0"}, {"steady_burn", "-bad_burn_steady_T0_max", "100"}, // below T0_min (200 K)
  };
  for (const auto &c : cases) {
    ScopedOptions o;
    o.Set("-bad_burn_type", c[0]);
    o.Set(c[1], c[2]);
    std::string msg;
    EXPECT_NE(CreateExpectingError("bad", msg), 0) << c[1];
    EXPECT_NE(msg.find(c[1]), std::string::npos) << msg;
  }
}

// ---------------------------------------------------------------------------------------------
// Simple Burn

TEST(burn, SimpleBurnRate)
{
  ScopedOptions o;
  o.Set("-pbx_burn_type", "simple_burn");
  auto m = Create("pbx");
  EXPECT_EQ(m->name_, "simple_burn");
  BurnInput in = BurningCell();
  PetscReal mdot, Ts;

  // 1 atm: mdot'' = A_b = 75.3 kg/(m^2 s); r = 75.3/1840 m/s = 4.0924 cm/s (ice.md: 4.1 cm/s)
  in.p = 101325;
  EXPECT_EQ(m->MassFlux(in, &mdot, &Ts), 0);
  ExpectRel("simple_burn mdot'' at 1 atm (kg/(m^2 s))", mdot, 75.3, 1e-14, "by hand: A_b");
  ExpectAbs("simple_burn r = mdot''/rho at 1 atm (cm/s)", 100 * mdot / 1840, 4.1, 0.05, "ice.md 3.2, half a unit of 4.1");
  // 10 MPa: (1e7/101325)^0.778 = exp(0.778 ln 98.69233) = exp(0.778 x 4.592007) = exp(3.572582) = 35.60840;
  //   mdot'' = 75.3 x 35.60840 = 2681.313 kg/(m^2 s); r = 2681.313/1840 = 1.457235 m/s (ice.md: 146 cm/s)
  in.p = 1e7;
  EXPECT_EQ(m->MassFlux(in, &mdot, &Ts), 0);
  ExpectRel("simple_burn mdot'' at 10 MPa (kg/(m^2 s))", mdot, 2681.3126167957594, 1e-12, "by hand");
  ExpectAbs("simple_burn r = mdot''/rho at 10 MPa (cm/s)", 100 * mdot / 1840, 146, 0.5, "ice.md 3.2, half a unit of 146");

  // Evaluate: dm = mdot'' A dt = 2681.313 x 1e-6 m^2 x 1e-6 s = 2.681313e-9 kg, Q = 2e6 J/kg
  BurnOutput out;
  EXPECT_EQ(m->Evaluate(in, &out), 0);
  EXPECT_EQ(out.burning, PETSC_TRUE);
  ExpectRel("simple_burn dm at 10 MPa (kg)", out.dm, 2681.3126167957594e-12, 1e-12, "mdot'' A dt");
  ExpectRel("simple_burn Q (J/kg)", out.Q, 2.0e6, 0, "default Enthalpy");
}

TEST(burn, SimpleBurnThresholds)
{
  ScopedOptions o;
  o.Set("-pbx_burn_type", "simple_burn");
  auto            m = Create("pbx");
  BurnOutput      out;
  const BurnInput base = BurningCell();
  EXPECT_TRUE(m->Ignites(base));
  struct Case {
    const char *what;
    void (*set)(BurnInput &);
    bool burns;
  } cases[] = {
    {"T_hot = T_th = 450 K", [](BurnInput &i) { i.T_hot = 450; }, false},
    {"T_hot = 449 K", [](BurnInput &i) { i.T_hot = 449; }, false},
    {"T_hot = 450.001 K", [](BurnInput &i) { i.T_hot = 450.001; }, true},
    {"p = p_th = 5e4 Pa", [](BurnInput &i) { i.p = 5e4; }, false},
    {"p = 4e4 Pa", [](BurnInput &i) { i.p = 4e4; }, false},
    {"p = 5.001e4 Pa", [](BurnInput &i) { i.p = 5.001e4; }, true},
    {"contrast = 0.4", [](BurnInput &i) { i.mass_contrast = 0.4; }, false},
    {"contrast = 0.2 (interior)", [](BurnInput &i) { i.mass_contrast = 0.2; }, false},
    {"contrast = 0.41", [](BurnInput &i) { i.mass_contrast = 0.41; }, true},
    {"contrast = 1 (lone node)", [](BurnInput &i) { i.mass_contrast = 1; }, false},
    // no one material above T_th, but the gases together fill > 0.2 of the cell at 900 K
    {"T_hot = 449 K, gases together at 900 K",
     [](BurnInput &i) {
       i.T_hot   = 449;
       i.T_gases = 900;
     },
     true},
    {"T_hot = 449 K, gases together at 450 K",
     [](BurnInput &i) {
       i.T_hot   = 449;
       i.T_gases = 450;
     },
     false},
  };
  for (const Case &c : cases) {
    BurnInput in = base;
    c.set(in);
    EXPECT_EQ(m->Evaluate(in, &out), 0);
    Report(std::string("simple_burn dm, ") + c.what, out.dm, c.burns ? 1 : 0, 0, c.burns ? "burns (dm > 0)" : "no burn (dm = 0)");
    EXPECT_EQ(out.burning == PETSC_TRUE, c.burns) << c.what;
    if (c.burns) EXPECT_GT(out.dm, 0.0) << c.what;
    else EXPECT_EQ(out.dm, 0.0) << c.what;
  }
}

TEST(burn, SimpleBurnCapAndOptions)
{
  ScopedOptions o;
  o.Set("-pbx_burn_type", "simple_burn");
  o.Set("-pbx_burn_simple_A", "100");
  o.Set("-pbx_burn_simple_T_th", "500");
  o.Set("-pbx_burn_simple_Q", "3e6");
  auto       m  = Create("pbx");
  BurnInput  in = BurningCell();
  BurnOutput out;
  // A_b = 100, p = p_ref: mdot'' = 100 kg/(m^2 s); uncapped dm = 100 x 1e-6 x 1e-6 = 1e-10 kg
  in.p = 101325;
  EXPECT_EQ(m->Evaluate(in, &out), 0);
  ExpectRel("simple_burn -A 100: mdot''", out.mdot, 100, 1e-14, "option");
  ExpectRel("simple_burn -Q 3e6: Q", out.Q, 3e6, 0, "option");
  ExpectRel("simple_burn uncapped dm", out.dm, 1e-10, 1e-14, "mdot'' A dt");
  // M_s = 5e-11 kg, M_tiny = 1e-15 kg: dm = M_s - M_tiny = 4.9999e-11 kg
  in.M_s = 5e-11;
  EXPECT_EQ(m->Evaluate(in, &out), 0);
  ExpectRel("simple_burn dm capped at M_s - M_tiny", out.dm, 5e-11 - 1e-15, 1e-14, "cap");
  // M_s below M_tiny: nothing to burn
  in.M_s = 5e-16;
  EXPECT_EQ(m->Evaluate(in, &out), 0);
  Report("simple_burn dm with M_s < M_tiny", out.dm, 0, 0, "cap at 0");
  EXPECT_EQ(out.dm, 0.0);
  // -T_th 500: 450 < T_hot = 480 < 500 does not ignite
  in.T_hot = 480;
  EXPECT_FALSE(m->Ignites(in));
}

TEST(burn, SimpleBurnGasesApart)
{
  // -burn_simple_gases_together false: each gas alone (Uintah's reading); the gases' mixture
  // temperature no longer counts
  ScopedOptions o;
  o.Set("-pbx_burn_type", "simple_burn");
  o.Set("-pbx_burn_simple_gases_together", "false");
  auto      m  = Create("pbx");
  BurnInput in = BurningCell();
  in.T_hot     = 449;
  in.T_gases   = 900;
  EXPECT_FALSE(m->Ignites(in));
  in.T_hot = 451;
  EXPECT_TRUE(m->Ignites(in));
}

// ---------------------------------------------------------------------------------------------
// Steady Burn (WSB)

// The oracle of ice.md 3.3 (kappa_c 0.2, rho_c 1840, T0 300 K; derived there from the same formulas).
// Tolerances: half a unit of the last printed digit of each entry, absolute (T_s 0.05 K, i.e.
// 3.8e-5 to 7.6e-5 relative; mdot 0.0005/0.005/0.005/0.05, i.e. 7.9e-4, 1.3e-3, 1.8e-4, 2.4e-4 relative;
// r 0.0005/0.0005/0.005/0.005 cm/s).
TEST(burn, SteadyBurnOracle)
{
  ScopedOptions o;
  o.Set("-pbx_burn_type", "steady_burn");
  auto m = Create("pbx");
  EXPECT_EQ(m->name_, "steady_burn");
  const struct {
    double p, Ts, dTs, mdot, dmdot, r, dr;
  } table[] = {
    {0.101325e6, 656.1, 0.05, 0.631, 0.0005, 0.034, 0.0005},
    {1e6, 743.2, 0.05, 3.99, 0.005, 0.217, 0.0005},
    {10e6, 862.9, 0.05, 28.27, 0.005, 1.54, 0.005},
    {100e6, 1027.8, 0.05, 204.2, 0.05, 11.10, 0.005},
  };
  for (const auto &row : table) {
    BurnInput in   = BurningCell();
    in.p           = row.p;
    in.T_s         = 300;
    in.rho_s       = 1840;
    PetscReal mdot = 0, Ts = 0;
    ASSERT_EQ(m->MassFlux(in, &mdot, &Ts), 0);
    const std::string at = "steady_burn p " + std::to_string(row.p / 1e6) + " MPa";
    ExpectAbs(at + " T_s (K)", Ts, row.Ts, row.dTs, "ice.md 3.3 table");
    ExpectAbs(at + " mdot (kg/(m^2 s))", mdot, row.mdot, row.dmdot, "ice.md 3.3 table");
    ExpectAbs(at + " r = mdot/rho_c (cm/s)", 100 * mdot / 1840, row.r, row.dr, "ice.md 3.3 table");
    // the returned T_s satisfies the WSB relation to the solver's 1e-6 K
    const double R = 8.314, Ac = 1.637e15, Ec = 1.76e5, Bg = 1.6e-3, Qc = 4.0e5, Qg = 3.018e6, kg = 0.07, kc = 0.2, Cp = 1400, W = 0.0342, T0 = 300;
    const double m_of = std::sqrt(kc * 1840 * Ac * R * Ts * Ts * std::exp(-Ec / (R * Ts)) / (Cp * Ec * (Ts - T0 - Qc / (2 * Cp))));
    const double Da   = 4 * kg * Bg * W * W * row.p * row.p / (Cp * R * R * m_of * m_of);
    const double F    = T0 + Qc / Cp + (Qg / Cp) * Da / std::pow(std::sqrt(1 + Da) + 1, 2);
    ExpectAbs(at + " residual T_s - F(T_s) (K)", Ts - F, 0, 1e-6, "solver tolerance");
    ExpectRel(at + " mdot = mdot(T_s)", mdot, m_of, 1e-12, "WSB condensed-phase relation");
    BurnOutput out;
    EXPECT_EQ(m->Evaluate(in, &out), 0);
    ExpectRel(at + " Q = Q_c + Q_g", out.Q, 3.418e6, 1e-15, "ice.md 3.3");
    EXPECT_EQ(out.T_surf, Ts);
  }
}

// The state at which a coupled cylinder run stopped (1.39 GPa, T0 clamped to 550 K, the reactant
// compressed to 3932 kg/m^3): the WSB relation is so steep there that one ulp of T_s moves the residual
// by more than 1e-6 K; the solver must return the root bracketed to double precision, and the rate
// must exceed the 100 MPa rate of the table (it grows with pressure).
TEST(burn, SteadyBurnHighPressure)
{
  ScopedOptions o;
  o.Set("-pbx_burn_type", "steady_burn");
  auto      m    = Create("pbx");
  BurnInput in   = BurningCell();
  in.p           = 1.39121e9;
  in.T_s         = 600;
  in.rho_s       = 3931.99;
  PetscReal mdot = 0, Ts = 0;
  ASSERT_EQ(m->MassFlux(in, &mdot, &Ts), 0);
  EXPECT_GT(Ts, 550 + 4.0e5 / 1400);
  EXPECT_LT(Ts, 550 + (4.0e5 + 3.018e6) / 1400);
  EXPECT_GT(mdot, 204.2);
}

TEST(burn, SteadyBurnIgnitionAndClamp)
{
  ScopedOptions o;
  o.Set("-pbx_burn_type", "steady_burn");
  auto            m    = Create("pbx");
  const BurnInput base = BurningCell(); // T_hot 600 > T_ign 550, p 1 MPa, contrast 0.5, 4 particles
  EXPECT_TRUE(m->Ignites(base));
  struct Case {
    const char *what;
    void (*set)(BurnInput &);
    bool burns;
  } cases[] = {
    {"T_hot = T_ign = 550 K", [](BurnInput &i) { i.T_hot = 550; }, false},     {"p = 4.9e4 Pa < p_th", [](BurnInput &i) { i.p = 4.9e4; }, false},           {"p = p_th = 5e4 Pa", [](BurnInput &i) { i.p = 5e4; }, true},
    {"M_min/M_max = 0.7", [](BurnInput &i) { i.mass_contrast = 0.3; }, false}, {"no particle in the cell", [](BurnInput &i) { i.n_particles = 0; }, false},
  };
  BurnOutput out;
  for (const Case &c : cases) {
    BurnInput in = base;
    c.set(in);
    EXPECT_EQ(m->Evaluate(in, &out), 0);
    Report(std::string("steady_burn dm, ") + c.what, out.dm, c.burns ? 1 : 0, 0, c.burns ? "burns (dm > 0)" : "no burn (dm = 0)");
    EXPECT_EQ(out.burning == PETSC_TRUE, c.burns) << c.what;
  }
  // T0 above T0_max = 550 K burns at the 550 K rate (at 1 MPa: T_s 838.45 K, mdot 32.6 kg/(m^2 s))
  BurnInput hot = base, at550 = base;
  hot.T_s   = 650;
  at550.T_s = 550;
  PetscReal m_hot, T_hot, m_550, T_550;
  EXPECT_EQ(m->MassFlux(hot, &m_hot, &T_hot), 0);
  EXPECT_EQ(m->MassFlux(at550, &m_550, &T_550), 0);
  ExpectRel("steady_burn T0 650 K clamped to 550 K: mdot", m_hot, m_550, 0, "T0_max clamp");
  ExpectAbs("steady_burn T0 550 K, 1 MPa: T_s (K)", T_550, 838.45, 0.01, "derived (Python bisection of the same relations)");
  ExpectAbs("steady_burn T0 550 K, 1 MPa: mdot (kg/(m^2 s))", m_550, 32.616, 0.001, "derived (Python bisection)");
}

// ---------------------------------------------------------------------------------------------
// Thermal decomposition (CVODE)

namespace {

// Independent integration of d lambda/dt = Z (1 - lambda) e^{-T_a/T}, c dT/dt = Q d lambda/dt + h (T_env - T),
// written out here (not ThermalDecomposition::Rates). A fixed time step cannot follow the runaway
// (the reaction time falls from seconds to nanoseconds), so classical RK4 integrates t(T) and
// lambda(T) with T as the independent variable, valid while dT/dt > 0 (checked), from T0 to T_end:
//   dt/dT = c/(Q r + h (T_env - T)),  d lambda/dT = r dt/dT,  r = Z (1 - lambda) e^{-T_a/T}.
struct RK4Result {
  double t, lambda;
  bool   monotone;
};
RK4Result RK4InTemperature(const ThermalDecompositionParameters &p, double T0, double T_end, int n)
{
  bool monotone = true;
  auto f        = [&](double T, double lambda, double *dt_dT, double *dl_dT) {
    const double r    = p.Z * (1 - lambda) * std::exp(-p.T_a / T);
    const double Tdot = (p.Q * r + p.h * (p.T_env - T)) / p.c;
    if (!(Tdot > 0)) monotone = false;
    *dt_dT = 1 / Tdot;
    *dl_dT = r / Tdot;
  };
  const double dT = (T_end - T0) / n;
  double       t = 0, lambda = 0, T = T0;
  for (int i = 0; i < n; ++i) {
    double a1, b1, a2, b2, a3, b3, a4, b4;
    f(T, lambda, &a1, &b1);
    f(T + dT / 2, lambda + dT / 2 * b1, &a2, &b2);
    f(T + dT / 2, lambda + dT / 2 * b2, &a3, &b3);
    f(T + dT, lambda + dT * b3, &a4, &b4);
    t += dT / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
    lambda += dT / 6 * (b1 + 2 * b2 + 2 * b3 + b4);
    T = T0 + (i + 1) * dT;
  }
  return {t, lambda, monotone};
}

} // namespace

// Adiabatic, lambda0 = 0, runaway at T0 + 500 K. With eps = T0/T_a, B = Q T_a/(c T0^2) and
// s = (T - T0) T_a/T0^2, the exact delay is t = t_ad int_0^{s_end} exp(-s + eps s^2/(1 + eps s))/(1 - s/B) ds
// (lambda = (c/Q)(T - T0) = s/B adiabatically), so
//   t/t_ad = 1 + d1 + d2 + ...,  d1 = 2 eps + 1/B (the O(R T0/E) correction),  d2 = 6 eps^2 + 6 eps/B + 2/B^2.
// At T0 = 500 K: eps = 0.018854, B = 585.78, d1 = 0.039415, d2 = 0.002332; t_ad = 3.7006 s.
// Asserted: |t/t_ad - 1| <= d1 + 2 d2 (agreement to first order), and |t/t_ad - 1 - d1| <= 2 d2
// (the first-order correction itself is right; a Simpson quadrature of the integral gives
// t/t_ad - 1 - d1 = 1.08 d2 at 450 K, 1.09 d2 at 500 K, 1.10 d2 at 550 K).
TEST(burn, ThermalDecompositionAsymptotic)
{
  ThermalDecomposition td;
  for (double T0 : {450.0, 500.0, 550.0}) {
    const ThermalDecompositionParameters &p       = td.par;
    PetscReal                             t       = 0;
    PetscBool                             ignited = PETSC_FALSE;
    ASSERT_EQ(td.IgnitionDelay(T0, 0, 1e6, &t, &ignited), 0);
    ASSERT_TRUE(ignited);
    const double      t_ad = td.AdiabaticInductionTime(T0);
    const double      eps = T0 / p.T_a, B = p.Q * p.T_a / (p.c * T0 * T0);
    const double      d1 = 2 * eps + 1 / B, d2 = 6 * eps * eps + 6 * eps / B + 2 / (B * B);
    const std::string at = "T0 " + std::to_string((int)T0) + " K";
    std::printf("[ measured ] %s: t %.10g s, t_ad %.10g s, t/t_ad - 1 = %.6f, d1 = 2 eps + 1/B = %.6f, d2 = %.6f, CVODE steps %ld\n", at.c_str(), (double)t, t_ad, t / t_ad - 1, d1, d2, td.last_steps());
    ExpectAbs(at + " t/t_ad - 1 (first order)", t / t_ad - 1, 0, d1 + 2 * d2, "|t/t_ad - 1| <= d1 + 2 d2");
    ExpectAbs(at + " t/t_ad - 1 - d1 (second order)", t / t_ad - 1 - d1, 0, 2 * d2, "|.| <= 2 d2");
    EXPECT_GT(t / t_ad - 1, 0.0); // both corrections lengthen the delay
  }
}

TEST(burn, ThermalDecompositionVsRK4)
{
  ThermalDecomposition td; // one integrator, re-initialised for each case
  struct Case {
    const char *what;
    double      T0, h, T_env;
  } cases[] = {
    {"adiabatic, T0 500 K", 500, 0, 300},
    {"adiabatic, T0 600 K", 600, 0, 300},
    // cook-off: an element at 300 K heated by a 520 K environment with time constant c/h = 10 s
    {"cook-off, T0 300 K, T_env 520 K, c/h 10 s", 300, 99.6, 520},
  };
  for (const Case &c : cases) {
    td.par.h     = c.h;
    td.par.T_env = c.T_env;
    PetscReal t = 0, T_end = 0;
    PetscBool ignited = PETSC_FALSE;
    ASSERT_EQ(td.IgnitionDelay(c.T0, 0, 1e6, &t, &ignited, &T_end), 0);
    ASSERT_TRUE(ignited) << c.what;
    const RK4Result fine = RK4InTemperature(td.par, c.T0, c.T0 + td.par.runaway_rise, 200000);
    const RK4Result half = RK4InTemperature(td.par, c.T0, c.T0 + td.par.runaway_rise, 100000);
    EXPECT_TRUE(fine.monotone) << c.what;
    std::printf("[ measured ] %s: CVODE t %.12g s (T %.6f K, %ld steps), RK4 t %.12g s, RK4 halving difference %.2e (rel)\n", c.what, (double)t, (double)T_end, td.last_steps(), fine.t, std::fabs(fine.t - half.t) / fine.t);
    ExpectRel(std::string(c.what) + " ignition delay vs RK4", t, fine.t, 1e-6, "RK4 in T, dT = 0.0025 K");
    // CVODE locates the root in t to ~100 u max(|t|, |h|); at runaway dT/dt ~ 1e11 K/s, so the state
    // interpolated there is off T0 + 500 K by dT/dt times that: compare in time, not in T.
    PetscReal dl, Tdot;
    td.Rates(0, T_end, &dl, &Tdot);
    const double dt_equiv = std::fabs(T_end - (c.T0 + 500)) / Tdot; // dT/dt at lambda = 0: an estimate (lambda < 0.1 there)
    ExpectAbs(std::string(c.what) + " |T_root - (T0 + 500 K)|/(dT/dt) (s)", dt_equiv, 0, 1e3 * PETSC_MACHINE_EPSILON * t, "root located in time to 1e3 u t");
    EXPECT_LE(std::fabs(fine.t - half.t), 1e-8 * fine.t) << "the RK4 reference itself is converged";
  }
  // re-use gives the same answer (CVodeReInit resets everything)
  td.par.h = 0;
  PetscReal t1, t2;
  PetscBool ig;
  ASSERT_EQ(td.IgnitionDelay(500, 0, 1e6, &t1, &ig), 0);
  ASSERT_EQ(td.IgnitionDelay(600, 0, 1e6, &t2, &ig), 0);
  ASSERT_EQ(td.IgnitionDelay(500, 0, 1e6, &t2, &ig), 0);
  ExpectRel("re-initialised integrator repeats the 500 K delay", t2, t1, 0, "CVodeReInit");
  // no runaway before t_max
  ASSERT_EQ(td.IgnitionDelay(500, 0, 1.0, &t1, &ig), 0);
  EXPECT_FALSE(ig);
  EXPECT_EQ(t1, 1.0);
  // the dT/dt criterion fires first. Near runaway t_end - t(T) ~ T^2/(T_a dT/dt) (high activation
  // energy: the remaining time is one e-folding of exp(-T_a/T) over the current rate), so with the
  // rate threshold 1e6 K/s reached at T* the two criteria differ by ~ T*^2/(T_a 1e6 K/s) (derived,
  // to O(T*/T_a) = 2.5 %; asserted within 10 %).
  ASSERT_EQ(td.IgnitionDelay(500, 0, 1e6, &t1, &ig), 0); // T0 + 500 K criterion
  td.par.runaway_rate = 1e6;                             // K/s
  PetscReal T_star    = 0;
  ASSERT_EQ(td.IgnitionDelay(500, 0, 1e6, &t2, &ig, &T_star), 0);
  td.par.runaway_rate = 0;
  EXPECT_TRUE(ig);
  const double gap = T_star * T_star / (td.par.T_a * 1e6);
  std::printf("[ measured ] dT/dt > 1e6 K/s at %.12g s (T* %.3f K), T0 + 500 K at %.12g s\n", (double)t2, (double)T_star, (double)t1);
  EXPECT_LT(t2, t1);
  ExpectRel("t(T0 + 500 K) - t(dT/dt = 1e6 K/s) (s)", t1 - t2, gap, 0.1, "T*^2/(T_a rate)");
}

// Advance over a slow (non-stiff) interval against RK4 in time: an element at 460 K in a 460 K
// environment with c/h = 100 s. Semenov: (Q/c) k(T) T_a/T^2 = 5522 x 4.6e-6 x 0.125 = 3.2e-3 /s < h/c =
// 1e-2 /s, so it is subcritical: it self-heats by a few K and reacts slowly for 200 s; fixed step 0.01 s.
TEST(burn, ThermalDecompositionAdvance)
{
  ThermalDecomposition td;
  td.par.h         = 9.96;
  td.par.T_env     = 460;
  PetscReal lambda = 0, T = 460;
  ASSERT_EQ(td.Advance(200, &lambda, &T), 0);
  const ThermalDecompositionParameters &p = td.par;

  auto f = [&](double l, double TT, double *dl, double *dT) {
    const double r = p.Z * (1 - l) * std::exp(-p.T_a / TT);
    *dl            = r;
    *dT            = (p.Q * r + p.h * (p.T_env - TT)) / p.c;
  };
  double       l = 0, TT = 460;
  const double h = 0.01;
  for (int i = 0; i < 20000; ++i) {
    double k1l, k1T, k2l, k2T, k3l, k3T, k4l, k4T;
    f(l, TT, &k1l, &k1T);
    f(l + h / 2 * k1l, TT + h / 2 * k1T, &k2l, &k2T);
    f(l + h / 2 * k2l, TT + h / 2 * k2T, &k3l, &k3T);
    f(l + h * k3l, TT + h * k3T, &k4l, &k4T);
    l += h / 6 * (k1l + 2 * k2l + 2 * k3l + k4l);
    TT += h / 6 * (k1T + 2 * k2T + 2 * k3T + k4T);
  }
  std::printf("[ measured ] Advance 200 s: CVODE (lambda %.10e, T %.10f K) in %ld steps, RK4 (lambda %.10e, T %.10f K)\n", (double)lambda, (double)T, td.last_steps(), l, TT);
  ExpectRel("Advance: T after 200 s", T, TT, 1e-9, "RK4 in time, 0.01 s");
  ExpectRel("Advance: lambda after 200 s", lambda, l, 1e-6, "RK4 in time, 0.01 s");
}

TEST(burn, ThermalDecompositionOptions)
{
  ScopedOptions o;
  o.Set("-pbx_decomposition_Z", "1e19");
  o.Set("-pbx_decomposition_h", "5");
  ThermalDecomposition td;
  ASSERT_EQ(td.SetFromOptions(PETSC_COMM_WORLD, "pbx"), 0);
  ExpectRel("-pbx_decomposition_Z", td.par.Z, 1e19, 0, "option");
  ExpectRel("-pbx_decomposition_h", td.par.h, 5, 0, "option");
  ExpectRel("T_a default (ice.md 5.2 E/R)", td.par.T_a, 2.652e4, 0, "default");
  // t_ad scales as 1/Z: 5x the default 500 K value 3.7006026 s
  ExpectRel("t_ad at 500 K with Z 1e19", td.AdiabaticInductionTime(500), 5 * 3.7006026346062337, 1e-12, "closed form");
  ScopedOptions bad;
  bad.Set("-bad_decomposition_rtol", "0.1");
  ThermalDecomposition tb;
  std::string          msg;
  PetscPushErrorHandler(CaptureHandler, &msg);
  const PetscErrorCode rc = tb.SetFromOptions(PETSC_COMM_WORLD, "bad");
  PetscPopErrorHandler();
  std::printf("[ measured ] error %d: %s\n", (int)rc, msg.c_str());
  EXPECT_NE(rc, 0);
  EXPECT_NE(msg.find("-bad_decomposition_rtol"), std::string::npos) << msg;
}
