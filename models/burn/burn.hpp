// Burn models (reactant solid -> product gas): pointwise kernels evaluated per cell by the MPM-ICE
// coupling (ice.md 2.4, 3). A model decides whether a cell burns and, if it does, how fast:
//   mdot''  burn rate (mass flux through the burning surface), kg/(m^2 s)
//   dm      = mdot'' A dt, capped at M_s - M_tiny (the reactant left in the cell), kg
//   Q       heat released per unit burned mass, J/kg (the product gas receives dm (c_v,s T_s + Q))
// The caller gathers the cell's inputs (BurnInput: pressure, temperatures, nodal-mass contrast, the
// burning area from BurnSurfaceArea, ...) and books the sources (ice.md 2.4); nothing here touches a
// grid. SI units throughout.
//
// Registered models (-<material>_burn_type, material = the reactant, e.g. -pbx_burn_type):
//   none          never burns (the default)
//   simple_burn   ice.md 3.2, mdot'' = A_b (p/p_ref)^n, ignition by temperature and pressure thresholds
//   steady_burn   ice.md 3.3, Ward-Son-Brewster (WSB) steady deflagration, surface temperature solve
//
// Adding a model: one file models/burn/<name>.cxx with a class derived from BurnModel and a create
// function, and one line in models/burn/registry.cxx.
#pragma once
#include "../petsc_compat.hpp"
#include <petscviewer.h>
#include <string>

namespace burst {

// What a burn model may read about one cell (the caller fills what the models need).
struct BurnInput {
  PetscReal p      = 0;   // equilibration pressure, Pa (Steady Burn: the product-side pressure of the 3x3x3 search, ice.md 3.3)
  PetscReal T_s    = 300; // reactant (solid) temperature, K (Steady Burn: T0 of the 3x3x3 search)
  PetscReal T_g    = 300; // product gas temperature, K (read by no current model; kept for Unsteady Burn and diagnostics)
  PetscReal rho_s  = 0;   // reactant material density rho_s = 1/v_s, kg/m^3
  PetscReal area   = 0;   // burning surface area in the cell, m^2 (BurnSurfaceArea)
  PetscReal dt     = 0;   // time step, s
  PetscReal M_s    = 0;   // reactant mass in the cell, kg
  PetscReal M_tiny = 0;   // reactant mass that must stay in the cell (V rho_tiny), kg
  // Ignition criteria (ice.md 3.2, 3.3):
  PetscReal mass_contrast = 0; // (M_max - M_min)/M_max of the nodal reactant mass over the cell's nodes, in [0, 1]
  PetscReal T_hot         = 0; // K: Simple Burn: the hottest material in the cell with volume fraction > 0.2;
                               //    Steady Burn: the same over the 3x3x3 neighbours holding <= BoundaryParticles particles
  PetscReal T_gases = 0;       // K: the cell's gases taken together, if their volume fractions sum to > 0.2: their
                               //    mixture temperature sum(m c_v T)/sum(m c_v); else 0 (Simple Burn)
  PetscInt n_particles = 1;    // reactant particles in the cell (Steady Burn needs >= 1)
};

// What it returns; all zero when the cell does not burn.
struct BurnOutput {
  PetscBool burning = PETSC_FALSE;
  PetscReal dm      = 0; // burned mass this step, kg, 0 <= dm <= max(M_s - M_tiny, 0)
  PetscReal Q       = 0; // heat released per unit burned mass, J/kg
  PetscReal mdot    = 0; // burn rate mdot'', kg/(m^2 s) (the linear rate is mdot''/rho_s)
  PetscReal T_surf  = 0; // burning-surface temperature, K (Steady Burn; 0 for the others)
};

class BurnModel {
public:
  virtual ~BurnModel() = default;
  // Reads the model's parameters under the reactant's prefix (-<material>_burn_simple_A, ...).
  virtual PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const char material[]) = 0;
  // Prints every parameter with its unit.
  virtual PetscErrorCode View(PetscViewer viewer) const = 0;
  // Does the cell burn (the model's ignition criteria)?
  virtual bool Ignites(const BurnInput &in) const = 0;
  // The burn rate mdot'' (kg/(m^2 s)) of a burning cell and, for models that solve for it, the
  // surface temperature (K; else 0). Fails only if an iteration does not converge.
  virtual PetscErrorCode MassFlux(const BurnInput &in, PetscReal *mdot, PetscReal *T_surf) const = 0;
  // Heat released per unit burned mass, J/kg.
  virtual PetscReal HeatOfReaction() const = 0;
  // The temperature its ignition criterion asks of the reactant, K (0: none; src/phases.cxx).
  virtual PetscReal IgnitionTemperature() const { return 0; }

  // Ignites + MassFlux, dm = mdot'' A dt capped at M_s - M_tiny (never negative), Q.
  PetscErrorCode Evaluate(const BurnInput &in, BurnOutput *out) const;

  std::string name_; // registered model name
};

using BurnModelCreateFn = PetscErrorCode (*)(BurnModel **);

// The burning surface area in a cell (ice.md 3.1, HE/Common.cc computeSurfaceArea):
//   A = V (max_i |n_i|)^(1/3) / sum_i h_i |n_i|,  n = g/|g| the unit normal, i < dim,
// with g the gradient of the nodal reactant mass. Axis-aligned this is the face area (V/h_i);
// A = 0 if g = 0 (inside the solid or away from it). h in m, V in m^3 (in 2-D the cell's volume
// with its depth), A in m^2.
PetscReal BurnSurfaceArea(PetscInt dim, const PetscReal h[3], const PetscReal mass_gradient[3], PetscReal volume);

// The registry (models/burn/registry.cxx): none, simple_burn, steady_burn.
PetscErrorCode BurnModelList(PetscFunctionList *list);
// Reads -<material>_burn_type (default none; an unknown name stops with the list of registered
// names), creates the model and reads its parameters.
PetscErrorCode BurnModelCreate(MPI_Comm comm, const char material[], BurnModel **model);
PetscErrorCode BurnModelRegistryDestroy();

} // namespace burst
