// Registry of the flow stress models: one declaration and one line per model.
#include "../plasticity/families.hpp"

namespace burst {

PetscErrorCode JohnsonCookCreate(SubModel **);
PetscErrorCode LinearHardeningCreate(SubModel **);
PetscErrorCode MTSFlowCreate(SubModel **);

namespace {
PetscFunctionList list_ = nullptr;
}

PetscErrorCode FlowStressList(PetscFunctionList *list)
{
  PetscFunctionBeginUser;
  if (!list_) {
    PetscCall(PetscFunctionListAdd(&list_, "johnson_cook", JohnsonCookCreate));
    PetscCall(PetscFunctionListAdd(&list_, "linear_hardening", LinearHardeningCreate));
    PetscCall(PetscFunctionListAdd(&list_, "mts", MTSFlowCreate));
  }
  *list = list_;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FlowStressListDestroy()
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&list_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
