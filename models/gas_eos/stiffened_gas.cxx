// Stiffened gas (liquids; Saurel & Abgrall 1999, Le Metayer, Massoni & Saurel 2004), T-form:
//   P = (gamma - 1) rho c_v T - p_inf      (equivalently P = (gamma - 1) rho e - gamma p_inf with
//                                           e = c_v T + p_inf/rho)
//   (dP/drho)_T = (gamma - 1) c_v T,  (dP/dT)_rho = (gamma - 1) c_v rho
//   c^2 = gamma (gamma - 1) c_v T = gamma (P + p_inf)/rho
//   e = c_v T + p_inf/rho (the cold energy p_inf v)
// p_inf = 0 is the ideal gas. Options (prefix -<material>_): -gamma (default 1.4, > 1),
// -cv (J/(kg K), default 716, > 0), -p_inf (Pa, default 0, >= 0).
#include "options.hpp"

namespace burst {

class StiffenedGas final : public GasEOS {
public:
  PetscReal gamma = 1.4, p_inf = 0;

  GasEOSPoint Evaluate(PetscReal rho, PetscReal T) const override
  {
    const PetscReal R = (gamma - 1) * cv;
    return {R * rho * T - p_inf, R * T, R * rho};
  }
  PetscReal Density(PetscReal p, PetscReal T) const override
  {
    const PetscReal rho = (p + p_inf) / ((gamma - 1) * cv * T);
    return (rho > 0 && rho < PETSC_MAX_REAL) ? rho : -1;
  }
  PetscReal Temperature(PetscReal rho, PetscReal p) const override { return (p + p_inf) / ((gamma - 1) * cv * rho); }
  PetscReal ColdEnergy(PetscReal rho) const override { return p_inf / rho; }
  // P = (gamma - 1) rho e - gamma p_inf; T >= 0 holds for every p > -p_inf
  PetscReal DensityAtEnergy(PetscReal p, PetscReal e, PetscReal) const override
  {
    const PetscReal rho = (p + gamma * p_inf) / ((gamma - 1) * e);
    return (rho > 0 && rho < PETSC_MAX_REAL) ? rho : -1;
  }
  bool HasColdEnergy() const override { return p_inf != 0; }

  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const char[]) override
  {
    PetscFunctionBeginUser;
    PetscCall(GasEOSOptionsReal(PetscOptionsObject, "-gamma", "Stiffened gas: ratio of specific heats gamma (-), > 1 and <= 100 (fits of liquids up to ~7)", &gamma, 1, 100, PETSC_TRUE));
    PetscCall(GasEOSOptionsReal(PetscOptionsObject, "-cv", "Stiffened gas: specific heat at constant volume c_v (J/(kg K)), > 0", &cv, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(GasEOSOptionsReal(PetscOptionsObject, "-p_inf", "Stiffened gas: stiffening pressure p_inf (Pa), >= 0", &p_inf, 0, PETSC_MAX_REAL, PETSC_FALSE));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscErrorCode View(PetscViewer viewer) const override { return PetscViewerASCIIPrintf(viewer, "  gas equation of state: stiffened_gas gamma %g, c_v %g J/(kg K), p_inf %g Pa\n", (double)gamma, (double)cv, (double)p_inf); }
};

PetscErrorCode StiffenedGasCreate(GasEOS **eos)
{
  *eos = new StiffenedGas();
  return PETSC_SUCCESS;
}

} // namespace burst
