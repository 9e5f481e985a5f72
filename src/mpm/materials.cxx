// Materials of a run: -materials name1,name2 and one prefixed block of options per name.
#include "simulation.hpp"
#include "util.hpp"
#include "mpm/geometry.hpp"
#include "scenes/analytic.hpp"

namespace burst {

PetscErrorCode CreateMaterials(Simulation &sim)
{
  char     *names[32];
  PetscInt  n = 32;
  PetscBool set;
  PetscFunctionBeginUser;
  PetscCall(MaterialRegisterAll());
  PetscOptionsBegin(sim.comm, "", "Materials", "Materials");
  PetscCall(PetscOptionsStringArray("-materials", "Names of the solid (MPM) materials; each is configured with -<name>_model and its parameters. None: no particles", "", names, &n, &set));
  PetscOptionsEnd();
  if (!(set && n > 0)) PetscFunctionReturn(PETSC_SUCCESS); // no solids (a gas-only scene, or -help without a scene)
  PetscReal densest = 0;
  for (PetscInt i = 0; i < n; ++i) {
    Material *m;
    for (PetscInt j = 0; j < i; ++j) PetscCheck(std::string(names[i]) != names[j], sim.comm, PETSC_ERR_USER_INPUT, "Option -materials lists '%s' twice", names[i]);
    PetscCall(MaterialCreate(sim.comm, names[i], &m));
    m->id_ = i;
    sim.materials.emplace_back(m);
    densest = PetscMax(densest, m->Density());
  }
  for (PetscInt i = 0; i < n; ++i) PetscCall(PetscFree(names[i])); // after the duplicate check used them
  sim.densest = densest; // the grid turns it into the nodal mass cut-off
  for (PetscInt i = 0; i < (PetscInt)sim.materials.size(); ++i)
    if (sim.materials[i]->IsRigid(sim.rigid_velocity)) {
      PetscCheck(sim.rigid_material < 0, sim.comm, PETSC_ERR_USER_INPUT, "Only one rigid material is supported; -materials lists %s and %s", sim.materials[sim.rigid_material]->Name(), sim.materials[i]->Name());
      sim.rigid_material = i;
    }
  if (!sim.contact_material_name.empty()) {
    for (PetscInt i = 0; i < (PetscInt)sim.materials.size(); ++i)
      if (sim.contact_material_name == sim.materials[i]->Name()) sim.contact_material = i;
    PetscCheck(sim.contact_material >= 0, sim.comm, PETSC_ERR_USER_INPUT, "Option -mpm_contact_material %s: not one of the materials of -materials", sim.contact_material_name.c_str());
    PetscCheck(sim.contact_material != sim.rigid_material, sim.comm, PETSC_ERR_USER_INPUT, "Option -mpm_contact_material %s: the rigid body has a field of its own already", sim.contact_material_name.c_str());
  }
  sim.grid.num_velocity_fields = 1 + (sim.TwoDeformableFields() ? 1 : 0) + (sim.rigid_material >= 0 ? 1 : 0);
  PetscFunctionReturn(PETSC_SUCCESS);
}

Simulation::~Simulation()
{
  VecDestroy(&grid.nodal);
  VecDestroy(&grid.nodal_local);
  VecScatterDestroy(&grid.ghost_sums);
  VecScatterDestroy(&grid.velocity_ghosts);
  VecDestroy(&grid.velocity);
  VecDestroy(&grid.velocity_local);
  VecDestroy(&grid.xpic_star);
  VecDestroy(&grid.xpic_w);
  VecDestroy(&grid.xpic_sum);
  VecDestroy(&grid.xpic_global);
  DMDestroy(&grid.da_velocity);
  DMDestroy(&grid.da_nodes);
  DMDestroy(&swarm);
}

} // namespace burst
