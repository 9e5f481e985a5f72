// Linear hypoelastic material with the Jaumann objective rate, sigma_dot - W sigma + sigma W = C : D,
// integrated with the Hughes-Winget rotation (IJNME 15 (1980) 1862):
//   sigma_{n+1} = Q sigma_n Q^T + dt [ lambda tr(D) I + 2 mu D ],  Q = (I - W dt/2)^{-1} (I + W dt/2),
// D = sym(L), W = skew(L). Q is exactly orthogonal, so a pure spin rotates the stress without
// changing its invariants, and the update is second-order in the spin. The co-rotational
// (Green-Naghdi) update of the metal models is in models/plasticity/.
#include "elastic_parameters.hpp"
#include "tensor.hpp"
#include <cmath>

namespace burst {

class LinearElastic final : public Material {
public:
  IsotropicElasticity elastic;

  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject) override
  {
    PetscFunctionBeginUser;
    PetscCall(elastic.SetFromOptions(PetscOptionsObject, *this));
    bulk_modulus_ = elastic.bulk_modulus;
    PetscFunctionReturn(PETSC_SUCCESS);
  }

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
      const Mat3      Q         = (I - 0.5 * dt * W).inverse() * (I + 0.5 * dt * W);
      sigma                     = Q * sigma_old * Q.transpose() + dt * (lambda * D.trace() * I + 2 * mu * D);
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
