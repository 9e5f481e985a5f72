// Access to several DMSwarm fields at once, restored together with one call.
//
//   SwarmAccess fields(sim.swarm);
//   PetscCall(fields.Get(field::mass, &mass));
//   PetscCall(fields.Get(field::velocity, &v));
//   ... flat loops over the arrays ...
//   PetscCall(fields.RestoreAll());
//
// Every field must be restored before the swarm changes size (migration, removal; petsc.md 3); the
// destructor restores whatever an error path left held.
#pragma once
#include "petsc_compat.hpp"
#include <petscdmswarm.h>
#include <array>
#include <string>
#include <utility>
#include <vector>

namespace burst {

// The names of the fields registered through RegisterSwarmField, kept with the swarm (a composed
// container): DMSwarm 3.18 has no public way to list its fields; the particle sort (swarm.cxx)
// permutes every one of them and the checkpoint writes them all, so a model's new state field is
// saved without further code.
inline PetscErrorCode SwarmFieldNamesDestroy(void *ctx)
{
  delete static_cast<std::vector<std::string> *>(ctx);
  return PETSC_SUCCESS;
}
inline PetscErrorCode SwarmFieldNames(DM swarm, std::vector<std::string> **names)
{
  PetscContainer container = nullptr;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectQuery((PetscObject)swarm, "burst_field_names", (PetscObject *)&container));
  if (!container) {
    PetscCall(PetscContainerCreate(PetscObjectComm((PetscObject)swarm), &container));
    PetscCall(PetscContainerSetPointer(container, new std::vector<std::string>()));
    PetscCall(PetscContainerSetUserDestroy(container, SwarmFieldNamesDestroy));
    PetscCall(PetscObjectCompose((PetscObject)swarm, "burst_field_names", (PetscObject)container));
    PetscCall(PetscContainerDestroy(&container));
    PetscCall(PetscObjectQuery((PetscObject)swarm, "burst_field_names", (PetscObject *)&container));
  }
  PetscCall(PetscContainerGetPointer(container, (void **)names));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Registers a swarm field and adds its bytes per particle to *bytes (the storage figure of the summary).
inline PetscErrorCode RegisterSwarmField(DM swarm, const char name[], PetscInt bs, PetscDataType type, PetscInt *bytes)
{
  size_t                    size;
  std::vector<std::string> *names;
  PetscFunctionBeginUser;
  PetscCall(DMSwarmRegisterPetscDatatypeField(swarm, name, bs, type));
  PetscCall(SwarmFieldNames(swarm, &names));
  names->push_back(name);
  PetscCall(PetscDataTypeGetSize(type, &size));
  *bytes += bs * (PetscInt)size;
  PetscFunctionReturn(PETSC_SUCCESS);
}

class SwarmAccess {
public:
  explicit SwarmAccess(DM swarm) : swarm_(swarm) {}
  SwarmAccess(const SwarmAccess &)            = delete;
  SwarmAccess &operator=(const SwarmAccess &) = delete;
  ~SwarmAccess()
  {
    for (int k = count_ - 1; k >= 0; --k) (void)DMSwarmRestoreField(swarm_, held_[k].first, nullptr, nullptr, &held_[k].second);
  }

  template <class T>
  PetscErrorCode Get(const char name[], T **data)
  {
    void *ptr = nullptr;
    *data     = nullptr;
    PetscFunctionBeginUser;
    PetscCheck(count_ < (int)held_.size(), PETSC_COMM_SELF, PETSC_ERR_PLIB, "SwarmAccess holds at most %d fields", (int)held_.size());
    PetscCall(DMSwarmGetField(swarm_, name, nullptr, nullptr, &ptr));
    held_[count_++] = {name, ptr};
    *data           = static_cast<T *>(ptr);
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  PetscErrorCode RestoreAll()
  {
    PetscFunctionBeginUser;
    for (; count_ > 0; --count_) PetscCall(DMSwarmRestoreField(swarm_, held_[count_ - 1].first, nullptr, nullptr, &held_[count_ - 1].second));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

private:
  DM                                              swarm_;
  std::array<std::pair<const char *, void *>, 48> held_{};
  int                                             count_ = 0;
};

} // namespace burst
