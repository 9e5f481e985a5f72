#include "submodel.hpp"
#include <memory>

namespace burst {

PetscErrorCode OptionsRequiredReal(PetscOptionItems *PetscOptionsObject, const char opt[], const char help[], PetscReal *value)
{
  PetscBool set = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsReal(opt, help, "", *value, value, &set));
  PetscCheck(set, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "Option -%s%s is required: %s", PetscOptionsObject->prefix ? PetscOptionsObject->prefix : "", opt + 1, help);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SubModelCreate(MPI_Comm comm, PetscFunctionList list, const MaterialConstants &material, const char family[], const char default_type[], const char help[], SubModel **model, PetscBool fixed_type)
{
  char        type[256];
  std::string prefix                    = material.name + "_" + family + "_";
  PetscErrorCode (*create)(SubModel **) = nullptr;
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(type, default_type, sizeof(type)));
  std::string names;
  PetscCall(FunctionListNames(list, names));
  if (!fixed_type) {
    PetscOptionsBegin(comm, prefix.c_str(), help, "Material");
    PetscCall(PetscOptionsString("-type", (std::string(help) + " (" + names + ")").c_str(), "", type, type, sizeof(type), nullptr));
    PetscOptionsEnd();
  }
  PetscCall(PetscFunctionListFind(list, type, &create));
  PetscCheck(create, comm, PETSC_ERR_USER_INPUT, "Unknown %s model '%s' for -%s%s; valid choices: %s", family, type, prefix.c_str(), fixed_type ? "types" : "type", names.c_str());
  SubModel *created = nullptr;
  PetscCall(create(&created));
  std::unique_ptr<SubModel> owner(created);
  owner->type   = type;
  owner->prefix = prefix;
  // a title of its own: PETSc prints -help once per (prefix, title)
  const std::string title = std::string(help) + ": " + type + " parameters";
  PetscOptionsBegin(comm, prefix.c_str(), title.c_str(), "Material");
  PetscCall(owner->SetFromOptions(PetscOptionsObject, material));
  PetscOptionsEnd();
  *model = owner.release();
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
