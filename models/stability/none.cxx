// No stability check.
#include "../plasticity/families.hpp"

namespace burst {

class NoStability final : public StabilityCheck {
public:
  void           Evaluate(Chunk &) const override {}
  PetscErrorCode SetFromOptions(PetscOptionItems *, const MaterialConstants &) override { return PETSC_SUCCESS; }
  PetscErrorCode View(PetscViewer viewer) const override { return PetscViewerASCIIPrintf(viewer, "  stability: none\n"); }
};

PetscErrorCode NoStabilityCreate(SubModel **model) { return CreateSubModel<NoStability>(model); }

} // namespace burst
