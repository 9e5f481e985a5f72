// Frees the registries of every sub-model family (each lives in models/FAMILY/registry.cxx).
#include "families.hpp"

namespace burst {

PetscErrorCode EquationOfStateListDestroy();
PetscErrorCode ShearModulusListDestroy();
PetscErrorCode MeltListDestroy();
PetscErrorCode SpecificHeatListDestroy();
PetscErrorCode FlowStressListDestroy();
PetscErrorCode DamageListDestroy();
PetscErrorCode StabilityListDestroy();

PetscErrorCode SubModelRegistriesDestroy()
{
  PetscFunctionBeginUser;
  PetscCall(EquationOfStateListDestroy());
  PetscCall(ShearModulusListDestroy());
  PetscCall(MeltListDestroy());
  PetscCall(SpecificHeatListDestroy());
  PetscCall(FlowStressListDestroy());
  PetscCall(DamageListDestroy());
  PetscCall(StabilityListDestroy());
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
