// Registry of the damage models: one declaration and one line per model.
#include "../plasticity/families.hpp"

namespace burst {

PetscErrorCode NoDamageCreate(SubModel **);

namespace {
PetscFunctionList list_ = nullptr;
}

PetscErrorCode DamageList(PetscFunctionList *list)
{
  PetscFunctionBeginUser;
  if (!list_) {
    PetscCall(PetscFunctionListAdd(&list_, "none", NoDamageCreate));
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
