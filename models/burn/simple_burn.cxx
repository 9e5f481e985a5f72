// Simple Burn (ice.md 3.2; Uintah HE/Simple_Burn.cc): a pressure-dependent burn rate behind
// threshold ignition.
//   burns if  c_min < (M_max - M_min)/M_max < 1   (the cell holds the reactant's surface)
//        and  T_hot > T_th                        (hottest material with volume fraction > 0.2; the
//                                                  gases count together, -burn_simple_gases_together)
//        and  p > p_th
//   mdot'' = A_b (p/p_ref)^n  kg/(m^2 s),  Q = enthalpy of reaction (J/kg).
// Defaults are Uintah's guni2dRT PBX 9501 values (ice.md 3.2); T_th 450 K is also the ignition
// temperature of PBX 9501 in the seed paper ("reacts at temperatures of 450 K and above").
// With rho 1840 the linear rate mdot''/rho is 4.1 cm/s at 1 atm and 146 cm/s at 10 MPa, far faster
// than measured HMX deflagration (Steady Burn: 0.034 cm/s at 1 atm): a demonstration rate.
// The gases together: Uintah releases the products in the burning cell itself, where they soon fill
// a fifth of it; burst releases them on the surface's gas side (src/coupling/burn.cxx), into air that
// they then share with. Counted one gas at a time, a burning cell whose products and air each hold
// less than a fifth at 1000 K goes out once the solids cool below T_th (the 3-D fire, doc/fire.md).
// Options (prefix -<material>_): -burn_simple_A, -burn_simple_p_ref, -burn_simple_n, -burn_simple_Q,
// -burn_simple_T_th, -burn_simple_p_th, -burn_simple_surface_contrast, -burn_simple_gases_together.
#include "options.hpp"
#include <cmath>

namespace burst {

class SimpleBurn final : public BurnModel {
public:
  PetscReal A_b            = 75.3;       // kg/(m^2 s), rate at p = p_ref
  PetscReal p_ref          = 101325;     // Pa
  PetscReal n              = 0.778;      // pressure exponent (-)
  PetscReal Q              = 2.0e6;      // J/kg
  PetscReal T_th           = 450;        // K
  PetscReal p_th           = 5e4;        // Pa
  PetscReal contrast       = 0.4;        // lower bound of (M_max - M_min)/M_max (-)
  PetscBool gases_together = PETSC_TRUE; // the cell's gases as one material in the T_hot test

  bool Ignites(const BurnInput &in) const override
  {
    const PetscReal T_hot = gases_together ? PetscMax(in.T_hot, in.T_gases) : in.T_hot;
    return in.mass_contrast > contrast && in.mass_contrast < 1 && T_hot > T_th && in.p > p_th;
  }
  PetscErrorCode MassFlux(const BurnInput &in, PetscReal *mdot, PetscReal *T_surf) const override
  {
    *mdot   = in.p > 0 ? A_b * std::pow(in.p / p_ref, n) : 0;
    *T_surf = 0;
    return PETSC_SUCCESS;
  }
  PetscReal HeatOfReaction() const override { return Q; }
  PetscReal IgnitionTemperature() const override { return T_th; }

  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const char[]) override
  {
    PetscFunctionBeginUser;
    PetscCall(BurnOptionsReal(PetscOptionsObject, "-burn_simple_A", "Simple Burn: burn rate A_b at p = p_ref (kg/(m^2 s)), > 0", &A_b, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(BurnOptionsReal(PetscOptionsObject, "-burn_simple_p_ref", "Simple Burn: reference pressure p_ref of the rate law (Pa), > 0", &p_ref, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(BurnOptionsReal(PetscOptionsObject, "-burn_simple_n", "Simple Burn: pressure exponent n of mdot'' = A_b (p/p_ref)^n (-), in [0, 3]", &n, 0, 3, PETSC_FALSE));
    PetscCall(BurnOptionsReal(PetscOptionsObject, "-burn_simple_Q", "Simple Burn: heat released per unit burned mass Q (J/kg), >= 0", &Q, 0, PETSC_MAX_REAL, PETSC_FALSE));
    PetscCall(BurnOptionsReal(PetscOptionsObject, "-burn_simple_T_th", "Simple Burn: ignition temperature threshold T_th (K), > 0", &T_th, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(BurnOptionsReal(PetscOptionsObject, "-burn_simple_p_th", "Simple Burn: ignition pressure threshold p_th (Pa), >= 0", &p_th, 0, PETSC_MAX_REAL, PETSC_FALSE));
    PetscCall(BurnOptionsReal(PetscOptionsObject, "-burn_simple_surface_contrast", "Simple Burn: a cell holds the surface if this < (M_max - M_min)/M_max < 1 over its nodes (-), in [0, 1)", &contrast, 0, 1, PETSC_FALSE, PETSC_TRUE));
    PetscCall(PetscOptionsBool("-burn_simple_gases_together", "Simple Burn: the T_hot test counts the cell's gases as one material (summed volume fraction, mixture temperature); false: each gas alone", "", gases_together, &gases_together, nullptr));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscErrorCode View(PetscViewer viewer) const override
  {
    return PetscViewerASCIIPrintf(viewer, "  burn model: simple_burn mdot'' = %g kg/(m^2 s) (p/%g Pa)^%g, Q %g J/kg; ignites if T > %g K, p > %g Pa, %g < (M_max-M_min)/M_max < 1%s\n", (double)A_b, (double)p_ref, (double)n, (double)Q, (double)T_th,
                                  (double)p_th, (double)contrast, gases_together ? "; the gases count together" : "");
  }
};

PetscErrorCode SimpleBurnCreate(BurnModel **model)
{
  *model = new SimpleBurn();
  return PETSC_SUCCESS;
}

} // namespace burst
