// Steinberg-Cochran-Guinan melt temperature (paper eq. 9; Steinberg, Cochran & Guinan 1980;
// models.md 4.4):  Tm = Tm0 exp[2a (1 - 1/eta)] eta^{2 (Gamma0 - a - 1/3)},  eta = rho/rho0.
// Options -MAT_melt_Tm0 (K, melt temperature at rho0), _Gamma0 (-), _a (-), all required
// (4340: 2310 K, 3.0, 1.67 in Uintah's SCGTm4340St.xml).
#include "../plasticity/families.hpp"
#include <cmath>

namespace burst {

class SCGMelt final : public MeltModel {
public:
  PetscReal Tm0 = 0, Gamma0 = 0, a = 0, rho0 = 0;

  void Evaluate(Chunk &c) const override
  {
    const PetscReal exponent = 2 * (Gamma0 - a - 1.0 / 3.0);
    for (int k = 0; k < c.n; ++k) {
      const PetscReal eta   = c.density[k] / rho0;
      c.melt_temperature[k] = Tm0 * std::exp(2 * a * (1 - 1 / eta)) * std::pow(eta, exponent);
    }
  }
  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const MaterialConstants &material) override
  {
    const std::string P = PetscOptionsObject->prefix;
    PetscFunctionBeginUser;
    rho0 = material.density;
    PetscCheck(rho0 > 0, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "SCG melt model -%s: the material density must be > 0", P.c_str());
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-Tm0", "SCG melt temperature at the reference density Tm0 (K), > 0", &Tm0));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-Gamma0", "SCG Gruneisen gamma at the reference state Gamma0 (-), > 0", &Gamma0));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-a", "SCG first-order volume correction to Gamma a (-), >= 0", &a));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "Tm0").c_str(), Tm0, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "Gamma0").c_str(), Gamma0, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "a").c_str(), a, 0, PETSC_MAX_REAL, PETSC_FALSE));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscErrorCode View(PetscViewer viewer) const override { return PetscViewerASCIIPrintf(viewer, "  melt temperature: scg Tm0 %g K, Gamma0 %g, a %g (eq. 9)\n", (double)Tm0, (double)Gamma0, (double)a); }
};

PetscErrorCode SCGMeltCreate(SubModel **model) { return CreateSubModel<SCGMelt>(model); }

} // namespace burst
