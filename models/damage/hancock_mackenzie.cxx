// Hancock-MacKenzie damage (paper eq. 21 read with the triaxiality, per NOTES; Hancock & MacKenzie
// 1976; models.md 4.10):
//   eps_f = 1.65 exp(-1.5 sigma_m / sigma_eq),   Delta D = Delta eps_p / eps_f
// with sigma_m/sigma_eq = c.triaxiality (not the sigma* = tr(sigma)/sigma_eq of eq. 20, which is three
// times larger: NOTES). No parameters. eps_f is evaluated at the state at t_{n+1} and floored at
// 1e-6 (a hydrostatic tension state, sigma_eq -> 0, has eps_f -> 0: immediate fracture); in
// compression it may overflow to +inf, which adds no damage and drops the strain term of TEPLA-F.
// D is not capped at 1.
#include "../plasticity/families.hpp"
#include <cmath>

namespace burst {

class HancockMacKenzieDamage final : public DamageModel {
public:
  static constexpr PetscReal kMinFractureStrain = 1e-6;

  static inline PetscReal FractureStrain(PetscReal triaxiality)
  {
    const PetscReal t     = std::isnan(triaxiality) ? 0 : triaxiality;
    const PetscReal eps_f = 1.65 * std::exp(-1.5 * t);
    return eps_f > kMinFractureStrain ? eps_f : kMinFractureStrain;
  }

  void Evaluate(Chunk &c) const override
  {
    for (int k = 0; k < c.n; ++k) {
      const PetscReal eps_f = FractureStrain(c.triaxiality[k]);
      c.fracture_strain[k]  = eps_f;
      c.damage[k] += c.delta_plastic_strain[k] / eps_f;
    }
  }
  PetscErrorCode SetFromOptions(PetscOptionItems *, const MaterialConstants &) override { return PETSC_SUCCESS; }
  PetscErrorCode View(PetscViewer viewer) const override { return PetscViewerASCIIPrintf(viewer, "  damage: hancock_mackenzie eps_f = 1.65 exp(-1.5 sigma_m/sigma_eq), eps_f >= %g\n", (double)kMinFractureStrain); }
};

PetscErrorCode HancockMacKenzieDamageCreate(SubModel **model) { return CreateSubModel<HancockMacKenzieDamage>(model); }

} // namespace burst
