// Constant shear modulus: mu = mu0 (-MAT_shear_modulus), zero at and above melt.
#include "../plasticity/families.hpp"

namespace burst {

class ConstantShear final : public ShearModulusModel {
public:
  PetscReal mu0 = 0;

  void Evaluate(Chunk &c) const override
  {
    for (int k = 0; k < c.n; ++k) c.shear_modulus[k] = c.temperature[k] < c.melt_temperature[k] ? mu0 : 0;
  }
  PetscReal      ReferenceShearModulus() const override { return mu0; }
  PetscErrorCode SetFromOptions(PetscOptionItems *, const MaterialConstants &material) override
  {
    mu0 = material.shear_modulus;
    return PETSC_SUCCESS;
  }
  PetscErrorCode View(PetscViewer viewer) const override { return PetscViewerASCIIPrintf(viewer, "  shear modulus: constant %g Pa\n", (double)mu0); }
};

PetscErrorCode ConstantShearCreate(SubModel **model) { return CreateSubModel<ConstantShear>(model); }

} // namespace burst
