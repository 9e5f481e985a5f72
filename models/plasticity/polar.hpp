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
