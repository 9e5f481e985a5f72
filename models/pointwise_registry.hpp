// The registry pattern of the pointwise model families (models/gas_eos/, models/burn/): a model is
// chosen by name with -<material>_<key>_type from a PetscFunctionList, then reads its parameters
// under the material's prefix. One implementation for every family; each family keeps its own list
// and registration lines.
#pragma once
#include "util.hpp"
#include <memory>
#include <string>

namespace burst {

// Reads -<material>_<key>_type (default `fallback`; an unknown name stops with the registered names),
// creates the model, sets its name_ and reads its parameters in an options block of its own (PETSc
// prints -help once per prefix and title). `what` names the family in messages and -help.
template <class Model>
PetscErrorCode PointwiseModelCreate(MPI_Comm comm, const char material[], PetscFunctionList list, const char key[], const char fallback[], const char what[], Model **out)
{
  using CreateFn = PetscErrorCode (*)(Model **);
  char              type[256];
  CreateFn          create = nullptr;
  const std::string prefix = std::string(material) + "_", opt = std::string("-") + key + "_type";
  std::string       names;
  PetscFunctionBeginUser;
  *out = nullptr;
  PetscCall(PetscStrncpy(type, fallback, sizeof(type)));
  PetscCall(FunctionListNames(list, names));
  PetscOptionsBegin(comm, prefix.c_str(), what, "Models");
  PetscCall(PetscOptionsFList(opt.c_str(), what, "PointwiseModelCreate", list, type, type, sizeof(type), nullptr));
  PetscOptionsEnd();
  PetscCall(PetscFunctionListFind(list, type, &create));
  PetscCheck(create, comm, PETSC_ERR_USER_INPUT, "Unknown %s '%s' for -%s%s_type; valid choices: %s", what, type, prefix.c_str(), key, names.c_str());
  Model *created = nullptr;
  PetscCall(create(&created));
  std::unique_ptr<Model> owner(created); // freed if reading the parameters fails
  owner->name_            = type;
  const std::string title = std::string(what) + ": " + type + " parameters";
  PetscOptionsBegin(comm, prefix.c_str(), title.c_str(), "Models");
  PetscCall(owner->SetFromOptions(PetscOptionsObject, material));
  PetscOptionsEnd();
  *out = owner.release();
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Reads the real option `opt` (under the block's prefix) with `help` (unit and valid range) and checks
// lo < value (open_lower) or lo <= value, value <= hi; out of range stops naming the full option.
inline PetscErrorCode PointwiseOptionsReal(PetscOptionItems *PetscOptionsObject, const char opt[], const char help[], PetscReal *value, PetscReal lo, PetscReal hi, PetscBool open_lower, PetscBool open_upper = PETSC_FALSE)
{
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsReal(opt, help, "Models", *value, value, nullptr));
  PetscCall(CheckRange(PetscOptionsObject->comm, Prefixed(PetscOptionsObject->prefix, opt).c_str(), *value, lo, hi, open_lower, open_upper));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
