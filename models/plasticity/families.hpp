// The sub-model families of the hypoelastic-plastic update and what each reads and writes in a
// Chunk. Each family has a registry, filled in models/FAMILY/registry.cxx: adding a model is one
// file in models/FAMILY/ and one line there.
#pragma once
#include "submodel.hpp"
#include <initializer_list>

namespace burst {

// A sub-model evaluated once per chunk: a flat loop over c.n points.
class ChunkModel : public SubModel {
public:
  virtual void Evaluate(Chunk &c) const = 0;
};

// Equation of state: reads density, specific_energy, temperature, trace_D, mean_stress_old, dt;
// writes pressure (t_{n+1}, Pa), bulk_modulus (tangent rho c^2, Pa) and gruneisen (Gamma rho0/rho,
// for the isentropic temperature change; 0 if none).
class EquationOfState : public ChunkModel {};
// Shear modulus: reads temperature, pressure, density, melt_temperature; writes shear_modulus.
class ShearModulusModel : public ChunkModel {
public:
  // Reference shear modulus mu0 that scales flow stresses (MTS: mu/mu0), Pa.
  virtual PetscReal ReferenceShearModulus() const = 0;
};
// Melt temperature: reads density; writes melt_temperature.
class MeltModel : public ChunkModel {};
// Specific heat: reads temperature; writes specific_heat.
class SpecificHeatModel : public ChunkModel {};
// Damage: reads delta_plastic_strain, plastic_strain_rate, triaxiality, temperature,
// melt_temperature; updates damage and writes fracture_strain (TEPLA-F's eps_p^f).
class DamageModel : public ChunkModel {};
// Stability: reads deviator, D_hat, shear_modulus, bulk_modulus, hardening, plastic, pressure;
// sets bits of unstable (1: Drucker, 2: loss of hyperbolicity).
class StabilityCheck : public ChunkModel {};

// One family's table entry: registered name and create function.
struct SubModelEntry {
  const char *name;
  PetscErrorCode (*create)(SubModel **);
};
// Returns the registry in *storage, filling it from `models` on first use; SubModelRegistriesDestroy
// frees every registry filled this way.
PetscErrorCode SubModelRegistryGet(PetscFunctionList *storage, std::initializer_list<SubModelEntry> models, PetscFunctionList *list);

// Registries, one per family (models/FAMILY/registry.cxx, created on first use).
PetscErrorCode EquationOfStateList(PetscFunctionList *list);
PetscErrorCode ShearModulusList(PetscFunctionList *list);
PetscErrorCode MeltList(PetscFunctionList *list);
PetscErrorCode SpecificHeatList(PetscFunctionList *list);
PetscErrorCode FlowStressList(PetscFunctionList *list);
PetscErrorCode DamageList(PetscFunctionList *list);
PetscErrorCode StabilityList(PetscFunctionList *list);
PetscErrorCode SubModelRegistriesDestroy();

// Registers a create function `Create<Class>` for a family: one line per model in registry.cxx.
template <class Class>
PetscErrorCode CreateSubModel(SubModel **model)
{
  *model = new Class();
  return PETSC_SUCCESS;
}

} // namespace burst
