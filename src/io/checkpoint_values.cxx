// The named values of a component's checkpoint part (checkpoint_values.hpp).
#include "checkpoint_values.hpp"

namespace burst {

PetscInt CheckpointValues::Count(bool per_rank) const
{
  PetscInt n = 0;
  for (const Entry &e : entries_)
    if (e.per_rank == per_rank) n += e.n;
  return n;
}

std::string CheckpointValues::Names(bool per_rank) const
{
  std::string s;
  for (const Entry &e : entries_)
    if (e.per_rank == per_rank) s += (s.empty() ? "" : ",") + e.name + ":" + std::to_string(e.n);
  return s;
}

PetscInt CheckpointValues::Offset(bool per_rank, const std::string &name) const
{
  PetscInt at = 0;
  for (const Entry &e : entries_) {
    if (e.per_rank != per_rank) continue;
    if (e.name == name) return at;
    at += e.n;
  }
  return -1;
}

// (integers as reals: exact below 2^53)
std::vector<PetscReal> CheckpointValues::Pack(bool per_rank) const
{
  std::vector<PetscReal> out;
  for (const Entry &e : entries_) {
    if (e.per_rank != per_rank) continue;
    for (PetscInt i = 0; i < e.n; ++i) {
      switch (e.kind) {
      case Kind::Real: out.push_back(((const PetscReal *)e.data)[i]); break;
      case Kind::Int: out.push_back((PetscReal)((const PetscInt *)e.data)[i]); break;
      case Kind::Int64: out.push_back((PetscReal)((const PetscInt64 *)e.data)[i]); break;
      }
    }
  }
  return out;
}

void CheckpointValues::Unpack(bool per_rank, const PetscReal *values)
{
  for (const Entry &e : entries_) {
    if (e.per_rank != per_rank) continue;
    for (PetscInt i = 0; i < e.n; ++i, ++values) {
      switch (e.kind) {
      case Kind::Real: ((PetscReal *)e.data)[i] = *values; break;
      case Kind::Int: ((PetscInt *)e.data)[i] = (PetscInt)*values; break;
      case Kind::Int64: ((PetscInt64 *)e.data)[i] = (PetscInt64)*values; break;
      }
    }
  }
}

} // namespace burst
