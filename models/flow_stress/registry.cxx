// Registry of the flow stress models: one declaration and one table entry per model.
#include "../plasticity/families.hpp"

namespace burst {

PetscErrorCode JohnsonCookCreate(SubModel **);
PetscErrorCode LinearHardeningCreate(SubModel **);
PetscErrorCode MTSFlowCreate(SubModel **);

PetscErrorCode FlowStressList(PetscFunctionList *list)
{
  static PetscFunctionList storage = nullptr;
  return SubModelRegistryGet(&storage,
                             {
                               {"johnson_cook", JohnsonCookCreate},
                               {"linear_hardening", LinearHardeningCreate},
                               {"mts", MTSFlowCreate},
                             },
                             list);
}

} // namespace burst
