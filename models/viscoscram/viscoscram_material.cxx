// The material `viscoscram`: the adapter between the Material interface (state fields, options,
// the co-rotated frame) and the point kernel of viscoscram.hpp, which knows neither swarm nor grid.
//
// Per particle and step (the Green-Naghdi frame of the metal update, models/plasticity/polar.hpp):
//   1. R_{n+1} from the polar decomposition of F_{n+1} (warm-started from the stored R_n);
//      D_hat = (R_n^T D R_n + R_{n+1}^T D R_{n+1}) / 2, D = sym L.
//   2. The kernel advances the element stresses, which are stored in the co-rotated frame (so they
//      never need rotating), and the crack radius, from the mean stress tr(sigma_n)/3 (invariant).
//   3. sigma_{n+1} = R_{n+1} (S + sigma_m I) R_{n+1}^T; the stress work of the interface
//      (StressWork) goes to internal_energy; the dissipated energies heat the particle and are
//      accumulated per particle (J); wave speed sqrt((K + 4 G/3)/rho) with the unsoftened G.
// The kernel is unit-tested on plain arrays (tests/unit/test_viscoscram.cxx), the adapter on the state
// arrays of models/material_state.hpp.
#include "viscoscram.hpp"
#include "../material.hpp"
#include "../plasticity/polar.hpp"
#include "../util.hpp"
#include <cmath>

namespace burst {

namespace {
constexpr const char *kElementStress      = "viscoscram_elements"; // S_1..S_5 in the co-rotated frame, bs 30 (xx yy zz xy yz xz per element), Pa
constexpr const char *kCrackRadius        = "crack_radius";        // c, m
constexpr const char *kRotation           = "viscoscram_rotation"; // R of the polar decomposition at t_n, bs 9
constexpr const char *kViscousDissipation = "viscous_dissipation"; // accumulated viscous dissipation, J
constexpr const char *kCrackDissipation   = "crack_dissipation";   // accumulated crack dissipation, J

const char *const CrackHeatingNames[] = {"crack_work", "release"};

} // namespace

class ViscoScram final : public Material {
public:
  viscoscram::Parameters params;
  PetscReal              poisson_ratio        = 0.3;  // nu
  PetscReal              initial_crack_radius = 3e-5; // c_0, m

  ViscoScram()
  {
    // PBX 9501 (options/materials/pbx9501_viscoscram.opts gives the sources)
    const PetscReal G[5] = {3.5e8, 1.739e8, 5.212e8, 9.085e8, 6.875e8}, rates[5] = {0, 7.32e3, 7.32e4, 7.32e5, 2e6};
    for (int i = 0; i < 5; ++i) params.shear_moduli[i] = G[i], params.relaxation_rates[i] = rates[i];
    params.gruneisen = 1.0; // Uintah's PBX 9501 Gamma
  }

  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject) override
  {
    const char *prefix = PetscOptionsObject->prefix;
    PetscInt    n = viscoscram::kMaxElements, n_rates = viscoscram::kMaxElements;
    PetscBool   set_G = PETSC_FALSE, set_rates = PETSC_FALSE;
    int         heating = (int)params.crack_heating;
    PetscFunctionBeginUser;
    PetscCall(PetscOptionsRealArray("-shear_moduli", "Shear moduli G_i of the Maxwell elements (Pa), 1 to 5 values, each > 0 (default PBX 9501)", "", params.shear_moduli, &n, &set_G));
    PetscCall(PetscOptionsRealArray("-relaxation_rates", "Inverse relaxation times 1/tau_i of the Maxwell elements (1/s), one per shear modulus, each >= 0 (0: purely elastic element)", "", params.relaxation_rates, &n_rates, &set_rates));
    if (!set_G) n = viscoscram::kMaxElements;
    if (!set_rates) n_rates = viscoscram::kMaxElements;
    PetscCheck(n >= 1 && n == n_rates, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "Material '%s': -%sshear_moduli has %" PetscInt_FMT " values and -%srelaxation_rates %" PetscInt_FMT ": give one relaxation rate per element (1 to 5 elements)", Name(),
               prefix, n, prefix, n_rates);
    params.elements = (int)n;
    for (int i = 0; i < params.elements; ++i) {
      PetscCheck(params.shear_moduli[i] > 0 && std::isfinite(params.shear_moduli[i]), PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "Option -%sshear_moduli: value %d = %g is out of range: each must be > 0 (Pa)", prefix, i + 1,
                 (double)params.shear_moduli[i]);
      PetscCheck(params.relaxation_rates[i] >= 0 && std::isfinite(params.relaxation_rates[i]), PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "Option -%srelaxation_rates: value %d = %g is out of range: each must be >= 0 (1/s)", prefix, i + 1,
                 (double)params.relaxation_rates[i]);
    }
    PetscCall(PetscOptionsReal("-poisson_ratio", "Poisson's ratio nu (-) giving the bulk modulus K = 2 G (1 + nu)/(3 (1 - 2 nu)), G = sum G_i; in (-1, 0.5)", "", poisson_ratio, &poisson_ratio, nullptr));
    PetscCheck(poisson_ratio > -1 && poisson_ratio < 0.5, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "Option -%spoisson_ratio = %g is out of range: it must be in (-1, 0.5)", prefix, (double)poisson_ratio);
    PetscCall(PetscOptionsReal("-crack_scale", "Crack-size scale a of the softening 1/(1 + (c/a)^3) (m), > 0", "", params.crack_scale, &params.crack_scale, nullptr));
    PetscCall(CheckRange(PETSC_COMM_WORLD, Prefixed(prefix, "crack_scale").c_str(), params.crack_scale, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(PetscOptionsReal("-initial_crack_radius", "Initial crack radius c_0 (m), >= 0 (0: no crack ever grows)", "", initial_crack_radius, &initial_crack_radius, nullptr));
    PetscCall(CheckRange(PETSC_COMM_WORLD, Prefixed(prefix, "initial_crack_radius").c_str(), initial_crack_radius, 0, PETSC_MAX_REAL, PETSC_FALSE));
    PetscCall(PetscOptionsReal("-fracture_toughness", "Crack-growth threshold K_0 of the stress intensity (Pa m^1/2), > 0", "", params.fracture_toughness, &params.fracture_toughness, nullptr));
    PetscCall(CheckRange(PETSC_COMM_WORLD, Prefixed(prefix, "fracture_toughness").c_str(), params.fracture_toughness, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(PetscOptionsReal("-crack_exponent", "Exponent m of the sub-critical crack growth (K_I/K_1)^m (-), > 0", "", params.crack_exponent, &params.crack_exponent, nullptr));
    PetscCall(CheckRange(PETSC_COMM_WORLD, Prefixed(prefix, "crack_exponent").c_str(), params.crack_exponent, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(PetscOptionsReal("-max_crack_speed", "Cap v_max of the crack speed (m/s), >= 0 (0: cracks never grow)", "", params.max_crack_speed, &params.max_crack_speed, nullptr));
    PetscCall(CheckRange(PETSC_COMM_WORLD, Prefixed(prefix, "max_crack_speed").c_str(), params.max_crack_speed, 0, PETSC_MAX_REAL, PETSC_FALSE));
    PetscCall(PetscOptionsReal("-crack_friction", "Friction coefficient mu of the closed crack faces (-), in [0, 1.2247) (3 - 2 mu^2 > 0)", "", params.friction, &params.friction, nullptr));
    PetscCall(CheckRange(PETSC_COMM_WORLD, Prefixed(prefix, "crack_friction").c_str(), params.friction, 0, std::sqrt(1.5) * (1 - 1e-12), PETSC_FALSE));
    PetscCall(PetscOptionsReal("-crack_tension_factor", "Factor phi on the crack speed in tension (mean stress > 0) (-), >= 0", "", params.tension_growth_factor, &params.tension_growth_factor, nullptr));
    PetscCall(CheckRange(PETSC_COMM_WORLD, Prefixed(prefix, "crack_tension_factor").c_str(), params.tension_growth_factor, 0, PETSC_MAX_REAL, PETSC_FALSE));
    PetscCall(PetscOptionsReal("-crack_speed_coefficient", "Coefficient A of the crack speed A (sqrt(3/2) |D'|)^n (m/s at 1/s), >= 0", "", params.crack_speed_coefficient, &params.crack_speed_coefficient, nullptr));
    PetscCall(CheckRange(PETSC_COMM_WORLD, Prefixed(prefix, "crack_speed_coefficient").c_str(), params.crack_speed_coefficient, 0, PETSC_MAX_REAL, PETSC_FALSE));
    PetscCall(PetscOptionsReal("-crack_speed_exponent", "Exponent n of the crack speed A (sqrt(3/2) |D'|)^n (-), in [0, 10]", "", params.crack_speed_exponent, &params.crack_speed_exponent, nullptr));
    PetscCall(CheckRange(PETSC_COMM_WORLD, Prefixed(prefix, "crack_speed_exponent").c_str(), params.crack_speed_exponent, 0, 10, PETSC_FALSE));
    PetscCall(PetscOptionsReal("-specific_heat", "Specific heat c_v of the dissipation heating (J/(kg K)), > 0", "", params.specific_heat, &params.specific_heat, nullptr));
    PetscCall(CheckRange(PETSC_COMM_WORLD, Prefixed(prefix, "specific_heat").c_str(), params.specific_heat, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(PetscOptionsReal("-gruneisen", "Grueneisen coefficient Gamma of the thermoelastic term -Gamma T tr(D) (-), in [0, 10]", "", params.gruneisen, &params.gruneisen, nullptr));
    PetscCall(CheckRange(PETSC_COMM_WORLD, Prefixed(prefix, "gruneisen").c_str(), params.gruneisen, 0, 10, PETSC_FALSE));
    PetscCall(OptionsChoice(PetscOptionsObject, "-crack_heating", "Crack heating: crack_work = S : d/dt(x S)/(2G) (Hackett & Bennett 2000, the reference code), release = only the energy crack growth releases, xdot S:S/(4G)", CrackHeatingNames, 2,
                            &heating, nullptr));
    params.crack_heating = (viscoscram::CrackHeating)heating;
    PetscCall(PetscOptionsReal("-max_relaxation_per_substep", "Sub-step so that each sub-step is at most this times the shortest time of the model: the relaxation times tau_i and the crack equations' own rates (-), in (0, 2.5]", "",
                               params.max_relaxation_per_substep, &params.max_relaxation_per_substep, nullptr));
    PetscCall(CheckRange(PETSC_COMM_WORLD, Prefixed(prefix, "max_relaxation_per_substep").c_str(), params.max_relaxation_per_substep, 0, 2.5, PETSC_TRUE));
    PetscCall(PetscOptionsReal("-crack_rate_change_per_substep",
                               "Sub-step so that the crack speed changes by at most this fraction of itself per sub-step; also the first sub-step after K_I rises through K' (where the growth law switches branch), as a fraction of the time K_I takes "
                               "to change by K' (-), in (0, 1]",
                               "", params.crack_rate_change_per_substep, &params.crack_rate_change_per_substep, nullptr));
    PetscCall(CheckRange(PETSC_COMM_WORLD, Prefixed(prefix, "crack_rate_change_per_substep").c_str(), params.crack_rate_change_per_substep, 0, 1, PETSC_TRUE));
    PetscInt max_substeps = params.max_substeps;
    PetscCall(PetscOptionsInt("-max_substeps", "Most sub-steps of one stress update (-), >= 1", "", max_substeps, &max_substeps, nullptr));
    PetscCheck(max_substeps >= 1 && max_substeps <= 1000000, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "Option -%smax_substeps = %" PetscInt_FMT " is out of range: it must be in [1, 1000000]", prefix, max_substeps);
    params.max_substeps = (int)max_substeps;
    params.Derive();
    params.bulk_modulus = 2 * params.shear_modulus * (1 + poisson_ratio) / (3 * (1 - 2 * poisson_ratio));
    bulk_modulus_       = params.bulk_modulus;
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  std::vector<StateField> StateFields() const override { return {{kElementStress, viscoscram::kStateSize, false}, {kRotation, 9, false}, {kCrackRadius, 1, false}, {kViscousDissipation, 1, false}, {kCrackDissipation, 1, false}}; }

  PetscErrorCode InitializeState(const MaterialPointFields &mp, PetscInt begin, PetscInt end) override
  {
    const MaterialState &fields   = *mp.state;
    const PetscInt      *material = mp.material;
    PetscReal           *S = nullptr, *R = nullptr, *c = nullptr, *heat_v = nullptr, *heat_c = nullptr;
    PetscFunctionBeginUser;
    PetscCall(fields.Get(kElementStress, &S));
    PetscCall(fields.Get(kRotation, &R));
    PetscCall(fields.Get(kCrackRadius, &c));
    PetscCall(fields.Get(kViscousDissipation, &heat_v));
    PetscCall(fields.Get(kCrackDissipation, &heat_c));
    for (PetscInt p = begin; p < end; ++p) {
      if (material[p] != id_) continue;
      for (int k = 0; k < viscoscram::kStateSize; ++k) S[viscoscram::kStateSize * p + k] = 0;
      for (int a = 0; a < 9; ++a) R[9 * p + a] = (a % 4 == 0) ? 1 : 0;
      c[p]      = initial_crack_radius;
      heat_v[p] = heat_c[p] = 0;
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  PetscErrorCode UpdateStress(const MaterialPointFields &mp, PetscInt id, PetscReal dt) override
  {
    const MaterialState &fields = *mp.state;
    PetscReal           *S = nullptr, *R = nullptr, *c = nullptr, *heat_v = nullptr, *heat_c = nullptr;
    PetscFunctionBeginUser;
    if (dt <= 0) PetscFunctionReturn(ComputeWaveSpeed(mp, id)); // initial call: stress stays as seeded
    PetscCall(fields.Get(kElementStress, &S));
    PetscCall(fields.Get(kRotation, &R));
    PetscCall(fields.Get(kCrackRadius, &c));
    PetscCall(fields.Get(kViscousDissipation, &heat_v));
    PetscCall(fields.Get(kCrackDissipation, &heat_c));
    const PetscReal modulus = params.bulk_modulus + 4.0 / 3.0 * params.shear_modulus;
    PetscInt        points = 0, substeps = 0, most_substeps = 0; // for -info
    for (PetscInt q = 0; q < mp.n; ++q) {
      if (mp.material[q] != id) continue;
      const PetscReal *L     = mp.L + 9 * q;
      PetscReal       *R_old = R + 9 * q, R_new[9];
      if (!PolarRotationWarm(mp.F + 9 * q, R_old, R_new)) { // warm start: R moves little per step
        Mat3Map R_fallback(R_new);
        R_fallback = PolarRotation(Mat3CMap(mp.F + 9 * q));
      }
      // D_hat = (R_old^T D R_old + R_new^T D R_new)/2 in the kernel's order xx yy zz xy yz xz
      const PetscReal       D_lab[9] = {L[0], 0.5 * (L[1] + L[3]), 0.5 * (L[2] + L[6]), 0.5 * (L[3] + L[1]), L[4], 0.5 * (L[5] + L[7]), 0.5 * (L[6] + L[2]), 0.5 * (L[7] + L[5]), L[8]};
      const SymmetricTensor d_old = RotatedToFrame(R_old, D_lab), d_new = RotatedToFrame(R_new, D_lab);
      const PetscReal       D_hat[6] = {0.5 * (d_old.xx + d_new.xx), 0.5 * (d_old.yy + d_new.yy), 0.5 * (d_old.zz + d_new.zz), 0.5 * (d_old.xy + d_new.xy), 0.5 * (d_old.yz + d_new.yz), 0.5 * (d_old.xz + d_new.xz)};
      PetscReal            *sigma    = mp.stress + 9 * q;
      const PetscReal       density  = mp.mass[q] / mp.volume[q];
      viscoscram::Result    r;
      viscoscram::Update(params, S + viscoscram::kStateSize * q, c + q, (sigma[0] + sigma[4] + sigma[8]) / 3, D_hat, dt, density, mp.temperature[q], &r);
      // sigma_{n+1} = R_new (S + sigma_m I) R_new^T
      const PetscReal *s        = r.deviator;
      const PetscReal  frame[9] = {s[0] + r.mean_stress, s[3], s[5], s[3], s[1] + r.mean_stress, s[4], s[5], s[4], s[2] + r.mean_stress};
      PetscReal        sigma_old[9];
      for (int a = 0; a < 9; ++a) sigma_old[a] = sigma[a];
      RotateFromFrame(R_new, frame, sigma);
      for (int a = 0; a < 9; ++a) R_old[a] = R_new[a];
      mp.internal_energy[q] += StressWork(sigma_old, sigma, L, mp.volume[q], dt);
      heat_v[q] += r.viscous_dissipation * mp.volume[q];
      heat_c[q] += r.crack_dissipation * mp.volume[q];
      mp.temperature[q] += r.temperature_change;
      mp.wave_speed[q] = std::sqrt(modulus / density);
      ++points;
      substeps += r.substeps;
      most_substeps = PetscMax(most_substeps, (PetscInt)r.substeps);
    }
    if (points) PetscCall(PetscInfo(nullptr, "Material %s (viscoscram): %" PetscInt_FMT " points, %.3g sub-steps per point on average, at most %" PetscInt_FMT "\n", Name(), points, (double)substeps / points, most_substeps));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  PetscErrorCode ComputeWaveSpeed(const MaterialPointFields &f, PetscInt id) override
  {
    const PetscReal modulus = params.bulk_modulus + 4.0 / 3.0 * params.shear_modulus;
    for (PetscInt p = 0; p < f.n; ++p)
      if (f.material[p] == id) f.wave_speed[p] = std::sqrt(modulus * f.volume[p] / f.mass[p]);
    return PETSC_SUCCESS;
  }

  std::vector<OutputField> OutputFields() const override { return {{kCrackRadius, 1, false}, {kViscousDissipation, 1, false}, {kCrackDissipation, 1, false}}; }

  PetscErrorCode View(PetscViewer viewer) const override
  {
    PetscFunctionBeginUser;
    PetscCall(PetscViewerASCIIPrintf(viewer, "Material %s: viscoscram (%d Maxwell elements + statistical crack, Green-Naghdi frame)\n  density %g kg/m^3, G = sum G_i %g Pa, bulk modulus %g Pa (nu %g)\n", Name(), params.elements, (double)density_,
                                     (double)params.shear_modulus, (double)params.bulk_modulus, (double)poisson_ratio));
    for (int i = 0; i < params.elements; ++i) PetscCall(PetscViewerASCIIPrintf(viewer, "  element %d: G %g Pa, 1/tau %g 1/s\n", i + 1, (double)params.shear_moduli[i], (double)params.relaxation_rates[i]));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  crack: a %g m, c_0 %g m, K_0 %g Pa m^1/2, m %g, v_max %g m/s, friction %g, tension factor %g, speed %g (sqrt(3/2)|D'|)^%g m/s\n", (double)params.crack_scale, (double)initial_crack_radius,
                                     (double)params.fracture_toughness, (double)params.crack_exponent, (double)params.max_crack_speed, (double)params.friction, (double)params.tension_growth_factor, (double)params.crack_speed_coefficient,
                                     (double)params.crack_speed_exponent));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  heating: c_v %g J/(kg K), Gamma %g, crack heating %s; sub-steps of at most %g times the shortest time (relaxation, crack), crack speed change %g per sub-step (at most %d)\n",
                                     (double)params.specific_heat, (double)params.gruneisen, CrackHeatingNames[(int)params.crack_heating], (double)params.max_relaxation_per_substep, (double)params.crack_rate_change_per_substep, params.max_substeps));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
};

PetscErrorCode ViscoScramCreate(Material **m)
{
  *m = new ViscoScram();
  return PETSC_SUCCESS;
}

} // namespace burst
