// Registry of the damage models: one declaration and one line per model.
#include "../plasticity/families.hpp"

namespace burst {

PetscErrorCode NoDamageCreate(SubModel **);
PetscErrorCode JohnsonCookDamageCreate(SubModel **);
PetscErrorCode HancockMacKenzieDamageCreate(SubModel **);

namespace {
PetscFunctionList list_ = nullptr;
}

PetscErrorCode DamageList(PetscFunctionList *list)
{
  PetscFunctionBeginUser;
  if (!list_) {
    PetscCall(PetscFunctionListAdd(&list_, "none", NoDamageCreate));
    PetscCall(PetscFunctionListAdd(&list_, "johnson_cook", JohnsonCookDamageCreate));
    PetscCall(PetscFunctionListAdd(&list_, "hancock_mackenzie", HancockMacKenzieDamageCreate));
  }
  *list = list_;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DamageListDestroy()
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&list_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
