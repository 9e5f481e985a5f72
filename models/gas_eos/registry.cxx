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
  PetscFunctionList list = nullptr;
  PetscFunctionBeginUser;
  PetscCall(GasEOSList(&list));
  PetscCall(PointwiseModelCreate(comm, material, list, "eos", "ideal_gas", "equation of state", eos));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
