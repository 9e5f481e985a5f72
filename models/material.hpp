// The material interface: the C++ layer that the particle loops of src/ call.
//
// A Material owns the parameters of one material region and updates the stress of its particles.
// Calls are per batch, never per particle: UpdateStress receives the raw DMSwarm field arrays and
// loops over the particles whose material id matches, so parameter lookups, virtual dispatch and
// model choices are hoisted out of the particle loop (STYLE.md 2.3).
//
// A model that needs per-particle state declares it in StateFields (name, block size, type); the
// core registers the fields and hands the model their arrays in MaterialPointFields::state
// (models/material_state.hpp), so a new model brings its own state without touching the core and
// never sees the swarm or the grid.
//
// Adding a model: write one file models/<family>/<name>.cxx with a class derived from Material and a
// create function, then add one line to models/registry.cxx.
#pragma once
#include "material_state.hpp"
#include <petscviewer.h>
#include <string>
#include <vector>

namespace burst {

// Views of the particle fields that a model may read or write for the local particles.
// Tensors are row-major 3x3 in every dimension: in 2-D the zz entries carry plane strain.
struct MaterialPointFields {
  PetscInt             n               = 0;       // local particle count
  const PetscInt      *material        = nullptr; // material id per particle
  const PetscReal     *L               = nullptr; // velocity gradient at t_{n+1/2}, 1/s
  const PetscReal     *F               = nullptr; // deformation gradient at t_{n+1} (already updated)
  PetscReal           *stress          = nullptr; // Cauchy stress, Pa (in: t_n, out: t_{n+1})
  const PetscReal     *mass            = nullptr; // kg
  const PetscReal     *volume          = nullptr; // current volume, m^3
  PetscReal           *temperature     = nullptr; // K
  PetscReal           *wave_speed      = nullptr; // out: longitudinal wave speed, m/s
  PetscReal           *internal_energy = nullptr; // in/out: accumulated stress work, J
  const MaterialState *state           = nullptr; // the state fields of every material's StateFields
  const PetscInt64    *id              = nullptr; // particle id, the same on any rank count (reproducible draws)
  const PetscReal     *half_width0     = nullptr; // bs dim: half-widths at seeding (m), if the particles have them
  const PetscReal     *volume0         = nullptr; // else the volume at seeding, m^3
  PetscInt             dim             = 3;       // spatial dimension of the run
  PetscReal            cell_size       = 0;       // m: the background grid's cell size in x; 0 without a grid (the point driver)
  PetscReal            time            = 0;       // t_{n+1}, s
};

// A per-particle field a model registered and wants in the output.
struct OutputField {
  const char *name;
  PetscInt    bs;
  bool        is_int;
};

class Material {
public:
  virtual ~Material() = default;
  // Reads the options under `-<name>_`: density plus the model's own parameters.
  virtual PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject) = 0;
  // Creates what depends on the parameters (sub-models); called after SetFromOptions.
  virtual PetscErrorCode SetUp(MPI_Comm comm)
  {
    (void)comm;
    return PETSC_SUCCESS;
  }
  // The model's per-particle state, in the order the fields are registered (each name once over
  // all materials: materials of one model share their fields).
  virtual std::vector<StateField> StateFields() const { return {}; }
  // Sets the model state of newly seeded particles [begin, end) of this material.
  virtual PetscErrorCode InitializeState(const MaterialPointFields &f, PetscInt begin, PetscInt end)
  {
    (void)f;
    (void)begin;
    (void)end;
    return PETSC_SUCCESS;
  }
  // Stress update over the particles with material == id: sigma_{n+1} from sigma_n, L, F, dt.
  // Also writes the wave speed and adds the stress work 0.5 (sigma_n + sigma_{n+1}) : D V_mid dt,
  // V_mid = V_{n+1} (1 - tr(D) dt / 2) (second order in dt; see StressWork).
  virtual PetscErrorCode UpdateStress(const MaterialPointFields &f, PetscInt id, PetscReal dt) = 0;
  // Wave speed of the particles at their current state (used before the first stress update).
  virtual PetscErrorCode ComputeWaveSpeed(const MaterialPointFields &f, PetscInt id) = 0;
  // Prints every parameter with its unit.
  virtual PetscErrorCode View(PetscViewer viewer) const = 0;
  // A rigid body returns true and its prescribed velocity (m/s).
  virtual bool IsRigid(PetscReal velocity[3]) const
  {
    (void)velocity;
    return false;
  }
  // Model fields written with the particles (HDF5/XDMF).
  virtual std::vector<OutputField> OutputFields() const { return {}; }
  // Nonlocal regularisation (src/mpm/nonlocal.cxx): a model that wants the per-particle values it
  // writes to kNonlocalSource averaged over a radius returns that radius (m) here, 0 otherwise; the
  // averages arrive in kNonlocalAverage after the step's stress update (and nonlocal_active_ is set).
  virtual PetscReal NonlocalLength() const { return 0; }

  const char *Name() const { return name_.c_str(); }
  const char *Model() const { return model_.c_str(); }
  PetscReal   Density() const { return density_; }
  PetscReal   BulkModulus() const { return bulk_modulus_; }

  std::string name_;                    // user's name, also the options prefix
  std::string model_;                   // registered model name
  PetscReal   density_         = -1;    // reference mass density, kg/m^3
  PetscReal   bulk_modulus_    = -1;    // reference bulk modulus, Pa (the solid's volume as the gas sees it, ice.md 2.2)
  PetscInt    id_              = -1;    // material id (index in -materials) of its particles
  bool        nonlocal_active_ = false; // the nonlocal average runs after the stress update (set by src/mpm/nonlocal.cxx)
};

// The fields of the nonlocal average (src/mpm/nonlocal.cxx), registered by a model that returns a
// NonlocalLength > 0: kNonlocalSource holds per particle a weight (kg; 0: the particle neither
// contributes nor receives) and kNonlocalComponents values; kNonlocalAverage receives the weighted
// averages of the values over the neighbourhood, sum_q w_q a(x_p, x_q) s_q / sum_q w_q a(x_p, x_q).
constexpr int                kNonlocalComponents = 2;
inline constexpr const char *kNonlocalSource     = "nonlocal_source";  // bs 1 + kNonlocalComponents
inline constexpr const char *kNonlocalAverage    = "nonlocal_average"; // bs kNonlocalComponents

// Work of the stress over one step, 0.5 (sigma_n + sigma_{n+1}) : D V_mid dt, with the mid-step
// volume V_mid = V_{n+1} (1 - tr(D) dt / 2). Arrays are row-major 3x3.
inline PetscReal StressWork(const PetscReal sigma_old[], const PetscReal sigma_new[], const PetscReal L[], PetscReal volume, PetscReal dt)
{
  PetscReal work = 0;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) work += 0.5 * (sigma_old[3 * a + b] + sigma_new[3 * a + b]) * 0.5 * (L[3 * a + b] + L[3 * b + a]);
  const PetscReal trace_D = L[0] + L[4] + L[8];
  return work * volume * (1.0 - 0.5 * trace_D * dt) * dt;
}

using MaterialCreateFn = PetscErrorCode (*)(Material **);

// Registry of material models (PetscFunctionList keyed by snake_case model names).
PetscErrorCode MaterialRegisterAll();
PetscErrorCode MaterialRegister(const char name[], MaterialCreateFn create);
PetscErrorCode MaterialCreate(MPI_Comm comm, const char name[], Material **material);
PetscErrorCode MaterialRegistryDestroy();

// Reads `-<prefix>_density` (required, > 0). Shared by every model.
PetscErrorCode MaterialReadDensity(PetscOptionItems *PetscOptionsObject, Material &m);

} // namespace burst
