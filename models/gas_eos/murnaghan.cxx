// Murnaghan equation of state of a solid reactant treated as an ICE material (Uintah's Murnaghan;
// PBX 9501 defaults):
//   rho >= rho0: P = p0 + ((rho/rho0)^n - 1)/(n K),   (dP/drho)_T = (rho/rho0)^(n-1)/(K rho0)
//   rho <  rho0: P = p0 (rho/rho0)^(1/(K p0)),        (dP/drho)_T = (rho/rho0)^(1/(K p0)) / (K rho)
// (P and dP/drho are continuous at rho0: p0 and 1/(K rho0).) K is a compressibility (1/Pa). No
// thermal part: (dP/dT)_rho = 0, so c^2 = dP/drho and alpha = 0; Temperature() returns T0.
// Cold energy (all of the energy: c_v T does not change with compression), the integral of P/rho^2
// from rho0 (zero there):
//   rho >= rho0: e_cold = p0 (1/rho0 - 1/rho) + [(rho^(n-1)/rho0^n - 1/rho0)/(n-1) + 1/rho - 1/rho0]/(n K)
//   rho <  rho0: e_cold = (p0/rho0) ((rho/rho0)^(m-1) - 1)/(m-1),  m = 1/(K p0)
// Inverse: p >= p0: rho = rho0 (1 + n K (p - p0))^(1/n);  p < p0: rho = rho0 (p/p0)^(K p0).
// Options (prefix -<material>_): -murnaghan_n (-, > 0), -murnaghan_K (1/Pa, > 0),
// -murnaghan_rho0 (kg/m^3, > 0), -murnaghan_p0 (Pa, > 0), -murnaghan_T0 (K, > 0), -cv (J/(kg K), > 0).
#include "options.hpp"
#include <cmath>

namespace burst {

class Murnaghan final : public GasEOS {
public:
  PetscReal n = 7.4, K = 2.78e-11, rho0 = 1840, p0 = 101325, T0 = 300;
  Murnaghan()
  {
    cv = 996;
    Update();
  }

  // With d = (rho - rho0)/rho0 (exact subtraction) and L = log1p(d): (rho/rho0)^n - 1 = expm1(n L),
  // so P - p0 keeps full relative accuracy near rho0 (pow(rho/rho0, n) - 1 would cancel).
  GasEOSPoint Evaluate(PetscReal rho, PetscReal) const override
  {
    if (!(rho > 0)) return {0, 0, 0};
    const PetscReal d = (rho - rho0) * inv_rho0_, L = std::log1p(d);
    if (d >= 0) {
      const PetscReal xn1 = std::expm1(n * L); // (rho/rho0)^n - 1
      return {p0 + xn1 * inv_nK_, (xn1 + 1) / (1 + d) * inv_K_rho0_, 0};
    }
    const PetscReal q = std::exp(m_ * L); // (rho/rho0)^(1/(K p0))
    return {p0 * q, q / (K * rho), 0};
  }
  PetscReal Density(PetscReal p, PetscReal) const override
  {
    if (!(p > 0) || !std::isfinite(p)) return -1;
    if (p >= p0) return rho0 * std::exp(std::log1p(n * K * (p - p0)) / n);
    return rho0 * std::exp(K * p0 * std::log(p / p0));
  }
  PetscReal Temperature(PetscReal, PetscReal) const override { return T0; }
  PetscReal ColdEnergy(PetscReal rho) const override
  {
    if (!(rho > 0)) return 0;
    const PetscReal d = (rho - rho0) * inv_rho0_, L = std::log1p(d), inv_rho = 1 / rho;
    if (d >= 0) {
      // (rho^(n-1)/rho0^n - 1/rho0)/(n-1) = (expm1((n-1) L))/((n-1) rho0), without cancellation
      const PetscReal power = (n == 1) ? L * inv_rho0_ : std::expm1((n - 1) * L) / ((n - 1) * rho0);
      return p0 * (inv_rho0_ - inv_rho) + (power + inv_rho - inv_rho0_) * inv_nK_;
    }
    return p0 * inv_rho0_ * std::expm1((m_ - 1) * L) / (m_ - 1);
  }
  bool HasColdEnergy() const override { return true; }

  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const char[]) override
  {
    PetscFunctionBeginUser;
    PetscCall(GasEOSOptionsReal(PetscOptionsObject, "-murnaghan_n", "Murnaghan: pressure exponent n (-), > 0", &n, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(GasEOSOptionsReal(PetscOptionsObject, "-murnaghan_K", "Murnaghan: compressibility K (1/Pa), > 0", &K, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(GasEOSOptionsReal(PetscOptionsObject, "-murnaghan_rho0", "Murnaghan: reference density rho0 (kg/m^3), > 0", &rho0, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(GasEOSOptionsReal(PetscOptionsObject, "-murnaghan_p0", "Murnaghan: reference pressure p0 at rho0 (Pa), > 0", &p0, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(GasEOSOptionsReal(PetscOptionsObject, "-murnaghan_T0", "Murnaghan: reference temperature T0 returned as the temperature (K), > 0", &T0, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(GasEOSOptionsReal(PetscOptionsObject, "-cv", "Murnaghan: specific heat at constant volume c_v (J/(kg K)), > 0", &cv, 0, PETSC_MAX_REAL, PETSC_TRUE));
    Update();
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscErrorCode View(PetscViewer viewer) const override
  {
    PetscFunctionBeginUser;
    PetscCall(PetscViewerASCIIPrintf(viewer, "  gas equation of state: murnaghan n %g, K %g 1/Pa (bulk modulus 1/K = %g Pa), rho0 %g kg/m^3,\n", (double)n, (double)K, (double)(1 / K), (double)rho0));
    PetscCall(PetscViewerASCIIPrintf(viewer, "    p0 %g Pa, T0 %g K, c_v %g J/(kg K)\n", (double)p0, (double)T0, (double)cv));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

private:
  PetscReal inv_rho0_ = 0, inv_nK_ = 0, inv_K_rho0_ = 0, m_ = 0;
  void      Update()
  {
    inv_rho0_   = 1 / rho0;
    inv_nK_     = 1 / (n * K);
    inv_K_rho0_ = 1 / (K * rho0);
    m_          = 1 / (K * p0);
  }
};

PetscErrorCode MurnaghanCreate(GasEOS **eos)
{
  *eos = new Murnaghan();
  return PETSC_SUCCESS;
}

} // namespace burst
