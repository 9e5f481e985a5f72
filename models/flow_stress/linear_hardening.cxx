// Linear isotropic hardening, for verification: sigma_f = sigma_0 + H eps_p (rate and temperature
// independent; models.md 4.6).
#include "flow_stress.hpp"

namespace burst {

class LinearHardening final : public FlowStressModel<LinearHardening> {
public:
  PetscReal yield_stress = 0, modulus = 0;

  inline void Evaluate(const FlowPoint &x, FlowValue &y) const
  {
    y.sigma         = yield_stress + modulus * x.plastic_strain;
    y.d_strain      = modulus;
    y.d_rate        = 0;
    y.d_temperature = 0;
  }

  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const MaterialConstants &) override
  {
    PetscFunctionBeginUser;
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-yield_stress", "Initial yield stress sigma_0 (Pa), > 0", &yield_stress));
    PetscCall(PetscOptionsReal("-hardening_modulus", "Hardening modulus H = d sigma_f / d eps_p (Pa), >= 0", "", modulus, &modulus, nullptr));
    const std::string P = PetscOptionsObject->prefix;
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "yield_stress").c_str(), yield_stress, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "hardening_modulus").c_str(), modulus, 0, PETSC_MAX_REAL, PETSC_FALSE));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  PetscErrorCode View(PetscViewer viewer) const override { return PetscViewerASCIIPrintf(viewer, "  flow stress: linear_hardening sigma_0 %g Pa, H %g Pa\n", (double)yield_stress, (double)modulus); }
};

PetscErrorCode LinearHardeningCreate(SubModel **model) { return CreateSubModel<LinearHardening>(model); }

} // namespace burst
