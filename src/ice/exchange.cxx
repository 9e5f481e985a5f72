// Cell exchange of momentum and heat between the materials (ice.md 1.8, step 13).
//
// Per cell, implicit in the exchange: (I + diag(sum_n beta) - beta) du = [sum_n beta_mn (u_n - u_m)]
// with beta_mn = dt theta_n K_nm v_m for momentum and dt theta_n H_nm v_m / c_v,m for heat.
// M_m beta_mn = V dt theta_m theta_n K is symmetric, so the exchange conserves momentum and energy.
// The kinetic energy that drag removes becomes heat (with -ice_conservative_energy): each material
// gets the kinetic energy of its own slip against the cell's centre of mass that the drag removes
// (below), so a gas that a solid's pressure field flung in a solid's cell gets back what the flight
// took from it, and the solid keeps its own; the reference drops it, and so does -ice_drag_heating 0.
// (Shared by heat capacity instead, the steel of the exploding cylinder's symmetry planes took the
// flung gas's energy: 4.5e6 K within 200 steps at 160 x 160 cells.)
// burst's equilibration takes each material's volume from its mass (sum rho_m/rho_micro_m = 1), so
// the reference's Lagrangian specific volume (its volume bookkeeping, ice.md 1.8 step 14) is not
// needed: the specific volume is an output of the equilibration.
#include "ice.hpp"
#include "exchange_matrix.hpp"
#include <cmath>

namespace burst {

template <int N>
static PetscErrorCode CellExchange(IceSolver &ice, PetscScalar *a)
{
  const PetscInt    S = ice.stride, dim = ice.dim;
  PetscReal         beta[kIceMaxMaterials][kIceMaxMaterials], q[kIceMaxMaterials];
  ExchangeMatrix<N> E;
  PetscBool         info = PETSC_FALSE; // -info: the fallbacks' diagnostics (below) are computed only then
  PetscCall(PetscInfoEnabled(DM_CLASSID, &info));
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        PetscScalar *c = a + ice.LocalIndex(i, j, k) * S;
        for (PetscInt m = 0; m < N; ++m)
          for (PetscInt l = 0; l < N; ++l) beta[m][l] = ice.dt * c[ice.Offset(l, icef::theta)] * ice.exchange_K[l][m] * c[ice.Offset(m, icef::spvol)];
        E.Factor(beta);
        // The drag's impulse on m, J_m = rho_m (u_m' - u_m), does the work J_m . u_cm at the cell's
        // centre-of-mass velocity (which the exchange keeps; sum_m J_m = 0, so the works cancel), so
        // m's internal energy gains (u_m' - u_m) . (u_cm - (u_m' + u_m)/2) = (|u_m - u_cm|^2 -
        // |u_m' - u_cm|^2)/2 per unit mass: the kinetic energy of its own slip that the drag
        // removes, >= 0 while the exchange brings every material towards u_cm.
        PetscReal heat[kIceMaxMaterials] = {0};
        // u_cm . (u_L - u) per unit mass: the pressure source's work on a material that the drag
        // carries at the cell's centre-of-mass velocity; the drag hands it to the others (the
        // fallbacks' PetscInfo below)
        PetscReal carried[kIceMaxMaterials] = {0};
        for (PetscInt d = 0; d < dim; ++d) {
          PetscReal mass = 0, momentum = 0, u_old[kIceMaxMaterials];
          for (PetscInt m = 0; m < N; ++m) {
            q[m] = u_old[m] = c[ice.Offset(m, icef::vel_L + d)];
            mass += c[ice.Offset(m, icef::rho_L)];
            momentum += c[ice.Offset(m, icef::rho_L)] * q[m];
          }
          E.Apply(beta, q);
          const PetscReal u_cm = momentum / mass;
          for (PetscInt m = 0; m < N; ++m) {
            heat[m] += (q[m] - u_old[m]) * (u_cm - 0.5 * (q[m] + u_old[m]));
            if (info) carried[m] += u_cm * (u_old[m] - c[ice.Offset(m, icef::vel + d)]);
            c[ice.Offset(m, icef::vel_L + d)] = q[m];
          }
        }
        const PetscReal V = ice.CellVolume(); // (the budgets' counters: J)
        for (PetscInt m = 0; m < N; ++m) {
          // a trace of gas did not pay for its kinetic energy (sources.cxx): it gets none back
          const bool back = ice.conservative_energy && ice.drag_heating && (ice.materials[m].solid || !IceIsTrace(ice, c, m));
          if (back) c[ice.Offset(m, icef::temp_L)] += heat[m] / ice.materials[m].eos->cv;
          else ice.drag_energy_change -= V * c[ice.Offset(m, icef::rho_L)] * heat[m]; // the kinetic energy the drag removes, dropped
        }
        // The heat exchange conserves sum_m rho_m c_v,m T_m, and each new temperature is a weighted
        // mean of the old ones (the matrix's rows sum to one and its inverse is non-negative). So a
        // gas that the drag left below 0 K is judged after it: in a cell the steel fills, the
        // steel's heat pays the deficit, and only what the exchange cannot cover falls back (the
        // temperature form below). Where the deficit would instead take a material that was above
        // 0 K to or below it (a cell whose gases dominate its heat capacity), the cell is done in
        // the other order: the fallback first, then the exchange.
        for (PetscInt m = 0; m < N; ++m)
          for (PetscInt l = 0; l < N; ++l) beta[m][l] = ice.dt * c[ice.Offset(l, icef::theta)] * ice.exchange_H[l][m] * c[ice.Offset(m, icef::spvol)] / ice.materials[m].eos->cv;
        E.Factor(beta);
        PetscReal T_drag[kIceMaxMaterials]; // after the drag heat, before the heat exchange
        bool      negative = false;
        for (PetscInt m = 0; m < N; ++m) {
          q[m] = T_drag[m] = c[ice.Offset(m, icef::temp_L)];
          negative         = negative || T_drag[m] <= 0;
        }
        E.Apply(beta, q);
        bool fallback_first = false;
        if (negative)
          for (PetscInt m = 0; m < N; ++m) fallback_first = fallback_first || (T_drag[m] > 0 && !(q[m] > 0));
        if (!fallback_first)
          for (PetscInt m = 0; m < N; ++m) c[ice.Offset(m, icef::temp_L)] = q[m];
        for (PetscInt m = 0; m < ice.ngas; ++m) {
          PetscReal &T_L = c[ice.Offset(m, icef::temp_L)];
          if (T_L > 0) continue;
          // the drag did not give back what the pressure gradient gave (sources.cxx): the
          // temperature form instead, counted
          const GasEOS   &eos      = *ice.materials[m].eos;
          const PetscReal T_before = T_L, cold_before = eos.HasColdEnergy() ? eos.cv * c[ice.Offset(m, icef::energy_L)] : 0;
          PetscReal       cold_L = 0;
          T_L                    = IceTemperatureForm(ice, c, ice.LocalIndex(i, j, k), m, &cold_L);
          if (eos.HasColdEnergy()) c[ice.Offset(m, icef::energy_L)] = cold_L / eos.cv;
          IceCountFallback(ice, c, ice.LocalIndex(i, j, k));
          ++ice.energy_fallbacks_exchange;
          PetscReal solid = 0;
          for (PetscInt l = ice.ngas; l < N; ++l) solid += c[ice.Offset(l, icef::theta)];
          PetscCall(PetscInfo(nullptr,
                              "Gas step %" PetscInt_FMT ": exchange fallback of %s in cell (%" PetscInt_FMT ", %" PetscInt_FMT ", %" PetscInt_FMT
                              "): volume fraction %g, solids' %g; temperature %g K after the drag heat %g J/kg, %g K after the heat exchange%s; the pressure source's work carried at the centre-of-mass velocity %g J/kg, c_v T %g J/kg\n",
                              ice.step, ice.materials[m].name.c_str(), i, j, k, (double)c[ice.Offset(m, icef::theta)], (double)solid, (double)T_drag[m], (double)heat[m], (double)q[m],
                              fallback_first ? " (not taken: it would cool another material below 0 K)" : "", (double)carried[m], (double)(eos.cv * c[ice.Offset(m, icef::temp)])));
          ice.exchange_fallback_energy += V * c[ice.Offset(m, icef::rho_L)] * (eos.cv * (T_L - T_before) + (eos.HasColdEnergy() ? cold_L - cold_before : 0));
          PetscCheck(T_L > 0 && std::isfinite(T_L), PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED,
                     "Gas step %" PetscInt_FMT ": the compression work makes the temperature of material %s in cell (%" PetscInt_FMT ", %" PetscInt_FMT ", %" PetscInt_FMT ") %g K; reduce -ice_cfl", ice.step, ice.materials[m].name.c_str(), i, j, k,
                     (double)T_L);
        }
        if (fallback_first) { // the exchange of the temperatures the fallback left
          for (PetscInt m = 0; m < N; ++m) q[m] = c[ice.Offset(m, icef::temp_L)];
          E.Apply(beta, q);
          for (PetscInt m = 0; m < N; ++m) c[ice.Offset(m, icef::temp_L)] = q[m];
        }
      }
  return PETSC_SUCCESS;
}

PetscErrorCode IceCellExchange(IceSolver &ice)
{
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ice.ev_exchange, 0, 0, 0, 0));
  PetscCall(IceGetLocalArray(ice, &a));
  PetscErrorCode ierr = PETSC_SUCCESS;
  if (ice.nmat > 1) DispatchMaterials(ice.nmat, [&](auto N) { ierr = CellExchange<N()>(ice, a); });
  PetscCall(ierr);
  PetscCall(IceRestoreLocalArray(ice, &a));
  PetscCall(IceUpdateGhosts(ice));
  PetscCall(PetscLogEventEnd(ice.ev_exchange, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
