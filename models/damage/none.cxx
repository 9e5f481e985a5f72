// No damage: D is kept as initialised and the fracture strain of TEPLA-F is infinite.
#include "../plasticity/families.hpp"

namespace burst {

class NoDamage final : public DamageModel {
public:
  void Evaluate(Chunk &c) const override
  {
    for (int k = 0; k < c.n; ++k) c.fracture_strain[k] = PETSC_INFINITY;
  }
  PetscErrorCode SetFromOptions(PetscOptionItems *, const MaterialConstants &) override { return PETSC_SUCCESS; }
  PetscErrorCode View(PetscViewer viewer) const override { return PetscViewerASCIIPrintf(viewer, "  damage: none\n"); }
};

PetscErrorCode NoDamageCreate(SubModel **model) { return CreateSubModel<NoDamage>(model); }

} // namespace burst
