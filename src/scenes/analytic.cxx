#include "scenes/analytic.hpp"
#include "mpm/swarm_access.hpp"
#include "util.hpp"
#include <cmath>

namespace burst {

class BarMode final : public AnalyticSolution {
public:
  PetscReal   length = 25, amplitude = 0.1, wave_number = 0, frequency = 0;
  const char *Name() const override { return "bar_mode"; }
  void        Displacement(const PetscReal X[], PetscReal t, PetscReal u[]) const override
  {
    for (int d = 0; d < 3; ++d) u[d] = 0;
    u[0] = amplitude / frequency * std::sin(frequency * t) * std::sin(wave_number * X[0]);
  }
  void Velocity(const PetscReal X[], PetscReal t, PetscReal v[]) const override
  {
    for (int d = 0; d < 3; ++d) v[d] = 0;
    v[0] = amplitude * std::cos(frequency * t) * std::sin(wave_number * X[0]);
  }
  void DeformationGradient(const PetscReal X[], PetscReal t, PetscReal F[]) const override
  {
    for (int a = 0; a < 9; ++a) F[a] = (a % 4 == 0) ? 1.0 : 0.0;
    F[0] += amplitude / frequency * std::sin(frequency * t) * wave_number * std::cos(wave_number * X[0]);
  }
};

class AxisAligned final : public AnalyticSolution {
public:
  PetscReal   amplitude = 0.05, mu = 0, lambda = 0, rho0 = 1, c = 0;
  const char *Name() const override { return "axis_aligned"; }
  // Phase of each displacement component: 0, 2 pi/3, 4 pi/3 (W&G 2008).
  PetscReal Phase(int d) const { return d * 2.0 * PETSC_PI / 3.0; }
  void      Displacement(const PetscReal X[], PetscReal t, PetscReal u[]) const override
  {
    for (int d = 0; d < 3; ++d) u[d] = d < dim ? amplitude * std::sin(PETSC_PI * X[d]) * std::sin(c * PETSC_PI * t + Phase(d)) : 0;
  }
  void Velocity(const PetscReal X[], PetscReal t, PetscReal v[]) const override
  {
    for (int d = 0; d < 3; ++d) v[d] = d < dim ? amplitude * c * PETSC_PI * std::sin(PETSC_PI * X[d]) * std::cos(c * PETSC_PI * t + Phase(d)) : 0;
  }
  void DeformationGradient(const PetscReal X[], PetscReal t, PetscReal F[]) const override
  {
    for (int a = 0; a < 9; ++a) F[a] = (a % 4 == 0) ? 1.0 : 0.0;
    for (int d = 0; d < dim; ++d) F[4 * d] += amplitude * PETSC_PI * std::cos(PETSC_PI * X[d]) * std::sin(c * PETSC_PI * t + Phase(d));
  }
  bool HasBodyForce() const override { return true; }
  // b_d = pi^2 u_d [mu/rho0 - c^2 - (lambda (ln J - 1) - mu) / (rho0 F_dd^2)]  (verification.md 1.3)
  void BodyForce(const PetscReal X[], PetscReal t, PetscReal b[]) const override
  {
    PetscReal u[3], F[9];
    Displacement(X, t, u);
    DeformationGradient(X, t, F);
    const PetscReal J = F[0] * F[4] * F[8], lnJ = std::log(J);
    for (int d = 0; d < 3; ++d) {
      const PetscReal Fdd = F[4 * d];
      b[d]                = d < dim ? PETSC_PI * PETSC_PI * u[d] * (mu / rho0 - c * c - (lambda * (lnJ - 1) - mu) / (rho0 * Fdd * Fdd)) : 0;
    }
  }
};

// Axisymmetric radial/axial manufactured solution for the neo-Hookean solid (burst's own, in the
// manner of Wallstedt & Guilkey 2008) on r, z in [0, 1] x [0, 1], u_theta = 0:
//   u_r = A sin(pi R) sin(c pi t),  u_z = A sin(pi Z) sin(c pi t + 2 pi/3),
// so F = diag(F_rr, F_zz, F_tt) with F_tt = 1 + u_r/R (the hoop stretch, -> 1 + A pi sin(c pi t) on
// the axis). With P_ii = mu (F_ii - 1/F_ii) + lambda ln J / F_ii, the body force makes it exact:
//   b_r = u_r'' - [dP_rr/dR + (P_rr - P_tt)/R] / rho0,  b_z = u_z'' - dP_zz/dZ / rho0.
// u_r = 0 on the axis and at R = 1, u_z = 0 at Z = 0, 1: rollers on every face, no shear traction.
class AxisymmetricRadial final : public AnalyticSolution {
public:
  PetscReal   amplitude = 0.05, mu = 0, lambda = 0, rho0 = 1, c = 0;
  const char *Name() const override { return "axisymmetric_radial"; }
  void        Phases(PetscReal t, PetscReal &sr, PetscReal &sz) const
  {
    sr = std::sin(c * PETSC_PI * t);
    sz = std::sin(c * PETSC_PI * t + 2.0 * PETSC_PI / 3.0);
  }
  // sin(pi R)/R and its derivative, with their series near the axis
  static void HoopShape(PetscReal R, PetscReal &g, PetscReal &dg)
  {
    const PetscReal pi = PETSC_PI;
    if (R < 1e-4) {
      g  = pi - pi * pi * pi * R * R / 6.0;
      dg = -pi * pi * pi * R / 3.0;
    } else {
      g  = std::sin(pi * R) / R;
      dg = (pi * R * std::cos(pi * R) - std::sin(pi * R)) / (R * R);
    }
  }
  void Displacement(const PetscReal X[], PetscReal t, PetscReal u[]) const override
  {
    PetscReal sr, sz;
    Phases(t, sr, sz);
    u[0] = amplitude * std::sin(PETSC_PI * X[0]) * sr;
    u[1] = amplitude * std::sin(PETSC_PI * X[1]) * sz;
    u[2] = 0;
  }
  void Velocity(const PetscReal X[], PetscReal t, PetscReal v[]) const override
  {
    const PetscReal w = c * PETSC_PI;
    v[0]              = amplitude * w * std::sin(PETSC_PI * X[0]) * std::cos(w * t);
    v[1]              = amplitude * w * std::sin(PETSC_PI * X[1]) * std::cos(w * t + 2.0 * PETSC_PI / 3.0);
    v[2]              = 0;
  }
  void DeformationGradient(const PetscReal X[], PetscReal t, PetscReal F[]) const override
  {
    PetscReal sr, sz, g, dg;
    Phases(t, sr, sz);
    HoopShape(X[0], g, dg);
    for (int a = 0; a < 9; ++a) F[a] = 0;
    F[0] = 1 + amplitude * PETSC_PI * std::cos(PETSC_PI * X[0]) * sr;
    F[4] = 1 + amplitude * PETSC_PI * std::cos(PETSC_PI * X[1]) * sz;
    F[8] = 1 + amplitude * g * sr;
  }
  bool HasBodyForce() const override { return true; }
  void BodyForce(const PetscReal X[], PetscReal t, PetscReal b[]) const override
  {
    const PetscReal pi = PETSC_PI, R = X[0], Z = X[1], A = amplitude;
    PetscReal       sr, sz, g, dg;
    Phases(t, sr, sz);
    HoopShape(R, g, dg);
    const PetscReal Frr = 1 + A * pi * std::cos(pi * R) * sr, dFrr = -A * pi * pi * std::sin(pi * R) * sr;
    const PetscReal Ftt = 1 + A * g * sr, dFtt = A * dg * sr;
    const PetscReal Fzz = 1 + A * pi * std::cos(pi * Z) * sz, dFzz = -A * pi * pi * std::sin(pi * Z) * sz;
    const PetscReal lnJ = std::log(Frr * Fzz * Ftt);
    const PetscReal Prr = mu * (Frr - 1 / Frr) + lambda * lnJ / Frr, Ptt = mu * (Ftt - 1 / Ftt) + lambda * lnJ / Ftt;
    const PetscReal dlnJ_R = dFrr / Frr + dFtt / Ftt, dlnJ_Z = dFzz / Fzz;
    const PetscReal dPrr = mu * (1 + 1 / (Frr * Frr)) * dFrr + lambda * (dlnJ_R / Frr - lnJ * dFrr / (Frr * Frr));
    const PetscReal dPzz = mu * (1 + 1 / (Fzz * Fzz)) * dFzz + lambda * (dlnJ_Z / Fzz - lnJ * dFzz / (Fzz * Fzz));
    // (P_rr - P_tt)/R: both -> the same value on the axis; R >= h/(2 ppc) > 0 for particles
    const PetscReal hoop = (Prr - Ptt) / R;
    const PetscReal w2   = (c * pi) * (c * pi);
    b[0]                 = -A * w2 * std::sin(pi * R) * sr - (dPrr + hoop) / rho0;
    b[1]                 = -A * w2 * std::sin(pi * Z) * sz - dPzz / rho0;
    b[2]                 = 0;
  }
};

// A decaying mode of the heat equation in a bar at rest: T0 + dT f(pi X/L) exp(-alpha pi^2 t/L^2),
// f = sin (ends held at T0) or cos (insulated ends).
class HeatMode final : public AnalyticSolution {
public:
  bool        cosine = false;
  PetscReal   length = 1, amplitude = 10, T0 = 300, alpha = 0;
  const char *Name() const override { return cosine ? "heat_cosine" : "heat_sine"; }
  void        Displacement(const PetscReal X[], PetscReal t, PetscReal u[]) const override
  {
    (void)X;
    (void)t;
    for (int d = 0; d < 3; ++d) u[d] = 0;
  }
  void Velocity(const PetscReal X[], PetscReal t, PetscReal v[]) const override
  {
    (void)X;
    (void)t;
    for (int d = 0; d < 3; ++d) v[d] = 0;
  }
  void DeformationGradient(const PetscReal X[], PetscReal t, PetscReal F[]) const override
  {
    (void)X;
    (void)t;
    for (int a = 0; a < 9; ++a) F[a] = (a % 4 == 0) ? 1.0 : 0.0;
  }
  bool      HasTemperature() const override { return true; }
  PetscReal Temperature(const PetscReal X[], PetscReal t) const override
  {
    const PetscReal kx = PETSC_PI * X[0] / length, decay = std::exp(-alpha * PETSC_PI * PETSC_PI * t / (length * length));
    return T0 + amplitude * (cosine ? std::cos(kx) : std::sin(kx)) * decay;
  }
};

static const char *const AnalyticNames[] = {"none", "bar_mode", "axis_aligned", "heat_sine", "heat_cosine", "axisymmetric_radial"};

PetscErrorCode CreateAnalyticSolution(Simulation &sim)
{
  int       type          = 0;
  char      material[256] = "";
  PetscBool has_material  = PETSC_FALSE;
  PetscReal amplitude = -1, length = -1, T0 = 300;
  PetscFunctionBeginUser;
  PetscOptionsBegin(sim.comm, "", "Analytic solutions for verification", "Analytic");
  PetscCall(OptionsChoice(PetscOptionsObject, "-analytic", "Analytic solution that sets the initial state, body force and the error monitor", AnalyticNames, 6, &type, nullptr));
  PetscCall(PetscOptionsString("-analytic_material", "Material whose parameters the analytic solution uses (default: the first of -materials)", "", material, material, sizeof(material), &has_material));
  PetscCall(PetscOptionsReal("-analytic_amplitude", "bar_mode: velocity amplitude v0 (m/s, default 0.1); axis_aligned: displacement amplitude A (m, default 0.05); heat_sine/heat_cosine: temperature amplitude dT (K, default 10)", "", amplitude,
                             &amplitude, nullptr));
  PetscCall(PetscOptionsReal("-analytic_length", "bar_mode: bar length L (m), default 25; heat_sine/heat_cosine: bar length L (m, the bar is [0, L] in x), default 1", "", length, &length, nullptr));
  PetscCall(PetscOptionsReal("-analytic_temperature", "heat_sine/heat_cosine: base temperature T0 (K), > 0 (heat_sine: give the same to -mpm_heat_bc_xmin/xmax)", "", T0, &T0, nullptr));
  PetscOptionsEnd();
  if (type == 0 || sim.mpm.materials.empty()) PetscFunctionReturn(PETSC_SUCCESS);

  const Material *m = sim.mpm.materials[0].get();
  if (has_material) {
    m = nullptr;
    for (auto &mm : sim.mpm.materials)
      if (mm->name_ == material) m = mm.get();
    PetscCheck(m, sim.comm, PETSC_ERR_USER_INPUT, "Option -analytic_material %s is not one of -materials", material);
  }
  PetscReal E = 0, nu = 0;
  PetscBool setE = PETSC_FALSE;
  PetscCall(PetscOptionsGetReal(nullptr, (m->name_ + "_").c_str(), "-youngs_modulus", &E, &setE));
  PetscCall(PetscOptionsGetReal(nullptr, (m->name_ + "_").c_str(), "-poisson_ratio", &nu, nullptr));
  PetscCheck(setE, sim.comm, PETSC_ERR_USER_INPUT, "-analytic %s needs an elastic material with -%s_youngs_modulus", AnalyticNames[type], m->Name());
  if (type == 3 || type == 4) {
    PetscReal k = -1, c = -1;
    PetscBool setk = PETSC_FALSE, setc = PETSC_FALSE, on = PETSC_FALSE;
    PetscCall(PetscOptionsGetBool(nullptr, nullptr, "-mpm_heat_conduction", &on, nullptr));
    PetscCheck(on, sim.comm, PETSC_ERR_USER_INPUT, "-analytic %s needs -mpm_heat_conduction true", AnalyticNames[type]);
    PetscCall(PetscOptionsGetReal(nullptr, (m->name_ + "_").c_str(), "-thermal_conductivity", &k, &setk));
    PetscCall(PetscOptionsGetReal(nullptr, (m->name_ + "_").c_str(), "-heat_capacity", &c, &setc));
    PetscCheck(setk && setc && k >= 0 && c > 0, sim.comm, PETSC_ERR_USER_INPUT, "-analytic %s needs -%s_thermal_conductivity >= 0 and -%s_heat_capacity > 0", AnalyticNames[type], m->Name(), m->Name());
    PetscCall(CheckRange(sim.comm, "-analytic_temperature", T0, 0, PETSC_MAX_REAL, PETSC_TRUE));
    auto heat       = std::make_unique<HeatMode>();
    heat->cosine    = type == 4;
    heat->amplitude = amplitude > 0 ? amplitude : 10;
    heat->length    = length > 0 ? length : 1;
    heat->T0        = T0;
    heat->alpha     = k / (m->Density() * c);
    sim.analytic    = std::move(heat);
  } else if (type == 1) {
    auto bar         = std::make_unique<BarMode>();
    bar->amplitude   = amplitude > 0 ? amplitude : 0.1;
    bar->length      = length > 0 ? length : 25;
    bar->wave_number = PETSC_PI / (2 * bar->length);
    bar->frequency   = bar->wave_number * std::sqrt(E / m->Density());
    sim.analytic     = std::move(bar);
  } else if (type == 5) {
    PetscCheck(sim.mpm.axisymmetric, sim.comm, PETSC_ERR_USER_INPUT, "-analytic axisymmetric_radial needs -axisymmetric (and -dim 2)");
    auto mms       = std::make_unique<AxisymmetricRadial>();
    mms->amplitude = amplitude > 0 ? amplitude : 0.05;
    mms->mu        = E / (2 * (1 + nu));
    mms->lambda    = E / (3 * (1 - 2 * nu)) - 2.0 * mms->mu / 3.0;
    mms->rho0      = m->Density();
    mms->c         = std::sqrt(E / mms->rho0);
    sim.analytic   = std::move(mms);
  } else {
    auto mms       = std::make_unique<AxisAligned>();
    mms->amplitude = amplitude > 0 ? amplitude : 0.05;
    mms->mu        = E / (2 * (1 + nu));
    mms->lambda    = E / (3 * (1 - 2 * nu)) - 2.0 * mms->mu / 3.0;
    mms->rho0      = m->Density();
    mms->c         = std::sqrt(E / mms->rho0);
    sim.analytic   = std::move(mms);
  }
  sim.analytic->dim = sim.mpm.grid.dim;
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Moves every particle to X + u(X, 0) with the exact velocity and deformation gradient.
PetscErrorCode ApplyAnalyticInitialCondition(Simulation &sim)
{
  PetscInt   n, dim = sim.mpm.grid.dim;
  PetscReal *x, *X0, *v, *F, *vol, *vol0, *T;
  PetscFunctionBeginUser;
  if (!sim.analytic) PetscFunctionReturn(PETSC_SUCCESS);
  const bool temperature = sim.analytic->HasTemperature();
  PetscCall(DMSwarmGetLocalSize(sim.mpm.swarm, &n));
  SwarmAccess fields(sim.mpm.swarm);
  PetscCall(fields.Get(DMSwarmPICField_coor, &x));
  PetscCall(fields.Get(field::position0, &X0));
  PetscCall(fields.Get(field::velocity, &v));
  PetscCall(fields.Get(field::F, &F));
  PetscCall(fields.Get(field::volume, &vol));
  PetscCall(fields.Get(field::volume0, &vol0));
  PetscCall(fields.Get(field::temperature, &T));
  for (PetscInt p = 0; p < n; ++p) {
    PetscReal X[3] = {0, 0, 0}, u[3], vel[3];
    for (PetscInt d = 0; d < dim; ++d) X[d] = X0[p * dim + d];
    sim.analytic->Displacement(X, 0, u);
    sim.analytic->Velocity(X, 0, vel);
    sim.analytic->DeformationGradient(X, 0, F + 9 * p);
    for (PetscInt d = 0; d < dim; ++d) {
      x[p * dim + d] = X[d] + u[d];
      v[p * dim + d] = vel[d];
    }
    const PetscReal *f = F + 9 * p;
    const PetscReal  J = f[0] * (f[4] * f[8] - f[5] * f[7]) - f[1] * (f[3] * f[8] - f[5] * f[6]) + f[2] * (f[3] * f[7] - f[4] * f[6]);
    vol[p]             = vol0[p] * J;
    if (temperature) T[p] = sim.analytic->Temperature(X, 0);
  }
  PetscCall(fields.RestoreAll());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode AnalyticDisplacementError(Simulation &sim, PetscReal *rms, PetscReal *max)
{
  PetscInt   n, dim = sim.mpm.grid.dim;
  PetscReal *x, *X0, *mass;
  PetscReal  local[3] = {0, 0, 0}, global[3]; // sum m e^2, sum m, max e
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(sim.mpm.swarm, &n));
  SwarmAccess fields(sim.mpm.swarm);
  PetscCall(fields.Get(DMSwarmPICField_coor, &x));
  PetscCall(fields.Get(field::position0, &X0));
  PetscCall(fields.Get(field::mass, &mass));
  for (PetscInt p = 0; p < n; ++p) {
    PetscReal X[3] = {0, 0, 0}, u[3], e2 = 0;
    for (PetscInt d = 0; d < dim; ++d) X[d] = X0[p * dim + d];
    sim.analytic->Displacement(X, sim.time, u);
    for (PetscInt d = 0; d < dim; ++d) {
      const PetscReal e = x[p * dim + d] - X[d] - u[d];
      e2 += e * e;
    }
    local[0] += mass[p] * e2;
    local[1] += mass[p];
    local[2] = PetscMax(local[2], std::sqrt(e2));
  }
  PetscCall(fields.RestoreAll());
  PetscCallMPI(MPI_Allreduce(local, global, 2, MPIU_REAL, MPI_SUM, sim.comm));
  PetscCallMPI(MPI_Allreduce(&local[2], &global[2], 1, MPIU_REAL, MPI_MAX, sim.comm));
  *rms = std::sqrt(global[0] / global[1]);
  *max = global[2];
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode AnalyticTemperatureError(Simulation &sim, PetscReal *rms, PetscReal *max)
{
  PetscInt   n, dim = sim.mpm.grid.dim;
  PetscReal *X0, *mass, *T;
  PetscReal  local[3] = {0, 0, 0}, global[3]; // sum m e^2, sum m, max |e|
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(sim.mpm.swarm, &n));
  SwarmAccess fields(sim.mpm.swarm);
  PetscCall(fields.Get(field::position0, &X0));
  PetscCall(fields.Get(field::mass, &mass));
  PetscCall(fields.Get(field::temperature, &T));
  for (PetscInt p = 0; p < n; ++p) {
    PetscReal X[3] = {0, 0, 0};
    for (PetscInt d = 0; d < dim; ++d) X[d] = X0[p * dim + d];
    const PetscReal e = T[p] - sim.analytic->Temperature(X, sim.time);
    local[0] += mass[p] * e * e;
    local[1] += mass[p];
    local[2] = PetscMax(local[2], std::fabs(e));
  }
  PetscCall(fields.RestoreAll());
  PetscCallMPI(MPI_Allreduce(local, global, 2, MPIU_REAL, MPI_SUM, sim.comm));
  PetscCallMPI(MPI_Allreduce(&local[2], &global[2], 1, MPIU_REAL, MPI_MAX, sim.comm));
  *rms = std::sqrt(global[0] / global[1]);
  *max = global[2];
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
