// Ideal gas: P = (gamma - 1) c_v rho T.
//   (dP/drho)_T = (gamma - 1) c_v T,  (dP/dT)_rho = (gamma - 1) c_v rho
//   c^2 = gamma (gamma - 1) c_v T = gamma P / rho,  alpha = 1/T
// Options (prefix -<material>_): -gamma (default 1.4, > 1), -cv (J/(kg K), default 716, > 0).
#include "options.hpp"

namespace burst {

class IdealGas final : public GasEOS {
public:
  PetscReal gamma = 1.4;

  GasEOSPoint Evaluate(PetscReal rho, PetscReal T) const override
  {
    const PetscReal R = (gamma - 1) * cv; // specific gas constant, J/(kg K)
    return {R * rho * T, R * T, R * rho};
  }
  PetscReal Density(PetscReal p, PetscReal T) const override
  {
    const PetscReal rho = p / ((gamma - 1) * cv * T);
    return (rho > 0 && rho < PETSC_MAX_REAL) ? rho : -1;
  }
  PetscReal Temperature(PetscReal rho, PetscReal p) const override { return p / ((gamma - 1) * cv * rho); }

  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const char[]) override
  {
    PetscFunctionBeginUser;
    PetscCall(GasEOSOptionsReal(PetscOptionsObject, "-gamma", "Ideal gas: ratio of specific heats gamma = c_p/c_v (-), > 1 and <= 100 (gases 1-5/3)", &gamma, 1, 100, PETSC_TRUE));
    PetscCall(GasEOSOptionsReal(PetscOptionsObject, "-cv", "Ideal gas: specific heat at constant volume c_v (J/(kg K)), > 0", &cv, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscErrorCode View(PetscViewer viewer) const override
  {
    return PetscViewerASCIIPrintf(viewer, "  gas equation of state: ideal_gas gamma %g, c_v %g J/(kg K) (gas constant (gamma-1) c_v = %g J/(kg K))\n", (double)gamma, (double)cv, (double)((gamma - 1) * cv));
  }
};

PetscErrorCode IdealGasCreate(GasEOS **eos)
{
  *eos = new IdealGas();
  return PETSC_SUCCESS;
}

} // namespace burst
