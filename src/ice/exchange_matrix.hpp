// The small dense system of an implicit exchange between the N materials of a cell or face
// (ice.md 1.4, 1.8): E = I + diag(sum_n beta_mn) - beta, factored once and applied to every
// quantity that shares the coefficients (the velocity components). The number of materials N is a
// compile-time constant (DispatchMaterials) so that these loops unroll: the exchanges ran a third of
// the gas step with a run-time count.
#pragma once
#include "ice.hpp"
#include <type_traits>

namespace burst {

// LU factors (no pivoting: the matrix is diagonally dominant) of E = I + diag(sum beta) - beta.
template <int N>
struct ExchangeMatrix {
  static constexpr PetscInt n = N;
  PetscReal                 E[N][N];
  void                      Factor(const PetscReal beta[kIceMaxMaterials][kIceMaxMaterials])
  {
    for (PetscInt m = 0; m < n; ++m) {
      PetscReal sum = 0;
      for (PetscInt k = 0; k < n; ++k)
        if (k != m) {
          E[m][k] = -beta[m][k];
          sum += beta[m][k];
        }
      E[m][m] = 1 + sum;
    }
    for (PetscInt k = 0; k < n; ++k)
      for (PetscInt i = k + 1; i < n; ++i) {
        E[i][k] /= E[k][k];
        for (PetscInt j = k + 1; j < n; ++j) E[i][j] -= E[i][k] * E[k][j];
      }
  }
  // q += E^{-1} [sum_n beta_mn (q_n - q_m)]
  void Apply(const PetscReal beta[kIceMaxMaterials][kIceMaxMaterials], PetscReal q[]) const
  {
    PetscReal x[kIceMaxMaterials];
    for (PetscInt m = 0; m < n; ++m) {
      x[m] = 0;
      for (PetscInt k = 0; k < n; ++k)
        if (k != m) x[m] += beta[m][k] * (q[k] - q[m]);
    }
    for (PetscInt i = 1; i < n; ++i)
      for (PetscInt j = 0; j < i; ++j) x[i] -= E[i][j] * x[j];
    for (PetscInt i = n - 1; i >= 0; --i) {
      for (PetscInt j = i + 1; j < n; ++j) x[i] -= E[i][j] * x[j];
      x[i] /= E[i][i];
    }
    for (PetscInt m = 0; m < n; ++m) q[m] += x[m];
  }
  // x = E^{-1} b
  void Solve(const PetscReal b[], PetscReal x[]) const
  {
    for (PetscInt i = 0; i < n; ++i) x[i] = b[i];
    for (PetscInt i = 1; i < n; ++i)
      for (PetscInt j = 0; j < i; ++j) x[i] -= E[i][j] * x[j];
    for (PetscInt i = n - 1; i >= 0; --i) {
      for (PetscInt j = i + 1; j < n; ++j) x[i] -= E[i][j] * x[j];
      x[i] /= E[i][i];
    }
  }
};

// Calls f(std::integral_constant<int, n>{}) for the run-time material count n in [2, kIceMaxMaterials].
template <class F>
void DispatchMaterials(PetscInt n, F &&f)
{
  static_assert(kIceMaxMaterials == 8, "extend the dispatch");
  switch (n) {
  case 2: f(std::integral_constant<int, 2>{}); break;
  case 3: f(std::integral_constant<int, 3>{}); break;
  case 4: f(std::integral_constant<int, 4>{}); break;
  case 5: f(std::integral_constant<int, 5>{}); break;
  case 6: f(std::integral_constant<int, 6>{}); break;
  case 7: f(std::integral_constant<int, 7>{}); break;
  default: f(std::integral_constant<int, 8>{}); break;
  }
}

} // namespace burst
