// Specific heat of HY-100 steel, paper eq. 19 (Goto et al., Metall. Mater. Trans. A 31A (2000) 1985):
//   Cp = 10^3 (0.09278 + 7.454e-4 T + 12404 / T^2)  J/(kg K), T in K.
// No parameters. T is floored at 1 K (the 1/T^2 term is unbounded at 0 K; the fit is meant for
// room temperature and above).
#include "../plasticity/families.hpp"

namespace burst {

class GotoSpecificHeat final : public SpecificHeatModel {
public:
  void Evaluate(Chunk &c) const override
  {
    for (int k = 0; k < c.n; ++k) {
      const PetscReal T  = c.temperature[k] > 1 ? c.temperature[k] : 1;
      c.specific_heat[k] = 1e3 * (0.09278 + 7.454e-4 * T + 12404.0 / (T * T));
    }
  }
  PetscErrorCode SetFromOptions(PetscOptionItems *, const MaterialConstants &) override { return PETSC_SUCCESS; }
  PetscErrorCode View(PetscViewer viewer) const override { return PetscViewerASCIIPrintf(viewer, "  specific heat: goto (eq. 19) Cp = 1e3 (0.09278 + 7.454e-4 T + 12404/T^2) J/(kg K)\n"); }
};

PetscErrorCode GotoSpecificHeatCreate(SubModel **model) { return CreateSubModel<GotoSpecificHeat>(model); }

} // namespace burst
