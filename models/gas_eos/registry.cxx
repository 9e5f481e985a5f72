// Registry of the ICE (gas) equations of state: one declaration and one registration line per model.
#include "options.hpp"
#include <cmath>
#include <memory>

namespace burst {

PetscErrorCode IdealGasCreate(GasEOS **);
PetscErrorCode StiffenedGasCreate(GasEOS **);
PetscErrorCode JWLCreate(GasEOS **);
PetscErrorCode MurnaghanCreate(GasEOS **);

// The density at fixed specific energy (gas_eos.hpp): a density whose temperature would be negative is
// too dense (the cold energy grows with compression), so the bracket [lo, hi] has P < p at lo and
// P >= p or T < 0 at hi.
PetscReal GasEOS::DensityAtEnergy(PetscReal p, PetscReal e, PetscReal guess) const
{
  if (!(p > 0) || !std::isfinite(p) || !std::isfinite(e)) return -1;
  // f(rho) = P(rho, T(rho)) - p, +1 marks T < 0
  auto residual = [&](PetscReal rho, PetscReal *slope) {
    const PetscReal T = (e - ColdEnergy(rho)) / cv;
    if (!(T >= 0)) return PetscReal(1);
    const GasEOSPoint s = Evaluate(rho, T);
    *slope              = s.dp_drho - s.dp_dT * (s.pressure - T * s.dp_dT) / (rho * rho * cv);
    return s.pressure - p;
  };
  PetscReal lo = 0, hi = guess > 0 && std::isfinite(guess) ? guess : 1, slope = 0;
  PetscReal f = residual(hi, &slope);
  for (int k = 0; f < 0; ++k) {
    if (k == 2000 || !std::isfinite(hi)) return -1;
    lo = hi;
    hi *= 2;
    f = residual(hi, &slope);
  }
  if (f == 0) return hi;
  PetscReal x = guess > lo && guess < hi ? guess : 0.5 * (lo + hi);
  for (int it = 0; it < 300; ++it) {
    PetscReal  fx    = residual(x, &slope);
    const bool dense = fx > 0 && (e - ColdEnergy(x)) < 0;
    if (fx == 0 && !dense) return x;
    if (fx < 0) lo = x;
    else hi = x;
    PetscReal xn = (!dense && slope > 0) ? x - fx / slope : 0.5 * (lo + hi);
    if (!(xn > lo && xn < hi)) xn = 0.5 * (lo + hi);
    if (std::fabs(xn - x) <= 1e-13 * xn || hi - lo <= 1e-14 * hi) {
      fx = residual(xn, &slope);
      return (e - ColdEnergy(xn)) >= 0 && std::fabs(fx) <= 1e-8 * p ? xn : -1;
    }
    x = xn;
  }
  return -1;
}

static PetscFunctionList gas_eos_list = nullptr;

PetscErrorCode GasEOSList(PetscFunctionList *list)
{
  PetscFunctionBeginUser;
  if (!gas_eos_list) {
    PetscCall(PetscFunctionListAdd(&gas_eos_list, "ideal_gas", IdealGasCreate));
    PetscCall(PetscFunctionListAdd(&gas_eos_list, "stiffened_gas", StiffenedGasCreate));
    PetscCall(PetscFunctionListAdd(&gas_eos_list, "jwl", JWLCreate));
    PetscCall(PetscFunctionListAdd(&gas_eos_list, "murnaghan", MurnaghanCreate));
  }
  *list = gas_eos_list;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GasEOSRegistryDestroy()
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&gas_eos_list));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GasEOSCreate(MPI_Comm comm, const char material[], GasEOS **eos)
{
  PetscFunctionList list = nullptr;
  PetscFunctionBeginUser;
  PetscCall(GasEOSList(&list));
  PetscCall(PointwiseModelCreate(comm, material, list, "eos", "ideal_gas", "equation of state", eos));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
