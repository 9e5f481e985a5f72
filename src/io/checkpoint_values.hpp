// A component's part of a checkpoint: the numbers it remembers between steps, each by name. A
// component lists them (pointers to its own members) in a function of its own; the checkpoint
// (src/io/checkpoint.cxx) writes every part to /<part>/values (one value set, rank 0's) and
// /<part>/rank_values (a row per rank), each with its names as an attribute, and reads them back
// by name, so that a checkpoint that lacks one is refused with that name.
#pragma once
#include "petsc_compat.hpp"
#include <petscvec.h>
#include <string>
#include <type_traits>
#include <vector>

namespace burst {

class CheckpointValues {
public:
  // Values that every rank holds the same (times, step counts, initial sums, run-wide counters).
  template <class T>
  void Global(const char *name, T *values, PetscInt n = 1)
  {
    Add(name, values, n, false);
  }
  // Each rank's own partial sum: a restart on as many ranks gives each rank its own, on another
  // number of ranks rank 0 gets their sum and the others zero.
  template <class T>
  void PerRank(const char *name, T *values, PetscInt n = 1)
  {
    Add(name, values, n, true);
  }

  PetscInt               Count(bool per_rank) const;
  std::string            Names(bool per_rank) const; // "name:n,name:n,..."
  std::vector<PetscReal> Pack(bool per_rank) const;  // the values in the order listed, as reals
  void                   Unpack(bool per_rank, const PetscReal *values);
  // Where the entry `name` starts in a packed row, -1 if it is not listed.
  PetscInt Offset(bool per_rank, const std::string &name) const;

private:
  enum class Kind { Real, Int, Int64 };
  struct Entry {
    std::string name;
    void       *data;
    Kind        kind;
    PetscInt    n;
    bool        per_rank;
  };
  std::vector<Entry> entries_;
  template <class T>
  void Add(const char *name, T *values, PetscInt n, bool per_rank)
  {
    static_assert(std::is_same<T, PetscReal>::value || std::is_same<T, PetscInt>::value || std::is_same<T, PetscInt64>::value, "checkpoint values are reals or integers");
    const Kind kind = std::is_same<T, PetscReal>::value ? Kind::Real : std::is_same<T, PetscInt64>::value ? Kind::Int64 : Kind::Int;
    entries_.push_back({name, (void *)values, kind, n, per_rank});
  }
};

// Adds the entries of Vec v (global numbering, the caller's ordering) to the checksum of the
// checkpoint being written, as dataset `path` (src/io/checkpoint.cxx).
PetscErrorCode CheckpointChecksumVec(Vec v, const std::string &path);

} // namespace burst
