// The per-particle state of the material models, as the models see it: arrays by field name.
//
// A model declares the fields it keeps (Material::StateFields: name, block size, type); the core
// (src/mpm/material_state.cxx) registers each name once on the particle swarm and, around every
// call, hands the model a MaterialState that maps the names to the swarm's arrays. A unit test
// hands it arrays of its own (MaterialStateStorage). Models therefore never see the swarm, and the
// arrays are looked up once per batch of particles, never per particle.
#pragma once
#include "petsc_compat.hpp"
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace burst {

// One per-particle field a model keeps: bs values of PetscReal or PetscInt per particle.
struct StateField {
  const char *name;
  PetscInt    bs;
  bool        is_int;
};

// State fields that models write and the core reads (fragments, load balance, multi-field contact,
// the Taylor scene); a model that tracks the quantity declares the field under this name.
namespace state_field {
inline constexpr const char *failed              = "failed";              // int: failure criterion bits, 0 = intact
inline constexpr const char *plastic_strain      = "plastic_strain";      // equivalent plastic strain, -
inline constexpr const char *plastic_strain_rate = "plastic_strain_rate"; // 1/s
inline constexpr const char *softening_criteria  = "softening_criteria";  // int: the criterion bits that started the crack band's softening
} // namespace state_field

// The arrays of the registered state fields, by name (at most kMaxFields).
class MaterialState {
public:
  static constexpr int kMaxFields = 48;

  PetscErrorCode Add(const char name[], PetscInt bs, bool is_int, void *array)
  {
    PetscFunctionBeginUser;
    PetscCheck(count_ < kMaxFields, PETSC_COMM_SELF, PETSC_ERR_PLIB, "MaterialState holds at most %d fields", kMaxFields);
    entries_[count_++] = {name, bs, is_int, array};
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  bool Has(const char name[]) const { return Find(name) != nullptr; }
  // The k-th field (0 <= k < Count()), in the order Add saw them: for code that moves every field
  // of a set of points at once (src/mpm/stress_share.cxx).
  struct FieldView {
    const char *name;
    PetscInt    bs;
    bool        is_int;
    void       *array;
  };
  int       Count() const { return count_; }
  FieldView Field(int k) const { return {entries_[k].name, entries_[k].bs, entries_[k].is_int, entries_[k].array}; }
  // The array of field `name`; stops if no model registered it or its type is not T.
  template <class T>
  PetscErrorCode Get(const char name[], T **array) const
  {
    static_assert(std::is_same<T, PetscReal>::value || std::is_same<T, PetscInt>::value, "state fields are PetscReal or PetscInt");
    constexpr bool want_int = std::is_same<T, PetscInt>::value;
    const Entry   *e        = Find(name);
    PetscFunctionBeginUser;
    PetscCheck(e, PETSC_COMM_SELF, PETSC_ERR_PLIB, "No material registered the state field %s", name);
    PetscCheck(e->is_int == want_int, PETSC_COMM_SELF, PETSC_ERR_PLIB, "State field %s is not of the requested type", name);
    *array = static_cast<T *>(e->array);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  // Like Get, but a field that nobody registered gives nullptr.
  template <class T>
  PetscErrorCode GetIfPresent(const char name[], T **array) const
  {
    PetscFunctionBeginUser;
    *array = nullptr;
    if (Has(name)) PetscCall(Get(name, array));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

private:
  struct Entry {
    const char *name;
    PetscInt    bs;
    bool        is_int;
    void       *array;
  };
  const Entry *Find(const char name[]) const
  {
    for (int k = 0; k < count_; ++k)
      if (!std::strcmp(entries_[k].name, name)) return &entries_[k];
    return nullptr;
  }
  int   count_ = 0;
  Entry entries_[kMaxFields]{};
};

// Plain arrays for the state of n points: the fields of the given declarations, each name once
// (unit tests and drivers without a swarm).
class MaterialStateStorage {
public:
  MaterialStateStorage()                                        = default;
  MaterialStateStorage(const MaterialStateStorage &)            = delete; // the views point into it
  MaterialStateStorage &operator=(const MaterialStateStorage &) = delete;
  PetscErrorCode        Allocate(const std::vector<StateField> &fields, PetscInt n)
  {
    PetscFunctionBeginUser;
    for (const StateField &f : fields) {
      bool seen = false;
      for (const Storage &s : storage_) seen = seen || s.name == f.name;
      if (seen) continue;
      storage_.push_back({f.name, f.bs, f.is_int, std::vector<PetscReal>(f.is_int ? 0 : f.bs * n), std::vector<PetscInt>(f.is_int ? f.bs * n : 0)});
    }
    for (Storage &s : storage_) PetscCall(state_.Add(s.name.c_str(), s.bs, s.is_int, s.is_int ? (void *)s.ints.data() : (void *)s.reals.data()));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  const MaterialState &State() const { return state_; }

private:
  struct Storage {
    std::string            name;
    PetscInt               bs;
    bool                   is_int;
    std::vector<PetscReal> reals;
    std::vector<PetscInt>  ints;
  };
  std::vector<Storage> storage_; // filled once, before the views are taken
  MaterialState        state_;
};

} // namespace burst
