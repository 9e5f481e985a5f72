// Materials of a run: -materials name1,name2 and one prefixed block of options per name.
#include "mpm/mpm.hpp"
#include "util.hpp"
#include "mpm/geometry.hpp"

namespace burst {

PetscErrorCode CreateMaterials(MpmSolver &mpm)
{
  char     *names[32];
  PetscInt  n = 32;
  PetscBool set;
  PetscFunctionBeginUser;
  PetscCall(MaterialRegisterAll());
  PetscOptionsBegin(mpm.comm, "", "Materials", "Materials");
  PetscCall(PetscOptionsStringArray("-materials", "Names of the solid (MPM) materials; each is configured with -<name>_model and its parameters. None: no particles", "", names, &n, &set));
  PetscOptionsEnd();
  if (!(set && n > 0)) PetscFunctionReturn(PETSC_SUCCESS); // no solids (a gas-only scene, or -help without a scene)
  PetscReal densest = 0;
  for (PetscInt i = 0; i < n; ++i) {
    Material *m;
    for (PetscInt j = 0; j < i; ++j) PetscCheck(std::string(names[i]) != names[j], mpm.comm, PETSC_ERR_USER_INPUT, "Option -materials lists '%s' twice", names[i]);
    PetscCall(MaterialCreate(mpm.comm, names[i], &m));
    m->id_ = i;
    mpm.materials.emplace_back(m);
    densest = PetscMax(densest, m->Density());
  }
  for (PetscInt i = 0; i < n; ++i) PetscCall(PetscFree(names[i])); // after the duplicate check used them
  mpm.densest = densest;                                           // the grid turns it into the nodal mass cut-off
  for (PetscInt i = 0; i < (PetscInt)mpm.materials.size(); ++i)
    if (mpm.materials[i]->IsRigid(mpm.rigid_velocity)) {
      PetscCheck(mpm.rigid_material < 0, mpm.comm, PETSC_ERR_USER_INPUT, "Only one rigid material is supported; -materials lists %s and %s", mpm.materials[mpm.rigid_material]->Name(), mpm.materials[i]->Name());
      mpm.rigid_material = i;
    }
  if (!mpm.contact_material_name.empty()) {
    for (PetscInt i = 0; i < (PetscInt)mpm.materials.size(); ++i)
      if (mpm.contact_material_name == mpm.materials[i]->Name()) mpm.contact_material = i;
    PetscCheck(mpm.contact_material >= 0, mpm.comm, PETSC_ERR_USER_INPUT, "Option -mpm_contact_material %s: not one of the materials of -materials", mpm.contact_material_name.c_str());
    PetscCheck(mpm.contact_material != mpm.rigid_material, mpm.comm, PETSC_ERR_USER_INPUT, "Option -mpm_contact_material %s: the rigid body has a field of its own already", mpm.contact_material_name.c_str());
  }
  mpm.grid.num_velocity_fields = 1 + (mpm.TwoDeformableFields() ? 1 : 0) + (mpm.rigid_material >= 0 ? 1 : 0);
  PetscFunctionReturn(PETSC_SUCCESS);
}

MpmSolver::~MpmSolver()
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
