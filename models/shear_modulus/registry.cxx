// Registry of the shear modulus models: one declaration and one table entry per model.
#include "../plasticity/families.hpp"

namespace burst {

PetscErrorCode ConstantShearCreate(SubModel **);
PetscErrorCode MTSShearCreate(SubModel **);
PetscErrorCode SCGShearCreate(SubModel **);

PetscErrorCode ShearModulusList(PetscFunctionList *list)
{
  static PetscFunctionList storage = nullptr;
  return SubModelRegistryGet(&storage,
                             {
                               {"constant", ConstantShearCreate},
                               {"mts", MTSShearCreate},
                               {"scg", SCGShearCreate},
                             },
                             list);
}

} // namespace burst
