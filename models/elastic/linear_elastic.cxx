// Linear hypoelastic material with the Jaumann objective rate:
//   sigma_{n+1} = sigma_n + dt [ lambda tr(D) I + 2 mu D + W sigma_n - sigma_n W ],
// D = sym(L), W = skew(L). Small-strain linear elasticity for small rotations; the co-rotational
// (Green-Naghdi) update of the metal models lives in the metal-model layer.
#include "elastic_parameters.hpp"
#include "tensor.hpp"
#include <cmath>

namespace burst {

class LinearElastic final : public Material {
public:
  IsotropicElasticity elastic;

  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject) override { return elastic.SetFromOptions(PetscOptionsObject, *this); }

  PetscErrorCode UpdateStress(const MaterialPointFields &f, PetscInt id, PetscReal dt) override
  {
    const PetscReal lambda = elastic.lame_lambda, mu = elastic.shear_modulus;
    const PetscReal modulus = lambda + 2 * mu;
    const Mat3      I       = Mat3::Identity();
    for (PetscInt p = 0; p < f.n; ++p) {
      if (f.material[p] != id) continue;
      Mat3CMap        L(f.L + 9 * p);
      Mat3Map         sigma(f.stress + 9 * p);
      const Mat3      D = 0.5 * (L + L.transpose()), W = 0.5 * (L - L.transpose());
      const Mat3      sigma_old = sigma;
      sigma += dt * (lambda * D.trace() * I + 2 * mu * D + W * sigma_old - sigma_old * W);
      f.internal_energy[p] += StressWork(sigma_old.data(), sigma.data(), f.L + 9 * p, f.volume[p], dt);
      f.wave_speed[p] = std::sqrt(modulus * f.volume[p] / f.mass[p]); // current density m/V
    }
    return PETSC_SUCCESS;
  }

  PetscErrorCode ComputeWaveSpeed(const MaterialPointFields &f, PetscInt id) override
  {
    const PetscReal modulus = elastic.lame_lambda + 2 * elastic.shear_modulus;
    for (PetscInt p = 0; p < f.n; ++p)
      if (f.material[p] == id) f.wave_speed[p] = std::sqrt(modulus * f.volume[p] / f.mass[p]);
    return PETSC_SUCCESS;
  }

  PetscErrorCode View(PetscViewer viewer) const override
  {
    PetscFunctionBeginUser;
    PetscCall(PetscViewerASCIIPrintf(viewer, "Material %s: linear_elastic (hypoelastic, Jaumann rate)\n  density          %g kg/m^3\n", Name(), (double)density_));
    PetscCall(elastic.View(viewer));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
};

PetscErrorCode LinearElasticCreate(Material **m)
{
  *m = new LinearElastic();
  return PETSC_SUCCESS;
}

} // namespace burst
