// The models' state fields on the swarm (src/mpm/material_state.hpp).
#include "mpm/mpm.hpp"
#include "mpm/material_state.hpp"
#include <string>

namespace burst {

namespace {
// The registered state fields, kept with the swarm (a composed container) like the field names.
PetscErrorCode StateFieldsDestroy(void *ctx)
{
  delete static_cast<std::vector<StateField> *>(ctx);
  return PETSC_SUCCESS;
}
PetscErrorCode RegisteredStateFields(DM swarm, bool create, std::vector<StateField> **registered)
{
  PetscContainer container = nullptr;
  PetscFunctionBeginUser;
  *registered = nullptr;
  PetscCall(PetscObjectQuery((PetscObject)swarm, "burst_state_fields", (PetscObject *)&container));
  if (!container && create) {
    PetscCall(PetscContainerCreate(PetscObjectComm((PetscObject)swarm), &container));
    PetscCall(PetscContainerSetPointer(container, new std::vector<StateField>()));
    PetscCall(PetscContainerSetUserDestroy(container, StateFieldsDestroy));
    PetscCall(PetscObjectCompose((PetscObject)swarm, "burst_state_fields", (PetscObject)container));
    PetscCall(PetscContainerDestroy(&container));
    PetscCall(PetscObjectQuery((PetscObject)swarm, "burst_state_fields", (PetscObject *)&container));
  }
  if (container) PetscCall(PetscContainerGetPointer(container, (void **)registered));
  PetscFunctionReturn(PETSC_SUCCESS);
}
} // namespace

PetscErrorCode RegisterMaterialState(DM swarm, const std::vector<std::unique_ptr<Material>> &materials, PetscInt *bytes)
{
  std::vector<StateField> *registered;
  PetscFunctionBeginUser;
  PetscCall(RegisteredStateFields(swarm, true, &registered));
  for (const auto &m : materials)
    for (const StateField &f : m->StateFields()) {
      const StateField *seen = nullptr;
      for (const StateField &r : *registered)
        if (std::string(r.name) == f.name) seen = &r;
      if (seen) {
        PetscCheck(seen->bs == f.bs && seen->is_int == f.is_int, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Material %s declares the state field %s with another block size or type than an earlier material", m->Name(), f.name);
        continue;
      }
      PetscCall(RegisterSwarmField(swarm, f.name, f.bs, f.is_int ? PETSC_INT : PETSC_REAL, bytes));
      registered->push_back(f);
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GetMaterialPointFields(SwarmAccess &fields, DM swarm, MaterialState &state, MaterialPointFields &f)
{
  std::vector<StateField>  *registered;
  std::vector<std::string> *names;
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(swarm, &f.n));
  PetscCall(DMGetDimension(swarm, &f.dim));
  PetscCall(fields.Get(field::material, &f.material));
  PetscCall(fields.Get(field::L, &f.L));
  PetscCall(fields.Get(field::F, &f.F));
  PetscCall(fields.Get(field::stress, &f.stress));
  PetscCall(fields.Get(field::mass, &f.mass));
  PetscCall(fields.Get(field::volume, &f.volume));
  PetscCall(fields.Get(field::temperature, &f.temperature));
  PetscCall(fields.Get(field::wave_speed, &f.wave_speed));
  PetscCall(fields.Get(field::internal_energy, &f.internal_energy));
  PetscCall(fields.Get(DMSwarmField_pid, &f.id));
  // the seeding size: the particles' half-widths where the swarm has them (a scene), their volume
  // otherwise (the point driver)
  PetscCall(SwarmFieldNames(swarm, &names));
  bool has_half_width = false;
  for (const std::string &n : *names) has_half_width = has_half_width || n == field::half_width0;
  if (has_half_width) PetscCall(fields.Get(field::half_width0, &f.half_width0));
  else PetscCall(fields.Get(field::volume0, &f.volume0));
  PetscCall(RegisteredStateFields(swarm, false, &registered));
  if (registered)
    for (const StateField &s : *registered) {
      void *array;
      PetscCall(fields.Get(s.name, &array));
      PetscCall(state.Add(s.name, s.bs, s.is_int, array));
    }
  f.state = &state;
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
