// Drucker's stability postulate (paper eq. 23; Drucker 1959), type `drucker`: a plastic point is
// unstable when sigma_dot : D^p <= 0, evaluated as the reference does, as the second-order work
// (C^ep : D) : D <= 0 with D = D_hat, the rate of deformation in the co-rotated frame. Sets bit 1.
//
// The tangent, derived consistently with the radial return of models/yield/von_mises.hpp:
//   q = sqrt(3/2 s:s), N = s/|s| (unit deviator), D^p = (3/2) eps_p_dot s/q = sqrt(3/2) eps_p_dot N,
//   s_dot = 2 mu (D' - D^p) (co-rotational), p_dot = -K tr D (K = EOS tangent, bulk_modulus).
//   Consistency q_dot = H eps_p_dot with q_dot = sqrt(3/2) N : s_dot = sqrt(6) mu N:D - 3 mu eps_p_dot:
//     eps_p_dot = sqrt(6) mu (N:D) / (3 mu + H)            (the Newton slope 3 mu + H of the return)
//   sigma_dot = C:D - beta (N:D) N,  beta = 6 mu^2 / (3 mu + H) = (2 mu)^2 / (2 mu + (2/3) H),
//   C = K I(x)I + 2 mu (I4_sym - 1/3 I(x)I), i.e. C^ep = C - beta N(x)N (models.md 4.11).
// H is the slope of sigma_f along the plastic path (EffectiveHardening, tangent.hpp): the strain
// hardening d sigma_f/d eps_p plus, if the material is adiabatic, the thermal softening through the
// plastic heating of eq. 18 (models.md pitfall 8): H = hardening + thermal_softening chi sigma_f/(rho Cp).
// The rate term of the return's Newton slope is left out (it grows without bound as dt shrinks).
// With a = N:D and D'_perp = D' - a N (the part of D' not coaxial with s):
//   w = (C^ep:D):D = K (tr D)^2 + 2 mu |D'_perp|^2 + 2 mu H / (3 mu + H) a^2.
// Written this way w has no cancellation, and its sign gives the threshold in closed form:
//   unstable  <=>  H <= H_D = -3 mu X / (1 + X),  X = (K (tr D)^2 + 2 mu |D'_perp|^2) / (2 mu a^2),
// so for an isochoric rate coaxial with s (X = 0) the switch is at H = 0, and any volumetric or
// non-coaxial part of D asks for more softening. (sigma_dot : D^p itself has the sign of H alone:
// sigma_dot : D^p = 6 mu^2 H a^2 / (3 mu + H)^2; the second-order work is the weaker condition.)
// If 3 mu + H <= 0 the return has no solution branch (snap-back) and the point is flagged.
// Points with plastic = 0, zero D or a zero deviator are not checked.
#include "../plasticity/families.hpp"
#include "tangent.hpp"
#include <cmath>

namespace burst {

class DruckerCheck final : public StabilityCheck {
public:
  void Evaluate(Chunk &c) const override
  {
    for (int k = 0; k < c.n; ++k) {
      if (!c.plastic[k]) continue;
      const PetscReal  mu = c.shear_modulus[k], K = c.bulk_modulus[k], H = EffectiveHardening(c, k);
      const PetscReal *S = c.deviator[k], *Dh = c.D_hat[k];
      PetscReal        s[9], D[9];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          s[3 * i + j] = 0.5 * (S[3 * i + j] + S[3 * j + i]);
          D[3 * i + j] = 0.5 * (Dh[3 * i + j] + Dh[3 * j + i]);
        }
      const PetscReal trs = (s[0] + s[4] + s[8]) / 3, trD = D[0] + D[4] + D[8];
      PetscReal       ss = 0, DD = 0;
      for (int i = 0; i < 3; ++i) {
        s[4 * i] -= trs;
        D[4 * i] -= trD / 3;
      }
      for (int a = 0; a < 9; ++a) {
        ss += s[a] * s[a];
        DD += D[a] * D[a];
      }
      if (ss <= 0 || mu <= 0 || (DD <= 0 && trD == 0)) continue;
      if (3 * mu + H <= 0) {
        c.unstable[k] |= 1;
        continue;
      }
      const PetscReal inv = 1 / std::sqrt(ss);
      PetscReal       a = 0, perp = 0;
      for (int b = 0; b < 9; ++b) a += s[b] * inv * D[b];
      for (int b = 0; b < 9; ++b) {
        const PetscReal d = D[b] - a * s[b] * inv;
        perp += d * d;
      }
      const PetscReal w = K * trD * trD + 2 * mu * perp + 2 * mu * H / (3 * mu + H) * a * a;
      if (w <= 0) c.unstable[k] |= 1;
    }
  }
  PetscErrorCode SetFromOptions(PetscOptionItems *, const MaterialConstants &) override { return PETSC_SUCCESS; }
  PetscErrorCode View(PetscViewer viewer) const override { return PetscViewerASCIIPrintf(viewer, "  stability: drucker ((C^ep:D):D <= 0, von Mises tangent with adiabatic thermal softening; bit 1)\n"); }
};

PetscErrorCode DruckerCheckCreate(SubModel **model) { return CreateSubModel<DruckerCheck>(model); }

} // namespace burst
