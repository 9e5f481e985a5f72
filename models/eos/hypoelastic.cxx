// Hypoelastic pressure (models.md 4.1): sigma_m <- sigma_m + K tr(D) dt with a constant bulk
// modulus K (-MAT_bulk_modulus), so p_{n+1} = -sigma_m,n - K tr(D) dt.
#include "../plasticity/families.hpp"

namespace burst {

class HypoelasticEOS final : public EquationOfState {
public:
  PetscReal bulk_modulus = 0;

  void Evaluate(Chunk &c) const override
  {
    for (int k = 0; k < c.n; ++k) {
      c.pressure[k]     = -c.mean_stress_old[k] - bulk_modulus * c.trace_D[k] * c.dt;
      c.bulk_modulus[k] = bulk_modulus;
      c.gruneisen[k]    = 0;
    }
  }
  PetscErrorCode SetFromOptions(PetscOptionItems *, const MaterialConstants &material) override
  {
    bulk_modulus = material.bulk_modulus;
    return PETSC_SUCCESS;
  }
  PetscErrorCode View(PetscViewer viewer) const override { return PetscViewerASCIIPrintf(viewer, "  equation of state: hypoelastic, bulk modulus %g Pa\n", (double)bulk_modulus); }
};

PetscErrorCode HypoelasticEOSCreate(SubModel **model) { return CreateSubModel<HypoelasticEOS>(model); }

} // namespace burst
