// The registries of the sub-model families (each family's table is in models/FAMILY/registry.cxx):
// filled on first use, freed together.
#include "families.hpp"
#include <vector>

namespace burst {

namespace {
std::vector<PetscFunctionList *> filled; // every registry filled so far
} // namespace

PetscErrorCode SubModelRegistryGet(PetscFunctionList *storage, std::initializer_list<SubModelEntry> models, PetscFunctionList *list)
{
  PetscFunctionBeginUser;
  if (!*storage) {
    for (const SubModelEntry &m : models) PetscCall(PetscFunctionListAdd(storage, m.name, m.create));
    filled.push_back(storage);
  }
  *list = *storage;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SubModelRegistriesDestroy()
{
  PetscFunctionBeginUser;
  for (PetscFunctionList *storage : filled) PetscCall(PetscFunctionListDestroy(storage));
  filled.clear();
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
