// Registry of the specific heat models: one declaration and one line per model.
#include "../plasticity/families.hpp"

namespace burst {

PetscErrorCode ConstantSpecificHeatCreate(SubModel **);
PetscErrorCode SteelSpecificHeatCreate(SubModel **);
PetscErrorCode GotoSpecificHeatCreate(SubModel **);
PetscErrorCode CopperSpecificHeatCreate(SubModel **);

namespace {
PetscFunctionList list_ = nullptr;
}

PetscErrorCode SpecificHeatList(PetscFunctionList *list)
{
  PetscFunctionBeginUser;
  if (!list_) {
    PetscCall(PetscFunctionListAdd(&list_, "constant", ConstantSpecificHeatCreate));
    PetscCall(PetscFunctionListAdd(&list_, "steel", SteelSpecificHeatCreate));
    PetscCall(PetscFunctionListAdd(&list_, "goto", GotoSpecificHeatCreate));
    PetscCall(PetscFunctionListAdd(&list_, "copper", CopperSpecificHeatCreate));
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
