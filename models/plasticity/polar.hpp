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
// Returns false when tr S I - S is not positive definite (U not positive definite near R0: far from
// the polar solution) or the iteration does not settle; the caller then falls back to PolarRotation.
// Row-major arrays, written out in scalars: this runs once per particle and step (the Eigen
// products with their temporaries cost about twice as many instructions). R must not overlap R0.
inline bool PolarRotationWarm(const PetscReal *F, const PetscReal *__restrict R0, PetscReal *__restrict R)
{
  // R_k is R0, then one of two buffers in turn (no copies); the last product goes to R
  PetscReal        buffer[2][9];
  const PetscReal *Rk = R0;
  for (int it = 0; it < 8; ++it) {
    PetscReal A[9]; // R_k^T F
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) A[3 * i + j] = Rk[i] * F[j] + Rk[3 + i] * F[3 + j] + Rk[6 + i] * F[6 + j];
    const PetscReal a[3] = {0.5 * (A[7] - A[5]), 0.5 * (A[2] - A[6]), 0.5 * (A[3] - A[1])};
    // M = tr(S) I - S, S = sym A (symmetric); solve M w = 2 a by Cramer's rule
    const PetscReal trS = A[0] + A[4] + A[8];
    const PetscReal m00 = trS - A[0], m11 = trS - A[4], m22 = trS - A[8];
    const PetscReal m01 = -0.5 * (A[1] + A[3]), m02 = -0.5 * (A[2] + A[6]), m12 = -0.5 * (A[5] + A[7]);
    const PetscReal c00 = m11 * m22 - m12 * m12, c01 = m02 * m12 - m01 * m22, c02 = m01 * m12 - m02 * m11;
    const PetscReal det = m00 * c00 + m01 * c01 + m02 * c02;
    if (!(m00 > 0 && m00 * m11 - m01 * m01 > 0 && det > 0)) return false; // not positive definite
    const PetscReal c11 = m00 * m22 - m02 * m02, c12 = m01 * m02 - m00 * m12, c22 = m00 * m11 - m01 * m01;
    const PetscReal inv  = 2 / det;
    const PetscReal w[3] = {inv * (c00 * a[0] + c01 * a[1] + c02 * a[2]), inv * (c01 * a[0] + c11 * a[1] + c12 * a[2]), inv * (c02 * a[0] + c12 * a[1] + c22 * a[2])};
    const PetscReal ww   = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    if (!(ww < 0.25)) return false; // more than about 0.5 rad from the start: not a warm start
    const PetscReal h0 = 0.5 * w[0], h1 = 0.5 * w[1], h2 = 0.5 * w[2], s = 2 / (1 + 0.25 * ww);
    // Q = I + s (H + H^2), H = [h]; H^2 = h h^T - |h|^2 I, its diagonal -(h_j^2 + h_k^2)
    const PetscReal Q[9] = {1 + s * -(h2 * h2 + h1 * h1), s * (-h2 + h0 * h1),          s * (h1 + h0 * h2),  //
                            s * (h2 + h0 * h1),           1 + s * -(h2 * h2 + h0 * h0), s * (-h0 + h1 * h2), //
                            s * (-h1 + h0 * h2),          s * (h0 + h1 * h2),           1 + s * -(h1 * h1 + h0 * h0)};
    const bool      last = ww < 1e-18; // |w| < 1e-9: the next correction, of order |w|^2, is round-off
    PetscReal      *out  = last ? R : buffer[it % 2];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) out[3 * i + j] = Rk[3 * i] * Q[j] + Rk[3 * i + 1] * Q[3 + j] + Rk[3 * i + 2] * Q[6 + j];
    if (last) return true;
    Rk = out;
  }
  return false;
}

inline Mat3 PolarRotationFrom(const Mat3 &F, const Mat3 &R0)
{
  Mat3 R;
  if (PolarRotationWarm(F.data(), R0.data(), R.data())) return R;
  return PolarRotation(F);
}

} // namespace burst

namespace burst {
// Rotations of a symmetric tensor between the laboratory and a co-rotated frame, row-major 3x3
// arrays written out in scalars (the per-particle stress updates do two or three of these, and the
// Eigen products with their temporaries cost about twice as many instructions). U = R^T S (or R S)
// in full, then only the upper triangle of U R (or U R^T), mirrored: 45 multiplications instead of
// 54, and the result is symmetric to the last bit. S itself need not be exactly symmetric.

// The upper triangle (xx, xy, xz, yy, yz, zz) of a symmetric 3x3 tensor, returned by value so that
// it stays in registers: the rotations below used to go through arrays on the stack that were
// written in scalars and read back in pairs, and a load that spans two earlier stores waits for
// them (no store forwarding).
struct SymmetricTensor {
  PetscReal xx, xy, xz, yy, yz, zz;
};

inline void StoreSymmetric(const SymmetricTensor &t, PetscReal *__restrict out) { out[0] = t.xx, out[1] = out[3] = t.xy, out[2] = out[6] = t.xz, out[4] = t.yy, out[5] = out[7] = t.yz, out[8] = t.zz; }

// R^T S R
inline SymmetricTensor RotatedToFrame(const PetscReal *__restrict R, const PetscReal *__restrict S)
{
  PetscReal U[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) U[i][j] = R[i] * S[j] + R[3 + i] * S[3 + j] + R[6 + i] * S[6 + j];
  auto o = [&](int i, int j) { return U[i][0] * R[j] + U[i][1] * R[3 + j] + U[i][2] * R[6 + j]; };
  return {o(0, 0), o(0, 1), o(0, 2), o(1, 1), o(1, 2), o(2, 2)};
}

// R S R^T
inline SymmetricTensor RotatedFromFrame(const PetscReal *__restrict R, const PetscReal *__restrict S)
{
  PetscReal U[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) U[i][j] = R[3 * i] * S[j] + R[3 * i + 1] * S[3 + j] + R[3 * i + 2] * S[6 + j];
  auto o = [&](int i, int j) { return U[i][0] * R[3 * j] + U[i][1] * R[3 * j + 1] + U[i][2] * R[3 * j + 2]; };
  return {o(0, 0), o(0, 1), o(0, 2), o(1, 1), o(1, 2), o(2, 2)};
}

// out = R^T S R (out must not overlap R or S)
inline void RotateToFrame(const PetscReal *__restrict R, const PetscReal *__restrict S, PetscReal *__restrict out) { StoreSymmetric(RotatedToFrame(R, S), out); }

// out = R S R^T (out must not overlap R or S)
inline void RotateFromFrame(const PetscReal *__restrict R, const PetscReal *__restrict S, PetscReal *__restrict out) { StoreSymmetric(RotatedFromFrame(R, S), out); }
} // namespace burst
