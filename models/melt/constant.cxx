// Constant melt temperature Tm (-MAT_melt_Tm, K; required: melting is never silently off,
// models.md 2.13).
#include "../plasticity/families.hpp"

namespace burst {

class ConstantMelt final : public MeltModel {
public:
  PetscReal Tm = 0;

  void Evaluate(Chunk &c) const override
  {
    for (int k = 0; k < c.n; ++k) c.melt_temperature[k] = Tm;
  }
  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const MaterialConstants &) override
  {
    PetscFunctionBeginUser;
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-Tm", "Melt temperature (K)", &Tm));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + std::string(PetscOptionsObject->prefix) + "Tm").c_str(), Tm, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscErrorCode View(PetscViewer viewer) const override { return PetscViewerASCIIPrintf(viewer, "  melt temperature: constant %g K\n", (double)Tm); }
};

PetscErrorCode ConstantMeltCreate(SubModel **model) { return CreateSubModel<ConstantMelt>(model); }

} // namespace burst
