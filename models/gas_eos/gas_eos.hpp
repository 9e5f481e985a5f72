// Equations of state of the ICE materials (gases, liquids, dense phases): pointwise kernels.
//
// Every model gives P(rho, T) with its two partial derivatives; everything the ICE step needs
// follows from them thermodynamically (ice.md 1.3, 4), so a new model is one class:
//   isentropic sound speed   c^2 = (dP/drho)_T + T (dP/dT)_rho^2 / (rho^2 c_v)
//   thermal expansivity      alpha = (dP/dT)_rho / (rho (dP/drho)_T)
//   energy of compression    c_v dT = -T (dP/dT)_rho dv   (ICE evolves M c_v T; for an ideal gas
//                            T (dP/dT)_rho = p, Uintah's -p dV; for a stiffened gas p + p_inf)
//   specific internal energy e(rho, T) = c_v T + e_cold(rho): every model here is linear in T,
//                            P = T f(rho) + g(rho), so (de/dv)_T = T (dP/dT)_rho - P = -g and
//                            e_cold = integral of g(rho)/rho^2 drho (ColdEnergy; 0 for an ideal gas)
// rho is the material ("micro") density in kg/m^3, T in K, P in Pa; c_v in J/(kg K) is constant.
//
// Adding a model: one file models/gas_eos/<name>.cxx with a class derived from GasEOS and a create
// function, and one line in models/gas_eos/registry.cxx.
#pragma once
#include "../petsc_compat.hpp"
#include <petscviewer.h>
#include <string>

namespace burst {

struct GasEOSPoint {
  PetscReal pressure; // Pa
  PetscReal dp_drho;  // (dP/drho)_T, m^2/s^2
  PetscReal dp_dT;    // (dP/dT)_rho, Pa/K
};

class GasEOS {
public:
  virtual ~GasEOS() = default;
  // Reads the model's parameters under the material's prefix (-<name>_gamma, ...); c_v too.
  virtual PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const char material[]) = 0;
  // Prints every parameter with its unit.
  virtual PetscErrorCode View(PetscViewer viewer) const = 0;
  // P(rho, T) and its partial derivatives.
  virtual GasEOSPoint Evaluate(PetscReal rho, PetscReal T) const = 0;
  // The inverse: the density at pressure p and temperature T (p > 0). Models without a closed form
  // use a safeguarded Newton-bisection; returns a negative value if no density gives p.
  virtual PetscReal Density(PetscReal p, PetscReal T) const = 0;
  // Density(p, T) and (dP/drho)_T there, for the equilibration's Newton: a model whose inverse gives
  // the slope for less than Evaluate costs overrides it.
  virtual PetscReal DensityAndSlope(PetscReal p, PetscReal T, PetscReal *dp_drho) const
  {
    const PetscReal rho = Density(p, T);
    *dp_drho            = rho > 0 ? Evaluate(rho, T).dp_drho : 0;
    return rho;
  }
  // The temperature at density rho and pressure p (initial conditions given as rho, u, p);
  // models without a thermal part return the reference temperature they were given.
  virtual PetscReal Temperature(PetscReal rho, PetscReal p) const = 0;

  // The cold (temperature-independent) part of the specific internal energy, e - c_v T, J/kg: the
  // energy that the total-energy form conserves is rho (c_v T + e_cold(rho) + |u|^2/2).
  virtual PetscReal ColdEnergy(PetscReal) const { return 0; }
  // Whether ColdEnergy is not identically zero (the ICE step skips its bookkeeping otherwise).
  virtual bool HasColdEnergy() const { return false; }
  // The density at pressure p > 0 and specific internal energy e (J/kg), with T = (e - e_cold)/c_v >= 0
  // (the ICE equilibration at fixed energy); negative if none. The default is Newton on
  // P(rho, T(rho)) - p from `guess`, safeguarded by bisection, with (dP/drho)_e =
  // (dP/drho)_T - (dP/dT)_rho (P - T dP/dT)/(rho^2 c_v); models with a closed form override it.
  virtual PetscReal DensityAtEnergy(PetscReal p, PetscReal e, PetscReal guess) const;
  // (dP/drho) at fixed e, m^2/s^2
  PetscReal DpDrhoAtEnergy(PetscReal rho, PetscReal T) const
  {
    const GasEOSPoint s = Evaluate(rho, T);
    return s.dp_drho - s.dp_dT * (s.pressure - T * s.dp_dT) / (rho * rho * cv);
  }

  PetscReal cv = 716; // specific heat at constant volume, J/(kg K)

  // Derived quantities (see the header comment), the same for every model.
  PetscReal SoundSpeed2(PetscReal rho, PetscReal T) const
  {
    const GasEOSPoint s = Evaluate(rho, T);
    return s.dp_drho + T * s.dp_dT * s.dp_dT / (rho * rho * cv);
  }
  PetscReal ThermalExpansivity(PetscReal rho, PetscReal T) const
  {
    const GasEOSPoint s = Evaluate(rho, T);
    return s.dp_dT / (rho * s.dp_drho);
  }
  // e(rho, T), J/kg
  PetscReal   InternalEnergy(PetscReal rho, PetscReal T) const { return cv * T + ColdEnergy(rho); }
  std::string name_; // registered model name
};

using GasEOSCreateFn = PetscErrorCode (*)(GasEOS **);

// The registry (models/gas_eos/registry.cxx): ideal_gas, stiffened_gas, jwl, murnaghan.
PetscErrorCode GasEOSList(PetscFunctionList *list);
// Reads -<material>_eos_type (an unknown name stops with the list of registered names), creates the
// model and reads its parameters.
PetscErrorCode GasEOSCreate(MPI_Comm comm, const char material[], GasEOS **eos);
PetscErrorCode GasEOSRegistryDestroy();

} // namespace burst
