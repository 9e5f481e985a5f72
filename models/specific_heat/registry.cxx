// Registry of the specific heat models: one declaration and one table entry per model.
#include "../plasticity/families.hpp"

namespace burst {

PetscErrorCode ConstantSpecificHeatCreate(SubModel **);
PetscErrorCode SteelSpecificHeatCreate(SubModel **);
PetscErrorCode GotoSpecificHeatCreate(SubModel **);
PetscErrorCode CopperSpecificHeatCreate(SubModel **);

PetscErrorCode SpecificHeatList(PetscFunctionList *list)
{
  static PetscFunctionList storage = nullptr;
  return SubModelRegistryGet(&storage,
                             {
                               {"constant", ConstantSpecificHeatCreate},
                               {"steel", SteelSpecificHeatCreate},
                               {"goto", GotoSpecificHeatCreate},
                               {"copper", CopperSpecificHeatCreate},
                             },
                             list);
}

} // namespace burst
