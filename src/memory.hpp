// Memory estimates at set-up: a run that cannot fit is refused with the figure before it allocates,
// instead of dying in an allocation (std::bad_alloc) or inside DMSetUp with an MPI abort.
//
// Per rank, the bytes available are -max_memory (bytes per rank) or, by default, MemAvailable of
// /proc/meminfo shared by the ranks on the node. Coefficients (max RSS of one-step runs, AMD EPYC
// 2-core VM, 2026-12-03; doc/running.md): particles 1.7 x the swarm's registered bytes per particle
// (the seeding buffer, output and migration copies); the MPM grid 300 B per node and velocity field
// in 2-D, 355 B in 3-D; the gas 48 B per cell and cell-state entry (six copies of the state).
#pragma once
#include "petsc_compat.hpp"
#include <petscsys.h>

namespace burst {

constexpr PetscReal kMemoryParticleFactor = 1.7;
constexpr PetscReal kMemoryNodeBytes2d    = 300;
constexpr PetscReal kMemoryNodeBytes3d    = 355;
constexpr PetscReal kMemoryCellEntryBytes = 48;

// What one rank may use (bytes): -max_memory, or MemAvailable over the ranks on this node.
PetscErrorCode MemoryAvailablePerRank(MPI_Comm comm, PetscReal *bytes);

// Refuses (PETSC_ERR_MEM, on every rank) when the largest `bytes_on_rank` over the ranks exceeds what
// a rank has, naming `what`, both figures and `advice`.
PetscErrorCode MemoryCheck(MPI_Comm comm, const char what[], PetscReal bytes_on_rank, const char advice[]);

} // namespace burst
