// The small dense system of an implicit exchange between the N materials of a cell or face
// (ice.md 1.4, 1.8): E = I + diag(sum_n beta_mn) - beta, factored once and applied to every
// quantity that shares the coefficients (the velocity components).
#pragma once
#include "ice.hpp"

namespace burst {

// LU factors (no pivoting: the matrix is diagonally dominant) of E = I + diag(sum beta) - beta.
struct ExchangeMatrix {
  PetscInt  n;
  PetscReal E[kIceMaxMaterials][kIceMaxMaterials];
  void      Factor(const PetscReal beta[kIceMaxMaterials][kIceMaxMaterials])
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

} // namespace burst
