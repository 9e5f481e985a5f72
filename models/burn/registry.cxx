// Registry of the burn models (one declaration and one registration line per model), the common
// Evaluate and the burning-surface area of ice.md 3.1.
#include "options.hpp"
#include <algorithm>
#include <cmath>
#include <memory>

namespace burst {

PetscErrorCode NoBurnCreate(BurnModel **);
PetscErrorCode SimpleBurnCreate(BurnModel **);
PetscErrorCode SteadyBurnCreate(BurnModel **);

static PetscFunctionList burn_list = nullptr;

PetscErrorCode BurnModelList(PetscFunctionList *list)
{
  PetscFunctionBeginUser;
  if (!burn_list) {
    PetscCall(PetscFunctionListAdd(&burn_list, "none", NoBurnCreate));
    PetscCall(PetscFunctionListAdd(&burn_list, "simple_burn", SimpleBurnCreate));
    PetscCall(PetscFunctionListAdd(&burn_list, "steady_burn", SteadyBurnCreate));
  }
  *list = burn_list;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BurnModelRegistryDestroy()
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&burn_list));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BurnModelCreate(MPI_Comm comm, const char material[], BurnModel **model)
{
  PetscFunctionList list = nullptr;
  PetscFunctionBeginUser;
  PetscCall(BurnModelList(&list));
  PetscCall(PointwiseModelCreate(comm, material, list, "burn", "none", "burn model", model));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BurnModel::Evaluate(const BurnInput &in, BurnOutput *out) const
{
  PetscFunctionBeginUser;
  *out = BurnOutput();
  if (!Ignites(in)) PetscFunctionReturn(PETSC_SUCCESS);
  PetscReal mdot = 0, T_surf = 0;
  PetscCall(MassFlux(in, &mdot, &T_surf));
  const PetscReal available = std::max(in.M_s - in.M_tiny, (PetscReal)0);
  out->burning              = PETSC_TRUE;
  out->mdot                 = mdot;
  out->T_surf               = T_surf;
  out->Q                    = HeatOfReaction();
  out->dm                   = std::min(std::max(mdot * in.area * in.dt, (PetscReal)0), available);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscReal BurnSurfaceArea(PetscInt dim, const PetscReal h[3], const PetscReal g[3], PetscReal volume)
{
  PetscReal norm2 = 0;
  for (PetscInt i = 0; i < dim; ++i) norm2 += g[i] * g[i];
  if (!(norm2 > 0)) return 0;
  const PetscReal norm = std::sqrt(norm2);
  PetscReal       nmax = 0, sum = 0;
  for (PetscInt i = 0; i < dim; ++i) {
    const PetscReal n = std::fabs(g[i]) / norm;
    nmax              = std::max(nmax, n);
    sum += h[i] * n;
  }
  return volume * std::cbrt(nmax) / sum;
}

} // namespace burst
