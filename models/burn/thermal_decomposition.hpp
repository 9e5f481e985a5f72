// Thermal decomposition (self-heating, cook-off) of a reactant element, per cell or per particle:
// one-step first-order Arrhenius kinetics with the heat released kept in the element,
//   d lambda/dt = Z (1 - lambda) exp(-T_a/T),            T_a = E/R
//   c dT/dt     = Q d lambda/dt + h (T_env - T)           (h = 0: adiabatic)
// lambda the reacted mass fraction (-), T (K), Z (1/s), Q (J/kg), c (J/(kg K)), h (W/(kg K)) a
// Newton heat-exchange coefficient per unit reactant mass (h_s A_s/m of the element) for cook-off
// by a hotter (or cooler) environment at T_env.
// Default parameters, PBX 9501 / HMX-like:
//   Z 5e19 1/s, T_a 2.652e4 K, Q 5.5e6 J/kg: the one-step HMX hot-spot fit that Uintah's ViscoSCRAM
//     material file carries (ice.md 5.2, "Hot-spot fields ... dH 5.5e6, Z 5e19, E/R 2.652e4");
//   c 996 J/(kg K): PBX 9501 c_p = c_v (ice.md 4, "PBX 9501 thermal").
// The system is stiff near runaway (the reaction time 1/(Z e^{-T_a/T}) falls from seconds at 500 K
// to nanoseconds at 1000 K), so it is integrated with SUNDIALS CVODE: BDF, Newton with a dense
// direct solver on the analytic 2x2 Jacobian, rtol 1e-10. One integrator is created once and
// re-initialised (CVodeReInit) for every use.
//
// Closed form for checks (Frank-Kamenetskii / Semenov high-activation-energy limit, adiabatic,
// lambda0 = 0): t_ad = c T0^2/(Q Z T_a) exp(T_a/T0) = c R T0^2/(Q Z E) exp(E/(R T0)). With
// eps = T0/T_a and B = Q T_a/(c T0^2) the exact adiabatic time to runaway is
//   t = t_ad (1 + 2 eps + 1/B + 6 eps^2 + 6 eps/B + 2/B^2 + ...)  (derived: with s = (T - T0) T_a/T0^2,
//   t/t_ad = int_0^{s_end} exp(-s + eps s^2/(1 + eps s))/(1 - s/B) ds).
#pragma once
#include "../petsc_compat.hpp"
#include <petscviewer.h>
#include <memory>

namespace burst {

struct ThermalDecompositionParameters {
  PetscReal Z     = 5e19;    // pre-exponential factor, 1/s
  PetscReal T_a   = 2.652e4; // activation temperature E/R, K
  PetscReal Q     = 5.5e6;   // heat of reaction, J/kg
  PetscReal c     = 996;     // specific heat, J/(kg K)
  PetscReal h     = 0;       // heat exchange with the environment per unit mass, W/(kg K) (0: adiabatic)
  PetscReal T_env = 300;     // environment temperature, K
  // Runaway (ignition) criteria of IgnitionDelay: T reaches T0 + runaway_rise, or dT/dt exceeds
  // runaway_rate (if > 0), whichever comes first.
  PetscReal runaway_rise = 500;   // K
  PetscReal runaway_rate = 0;     // K/s (0: off)
  PetscReal rtol         = 1e-10; // CVODE relative tolerance
};

class ThermalDecomposition {
public:
  ThermalDecomposition();
  ~ThermalDecomposition();
  ThermalDecomposition(const ThermalDecomposition &)            = delete;
  ThermalDecomposition &operator=(const ThermalDecomposition &) = delete;

  // Reads the parameters under the material's prefix: -<material>_decomposition_{Z,T_a,Q,c,h,T_env,
  // runaway_rise,runaway_rate,rtol}.
  PetscErrorCode SetFromOptions(MPI_Comm comm, const char material[]);
  PetscErrorCode View(PetscViewer viewer) const;

  // Right-hand side: d lambda/dt and dT/dt at (lambda, T).
  void Rates(PetscReal lambda, PetscReal T, PetscReal *dlambda, PetscReal *dT) const;

  // Advances one element by dt from (lambda, T) in place (no runaway detection).
  PetscErrorCode Advance(PetscReal dt, PetscReal *lambda, PetscReal *T);

  // Time from (lambda0, T0) at t = 0 until runaway (see the criteria above), located by CVODE's root
  // finding. If there is none by t_max: *ignited = PETSC_FALSE and *t_ign = t_max.
  PetscErrorCode IgnitionDelay(PetscReal T0, PetscReal lambda0, PetscReal t_max, PetscReal *t_ign, PetscBool *ignited, PetscReal *T_end = nullptr);

  // The closed-form adiabatic induction time t_ad = c T0^2/(Q Z T_a) exp(T_a/T0) (s).
  PetscReal AdiabaticInductionTime(PetscReal T0) const;

  // CVODE steps taken by the last Advance or IgnitionDelay.
  long last_steps() const { return last_steps_; }

  ThermalDecompositionParameters par;

  struct Impl; // the CVODE objects (opaque)

private:
  std::unique_ptr<Impl> impl_;
  long                  last_steps_ = 0;

  PetscErrorCode Start(PetscReal lambda, PetscReal T, int nroots);
};

} // namespace burst
