// Constant specific heat Cp (-MAT_specific_heat_Cp, J/(kg K); paper Table 1: 477 for both steels).
#include "../plasticity/families.hpp"

namespace burst {

class ConstantSpecificHeat final : public SpecificHeatModel {
public:
  PetscReal Cp = 0;

  void Evaluate(Chunk &c) const override
  {
    for (int k = 0; k < c.n; ++k) c.specific_heat[k] = Cp;
  }
  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const MaterialConstants &) override
  {
    PetscFunctionBeginUser;
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-Cp", "Specific heat (J/(kg K))", &Cp));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + std::string(PetscOptionsObject->prefix) + "Cp").c_str(), Cp, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscErrorCode View(PetscViewer viewer) const override { return PetscViewerASCIIPrintf(viewer, "  specific heat: constant %g J/(kg K)\n", (double)Cp); }
};

PetscErrorCode ConstantSpecificHeatCreate(SubModel **model) { return CreateSubModel<ConstantSpecificHeat>(model); }

} // namespace burst
