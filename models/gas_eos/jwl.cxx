// JWL detonation products, T-form (Uintah's JWL; PBX 9501 defaults from Uintah's DDT.ups):
//   P = A exp(-R1 rho0/rho) + B exp(-R2 rho0/rho) + omega rho c_v T
//   (dP/drho)_T = (A R1 exp(-R1 rho0/rho) + B R2 exp(-R2 rho0/rho)) rho0/rho^2 + omega c_v T
//   (dP/dT)_rho = omega rho c_v
// Isentropes: c_v dT = T omega rho c_v drho/rho^2, so T rho^(-omega) is constant along them.
// Cold energy (zero as rho -> 0): e_cold = A/(R1 rho0) exp(-R1 rho0/rho) + B/(R2 rho0) exp(-R2 rho0/rho),
// so e = c_v T + e_cold gives the usual energy form P = A (1 - omega rho/(R1 rho0)) exp(-R1 rho0/rho)
// + B (1 - omega rho/(R2 rho0)) exp(-R2 rho0/rho) + omega rho e.
// With A, B >= 0, R1, R2, omega > 0, P increases strictly with rho from 0 (rho -> 0) to infinity, so
// Density(p, T) has exactly one root for p > 0; it is found by Newton's method safeguarded by
// bisection on a bracket [lo, hi] with P(lo) <= p <= P(hi): lo = 0, hi from the thermal-only density
// p/(omega c_v T) (an upper bound when A, B >= 0), doubled until P(hi) >= p.
// Options (prefix -<material>_): -jwl_A, -jwl_B (Pa, >= 0), -jwl_R1, -jwl_R2, -jwl_omega (-, > 0),
// -jwl_rho0 (kg/m^3, > 0), -cv (J/(kg K), > 0).
#include "options.hpp"
#include <cmath>

namespace burst {

class JWL final : public GasEOS {
public:
  PetscReal A = 1668.9e9, B = 59.69e9, R1 = 5.9, R2 = 2.1, omega = 0.45, rho0 = 1832;
  JWL() { cv = 594.96; }

  GasEOSPoint Evaluate(PetscReal rho, PetscReal T) const override
  {
    const PetscReal wcv = omega * cv;
    if (!(rho > 0)) return {0, wcv * T, 0};
    const PetscReal inv = 1 / rho, a = R1rho0_ * inv, b = R2rho0_ * inv;
    const PetscReal e1 = A * std::exp(-a), e2 = B * std::exp(-b);
    return {e1 + e2 + wcv * rho * T, (e1 * a + e2 * b) * inv + wcv * T, wcv * rho};
  }

  PetscReal Density(PetscReal p, PetscReal T) const override
  {
    if (!(p > 0) || !(T >= 0) || !std::isfinite(p) || !std::isfinite(T)) return -1;
    // upper end of the bracket: the thermal-only density, else (T = 0) rho0; doubled until P >= p
    PetscReal lo = 0, hi = T > 0 ? p / (omega * cv * T) : rho0;
    if (!(hi > 0) || !std::isfinite(hi)) hi = rho0;
    GasEOSPoint s = Evaluate(hi, T);
    for (int k = 0; s.pressure < p; ++k) {
      if (k == 2000 || !std::isfinite(hi)) return -1;
      lo = hi;
      hi *= 2;
      s = Evaluate(hi, T);
    }
    if (s.pressure == p) return hi;
    // safeguarded Newton from hi: a step leaving (lo, hi) is replaced by bisection
    PetscReal x = hi;
    for (int it = 0; it < 300; ++it) {
      const PetscReal f = s.pressure - p;
      if (f == 0) return x;
      if (f < 0) lo = x;
      else hi = x;
      PetscReal xn = s.dp_drho > 0 ? x - f / s.dp_drho : 0.5 * (lo + hi);
      if (!(xn > lo && xn < hi)) xn = 0.5 * (lo + hi);
      if (std::fabs(xn - x) <= 1e-12 * xn || hi - lo <= 1e-12 * hi) return xn;
      x = xn;
      s = Evaluate(x, T);
    }
    return -1;
  }

  PetscReal ColdEnergy(PetscReal rho) const override
  {
    if (!(rho > 0)) return 0;
    return A / R1rho0_ * std::exp(-R1rho0_ / rho) + B / R2rho0_ * std::exp(-R2rho0_ / rho);
  }
  bool HasColdEnergy() const override { return A != 0 || B != 0; }

  // May be <= 0 if p lies at or below the cold curve A exp(-R1 rho0/rho) + B exp(-R2 rho0/rho).
  PetscReal Temperature(PetscReal rho, PetscReal p) const override
  {
    const PetscReal inv = 1 / rho;
    return (p - A * std::exp(-R1rho0_ * inv) - B * std::exp(-R2rho0_ * inv)) / (omega * cv * rho);
  }

  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const char[]) override
  {
    PetscFunctionBeginUser;
    PetscCall(GasEOSOptionsReal(PetscOptionsObject, "-jwl_A", "JWL: first pressure coefficient A (Pa), >= 0", &A, 0, PETSC_MAX_REAL, PETSC_FALSE));
    PetscCall(GasEOSOptionsReal(PetscOptionsObject, "-jwl_B", "JWL: second pressure coefficient B (Pa), >= 0", &B, 0, PETSC_MAX_REAL, PETSC_FALSE));
    PetscCall(GasEOSOptionsReal(PetscOptionsObject, "-jwl_R1", "JWL: first decay constant R1 (-), > 0", &R1, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(GasEOSOptionsReal(PetscOptionsObject, "-jwl_R2", "JWL: second decay constant R2 (-), > 0", &R2, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(GasEOSOptionsReal(PetscOptionsObject, "-jwl_omega", "JWL: Gruneisen coefficient omega (-), > 0", &omega, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(GasEOSOptionsReal(PetscOptionsObject, "-jwl_rho0", "JWL: reference (explosive) density rho0 (kg/m^3), > 0", &rho0, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(GasEOSOptionsReal(PetscOptionsObject, "-cv", "JWL: specific heat at constant volume c_v (J/(kg K)), > 0", &cv, 0, PETSC_MAX_REAL, PETSC_TRUE));
    R1rho0_ = R1 * rho0;
    R2rho0_ = R2 * rho0;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscErrorCode View(PetscViewer viewer) const override
  {
    PetscFunctionBeginUser;
    PetscCall(PetscViewerASCIIPrintf(viewer, "  gas equation of state: jwl A %g Pa, B %g Pa, R1 %g, R2 %g, omega %g,\n", (double)A, (double)B, (double)R1, (double)R2, (double)omega));
    PetscCall(PetscViewerASCIIPrintf(viewer, "    rho0 %g kg/m^3, c_v %g J/(kg K)\n", (double)rho0, (double)cv));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

private:
  PetscReal R1rho0_ = 5.9 * 1832, R2rho0_ = 2.1 * 1832; // kg/m^3
};

PetscErrorCode JWLCreate(GasEOS **eos)
{
  *eos = new JWL();
  return PETSC_SUCCESS;
}

} // namespace burst
