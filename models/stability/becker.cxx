// Becker's simplification of the loss-of-hyperbolicity check (paper eq. 24; Becker 2002, Int. J.
// Solids Struct. 39, 3555), type `becker`: the band normal is restricted to the plane of the largest
// and smallest principal stresses, n = cos(theta) e1 + sin(theta) e3, where det R = 0 becomes a
// quadratic in tan^2(theta). Sets bit 2. The full search over normals is `acoustic` (acoustic.cxx,
// which also derives R and the choice of its stress terms).
//
// In the principal frame of s (e1, e2, e3 for s1 >= s2 >= s3) the von Mises tangent C^ep = C - beta N(x)N,
// beta = 6 mu^2/(3 mu + H), N = s/|s|, has
//   M1111 = lambda + 2 mu - beta N1^2,  M3333 = lambda + 2 mu - beta N3^2,  M1133 = M3311 = lambda - beta N1 N3,
//   M1313 = M1212 = M2323 = mu  (N has no off-diagonal components there),
// and with the Rudnicki-Rice stress terms (Delta = (s1 - s3)/2, c = cos theta, s = sin theta)
//   R11 = M1111 c^2 + (mu - Delta) s^2,   R33 = (mu + Delta) c^2 + M3333 s^2,
//   R13 = (M1133 + mu + Delta) c s,       R31 = (M1133 + mu - Delta) c s,
//   R22 = mu + 1/2 (s1 c^2 + s3 s^2 - s2),  R12 = R21 = R23 = R32 = 0,
// so det R = R22 (R11 R33 - R13 R31) and R11 R33 - R13 R31 = c^4 P(t), t = tan^2 theta,
//   P(t) = a t^2 + b t + c0,  a = (mu - Delta) M3333,  b = M1111 M3333 - M1133^2 - 2 mu M1133,
//   c0 = (mu + Delta) M1111   (Delta drops out of b).
// (-MAT_stability_stress_terms false sets Delta = 0 and the stress part of R22 to 0.)
//
// Decision rule: some theta in the plane has det R <= 0 exactly when P(t) <= 0 for some t in [0, inf]
// (t = inf is theta = 90 degrees, where the sign is that of a) or R22 <= 0. So the point is flagged when
//   c0 <= 0, or a <= 0, or (b < 0 and b^2 >= 4 a c0), or mu + (s3 - s2)/2 <= 0 (R22 at theta = 90 deg).
// For a, c0 > 0 the third condition is the reference's rule (Uintah BeckerCheck.cc): both roots t real
// and positive, i.e. all four roots in tan theta real. Checked against that source, the reference
// differs in two ways that this file does not copy: (i) when a c0 < 0 the roots t have opposite signs,
// P changes sign on t > 0 and a band exists, but the reference reports "two real roots" as stable
// (for uniaxial stress and nu = 0.3 this is every H below 4 mu^2/(lambda + 2 mu) - 3 mu = -1.86 mu);
// (ii) it reads M1111, M3333, ... from the tangent in the laboratory frame while taking s1, s3 from
// the eigenvalues, which is only right when the principal axes are the laboratory axes. Here the
// principal values come from the Lode-angle closed form and the moduli are built in that frame, so
// the check is frame invariant. It never needs the eigenvectors.
//
// When the plane is exact: without stress terms det R = mu^2 (lambda + 2 mu) (1 - beta f(x)), with
// x_i = n_i^2 on the simplex and f = sum N_i^2 x_i / mu - (1/mu - 1/(lambda + 2 mu)) (sum N_i x_i)^2
// concave; its stationarity condition is a quadratic in N_i, met by at most two distinct principal
// values, so the critical normal lies in a principal plane, and (Rudnicki & Rice 1975) in the
// sigma_1 - sigma_3 plane. The unit tests find the same with the stress terms: for the von Mises
// tangent this check and the full search agree to the search tolerance; they differ only where the
// search is inexact, and in the cases the reference's rule gets wrong. Cost: one closed-form
// eigenvalue problem and a few flops per plastic point.
#include "../plasticity/families.hpp"
#include "tangent.hpp"
#include <cmath>

namespace burst {

class BeckerCheck final : public StabilityCheck {
public:
  PetscBool stress_terms = PETSC_TRUE;

  void Evaluate(Chunk &c) const override
  {
    for (int k = 0; k < c.n; ++k) {
      if (!c.plastic[k]) continue;
      const PetscReal mu = c.shear_modulus[k], H = EffectiveHardening(c, k);
      PetscReal       ev[3];
      PrincipalDeviator(c.deviator[k], ev);
      const PetscReal norm2 = ev[0] * ev[0] + ev[1] * ev[1] + ev[2] * ev[2];
      if (norm2 <= 0 || mu <= 0) continue;
      if (3 * mu + H <= 0) {
        c.unstable[k] |= 2;
        continue;
      }
      // everything divided by mu
      const PetscReal lam = (c.bulk_modulus[k] - 2 * mu / 3) / mu, beta = 6 / (3 + H / mu) / norm2;
      const PetscReal M11 = lam + 2 - beta * ev[0] * ev[0], M33 = lam + 2 - beta * ev[2] * ev[2], M13 = lam - beta * ev[0] * ev[2];
      const PetscReal Delta = stress_terms ? 0.5 * (ev[0] - ev[2]) / mu : 0.0;
      const PetscReal a = (1 - Delta) * M33, b = M11 * M33 - M13 * M13 - 2 * M13, c0 = (1 + Delta) * M11;
      const bool      antiplane = stress_terms && 1 + 0.5 * (ev[2] - ev[1]) / mu <= 0;
      if (c0 <= 0 || a <= 0 || (b < 0 && b * b >= 4 * a * c0) || antiplane) c.unstable[k] |= 2;
    }
  }

  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const MaterialConstants &) override
  {
    PetscFunctionBeginUser;
    PetscCall(PetscOptionsBool("-stress_terms", "Include the Rudnicki-Rice stress terms of the localization tensor (eq. 24)", "", stress_terms, &stress_terms, nullptr));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscErrorCode View(PetscViewer viewer) const override
  {
    return PetscViewerASCIIPrintf(viewer, "  stability: becker (det R <= 0 for a normal in the sigma_1-sigma_3 plane, quadratic in tan^2; bit 2): stress terms %s\n", stress_terms ? "on" : "off");
  }
};

PetscErrorCode BeckerCheckCreate(SubModel **model) { return CreateSubModel<BeckerCheck>(model); }

} // namespace burst
