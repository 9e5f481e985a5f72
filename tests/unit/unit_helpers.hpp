// Helpers shared by the unit tests.
#pragma once
#include <gtest/gtest.h>
#include <petscsys.h>
#include <string>
#include <utility>
#include <vector>

// Sets PETSc options for one test and clears them when it ends.
class ScopedOptions {
public:
  ~ScopedOptions()
  {
    for (const std::string &n : names_) PetscOptionsClearValue(nullptr, n.c_str());
  }
  void Set(const std::string &name, const std::string &value)
  {
    EXPECT_EQ(PetscOptionsSetValue(nullptr, name.c_str(), value.c_str()), 0) << name;
    names_.push_back(name);
  }
  // -<mat>_model, -<mat>_density, -<mat>_youngs_modulus, -<mat>_poisson_ratio (empty: not set)
  void Material(const std::string &mat, const std::string &model, const std::string &density, const std::string &E, const std::string &nu)
  {
    if (!model.empty()) Set("-" + mat + "_model", model);
    if (!density.empty()) Set("-" + mat + "_density", density);
    if (!E.empty()) Set("-" + mat + "_youngs_modulus", E);
    if (!nu.empty()) Set("-" + mat + "_poisson_ratio", nu);
  }
  // -MAT_FAMILY_KEY VALUE for each pair
  void Family(const std::string &mat, const std::string &family, const std::vector<std::pair<std::string, std::string>> &kv)
  {
    for (const auto &p : kv) Set("-" + mat + "_" + family + "_" + p.first, p.second);
  }

private:
  std::vector<std::string> names_;
};
