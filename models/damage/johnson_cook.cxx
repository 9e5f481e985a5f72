// Johnson-Cook damage (paper eq. 20 in the triaxiality form of NOTES; Johnson & Cook 1985;
// models.md 4.10):
//   eps_f = [D1 + D2 exp(D3 sigma*)] [1 + D4 ln(rate*)] [1 + D5 T*],   Delta D = Delta eps_p / eps_f
//   sigma* = sigma_m / sigma_eq (c.triaxiality; the paper's exp(D3/3 tr(sigma)/sigma_eq) is the same),
//   rate*  = max(eps_p_dot, min_rate) / rate0,
//   T*     = (T - T_r) / (T_m - T_r) clamped to [0, 1], T_r the material's room temperature,
//            T_m the melt model's c.melt_temperature.
// Choices (documented in -help):
// - sigma* is clipped to [-L, L], L = -MAT_damage_triaxiality_limit (default 1.5, the reference's
//   clip). The exponential of a triaxiality beyond the calibration range means little, and a purely
//   hydrostatic state (sigma_eq -> 0, sigma* -> +-inf) then gets the fracture strain at |sigma*| = L.
//   Use a large L to switch the clip off (+-inf are then handled: exp -> 0 or inf).
// - The plastic rate is floored at -MAT_damage_min_rate (default 1e-3 1/s, the flow models' floor)
//   before the logarithm; an elastic step (rate 0) gets eps_f at the floor (TEPLA-F reads it).
// - eps_f is floored at kMinFractureStrain = 1e-6 (Armco iron has D1 = -2.20, so the bracket can be
//   negative at high triaxiality, and the rate factor at low rates): a non-positive fracture strain
//   means immediate fracture, which the floor reproduces without dividing by zero.
// - eps_f is evaluated at the state at t_{n+1} (after the return, heating and triaxiality update) and
//   the increment is Delta eps_p / eps_f (explicit in eps_f). D is not capped at 1.
#include "../plasticity/families.hpp"
#include <cmath>

namespace burst {

class JohnsonCookDamage final : public DamageModel {
public:
  static constexpr PetscReal kMinFractureStrain = 1e-6;
  PetscReal                  D1 = 0, D2 = 0, D3 = 0, D4 = 0, D5 = 0, rate0 = 1, min_rate = 1e-3, triaxiality_limit = 1.5, room_temperature = 298;

  // Fracture strain at triaxiality t, plastic rate r (1/s), temperature T and melt temperature Tm.
  inline PetscReal FractureStrain(PetscReal t, PetscReal r, PetscReal T, PetscReal Tm) const
  {
    PetscReal sigma_star = t;
    if (std::isnan(sigma_star)) sigma_star = 0;
    sigma_star                 = PetscMin(PetscMax(sigma_star, -triaxiality_limit), triaxiality_limit);
    const PetscReal rate_star  = PetscMax(r, min_rate) / rate0;
    PetscReal       homologous = Tm > room_temperature ? (T - room_temperature) / (Tm - room_temperature) : 1;
    homologous                 = PetscMin(PetscMax(homologous, 0.0), 1.0);
    const PetscReal eps_f      = (D1 + D2 * std::exp(D3 * sigma_star)) * (1 + D4 * std::log(rate_star)) * (1 + D5 * homologous);
    return eps_f > kMinFractureStrain ? eps_f : kMinFractureStrain; // NaN-safe: a NaN becomes the floor
  }

  void Evaluate(Chunk &c) const override
  {
    for (int k = 0; k < c.n; ++k) {
      const PetscReal eps_f = FractureStrain(c.triaxiality[k], c.plastic_strain_rate[k], c.temperature[k], c.melt_temperature[k]);
      c.fracture_strain[k]  = eps_f;
      c.damage[k] += c.delta_plastic_strain[k] / eps_f;
    }
  }

  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const MaterialConstants &material) override
  {
    PetscFunctionBeginUser;
    room_temperature = material.room_temperature;
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-D1", "Johnson-Cook damage D1 (-) of eps_f = [D1 + D2 exp(D3 sigma*)][1 + D4 ln rate*][1 + D5 T*]", &D1));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-D2", "Johnson-Cook damage D2 (-)", &D2));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-D3", "Johnson-Cook damage D3 (-), multiplies the triaxiality sigma_m/sigma_eq", &D3));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-D4", "Johnson-Cook damage D4 (-), rate term", &D4));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-D5", "Johnson-Cook damage D5 (-), temperature term (T* from the material's room temperature and melt model, clamped to [0, 1])", &D5));
    PetscCall(PetscOptionsReal("-reference_rate", "Reference plastic strain rate rate0 of rate* = eps_p_dot / rate0 (1/s), > 0", "", rate0, &rate0, nullptr));
    PetscCall(PetscOptionsReal("-min_rate", "Floor of the plastic strain rate in ln(rate*) (1/s), > 0", "", min_rate, &min_rate, nullptr));
    PetscCall(PetscOptionsReal("-triaxiality_limit", "sigma* = sigma_m/sigma_eq is clipped to [-limit, limit] (-), > 0 (the reference clips at 1.5)", "", triaxiality_limit, &triaxiality_limit, nullptr));
    const std::string P = PetscOptionsObject->prefix;
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "reference_rate").c_str(), rate0, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "min_rate").c_str(), min_rate, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "triaxiality_limit").c_str(), triaxiality_limit, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  PetscErrorCode View(PetscViewer viewer) const override
  {
    return PetscViewerASCIIPrintf(viewer, "  damage: johnson_cook D1 %g, D2 %g, D3 %g, D4 %g, D5 %g, reference rate %g 1/s, rate floor %g 1/s, |sigma*| <= %g, T_r %g K, eps_f >= %g\n", (double)D1, (double)D2, (double)D3, (double)D4, (double)D5,
                                  (double)rate0, (double)min_rate, (double)triaxiality_limit, (double)room_temperature, (double)kMinFractureStrain);
  }
};

PetscErrorCode JohnsonCookDamageCreate(SubModel **model) { return CreateSubModel<JohnsonCookDamage>(model); }

} // namespace burst
