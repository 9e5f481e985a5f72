// Equilibration pressure (ice.md 1.3, step 4): in every cell, the single pressure p at which the
// materials' volumes fill the cell, sum_m rho_m / rho_micro_m(p, T_m) = 1, with rho_m = M_m/V the
// bulk density; with -ice_equilibration normalized, in a cell that holds a solid, the bulk densities
// are first rescaled so that the volumes fill the cell at the old pressure (below). Newton on p (d theta_m/dp = -theta_m/(rho_micro dP/drho)), with a bisection on
// log p as the fallback; a cell where both fail stops the run with its state.
//
// Then the derived fields of each material: theta, specific volume 1/rho_micro, sound speed,
// compressibility kappa = v/c^2 and the compression-work pressure T dP/dT.
// Cells are independent, so every local cell (ghosts included) is equilibrated: the face phase
// needs its neighbours' values without another ghost exchange.
#include "ice.hpp"
#include <cmath>

namespace burst {

namespace {
// sum theta(p) - 1 and its derivative for the bulk densities scale * rho_m; rho_micro is written. A gas with a cold energy keeps its
// specific energy e[m] (so the equilibration conserves energy: gas_eos.hpp), the others their
// temperature; cold[m] says which (e[m] unused otherwise).
// point[m] (if given) keeps the equation of state at rho_micro[m] and T_m of a material without a
// cold energy, which the derived fields reuse.
PetscReal VolumeResidual(const IceSolver &ice, const PetscScalar *c, PetscReal scale, PetscReal p, const bool cold[], const PetscReal e[], PetscReal rho_micro[], PetscReal *dfdp, GasEOSPoint *point = nullptr)
{
  PetscReal sum = 0, deriv = 0;
  for (PetscInt m = 0; m < ice.nmat; ++m) {
    const GasEOS   &eos = *ice.materials[m].eos;
    const PetscReal rho = scale * c[ice.Offset(m, icef::rho)];
    PetscReal       dp_drho;
    if (cold[m]) {
      rho_micro[m] = eos.DensityAtEnergy(p, e[m], rho_micro[m] > 0 ? rho_micro[m] : 1 / c[ice.Offset(m, icef::spvol)]);
      if (!(rho_micro[m] > 0)) return NAN;
      dp_drho = eos.DpDrhoAtEnergy(rho_micro[m], (e[m] - eos.ColdEnergy(rho_micro[m])) / eos.cv);
    } else {
      const PetscReal T = c[ice.Offset(m, icef::temp)];
      if (point) { // the last call: the whole EOS point, for the derived fields
        rho_micro[m] = eos.Density(p, T);
        if (!(rho_micro[m] > 0)) return NAN;
        point[m] = eos.Evaluate(rho_micro[m], T);
        dp_drho  = point[m].dp_drho;
      } else {
        rho_micro[m] = eos.DensityAndSlope(p, T, &dp_drho);
        if (!(rho_micro[m] > 0)) return NAN;
      }
    }
    const PetscReal theta = rho / rho_micro[m];
    sum += theta;
    deriv -= theta / (rho_micro[m] * dp_drho);
  }
  if (dfdp) *dfdp = deriv;
  return sum - 1;
}
} // namespace

PetscErrorCode IceEquilibrate(IceSolver &ice)
{
  PetscScalar   *a;
  const PetscInt S = ice.stride, n = ice.nmat;
  PetscReal      rho_micro[kIceMaxMaterials], e[kIceMaxMaterials];
  GasEOSPoint    point[kIceMaxMaterials];
  bool           cold[kIceMaxMaterials], any_cold = false;
  PetscFunctionBeginUser;
  for (PetscInt m = 0; m < n; ++m) {
    cold[m]  = !ice.materials[m].solid && ice.materials[m].eos->HasColdEnergy();
    any_cold = any_cold || cold[m];
  }
  const bool normalize = ice.equilibration_form == IceEquilibrationForm::Normalized && ice.nmat > ice.ngas;
  PetscCall(PetscLogEventBegin(ice.ev_equilibrate, 0, 0, 0, 0));
  PetscCall(IceGetLocalArray(ice, &a));
  const PetscInt ncells = ice.gxm[0] * ice.gxm[1] * ice.gxm[2];
  for (PetscInt idx = 0; idx < ncells; ++idx) {
    PetscScalar *c = a + idx * S;
    PetscReal    p = c[ice.CellOffset(icef::press)], scale = 1;
    if (normalize) {
      // Normalized (Uintah's MPMICE, mpmice-lessons.md section 0): in a cell that holds a solid,
      // the volumes at the old pressure (the solids' from their EOS, the gases' from their
      // transported specific volume) are rescaled to fill the cell, so what the projection, the
      // advection or a burn puts in too much or too little does not become pressure through the
      // stiffest material; the pressure moves with the materials' own states.
      PetscReal solid_volume = 0, volume = 0;
      for (PetscInt m = 0; m < n; ++m) {
        const PetscReal rho = c[ice.Offset(m, icef::rho)];
        if (ice.materials[m].solid) {
          const PetscReal rho_s = ice.materials[m].eos->Density(p, c[ice.Offset(m, icef::temp)]);
          solid_volume += rho_s > 0 ? rho / rho_s : 0;
        } else volume += rho * c[ice.Offset(m, icef::spvol)];
      }
      volume += solid_volume;
      if (solid_volume > ice.trace_fraction && volume > 0 && std::isfinite(volume)) scale = 1 / volume;
    }
    if (any_cold)
      for (PetscInt m = 0; m < n; ++m) {
        rho_micro[m] = -1; // DensityAtEnergy's first guess: the stored specific volume
        if (cold[m]) e[m] = ice.materials[m].eos->InternalEnergy(1 / c[ice.Offset(m, icef::spvol)], c[ice.Offset(m, icef::temp)]);
      }
    bool have_point = false; // point[m]: the EOS at the final rho_micro of the materials without a cold energy
    if (n == 1) {            // one material fills the cell: no solve
      rho_micro[0] = c[ice.Offset(0, icef::rho)];
      if (cold[0]) c[ice.Offset(0, icef::temp)] = (e[0] - ice.materials[0].eos->ColdEnergy(rho_micro[0])) / ice.materials[0].eos->cv;
      p = ice.materials[0].eos->Evaluate(rho_micro[0], c[ice.Offset(0, icef::temp)]).pressure;
    } else {
      const PetscReal tol       = 1e-12;
      bool            converged = false;
      for (PetscInt it = 0; it < ice.equilibration_max_iterations && p > 0 && std::isfinite(p); ++it) {
        PetscReal       dfdp;
        const PetscReal f = VolumeResidual(ice, c, scale, p, cold, e, rho_micro, &dfdp);
        if (!std::isfinite(f)) break;
        if (std::fabs(f) < tol) {
          converged = true;
          break;
        }
        PetscReal next = p - f / dfdp;
        if (!(next > 0)) next = 0.1 * p; // stay positive (ice.md 7.3)
        p = next;
      }
      if (!converged) { // bisection on log p: sum theta decreases with p
        PetscReal lo = 1e-6, hi = 1e15, f_lo, f_hi;
        f_lo = VolumeResidual(ice, c, scale, lo, cold, e, rho_micro, nullptr);
        f_hi = VolumeResidual(ice, c, scale, hi, cold, e, rho_micro, nullptr);
        if (f_lo > 0 && f_hi < 0) {
          for (PetscInt it = 0; it < 200; ++it) {
            const PetscReal mid = std::sqrt(lo * hi), f = VolumeResidual(ice, c, scale, mid, cold, e, rho_micro, nullptr);
            if (!std::isfinite(f)) break;
            if (f > 0) lo = mid;
            else hi = mid;
            p = mid;
            if (std::fabs(f) < tol || hi / lo - 1 < 1e-14) {
              converged = true;
              break;
            }
          }
        }
        if (!converged) {
          PetscInt    i = idx % ice.gxm[0] + ice.gxs[0], j = (idx / ice.gxm[0]) % ice.gxm[1] + ice.gxs[1], k = idx / (ice.gxm[0] * ice.gxm[1]) + ice.gxs[2];
          std::string state;
          for (PetscInt m = 0; m < n; ++m) state += " " + ice.materials[m].name + ": rho " + std::to_string(c[ice.Offset(m, icef::rho)]) + " kg/m^3, T " + std::to_string(c[ice.Offset(m, icef::temp)]) + " K;";
          SETERRQ(PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED,
                  "Gas step %" PetscInt_FMT ": the equilibration pressure of cell (%" PetscInt_FMT ", %" PetscInt_FMT ", %" PetscInt_FMT ") did not converge (Newton and bisection on [1e-6, 1e15] Pa); state:%s", ice.step, i, j, k, state.c_str());
        }
      }
      have_point = std::isfinite(VolumeResidual(ice, c, scale, p, cold, e, rho_micro, nullptr, point));
    }
    PetscReal sum_kappa = 0;
    for (PetscInt m = 0; m < n; ++m) {
      const GasEOS &eos = *ice.materials[m].eos;
      if (cold[m]) c[ice.Offset(m, icef::temp)] = (e[m] - eos.ColdEnergy(rho_micro[m])) / eos.cv;
      const PetscReal   T            = c[ice.Offset(m, icef::temp)];
      const GasEOSPoint s            = have_point && !cold[m] ? point[m] : eos.Evaluate(rho_micro[m], T);
      const PetscReal   c2           = s.dp_drho + T * s.dp_dT * s.dp_dT / (rho_micro[m] * rho_micro[m] * eos.cv);
      const PetscReal   theta        = scale * c[ice.Offset(m, icef::rho)] / rho_micro[m];
      c[ice.Offset(m, icef::theta)]  = theta;
      c[ice.Offset(m, icef::spvol)]  = 1 / rho_micro[m];
      c[ice.Offset(m, icef::kappa)]  = 1 / (rho_micro[m] * c2);
      c[ice.Offset(m, icef::work_p)] = T * s.dp_dT;
      sum_kappa += theta / (rho_micro[m] * c2);
    }
    c[ice.CellOffset(icef::press_eq)]  = p;
    c[ice.CellOffset(icef::sum_kappa)] = sum_kappa;
  }
  PetscCall(IceRestoreLocalArray(ice, &a));
  PetscCall(PetscLogEventEnd(ice.ev_equilibrate, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
