// The registry of material models: one registration line per model.
#include "material.hpp"
#include "util.hpp"
#include <cmath>
#include <memory>

namespace burst {

PetscErrorCode LinearElasticCreate(Material **);
PetscErrorCode NeoHookeanCreate(Material **);
PetscErrorCode ElasticPlasticCreate(Material **);
PetscErrorCode RigidCreate(Material **);
PetscErrorCode ViscoScramCreate(Material **);
PetscErrorCode SubModelRegistriesDestroy();

static PetscFunctionList material_list  = nullptr;
static PetscBool         registered_all = PETSC_FALSE;

PetscErrorCode MaterialRegister(const char name[], MaterialCreateFn create)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListAdd(&material_list, name, create));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MaterialRegisterAll()
{
  PetscFunctionBeginUser;
  if (registered_all) PetscFunctionReturn(PETSC_SUCCESS);
  registered_all = PETSC_TRUE;
  PetscCall(MaterialRegister("linear_elastic", LinearElasticCreate));
  PetscCall(MaterialRegister("neo_hookean", NeoHookeanCreate));
  PetscCall(MaterialRegister("elastic_plastic", ElasticPlasticCreate));
  PetscCall(MaterialRegister("rigid", RigidCreate));
  PetscCall(MaterialRegister("viscoscram", ViscoScramCreate));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MaterialRegistryDestroy()
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&material_list));
  PetscCall(SubModelRegistriesDestroy());
  registered_all = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Creates the material called `name`: reads -<name>_model from the registry, then its options.
PetscErrorCode MaterialCreate(MPI_Comm comm, const char name[], Material **material)
{
  char             model[256] = "linear_elastic";
  PetscBool        set        = PETSC_FALSE;
  MaterialCreateFn create     = nullptr;
  std::string      prefix     = std::string(name) + "_";

  PetscFunctionBeginUser;
  PetscCall(MaterialRegisterAll());
  PetscOptionsBegin(comm, prefix.c_str(), "Material options", "Material");
  PetscCall(PetscOptionsFList("-model", "Material model", "MaterialCreate", material_list, model, model, sizeof(model), &set));
  PetscOptionsEnd();
  PetscCheck(set, comm, PETSC_ERR_USER_INPUT, "Material '%s' has no model: give -%smodel with one of the registered models (run with -help to list them)", name, prefix.c_str());
  PetscCall(PetscFunctionListFind(material_list, model, &create));
  if (!create) {
    std::string names;
    PetscCall(FunctionListNames(material_list, names));
    SETERRQ(comm, PETSC_ERR_USER_INPUT, "Unknown material model '%s' for -%smodel; valid choices: %s", model, prefix.c_str(), names.c_str());
  }
  Material *created = nullptr;
  PetscCall(create(&created));
  std::unique_ptr<Material> owner(created); // freed if reading the parameters fails
  owner->name_  = name;
  owner->model_ = model;
  PetscOptionsBegin(comm, prefix.c_str(), "Material parameters", "Material");
  PetscCall(MaterialReadDensity(PetscOptionsObject, *owner));
  PetscCall(owner->SetFromOptions(PetscOptionsObject));
  PetscOptionsEnd();
  PetscCall(owner->SetUp(comm));
  *material = owner.release();
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MaterialReadDensity(PetscOptionItems *PetscOptionsObject, Material &m)
{
  PetscBool set = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsReal("-density", "Reference mass density (kg/m^3), required, in (0, 1e10]", "Material", m.density_, &m.density_, &set));
  PetscCheck(set, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "Material '%s': -%s_density is required (kg/m^3, in (0, 1e10])", m.Name(), m.Name());
  // bounded to catch a mistyped exponent; a verification deck's heavy piston (tests/decks/gas_piston.opts) takes 1e7 kg/m^3
  PetscCheck(m.density_ > 0 && m.density_ <= 1e10, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "Material '%s': -%s_density = %g is out of range; it must be in (0, 1e10] (kg/m^3)", m.Name(), m.Name(), (double)m.density_);
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
