// MTS shear modulus (paper, below eq. 11; Varshni 1970, as used by Follansbee & Kocks 1988 and
// Goto et al. 2000; models.md 4.3):  mu(T) = mu0 - D / (exp(T0/T) - 1),  zero at and above melt.
// mu0 (the 0 K modulus) is also the reference modulus of the MTS flow stress (mu/mu0).
// Options -MAT_shear_modulus_mu0 (Pa), _D (Pa), _T0 (K), all required.
#include "../plasticity/families.hpp"
#include <cmath>

namespace burst {

class MTSShear final : public ShearModulusModel {
public:
  PetscReal mu0 = 0, D = 0, T0 = 0;

  void Evaluate(Chunk &c) const override
  {
    for (int k = 0; k < c.n; ++k) {
      const PetscReal T  = c.temperature[k];
      const PetscReal mu = T > 0 ? mu0 - D / std::expm1(T0 / T) : mu0; // T -> 0: mu -> mu0
      c.shear_modulus[k] = T < c.melt_temperature[k] && mu > 0 ? mu : 0;
    }
  }
  PetscReal      ReferenceShearModulus() const override { return mu0; }
  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const MaterialConstants &) override
  {
    const std::string P = PetscOptionsObject->prefix;
    PetscFunctionBeginUser;
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-mu0", "MTS shear modulus at 0 K mu0 (Pa), > 0", &mu0));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-D", "MTS shear modulus constant D in mu0 - D/(exp(T0/T) - 1) (Pa), >= 0", &D));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-T0", "MTS shear modulus constant T0 (K), > 0", &T0));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "mu0").c_str(), mu0, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "D").c_str(), D, 0, PETSC_MAX_REAL, PETSC_FALSE));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "T0").c_str(), T0, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscErrorCode View(PetscViewer viewer) const override { return PetscViewerASCIIPrintf(viewer, "  shear modulus: mts mu0 %g Pa, D %g Pa, T0 %g K (mu = mu0 - D/(exp(T0/T) - 1), 0 at melt)\n", (double)mu0, (double)D, (double)T0); }
};

PetscErrorCode MTSShearCreate(SubModel **model) { return CreateSubModel<MTSShear>(model); }

} // namespace burst
