// Registry of the shear modulus models: one declaration and one line per model.
#include "../plasticity/families.hpp"

namespace burst {

PetscErrorCode ConstantShearCreate(SubModel **);

namespace {
PetscFunctionList list_ = nullptr;
}

PetscErrorCode ShearModulusList(PetscFunctionList *list)
{
  PetscFunctionBeginUser;
  if (!list_) {
    PetscCall(PetscFunctionListAdd(&list_, "constant", ConstantShearCreate));
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
