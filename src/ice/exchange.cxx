// Cell exchange of momentum and heat between the materials, and the Lagrangian specific volume
// (ice.md 1.8, steps 13-14).
//
// Per cell, implicit in the exchange: (I + diag(sum_n beta) - beta) du = [sum_n beta_mn (u_n - u_m)]
// with beta_mn = dt theta_n K_nm v_m for momentum and dt theta_n H_nm v_m / c_v,m for heat.
// M_m beta_mn = V dt theta_m theta_n K is symmetric, so the exchange conserves momentum and energy.
// The kinetic energy that drag removes becomes heat (with -ice_conservative_energy), shared so that
// every material warms alike; the reference drops it.
// Specific volume: (rho v)^L = rho v - theta kappa dp_dil + dt (theta alpha dT/dt - f sum theta
// alpha dT/dt) with f = theta kappa / sum theta kappa (ice.md 1.1, the rate form).
#include "ice.hpp"
#include <cmath>

namespace burst {

// Solves (I + diag(sum beta) - beta) x = [sum_n beta_mn (q_n - q_m)] for one cell and adds x to q.
static void ExchangeSolve(PetscInt n, const PetscReal beta[kIceMaxMaterials][kIceMaxMaterials], PetscReal q[kIceMaxMaterials])
{
  PetscReal E[kIceMaxMaterials][kIceMaxMaterials], x[kIceMaxMaterials];
  for (PetscInt m = 0; m < n; ++m) {
    PetscReal sum = 0;
    x[m]          = 0;
    for (PetscInt k = 0; k < n; ++k) {
      if (k == m) continue;
      E[m][k] = -beta[m][k];
      sum += beta[m][k];
      x[m] += beta[m][k] * (q[k] - q[m]);
    }
    E[m][m] = 1 + sum;
  }
  for (PetscInt k = 0; k < n; ++k)
    for (PetscInt i = k + 1; i < n; ++i) {
      const PetscReal f = E[i][k] / E[k][k];
      for (PetscInt j = k; j < n; ++j) E[i][j] -= f * E[k][j];
      x[i] -= f * x[k];
    }
  for (PetscInt i = n - 1; i >= 0; --i) {
    PetscReal s = x[i];
    for (PetscInt j = i + 1; j < n; ++j) s -= E[i][j] * x[j];
    x[i] = s / E[i][i];
  }
  for (PetscInt m = 0; m < n; ++m) q[m] += x[m];
}

PetscErrorCode IceCellExchange(IceSolver &ice)
{
  PetscScalar   *a;
  const PetscInt S = ice.stride, n = ice.nmat, dim = ice.dim;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ice.ev_exchange, 0, 0, 0, 0));
  PetscCall(IceGetLocalArray(ice, &a));
  PetscReal beta[kIceMaxMaterials][kIceMaxMaterials], q[kIceMaxMaterials], Tdot[kIceMaxMaterials];
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        PetscScalar *c = a + ice.LocalIndex(i, j, k) * S;
        if (n > 1) {
          for (PetscInt m = 0; m < n; ++m)
            for (PetscInt l = 0; l < n; ++l) beta[m][l] = ice.dt * c[ice.Offset(l, icef::theta)] * ice.exchange_K[l][m] * c[ice.Offset(m, icef::spvol)];
          PetscReal dissipated = 0, heat_capacity = 0; // drag turns kinetic energy into heat
          for (PetscInt d = 0; d < dim; ++d) {
            for (PetscInt m = 0; m < n; ++m) q[m] = c[ice.Offset(m, icef::vel_L + d)];
            for (PetscInt m = 0; m < n; ++m) dissipated += 0.5 * c[ice.Offset(m, icef::rho_L)] * q[m] * q[m];
            ExchangeSolve(n, beta, q);
            for (PetscInt m = 0; m < n; ++m) dissipated -= 0.5 * c[ice.Offset(m, icef::rho_L)] * q[m] * q[m];
            for (PetscInt m = 0; m < n; ++m) c[ice.Offset(m, icef::vel_L + d)] = q[m];
          }
          if (ice.conservative_energy) { // to every material alike: one temperature rise
            for (PetscInt m = 0; m < n; ++m) heat_capacity += c[ice.Offset(m, icef::rho_L)] * ice.materials[m].eos->cv;
            for (PetscInt m = 0; m < n; ++m) c[ice.Offset(m, icef::temp_L)] += PetscMax(dissipated, 0.0) / heat_capacity;
          }
          for (PetscInt m = 0; m < n; ++m)
            for (PetscInt l = 0; l < n; ++l) beta[m][l] = ice.dt * c[ice.Offset(l, icef::theta)] * ice.exchange_H[l][m] * c[ice.Offset(m, icef::spvol)] / ice.materials[m].eos->cv;
          for (PetscInt m = 0; m < n; ++m) q[m] = c[ice.Offset(m, icef::temp_L)];
          ExchangeSolve(n, beta, q);
          for (PetscInt m = 0; m < n; ++m) c[ice.Offset(m, icef::temp_L)] = q[m];
        }
        // Lagrangian specific volume
        const PetscReal dp_dil = c[ice.CellOffset(icef::dp_dil)], sum_kappa = c[ice.CellOffset(icef::sum_kappa)];
        PetscReal       sum_expansion = 0;
        for (PetscInt m = 0; m < n; ++m) {
          Tdot[m] = (c[ice.Offset(m, icef::temp_L)] - c[ice.Offset(m, icef::temp)]) / ice.dt;
          sum_expansion += c[ice.Offset(m, icef::theta)] * c[ice.Offset(m, icef::alpha)] * Tdot[m];
        }
        for (PetscInt m = 0; m < n; ++m) {
          const PetscReal theta = c[ice.Offset(m, icef::theta)], kappa = c[ice.Offset(m, icef::kappa)];
          const PetscReal rho   = c[ice.Offset(m, icef::rho)], v = c[ice.Offset(m, icef::spvol)];
          const PetscReal f     = theta * kappa / sum_kappa;
          PetscReal       rho_v = rho * v - theta * kappa * dp_dil;
          if (n > 1) rho_v += ice.dt * (theta * c[ice.Offset(m, icef::alpha)] * Tdot[m] - f * sum_expansion);
          rho_v = PetscMax(rho_v, ice.rho_tiny * rho * v); // ClampSpecificVolume (ice.md 1.8)
          c[ice.Offset(m, icef::spvol_L)] = rho_v / c[ice.Offset(m, icef::rho_L)];
        }
      }
  PetscCall(IceRestoreLocalArray(ice, &a));
  PetscCall(IceUpdateGhosts(ice));
  PetscCall(PetscLogEventEnd(ice.ev_exchange, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
