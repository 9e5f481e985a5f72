// Linear hypoelastic material with the Jaumann objective rate, sigma_dot - W sigma + sigma W = C : D,
// integrated with the Hughes-Winget rotation (IJNME 15 (1980) 1862):
//   sigma_{n+1} = Q sigma_n Q^T + dt [ lambda tr(D) I + 2 mu D ],  Q = (I - W dt/2)^{-1} (I + W dt/2),
// D = sym(L), W = skew(L). Q is exactly orthogonal, so a pure spin rotates the stress without
// changing its invariants, and the update is second-order in the spin. The co-rotational
// (Green-Naghdi) update of the metal models is in models/plasticity/.
#include "elastic_parameters.hpp"
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

  // Written out on plain arrays (the stress stays exactly symmetric): the general Eigen form with a
  // 3x3 inverse took about 620 instructions per point, a quarter of the 2-D elastic step.
  PetscErrorCode UpdateStress(const MaterialPointFields &f, PetscInt id, PetscReal dt) override
  {
    const PetscReal lambda = elastic.lame_lambda, mu = elastic.shear_modulus;
    const PetscReal modulus = lambda + 2 * mu;
    for (PetscInt p = 0; p < f.n; ++p) {
      if (f.material[p] != id) continue;
      const PetscReal *L     = f.L + 9 * p;
      PetscReal       *sigma = f.stress + 9 * p;
      if (L[2] == 0 && L[5] == 0 && L[6] == 0 && L[7] == 0 && sigma[2] == 0 && sigma[5] == 0) {
        UpdatePlane(L, sigma, f, p, dt);
        continue;
      }
      // Cayley form of Q for the skew A = W dt/2 with axial vector w (A x = w x x):
      // (I - A)^{-1} (I + A) = I + 2 (A + A^2) / (1 + |w|^2), exact since A^3 = -|w|^2 A,
      // with A^2 = w w^T - |w|^2 I
      const PetscReal w[3] = {0.25 * dt * (L[7] - L[5]), 0.25 * dt * (L[2] - L[6]), 0.25 * dt * (L[3] - L[1])};
      const PetscReal w2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2], c = 2 / (1 + w2);
      PetscReal       Q[9];
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) Q[3 * a + b] = c * w[a] * w[b] + (a == b ? 1 - c * w2 : 0);
      Q[1] -= c * w[2], Q[3] += c * w[2], Q[2] += c * w[1], Q[6] -= c * w[1], Q[5] -= c * w[0], Q[7] += c * w[0];
      PetscReal sigma_old[9], T[9];
      for (int i = 0; i < 9; ++i) sigma_old[i] = sigma[i];
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) T[3 * a + b] = Q[3 * a] * sigma_old[b] + Q[3 * a + 1] * sigma_old[3 + b] + Q[3 * a + 2] * sigma_old[6 + b];
      const PetscReal trace_D = L[0] + L[4] + L[8];
      for (int a = 0; a < 3; ++a)
        for (int b = a; b < 3; ++b) {
          const PetscReal rotated = T[3 * a] * Q[3 * b] + T[3 * a + 1] * Q[3 * b + 1] + T[3 * a + 2] * Q[3 * b + 2];
          const PetscReal D_ab    = 0.5 * (L[3 * a + b] + L[3 * b + a]);
          sigma[3 * a + b]        = rotated + dt * ((a == b ? lambda * trace_D : 0) + 2 * mu * D_ab);
          sigma[3 * b + a]        = sigma[3 * a + b];
        }
      f.internal_energy[p] += StressWork(sigma_old, sigma, L, f.volume[p], dt);
      f.wave_speed[p] = std::sqrt(modulus * f.volume[p] / f.mass[p]); // current density m/V
    }
    return PETSC_SUCCESS;
  }

  // The same update for a point without out-of-plane shear (2-D plane strain: L and sigma have
  // no xz, yz entries, so the spin is about z): the expressions above with their zero terms left
  // out, in the same order (the same bits), about a third of the work.
  void UpdatePlane(const PetscReal *L, PetscReal *sigma, const MaterialPointFields &f, PetscInt p, PetscReal dt) const
  {
    const PetscReal lambda = elastic.lame_lambda, mu = elastic.shear_modulus;
    const PetscReal w = 0.25 * dt * (L[3] - L[1]), w2 = w * w, c = 2 / (1 + w2);
    const PetscReal q00 = 1 - c * w2, q01 = -(c * w), q10 = c * w, q22 = c * w * w + (1 - c * w2);
    const PetscReal s00 = sigma[0], s01 = sigma[1], s10 = sigma[3], s11 = sigma[4], s22 = sigma[8];
    const PetscReal t00 = q00 * s00 + q01 * s10, t01 = q00 * s01 + q01 * s11, t10 = q10 * s00 + q00 * s10, t11 = q10 * s01 + q00 * s11;
    const PetscReal trace_D = L[0] + L[4];
    const PetscReal d01     = 0.5 * (L[1] + L[3]);
    sigma[0]                = t00 * q00 + t01 * q01 + dt * (lambda * trace_D + 2 * mu * L[0]);
    sigma[1]                = t00 * q10 + t01 * q00 + dt * (2 * mu * d01);
    sigma[4]                = t10 * q10 + t11 * q00 + dt * (lambda * trace_D + 2 * mu * L[4]);
    sigma[8]                = (q22 * s22) * q22 + dt * (lambda * trace_D);
    sigma[3]                = sigma[1];
    // StressWork with the zero terms left out
    const PetscReal work = 0.5 * (s00 + sigma[0]) * 0.5 * (L[0] + L[0]) + 0.5 * (s01 + sigma[1]) * 0.5 * (L[1] + L[3]) + 0.5 * (s10 + sigma[3]) * 0.5 * (L[3] + L[1]) + 0.5 * (s11 + sigma[4]) * 0.5 * (L[4] + L[4]);
    f.internal_energy[p] += work * f.volume[p] * (1.0 - 0.5 * trace_D * dt) * dt;
    f.wave_speed[p] = std::sqrt((lambda + 2 * mu) * f.volume[p] / f.mass[p]);
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
