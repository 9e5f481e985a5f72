// Registry of the stability models: one declaration and one line per model.
#include "../plasticity/families.hpp"

namespace burst {

PetscErrorCode NoStabilityCreate(SubModel **);
PetscErrorCode DruckerCheckCreate(SubModel **);
PetscErrorCode AcousticCheckCreate(SubModel **);
PetscErrorCode BeckerCheckCreate(SubModel **);

namespace {
PetscFunctionList list_ = nullptr;
}

PetscErrorCode StabilityList(PetscFunctionList *list)
{
  PetscFunctionBeginUser;
  if (!list_) {
    PetscCall(PetscFunctionListAdd(&list_, "none", NoStabilityCreate));
    PetscCall(PetscFunctionListAdd(&list_, "drucker", DruckerCheckCreate));
    PetscCall(PetscFunctionListAdd(&list_, "acoustic", AcousticCheckCreate));
    PetscCall(PetscFunctionListAdd(&list_, "becker", BeckerCheckCreate));
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
