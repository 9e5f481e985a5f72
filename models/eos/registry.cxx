// Registry of the equation of state models: one declaration and one table entry per model.
#include "../plasticity/families.hpp"

namespace burst {

PetscErrorCode HypoelasticEOSCreate(SubModel **);
PetscErrorCode MieGruneisenCreate(SubModel **);

PetscErrorCode EquationOfStateList(PetscFunctionList *list)
{
  static PetscFunctionList storage = nullptr;
  return SubModelRegistryGet(&storage,
                             {
                               {"hypoelastic", HypoelasticEOSCreate},
                               {"mie_gruneisen", MieGruneisenCreate},
                             },
                             list);
}

} // namespace burst
