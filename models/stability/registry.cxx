// Registry of the stability models: one declaration and one line per model.
#include "../plasticity/families.hpp"

namespace burst {

PetscErrorCode NoStabilityCreate(SubModel **);

namespace {
PetscFunctionList list_ = nullptr;
}

PetscErrorCode StabilityList(PetscFunctionList *list)
{
  PetscFunctionBeginUser;
  if (!list_) {
    PetscCall(PetscFunctionListAdd(&list_, "none", NoStabilityCreate));
  }
  *list = list_;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode StabilityListDestroy()
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&list_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
