// The particle side of the material interface: registers the state fields the models declare on the
// swarm and hands the models views of the swarm's arrays (models/material_state.hpp), so that no
// model sees the swarm.
#pragma once
#include "material.hpp"
#include "mpm/swarm_access.hpp"
#include <memory>
#include <vector>

namespace burst {

// Registers the StateFields of every material on `swarm` (before DMSwarmFinalizeFieldRegister):
// each name once, in the materials' order and each material's declaration order; a name declared
// twice with another block size or type stops the run. Adds the bytes per particle to *bytes.
PetscErrorCode RegisterMaterialState(DM swarm, const std::vector<std::unique_ptr<Material>> &materials, PetscInt *bytes);

// The fields a model reads or writes, gotten through `fields` (which restores them): the core
// particle fields of MaterialPointFields, the particle ids and seeding sizes, and every registered
// state field in `state`, which f.state then points to.
PetscErrorCode GetMaterialPointFields(SwarmAccess &fields, DM swarm, MaterialState &state, MaterialPointFields &f);

} // namespace burst
