// Compressible neo-Hookean material (Simo & Pister form, as in Wallstedt & Guilkey 2008 and
// Sulsky et al. 1994's disk problem):
//   sigma = (lambda ln J / J) I + (mu / J) (B - I),  B = F F^T,  J = det F,
//   W     = mu/2 (tr B - 3) - mu ln J + lambda/2 (ln J)^2   (per reference volume).
// Hyperelastic: the stress follows from F alone, so it is exactly objective.
#include "elastic_parameters.hpp"
#include "tensor.hpp"
#include <cmath>

namespace burst {

class NeoHookean final : public Material {
public:
  IsotropicElasticity elastic;

  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject) override
  {
    PetscFunctionBeginUser;
    PetscCall(elastic.SetFromOptions(PetscOptionsObject, *this));
    bulk_modulus_ = elastic.bulk_modulus;
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  // Longitudinal wave speed from the tangent moduli at J: lambda/J and (mu - lambda ln J)/J.
  inline PetscReal WaveSpeed(PetscReal J) const
  {
    const PetscReal lnJ = std::log(J), lambda = elastic.lame_lambda, mu = elastic.shear_modulus;
    const PetscReal modulus = (lambda + 2.0 * (mu - lambda * lnJ)) / J;
    return std::sqrt(std::fabs(modulus) * J / density_);
  }

  PetscErrorCode UpdateStress(const MaterialPointFields &f, PetscInt id, PetscReal dt) override
  {
    const PetscReal lambda = elastic.lame_lambda, mu = elastic.shear_modulus;
    const Mat3      I = Mat3::Identity();
    for (PetscInt p = 0; p < f.n; ++p) {
      if (f.material[p] != id) continue;
      Mat3CMap        F(f.F + 9 * p), L(f.L + 9 * p);
      Mat3Map         sigma(f.stress + 9 * p);
      const PetscReal J         = F.determinant();
      const Mat3      sigma_old = sigma;
      sigma                     = (lambda * std::log(J) / J) * I + (mu / J) * (F * F.transpose() - I);
      (void)L;
      f.internal_energy[p] += StressWork(sigma_old.data(), sigma.data(), f.L + 9 * p, f.volume[p], dt);
      f.wave_speed[p] = WaveSpeed(J);
    }
    return PETSC_SUCCESS;
  }

  PetscErrorCode ComputeWaveSpeed(const MaterialPointFields &f, PetscInt id) override
  {
    for (PetscInt p = 0; p < f.n; ++p)
      if (f.material[p] == id) f.wave_speed[p] = WaveSpeed(Mat3CMap(f.F + 9 * p).determinant());
    return PETSC_SUCCESS;
  }

  PetscErrorCode View(PetscViewer viewer) const override
  {
    PetscFunctionBeginUser;
    PetscCall(PetscViewerASCIIPrintf(viewer, "Material %s: neo_hookean (compressible, hyperelastic)\n  density          %g kg/m^3\n", Name(), (double)density_));
    PetscCall(elastic.View(viewer));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
};

PetscErrorCode NeoHookeanCreate(Material **m)
{
  *m = new NeoHookean();
  return PETSC_SUCCESS;
}

} // namespace burst
