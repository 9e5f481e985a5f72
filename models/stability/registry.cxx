// Registry of the stability models: one declaration and one table entry per model.
#include "../plasticity/families.hpp"

namespace burst {

PetscErrorCode NoStabilityCreate(SubModel **);
PetscErrorCode DruckerCheckCreate(SubModel **);
PetscErrorCode AcousticCheckCreate(SubModel **);
PetscErrorCode BeckerCheckCreate(SubModel **);

PetscErrorCode StabilityList(PetscFunctionList *list)
{
  static PetscFunctionList storage = nullptr;
  return SubModelRegistryGet(&storage,
                             {
                               {"none", NoStabilityCreate},
                               {"drucker", DruckerCheckCreate},
                               {"acoustic", AcousticCheckCreate},
                               {"becker", BeckerCheckCreate},
                             },
                             list);
}

} // namespace burst
