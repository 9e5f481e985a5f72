// Specific heat of copper, J/(kg K), formula and constants of Uintah's CopperCp model
// (github.com/Uintah/Uintah, src/CCA/Components/MPM/Materials/ConstitutiveModel/PlasticityModels/CopperCp.cc):
//   T <  270 K: Cp = 4.16e-5 T^3 - 0.027 T^2 + 6.21 T - 142.6
//   T >= 270 K: Cp = 0.1009 T + 358.4
// (the branches meet within 1 J/(kg K) at 270 K: 384.6 vs 385.6). The cubic turns negative near 25 K,
// so it is evaluated at max(T, 40 K) (65 J/(kg K), close to measured copper there); no parameters.
#include "../plasticity/families.hpp"

namespace burst {

class CopperSpecificHeat final : public SpecificHeatModel {
public:
  void Evaluate(Chunk &c) const override
  {
    for (int k = 0; k < c.n; ++k) {
      const PetscReal T = c.temperature[k];
      if (T >= 270) c.specific_heat[k] = 0.1009 * T + 358.4;
      else {
        const PetscReal t  = T > 40 ? T : 40;
        c.specific_heat[k] = ((4.16e-5 * t - 0.027) * t + 6.21) * t - 142.6;
      }
    }
  }
  PetscErrorCode SetFromOptions(PetscOptionItems *, const MaterialConstants &) override { return PETSC_SUCCESS; }
  PetscErrorCode View(PetscViewer viewer) const override { return PetscViewerASCIIPrintf(viewer, "  specific heat: copper (Uintah CopperCp: cubic below 270 K, 0.1009 T + 358.4 above) J/(kg K)\n"); }
};

PetscErrorCode CopperSpecificHeatCreate(SubModel **model) { return CreateSubModel<CopperSpecificHeat>(model); }

} // namespace burst
