// Cell exchange of momentum and heat between the materials (ice.md 1.8, step 13).
//
// Per cell, implicit in the exchange: (I + diag(sum_n beta) - beta) du = [sum_n beta_mn (u_n - u_m)]
// with beta_mn = dt theta_n K_nm v_m for momentum and dt theta_n H_nm v_m / c_v,m for heat.
// M_m beta_mn = V dt theta_m theta_n K is symmetric, so the exchange conserves momentum and energy.
// The kinetic energy that drag removes becomes heat (with -ice_conservative_energy), shared so that
// every material warms alike; the reference drops it, and so does -ice_drag_heating 0 (in the mixed
// cells of a stiff solid the drag dissipates each step's pressure noise: heat that the exploding
// cylinder's steel at its symmetry planes took to 4.5e6 K within 200 steps at 160 x 160 cells).
// burst's equilibration takes each material's volume from its mass (sum rho_m/rho_micro_m = 1), so
// the reference's Lagrangian specific volume (its volume bookkeeping, ice.md 1.8 step 14) is not
// needed: the specific volume is an output of the equilibration.
#include "ice.hpp"
#include "exchange_matrix.hpp"
#include <cmath>

namespace burst {


template <int N>
static void CellExchange(IceSolver &ice, PetscScalar *a)
{
  const PetscInt S = ice.stride, dim = ice.dim;
  PetscReal      beta[kIceMaxMaterials][kIceMaxMaterials], q[kIceMaxMaterials];
  ExchangeMatrix<N> E;
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        PetscScalar *c = a + ice.LocalIndex(i, j, k) * S;
        for (PetscInt m = 0; m < N; ++m)
          for (PetscInt l = 0; l < N; ++l) beta[m][l] = ice.dt * c[ice.Offset(l, icef::theta)] * ice.exchange_K[l][m] * c[ice.Offset(m, icef::spvol)];
        E.Factor(beta);
        PetscReal dissipated = 0; // drag turns kinetic energy into heat
        for (PetscInt d = 0; d < dim; ++d) {
          for (PetscInt m = 0; m < N; ++m) {
            q[m] = c[ice.Offset(m, icef::vel_L + d)];
            dissipated += 0.5 * c[ice.Offset(m, icef::rho_L)] * q[m] * q[m];
          }
          E.Apply(beta, q);
          for (PetscInt m = 0; m < N; ++m) {
            dissipated -= 0.5 * c[ice.Offset(m, icef::rho_L)] * q[m] * q[m];
            c[ice.Offset(m, icef::vel_L + d)] = q[m];
          }
        }
        if (ice.conservative_energy && ice.drag_heating) { // to every material alike: one temperature rise
          PetscReal heat_capacity = 0;
          for (PetscInt m = 0; m < N; ++m) heat_capacity += c[ice.Offset(m, icef::rho_L)] * ice.materials[m].eos->cv;
          for (PetscInt m = 0; m < N; ++m) c[ice.Offset(m, icef::temp_L)] += PetscMax(dissipated, 0.0) / heat_capacity;
          ice.drag_energy_change += ice.CellVolume() * (PetscMax(dissipated, 0.0) - dissipated); // (the budgets)
        } else ice.drag_energy_change -= ice.CellVolume() * dissipated; // the kinetic energy the drag dissipates is dropped
        for (PetscInt m = 0; m < N; ++m)
          for (PetscInt l = 0; l < N; ++l) beta[m][l] = ice.dt * c[ice.Offset(l, icef::theta)] * ice.exchange_H[l][m] * c[ice.Offset(m, icef::spvol)] / ice.materials[m].eos->cv;
        E.Factor(beta);
        for (PetscInt m = 0; m < N; ++m) q[m] = c[ice.Offset(m, icef::temp_L)];
        E.Apply(beta, q);
        for (PetscInt m = 0; m < N; ++m) c[ice.Offset(m, icef::temp_L)] = q[m];
      }
}

PetscErrorCode IceCellExchange(IceSolver &ice)
{
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ice.ev_exchange, 0, 0, 0, 0));
  PetscCall(IceGetLocalArray(ice, &a));
  if (ice.nmat > 1) DispatchMaterials(ice.nmat, [&](auto N) { CellExchange<N()>(ice, a); });
  PetscCall(IceRestoreLocalArray(ice, &a));
  PetscCall(IceUpdateGhosts(ice));
  PetscCall(PetscLogEventEnd(ice.ev_exchange, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
