// Rotation of the polar decomposition F = R U, by Higham's scaled Newton iteration
// X <- (g X + X^{-T}/g)/2, g = (|X^{-1}|_F / |X|_F)^{1/2}, which converges quadratically from X = F
// (typically 5-7 iterations for metal-forming stretches). Used for the Green-Naghdi (co-rotational)
// frame of the stress update.
#pragma once
#include "../elastic/tensor.hpp"
#include <cmath>

namespace burst {

inline Mat3 PolarRotation(const Mat3 &F)
{
  Mat3 X = F;
  for (int it = 0; it < 30; ++it) {
    const Mat3      Xinv_T = X.inverse().transpose();
    const PetscReal g      = std::sqrt(std::sqrt(Xinv_T.squaredNorm() / X.squaredNorm()));
    const Mat3      next   = 0.5 * (g * X + Xinv_T / g);
    const PetscReal change = (next - X).norm();
    X                      = next;
    if (change < 1e-14) break;
  }
  return X;
}

} // namespace burst

namespace burst {

// The same rotation, warm-started from a nearby rotation R0 (the previous step's R of the particle):
// Newton on the condition that R^T F be symmetric, R = R_k Q(w) with the Cayley rotation
// Q(w) = I + 2/(1 + |w/2|^2) ([w/2] + [w/2]^2) (orthogonal to round-off at any w). With A = R_k^T F,
// S = sym A and a the axial vector of skew A, the linearisation gives (tr S I - S) w = 2 a (exact
// for symmetric A, quadratically convergent). A step's rotation increment is small (|w| ~ |W| dt),
// so two or three iterations reach round-off, against five to seven of the scaled Newton from F.
// Falls back to PolarRotation(F) when tr S I - S is not positive definite (U not positive definite
// near R0: far from the polar solution) or the iteration does not settle.
inline Mat3 PolarRotationFrom(const Mat3 &F, const Mat3 &R0)
{
  Mat3 R = R0;
  for (int it = 0; it < 8; ++it) {
    const Mat3      A = R.transpose() * F;
    const PetscReal a[3] = {0.5 * (A(2, 1) - A(1, 2)), 0.5 * (A(0, 2) - A(2, 0)), 0.5 * (A(1, 0) - A(0, 1))};
    // M = tr(S) I - S, S = sym A (symmetric); solve M w = 2 a by Cramer's rule
    const PetscReal trS = A(0, 0) + A(1, 1) + A(2, 2);
    const PetscReal m00 = trS - A(0, 0), m11 = trS - A(1, 1), m22 = trS - A(2, 2);
    const PetscReal m01 = -0.5 * (A(0, 1) + A(1, 0)), m02 = -0.5 * (A(0, 2) + A(2, 0)), m12 = -0.5 * (A(1, 2) + A(2, 1));
    const PetscReal c00 = m11 * m22 - m12 * m12, c01 = m02 * m12 - m01 * m22, c02 = m01 * m12 - m02 * m11;
    const PetscReal det = m00 * c00 + m01 * c01 + m02 * c02;
    if (!(m00 > 0 && m00 * m11 - m01 * m01 > 0 && det > 0)) break; // not positive definite: fall back
    const PetscReal c11 = m00 * m22 - m02 * m02, c12 = m01 * m02 - m00 * m12, c22 = m00 * m11 - m01 * m01;
    const PetscReal inv = 2 / det;
    const PetscReal w[3] = {inv * (c00 * a[0] + c01 * a[1] + c02 * a[2]), inv * (c01 * a[0] + c11 * a[1] + c12 * a[2]), inv * (c02 * a[0] + c12 * a[1] + c22 * a[2])};
    const PetscReal ww = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    if (!(ww < 0.25)) break; // more than about 0.5 rad from the start: not a warm start
    const PetscReal h[3] = {0.5 * w[0], 0.5 * w[1], 0.5 * w[2]}, s = 2 / (1 + 0.25 * ww);
    Mat3            H;
    H << 0, -h[2], h[1], h[2], 0, -h[0], -h[1], h[0], 0;
    const Mat3 Q = Mat3::Identity() + s * (H + H * H);
    R            = R * Q;
    if (ww < 1e-18) return R; // |w| < 1e-9: the next correction, of order |w|^2, is round-off
  }
  return PolarRotation(F);
}

} // namespace burst
