// Fragments and the Grady-Hightower estimate (src/mpm/fragments.cxx): the options and what the
// searches measured, owned by Simulation; the checkpoint keeps the measurements.
#pragma once
#include "petsc_compat.hpp"
#include <vector>

namespace burst {

struct FragmentOptions {
  PetscBool         enabled           = PETSC_FALSE;
  PetscReal         distance_factor   = 1.5;
  PetscInt          min_particles     = 4;
  PetscReal         min_mass_fraction = 0; // of the counted materials' mass at t = 0: a size threshold that does not change with the particle spacing
  std::vector<char> counted;               // per material: part of the fragments (-fragments_materials; empty: all)

  bool Counts(PetscInt material) const { return counted.empty() || counted[material]; }
  // Grady-Hightower (eqs. 25-26)
  PetscBool grady     = PETSC_FALSE;
  PetscReal center[3] = {0, 0, 0}, radius = 0, sector = 360;
  PetscReal density = 0, youngs_modulus = 0, toughness = 0, specific_heat = 0, expansion = 0, diffusivity = 0, yield_stress = 0, shear_rate = 0;
};

class CheckpointValues; // src/io/checkpoint_values.hpp

struct Fragments {
  FragmentOptions        options;
  PetscReal              fracture_velocity = -1, fracture_time = -1; // measured at the first failure
  PetscInt64             last_count   = 0;
  PetscReal              initial_mass = -1; // total mass of the counted materials at t = 0 (kg)
  PetscReal              largest_mass = 0, total_intact_mass = 0;
  std::vector<PetscReal> counted_masses; // rank 0: the counted fragments' masses at the last search, kg

  void Checkpoint(CheckpointValues &values); // its part of a checkpoint (fragments.cxx)
};

} // namespace burst
