// Registry of the melt temperature models: one declaration and one table entry per model.
#include "../plasticity/families.hpp"

namespace burst {

PetscErrorCode ConstantMeltCreate(SubModel **);
PetscErrorCode SCGMeltCreate(SubModel **);

PetscErrorCode MeltList(PetscFunctionList *list)
{
  static PetscFunctionList storage = nullptr;
  return SubModelRegistryGet(&storage,
                             {
                               {"constant", ConstantMeltCreate},
                               {"scg", SCGMeltCreate},
                             },
                             list);
}

} // namespace burst
