// Memory estimates at set-up (memory.hpp).
#include "memory.hpp"
#include <cstdio>
#include <cstring>

namespace burst {

// MemAvailable of /proc/meminfo in bytes, or -1 where there is none.
static PetscReal MemAvailable()
{
  FILE *f = std::fopen("/proc/meminfo", "r");
  if (!f) return -1;
  char      line[256];
  PetscReal bytes = -1;
  while (std::fgets(line, sizeof(line), f)) {
    long long kb = 0;
    if (std::sscanf(line, "MemAvailable: %lld kB", &kb) == 1) {
      bytes = 1024.0 * (PetscReal)kb;
      break;
    }
  }
  std::fclose(f);
  return bytes;
}

PetscErrorCode MemoryAvailablePerRank(MPI_Comm comm, PetscReal *bytes)
{
  PetscReal given = -1;
  PetscBool set   = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "", "Memory", "Run");
  PetscCall(PetscOptionsReal("-max_memory", "Memory a rank may use (bytes), for the set-up's estimate of particles, grid and gas; default: MemAvailable of /proc/meminfo shared by the ranks on the node", "", given, &given, &set));
  PetscOptionsEnd();
  if (set) {
    PetscCheck(given > 0, comm, PETSC_ERR_USER_INPUT, "Option -max_memory = %g is out of range: it must be > 0 (bytes per rank)", (double)given);
    *bytes = given;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  MPI_Comm    node;
  PetscMPIInt on_node = 1;
  PetscCallMPI(MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node));
  PetscCallMPI(MPI_Comm_size(node, &on_node));
  PetscCallMPI(MPI_Comm_free(&node));
  const PetscReal available = MemAvailable();
  PetscReal       mine      = available > 0 ? available / on_node : PETSC_MAX_REAL, least;
  PetscCallMPI(MPI_Allreduce(&mine, &least, 1, MPIU_REAL, MPI_MIN, comm));
  *bytes = least;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MemoryCheck(MPI_Comm comm, const char what[], PetscReal bytes_on_rank, const char advice[])
{
  PetscReal most, available;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(&bytes_on_rank, &most, 1, MPIU_REAL, MPI_MAX, comm));
  PetscCall(MemoryAvailablePerRank(comm, &available));
  PetscCall(PetscInfo(nullptr, "Memory estimate for %s: %g bytes on the fullest rank, %g available per rank\n", what, (double)most, (double)available));
  PetscCheck(most <= available, comm, PETSC_ERR_MEM, "%s needs about %.3g GB on a rank (set-up's estimate), more than the %.3g GB a rank has (-max_memory, default MemAvailable over the ranks on the node): %s", what, (double)(most / 1e9),
             (double)(available / 1e9), advice);
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
