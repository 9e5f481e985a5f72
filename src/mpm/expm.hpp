// Matrix exponential of a small 3x3 tensor, for the deformation-gradient update F <- exp(L dt) F.
#pragma once
#include "../../models/elastic/tensor.hpp"
#include <cmath>

namespace burst {

// exp(A) by scaling and squaring with a degree-8 Taylor polynomial; A = L dt is small in practice.
inline Mat3 Expm(const Mat3 &A)
{
  const PetscReal norm = A.cwiseAbs().rowwise().sum().maxCoeff();
  const int       s    = norm > 0.5 ? (int)std::ceil(std::log2(norm / 0.5)) : 0;
  const Mat3      B    = A / std::ldexp(1.0, s);
  Mat3            term = Mat3::Identity(), result = Mat3::Identity();
  for (int k = 1; k <= 8; ++k) {
    term = term * B / (PetscReal)k;
    result += term;
  }
  for (int k = 0; k < s; ++k) result = result * result;
  return result;
}

} // namespace burst
