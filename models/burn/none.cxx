// Burn model "none": the reactant never burns (the default of -<material>_burn_type).
#include "options.hpp"

namespace burst {

class NoBurn final : public BurnModel {
public:
  PetscErrorCode SetFromOptions(PetscOptionItems *, const char[]) override { return PETSC_SUCCESS; }
  PetscErrorCode View(PetscViewer viewer) const override { return PetscViewerASCIIPrintf(viewer, "  burn model: none (the reactant does not burn)\n"); }
  bool           Ignites(const BurnInput &) const override { return false; }
  PetscErrorCode MassFlux(const BurnInput &, PetscReal *mdot, PetscReal *T_surf) const override
  {
    *mdot   = 0;
    *T_surf = 0;
    return PETSC_SUCCESS;
  }
  PetscReal HeatOfReaction() const override { return 0; }
};

PetscErrorCode NoBurnCreate(BurnModel **model)
{
  *model = new NoBurn();
  return PETSC_SUCCESS;
}

} // namespace burst
