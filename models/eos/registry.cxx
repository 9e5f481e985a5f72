// Registry of the equation of state models: one declaration and one line per model.
#include "../plasticity/families.hpp"

namespace burst {

PetscErrorCode HypoelasticEOSCreate(SubModel **);
PetscErrorCode MieGruneisenCreate(SubModel **);

namespace {
PetscFunctionList list_ = nullptr;
}

PetscErrorCode EquationOfStateList(PetscFunctionList *list)
{
  PetscFunctionBeginUser;
  if (!list_) {
    PetscCall(PetscFunctionListAdd(&list_, "hypoelastic", HypoelasticEOSCreate));
    PetscCall(PetscFunctionListAdd(&list_, "mie_gruneisen", MieGruneisenCreate));
  }
  *list = list_;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode EquationOfStateListDestroy()
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&list_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
