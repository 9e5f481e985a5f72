// Registry of the shear modulus models: one declaration and one line per model.
#include "../plasticity/families.hpp"

namespace burst {

PetscErrorCode ConstantShearCreate(SubModel **);
PetscErrorCode MTSShearCreate(SubModel **);
PetscErrorCode SCGShearCreate(SubModel **);

namespace {
PetscFunctionList list_ = nullptr;
}

PetscErrorCode ShearModulusList(PetscFunctionList *list)
{
  PetscFunctionBeginUser;
  if (!list_) {
    PetscCall(PetscFunctionListAdd(&list_, "constant", ConstantShearCreate));
    PetscCall(PetscFunctionListAdd(&list_, "mts", MTSShearCreate));
    PetscCall(PetscFunctionListAdd(&list_, "scg", SCGShearCreate));
  }
  *list = list_;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ShearModulusListDestroy()
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&list_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
