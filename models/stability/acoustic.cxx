// Loss of hyperbolicity by a full search over band normals (paper eq. 24; Rudnicki & Rice 1975,
// Rice 1976), type `acoustic`: a plastic point is flagged (bit 2) when det R(n) <= 0 for some unit
// band normal n. This is the reference for the fast `becker` check (models.md pitfall 5, NOTES eq. 24).
//
// Localization tensor. A band with normal n and velocity-gradient jump [L] = g (x) n is possible when
// the rate of equilibrium n_i [N_dot_ij] = 0 (N = nominal stress, current configuration as
// reference) has a non-zero g. With the constitutive law sigma^o = C^ep : D for an objective
// co-rotational rate taken as the Jaumann rate (sigma_dot = sigma^o + W sigma - sigma W) and
// N_dot = sigma_dot + (tr L) sigma - L sigma, the terms (tr L) sigma and L sigma cancel across the
// band and R_jk g_k = 0 with
//   R_jk = n_i C^ep_ijkl n_l + 1/2 [ (sigma n)_j n_k - sigma_jk - n_j (sigma n)_k + (n.sigma.n) delta_jk ].
// The first term is the acoustic tensor A(n); the bracket holds Rudnicki & Rice's stress terms. They
// are O(sigma/mu) and unchanged by a superposed pressure (only the deviator s enters), and the
// antisymmetric part does not change the sign analysis (det(S + K) = det S + k.S k for a 3x3 skew K).
// -MAT_stability_stress_terms false drops them (R = A, the classical acoustic tensor).
// The extracted eq. 24, R_ij = M_ijkl n_k n_l + M_ilkj n_k n_l - sigma_ik n_j n_k, is garbled: the
// Uintah source it comes from (BeckerCheck.h) has M_ikjl n_k n_l + M_ilkj n_k n_l - sigma_ik n_j n_k,
// i.e. 2 A - (sigma n)(x)n, whose stress term is neither Rudnicki & Rice's nor pressure independent.
// We use the derived form above; Green-Naghdi and Jaumann spins differ by a term that enters only the
// O(sigma/mu) stress terms, and the Jaumann spin is the one the jump analysis can express locally.
//
// Tangent: the von Mises continuum tangent C^ep = C - beta N(x)N, beta = 6 mu^2/(3 mu + H), N = s/|s|,
// with H = EffectiveHardening (tangent.hpp: strain hardening plus adiabatic thermal softening).
// In the principal frame of s everything is diagonal, so with m = N n (componentwise):
//   R/mu = (1 + 1/2 n.s^.n) I + (lambda/mu + 1) n(x)n - (beta/mu) m(x)m - 1/2 diag(s^)
//          + antisymmetric part 1/2 (s^_j - s^_k) n_j n_k,          s^ = s/mu, lambda = K - 2 mu/3.
// det R is even in every component of n (reflections n_i -> -n_i conjugate R by a diagonal sign
// matrix), so one octant of the sphere (n_i >= 0) is searched.
//
// Search: both spherical angles of the octant, phi (from axis 3) and theta (about it), on a coarse grid
// of -MAT_stability_acoustic_grid intervals per 90 degrees (1 + g (g + 1) normals; the default g = 8
// gives 73 normals 11.25 degrees apart, edges included, which are the principal planes). From the
// -MAT_stability_acoustic_starts best grid normals more than 1.5 grid steps apart, a local
// minimization (Newton steps on the tangent plane with finite-difference gradient and Hessian, see
// Refine) runs until its step is below -MAT_stability_acoustic_tolerance radians. Any det <= 0 met
// on the way flags the point at once. Measured (tests/unit/test_stability.cxx): with the defaults
// (8, 2, 1e-5) about 140 determinant evaluations and 1.5-2 us per stable plastic point (one start
// halves that), and critical hardening moduli within 1e-8 mu of the Rudnicki-Rice closed form and of
// Becker's quadratic; grid 2 with tolerance 0.05 rad flags up to 1e-3 mu late. The search can only
// miss a band (it returns an upper bound of min det), never invent one.
// Points with plastic = 0 are never flagged; 3 mu + H <= 0 (no return branch) is flagged.
#include "../plasticity/families.hpp"
#include "tangent.hpp"
#include <cmath>
#include <string>
#include <vector>

namespace burst {

namespace {
constexpr int kMaxGrid    = 45; // 2 degrees
constexpr int kMaxNormals = 1 + kMaxGrid * (kMaxGrid + 1);

// The state of one point in the principal frame (everything divided by mu), as the coefficients of
// det R in x = n*n (componentwise): R_jj = 1 + h (n.s^.n - s^_j) + c_jj x_j and, for j != k,
// R_jk = n_j n_k c_jk with c_jk = L - b N_j N_k + h (s^_j - s^_k), L = lambda/mu + 1, b = beta/mu,
// h = 1/2 with stress terms and 0 without. Then
//   det R = e0 e1 e2 - e0 x1 x2 p12 - e1 x0 x2 p02 - e2 x0 x1 p01 + x0 x1 x2 t,
// e_j = R_jj, p_jk = c_jk c_kj, t = c01 c12 c20 + c02 c21 c10: a cubic polynomial in x.
struct LocalizationPoint {
  PetscReal hs[3]; // h s^_j
  PetscReal cd[3]; // c_jj = L - b N_j^2
  PetscReal p01, p02, p12, t;

  LocalizationPoint(PetscReal L, PetscReal b, const PetscReal N[3], const PetscReal s[3], PetscReal h)
  {
    PetscReal c[3][3];
    for (int j = 0; j < 3; ++j) {
      hs[j] = h * s[j];
      for (int k = 0; k < 3; ++k) c[j][k] = L - b * N[j] * N[k] + h * (s[j] - s[k]);
      cd[j] = c[j][j];
    }
    p01 = c[0][1] * c[1][0];
    p02 = c[0][2] * c[2][0];
    p12 = c[1][2] * c[2][1];
    t   = c[0][1] * c[1][2] * c[2][0] + c[0][2] * c[2][1] * c[1][0];
  }
};

// det(R(n)/mu) for a unit normal n given in the principal frame.
inline PetscReal LocalizationDet(const LocalizationPoint &p, const PetscReal n[3])
{
  const PetscReal x0 = n[0] * n[0], x1 = n[1] * n[1], x2 = n[2] * n[2];
  const PetscReal nsn = p.hs[0] * x0 + p.hs[1] * x1 + p.hs[2] * x2;
  const PetscReal e0 = 1 + nsn - p.hs[0] + p.cd[0] * x0, e1 = 1 + nsn - p.hs[1] + p.cd[1] * x1, e2 = 1 + nsn - p.hs[2] + p.cd[2] * x2;
  return e0 * (e1 * e2 - x1 * x2 * p.p12) - e1 * x0 * x2 * p.p02 - e2 * x0 * x1 * p.p01 + x0 * x1 * x2 * p.t;
}
} // namespace

class AcousticCheck final : public StabilityCheck {
public:
  PetscInt  grid = 8, starts = 2;
  PetscReal tolerance    = 1e-5; // rad
  PetscBool stress_terms = PETSC_TRUE;

  void Evaluate(Chunk &c) const override
  {
    PetscReal value[kMaxNormals];
    for (int k = 0; k < c.n; ++k) {
      if (!c.plastic[k]) continue;
      const PetscReal mu = c.shear_modulus[k], H = EffectiveHardening(c, k);
      PetscReal       ev[3];
      PrincipalDeviator(c.deviator[k], ev);
      const PetscReal norm = std::sqrt(ev[0] * ev[0] + ev[1] * ev[1] + ev[2] * ev[2]);
      if (norm <= 0 || mu <= 0) continue;
      if (3 * mu + H <= 0) {
        c.unstable[k] |= 2;
        continue;
      }
      PetscReal N[3], sh[3];
      for (int i = 0; i < 3; ++i) {
        N[i]  = ev[i] / norm;
        sh[i] = ev[i] / mu;
      }
      const LocalizationPoint p((c.bulk_modulus[k] - 2 * mu / 3) / mu + 1, 6 / (3 + H / mu), N, sh, stress_terms ? 0.5 : 0.0);
      if (Unstable(p, value)) c.unstable[k] |= 2;
    }
  }

  // Coarse grid, then the local Newton search from the best grid normals that are far enough apart.
  bool Unstable(const LocalizationPoint &p, PetscReal value[]) const
  {
    const int nn = (int)normals_.size() / 3;
    for (int i = 0; i < nn; ++i)
      if ((value[i] = LocalizationDet(p, &normals_[3 * i])) <= 0) return true;
    const PetscReal step = 0.5 * PETSC_PI / grid, separation = std::cos(1.5 * step);
    int             chosen[8], n_chosen                      = 0;
    while (n_chosen < starts) {
      int best = -1;
      for (int i = 0; i < nn; ++i) {
        bool far = true;
        for (int c = 0; c < n_chosen && far; ++c) {
          const PetscReal *a = &normals_[3 * i], *b = &normals_[3 * chosen[c]];
          far = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] < separation;
        }
        if (far && (best < 0 || value[i] < value[best])) best = i;
      }
      if (best < 0) break;
      chosen[n_chosen++] = best;
      if (Refine(p, &normals_[3 * best], value[best], 0.5 * step) <= 0) return true;
    }
    return false;
  }

  // Local minimization of det R on the sphere from n0 (det f, finite-difference step h): Newton
  // steps in gnomonic tangent-plane coordinates (u, v) -> (n + u t1 + v t2)/|...|, with the gradient
  // and Hessian from 5 samples at distance h, a Levenberg shift where the Hessian is not positive
  // definite (flat rings of minima in axisymmetric states) and the step capped at 2h. The best of the
  // samples and the Newton point is kept; h follows the step length and is quartered when nothing
  // improves. det R is even in each component of n, so no folding into the octant is needed.
  // Returns the smallest det found; stops as soon as it is <= 0.
  PetscReal Refine(const LocalizationPoint &p, const PetscReal n0[3], PetscReal f, PetscReal h) const
  {
    PetscReal n[3] = {n0[0], n0[1], n0[2]};
    for (int it = 0; it < 60 && h >= tolerance; ++it) {
      // tangent basis: t1 = normalized (e x n) with e the axis least aligned with n, t2 = n x t1
      const int a       = (std::fabs(n[0]) <= std::fabs(n[1]) && std::fabs(n[0]) <= std::fabs(n[2])) ? 0 : (std::fabs(n[1]) <= std::fabs(n[2]) ? 1 : 2);
      PetscReal t1[3]   = {0, 0, 0}, t2[3];
      t1[(a + 1) % 3]   = -n[(a + 2) % 3];
      t1[(a + 2) % 3]   = n[(a + 1) % 3];
      const PetscReal l = 1 / std::sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
      for (int i = 0; i < 3; ++i) t1[i] *= l;
      t2[0]           = n[1] * t1[2] - n[2] * t1[1];
      t2[1]           = n[2] * t1[0] - n[0] * t1[2];
      t2[2]           = n[0] * t1[1] - n[1] * t1[0];
      PetscReal  best = f, best_n[3] = {n[0], n[1], n[2]};
      const auto sample = [&](PetscReal u, PetscReal v) {
        PetscReal m[3], mm = 0;
        for (int i = 0; i < 3; ++i) {
          m[i] = n[i] + u * t1[i] + v * t2[i];
          mm += m[i] * m[i];
        }
        mm = 1 / std::sqrt(mm);
        for (int i = 0; i < 3; ++i) m[i] *= mm;
        const PetscReal fm = LocalizationDet(p, m);
        if (fm < best) {
          best = fm;
          for (int i = 0; i < 3; ++i) best_n[i] = m[i];
        }
        return fm;
      };
      const PetscReal fpu = sample(h, 0), fmu = sample(-h, 0), fpv = sample(0, h), fmv = sample(0, -h), fpp = sample(h, h);
      const PetscReal gu = (fpu - fmu) / (2 * h), gv = (fpv - fmv) / (2 * h);
      PetscReal       huu = (fpu - 2 * f + fmu) / (h * h), hvv = (fpv - 2 * f + fmv) / (h * h);
      const PetscReal huv   = (fpp - fpu - fpv + f) / (h * h);
      const PetscReal lmin  = 0.5 * (huu + hvv) - std::sqrt(0.25 * (huu - hvv) * (huu - hvv) + huv * huv);
      const PetscReal lmax  = 0.5 * (huu + hvv) + std::sqrt(0.25 * (huu - hvv) * (huu - hvv) + huv * huv);
      const PetscReal floor = 1e-3 * std::fabs(lmax) + 1e-12;
      if (lmin < floor) {
        huu += floor - lmin;
        hvv += floor - lmin;
      }
      const PetscReal det = huu * hvv - huv * huv;
      PetscReal       du = -(hvv * gu - huv * gv) / det, dv = -(huu * gv - huv * gu) / det;
      const PetscReal step = std::sqrt(du * du + dv * dv);
      if (step > 2 * h) {
        du *= 2 * h / step;
        dv *= 2 * h / step;
      }
      const PetscReal fn = sample(du, dv), f_prev = f;
      if (best < f) {
        f = best;
        for (int i = 0; i < 3; ++i) n[i] = best_n[i];
      }
      if (f <= 0) break;
      if (!(f < f_prev)) h *= 0.25;                                          // nothing improved
      else if (fn == best) h = PetscMax(PetscMin(h, step), 0.5 * tolerance); // Newton step taken
    }
    return f;
  }

  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const MaterialConstants &) override
  {
    const std::string P = PetscOptionsObject->prefix;
    PetscFunctionBeginUser;
    PetscCall(PetscOptionsInt("-acoustic_grid", "Acoustic check: coarse-grid intervals per 90 degrees of each spherical angle (2..45)", "", grid, &grid, nullptr));
    PetscCall(PetscOptionsInt("-acoustic_starts", "Acoustic check: best separated grid normals refined by the local Newton search (1..8)", "", starts, &starts, nullptr));
    PetscCall(PetscOptionsReal("-acoustic_tolerance", "Acoustic check: final step of the local Newton search (rad)", "", tolerance, &tolerance, nullptr));
    PetscCall(PetscOptionsBool("-stress_terms", "Include the Rudnicki-Rice stress terms of the localization tensor (eq. 24)", "", stress_terms, &stress_terms, nullptr));
    PetscCheck(grid >= 2 && grid <= kMaxGrid, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "Option -%sacoustic_grid = %" PetscInt_FMT " is out of range: it must be in [2, %d]", P.c_str(), grid, kMaxGrid);
    PetscCheck(starts >= 1 && starts <= 8, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "Option -%sacoustic_starts = %" PetscInt_FMT " is out of range: it must be in [1, 8]", P.c_str(), starts);
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "acoustic_tolerance").c_str(), tolerance, 0, 0.1, PETSC_TRUE));
    normals_.clear();
    const PetscReal step = 0.5 * PETSC_PI / grid;
    normals_.insert(normals_.end(), {0.0, 0.0, 1.0}); // the pole phi = 0
    for (PetscInt i = 1; i <= grid; ++i)
      for (PetscInt j = 0; j <= grid; ++j) {
        const PetscReal phi = i * step, theta = j * step;
        normals_.insert(normals_.end(), {std::sin(phi) * std::cos(theta), std::sin(phi) * std::sin(theta), std::cos(phi)});
      }
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  PetscErrorCode View(PetscViewer viewer) const override
  {
    return PetscViewerASCIIPrintf(viewer, "  stability: acoustic (min over n of det R(n) <= 0; bit 2): grid %d intervals per 90 deg (%d normals), %d refined starts, angular tolerance %g rad, stress terms %s\n", (int)grid, (int)(normals_.size() / 3),
                                  (int)starts, (double)tolerance, stress_terms ? "on" : "off");
  }

private:
  std::vector<PetscReal> normals_; // the coarse grid of the octant, 3 per normal
};

PetscErrorCode AcousticCheckCreate(SubModel **model) { return CreateSubModel<AcousticCheck>(model); }

} // namespace burst
