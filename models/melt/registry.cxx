// Registry of the melt temperature models: one declaration and one line per model.
#include "../plasticity/families.hpp"

namespace burst {

PetscErrorCode ConstantMeltCreate(SubModel **);
PetscErrorCode SCGMeltCreate(SubModel **);

namespace {
PetscFunctionList list_ = nullptr;
}

PetscErrorCode MeltList(PetscFunctionList *list)
{
  PetscFunctionBeginUser;
  if (!list_) {
    PetscCall(PetscFunctionListAdd(&list_, "constant", ConstantMeltCreate));
    PetscCall(PetscFunctionListAdd(&list_, "scg", SCGMeltCreate));
  }
  *list = list_;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MeltListDestroy()
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&list_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
