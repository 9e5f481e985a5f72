#include "util.hpp"
#include <cmath>
#include <cstring>

namespace burst {

PetscErrorCode FunctionListNames(PetscFunctionList list, std::string &names)
{
  const char **array = nullptr;
  int          n     = 0;
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListGet(list, &array, &n));
  names.clear();
  for (int i = 0; i < n; ++i) // 3.18 counts a terminating NULL entry
    if (array[i]) names += std::string(names.empty() ? "" : ", ") + array[i];
  PetscCall(PetscFree(array));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode OptionsChoice(PetscOptionItems *PetscOptionsObject, const char opt[], const char help[], const char *const choices[], int n, int *value, PetscBool *set)
{
  char        buf[256];
  PetscBool   flg = PETSC_FALSE;
  std::string list, full_help;
  PetscFunctionBeginUser;
  for (int i = 0; i < n; ++i) list += std::string(i ? ", " : "") + choices[i];
  full_help = std::string(help) + " (" + list + ")";
  PetscCall(PetscStrncpy(buf, choices[*value], sizeof(buf)));
  PetscCall(PetscOptionsString(opt, full_help.c_str(), "", choices[*value], buf, sizeof(buf), &flg));
  if (set) *set = flg;
  if (!flg) PetscFunctionReturn(PETSC_SUCCESS);
  for (int i = 0; i < n; ++i) {
    if (!std::strcmp(buf, choices[i])) {
      *value = i;
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  SETERRQ(PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "Unknown value '%s' for -%s%s; valid choices: %s", buf, PetscOptionsObject->prefix ? PetscOptionsObject->prefix : "", opt + 1, list.c_str());
}

PetscErrorCode OptionsRealVector(PetscOptionItems *PetscOptionsObject, const char opt[], const char help[], PetscReal values[], PetscInt n, PetscBool *set)
{
  PetscReal buf[16];
  PetscInt  got = 16;
  PetscBool flg = PETSC_FALSE;
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < n; ++i) buf[i] = values[i];
  PetscCall(PetscOptionsRealArray(opt, help, "", buf, &got, &flg));
  if (flg) {
    PetscCheck(got == n, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "Option -%s%s needs %" PetscInt_FMT " comma-separated values, got %" PetscInt_FMT, PetscOptionsObject->prefix ? PetscOptionsObject->prefix : "", opt + 1, n, got);
    for (PetscInt i = 0; i < n; ++i) values[i] = buf[i];
  }
  if (set) *set = flg;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckRange(MPI_Comm comm, const char opt[], PetscReal value, PetscReal lo, PetscReal hi, PetscBool open_lower, PetscBool open_upper)
{
  PetscFunctionBeginUser;
  const bool ok = std::isfinite(value) && (open_lower ? value > lo : value >= lo) && (open_upper ? value < hi : value <= hi);
  if (!ok) {
    if (hi >= PETSC_MAX_REAL) SETERRQ(comm, PETSC_ERR_USER_INPUT, "Option %s = %g is out of range: it must be %s %g", opt, (double)value, open_lower ? ">" : ">=", (double)lo);
    SETERRQ(comm, PETSC_ERR_USER_INPUT, "Option %s = %g is out of range: it must be in %s%g, %g%s", opt, (double)value, open_lower ? "(" : "[", (double)lo, (double)hi, open_upper ? ")" : "]");
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::string Prefixed(const char prefix[], const char opt[]) { return std::string("-") + (prefix ? prefix : "") + (opt[0] == '-' ? opt + 1 : opt); }

} // namespace burst
