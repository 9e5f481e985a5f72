// Registry of the damage models: one declaration and one table entry per model.
#include "../plasticity/families.hpp"

namespace burst {

PetscErrorCode NoDamageCreate(SubModel **);
PetscErrorCode JohnsonCookDamageCreate(SubModel **);
PetscErrorCode HancockMacKenzieDamageCreate(SubModel **);

PetscErrorCode DamageList(PetscFunctionList *list)
{
  static PetscFunctionList storage = nullptr;
  return SubModelRegistryGet(&storage,
                             {
                               {"none", NoDamageCreate},
                               {"johnson_cook", JohnsonCookDamageCreate},
                               {"hancock_mackenzie", HancockMacKenzieDamageCreate},
                             },
                             list);
}

} // namespace burst
