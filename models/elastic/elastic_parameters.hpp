// Isotropic elastic constants read as Young's modulus and Poisson's ratio, shared by the elastic models.
#pragma once
#include "../material.hpp"

namespace burst {

struct IsotropicElasticity {
  PetscReal youngs_modulus = -1; // Pa
  PetscReal poisson_ratio  = 0.3;
  PetscReal shear_modulus = 0, bulk_modulus = 0, lame_lambda = 0; // Pa, derived

  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const Material &m);
  PetscErrorCode View(PetscViewer viewer) const;
};

} // namespace burst
