// Sub-models of the hypoelastic-plastic material (equation of state, shear modulus, melt
// temperature, specific heat, flow stress, damage, stability): the common base class and a
// registry per family.
//
// A sub-model of family FAMILY in material MAT reads its options under the prefix -MAT_FAMILY_
// (for example -steel_flow_stress_A 792e6) and is chosen with -MAT_FAMILY_type NAME. Each family
// keeps a PetscFunctionList filled by its registration file (models/FAMILY/registry.cxx).
#pragma once
#include "chunk.hpp"
#include "../util.hpp"
#include <petscviewer.h>
#include <string>

namespace burst {

// Material constants a sub-model may need from its material (set before SetFromOptions).
struct MaterialConstants {
  std::string name;                   // material name (options prefix)
  PetscReal   density          = 0;   // reference density rho0, kg/m^3
  PetscReal   shear_modulus    = 0;   // reference shear modulus mu0, Pa
  PetscReal   bulk_modulus     = 0;   // reference bulk modulus K0, Pa
  PetscReal   room_temperature = 298; // K
};

class SubModel {
public:
  virtual ~SubModel() = default;
  // Reads the parameters; PetscOptionsObject has the prefix -MAT_FAMILY_.
  virtual PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const MaterialConstants &material) = 0;
  // Prints every parameter with its unit.
  virtual PetscErrorCode View(PetscViewer viewer) const = 0;
  std::string            type;   // registered name
  std::string            prefix; // options prefix MAT_FAMILY_
};

// Reads a required real parameter: stops with a message naming the option if it is missing.
PetscErrorCode OptionsRequiredReal(PetscOptionItems *PetscOptionsObject, const char opt[], const char help[], PetscReal *value);

// Creates the sub-model of `family` for a material: reads -MAT_FAMILY_type (default `default_type`),
// creates it from `list` and reads its options. An unknown name stops with the list of valid names.
// With fixed_type, `default_type` is the type and -MAT_FAMILY_type is not read (lists of checks).
PetscErrorCode SubModelCreate(MPI_Comm comm, PetscFunctionList list, const MaterialConstants &material, const char family[], const char default_type[], const char help[], SubModel **model, PetscBool fixed_type = PETSC_FALSE);

} // namespace burst
