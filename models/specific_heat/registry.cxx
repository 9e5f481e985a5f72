// Registry of the specific heat models: one declaration and one line per model.
#include "../plasticity/families.hpp"

namespace burst {

PetscErrorCode ConstantSpecificHeatCreate(SubModel **);

namespace {
PetscFunctionList list_ = nullptr;
}

PetscErrorCode SpecificHeatList(PetscFunctionList *list)
{
  PetscFunctionBeginUser;
  if (!list_) {
    PetscCall(PetscFunctionListAdd(&list_, "constant", ConstantSpecificHeatCreate));
  }
  *list = list_;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SpecificHeatListDestroy()
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&list_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
