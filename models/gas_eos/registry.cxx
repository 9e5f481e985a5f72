// Registry of the ICE (gas) equations of state: one declaration and one registration line per model.
#include "options.hpp"
#include <memory>

namespace burst {

PetscErrorCode IdealGasCreate(GasEOS **);
PetscErrorCode StiffenedGasCreate(GasEOS **);
PetscErrorCode JWLCreate(GasEOS **);
PetscErrorCode MurnaghanCreate(GasEOS **);

static PetscFunctionList gas_eos_list = nullptr;

PetscErrorCode GasEOSList(PetscFunctionList *list)
{
  PetscFunctionBeginUser;
  if (!gas_eos_list) {
    PetscCall(PetscFunctionListAdd(&gas_eos_list, "ideal_gas", IdealGasCreate));
    PetscCall(PetscFunctionListAdd(&gas_eos_list, "stiffened_gas", StiffenedGasCreate));
    PetscCall(PetscFunctionListAdd(&gas_eos_list, "jwl", JWLCreate));
    PetscCall(PetscFunctionListAdd(&gas_eos_list, "murnaghan", MurnaghanCreate));
  }
  *list = gas_eos_list;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GasEOSRegistryDestroy()
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&gas_eos_list));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GasEOSCreate(MPI_Comm comm, const char material[], GasEOS **eos)
{
  char              type[256] = "ideal_gas";
  PetscFunctionList list      = nullptr;
  GasEOSCreateFn    create    = nullptr;
  const std::string prefix    = std::string(material) + "_";
  std::string       names;

  PetscFunctionBeginUser;
  *eos = nullptr;
  PetscCall(GasEOSList(&list));
  PetscCall(FunctionListNames(list, names));
  PetscOptionsBegin(comm, prefix.c_str(), "ICE material equation of state", "ICE");
  PetscCall(PetscOptionsFList("-eos_type", "Equation of state of the ICE material", "GasEOSCreate", list, type, type, sizeof(type), nullptr));
  PetscOptionsEnd();
  PetscCall(PetscFunctionListFind(list, type, &create));
  PetscCheck(create, comm, PETSC_ERR_USER_INPUT, "Unknown equation of state '%s' for -%seos_type; valid choices: %s", type, prefix.c_str(), names.c_str());
  GasEOS *created = nullptr;
  PetscCall(create(&created));
  std::unique_ptr<GasEOS> owner(created); // freed if reading the parameters fails
  owner->name_ = type;
  // a title of its own: PETSc prints -help once per (prefix, title)
  const std::string title = std::string("ICE material equation of state: ") + type + " parameters";
  PetscOptionsBegin(comm, prefix.c_str(), title.c_str(), "ICE");
  PetscCall(owner->SetFromOptions(PetscOptionsObject, material));
  PetscOptionsEnd();
  *eos = owner.release();
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GasEOSOptionsReal(PetscOptionItems *PetscOptionsObject, const char opt[], const char help[], PetscReal *value, PetscReal lo, PetscReal hi, PetscBool open_lower)
{
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsReal(opt, help, "GasEOS", *value, value, nullptr));
  PetscCall(CheckRange(PetscOptionsObject->comm, Prefixed(PetscOptionsObject->prefix, opt).c_str(), *value, lo, hi, open_lower));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
