// Steinberg-Cochran-Guinan shear modulus (paper eq. 8; Steinberg, Cochran & Guinan 1980; models.md 4.3):
//   mu = mu0 [1 + A p eta^{-1/3} - B (T - 300 K)],  eta = rho/rho0,
// p the pressure (compression positive, Chunk::pressure), A = (1/mu0) dmu/dp >= 0 and
// B = -(1/mu0) dmu/dT >= 0, so mu rises with pressure and falls with temperature (NOTES eq. 8; the
// paper's "B = (1/mu0) dmu/dT" has the opposite sign). mu = 0 at and above melt and is floored at 0.
// Options -MAT_shear_modulus_mu0 (Pa, default: the material's -MAT_shear_modulus), _A (1/Pa), _B (1/K).
#include "../plasticity/families.hpp"
#include <cmath>

namespace burst {

class SCGShear final : public ShearModulusModel {
public:
  PetscReal mu0 = 0, A = 0, B = 0, rho0 = 0;

  void Evaluate(Chunk &c) const override
  {
    for (int k = 0; k < c.n; ++k) {
      const PetscReal eta = c.density[k] / rho0;
      const PetscReal mu  = mu0 * (1 + A * c.pressure[k] / std::cbrt(eta) - B * (c.temperature[k] - 300));
      c.shear_modulus[k]  = c.temperature[k] < c.melt_temperature[k] && mu > 0 ? mu : 0;
    }
  }
  PetscReal      ReferenceShearModulus() const override { return mu0; }
  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const MaterialConstants &material) override
  {
    const std::string P = PetscOptionsObject->prefix;
    PetscFunctionBeginUser;
    mu0  = material.shear_modulus;
    rho0 = material.density;
    PetscCheck(rho0 > 0, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "SCG shear modulus -%s: the material density must be > 0", P.c_str());
    PetscCall(PetscOptionsReal("-mu0", "SCG shear modulus at T = 300 K, p = 0 mu0 (Pa), > 0 (default: the material's shear modulus)", "", mu0, &mu0, nullptr));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-A", "SCG pressure coefficient A = (1/mu0) dmu/dp (1/Pa), >= 0", &A));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-B", "SCG temperature coefficient B = -(1/mu0) dmu/dT (1/K), >= 0: mu falls with T", &B));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "mu0").c_str(), mu0, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "A").c_str(), A, 0, PETSC_MAX_REAL, PETSC_FALSE));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "B").c_str(), B, 0, PETSC_MAX_REAL, PETSC_FALSE));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscErrorCode View(PetscViewer viewer) const override { return PetscViewerASCIIPrintf(viewer, "  shear modulus: scg mu0 %g Pa, A %g 1/Pa, B %g 1/K (mu = mu0 [1 + A p eta^-1/3 - B (T - 300)], 0 at melt)\n", (double)mu0, (double)A, (double)B); }
};

PetscErrorCode SCGShearCreate(SubModel **model) { return CreateSubModel<SCGShear>(model); }

} // namespace burst
