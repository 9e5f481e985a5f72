// Face pressure, momentum and energy sources, and the Lagrangian values (ice.md 1.6-1.8, steps
// 9, 10, 12).
//
// Face pressure from continuity of acceleration: p_f = (p_R rho_L + p_L rho_R)/(rho_L + rho_R),
// rho the sum of the bulk densities. Per material, per unit volume:
//   momentum  -dt theta_m grad p_f + dt rho_m g
//   energy    (-ice_conservative_energy, the default) the work of the face pressures on the face
//             volume fluxes, minus the kinetic energy the momentum source gives: total energy is
//             conserved; where that would leave a negative temperature (a step that gives a gas
//             more kinetic energy than it holds, counted in ice.energy_fallbacks), and with
//             -ice_conservative_energy 0, theta_m kappa_m (T dP/dT + dp_dil) dp_dil, the work of
//             compression c_v dT = -T (dP/dT)_rho dv at the end-of-step pressure (for an ideal
//             gas Uintah's p^{n+1} theta kappa dp_dil, its only form)
//   burning   the mass, momentum and energy of the converted solid (ice.md 2.4)
// The Lagrangian values are the state plus these sources.
#include "ice.hpp"
#include <cmath>

namespace burst {

PetscReal IceTemperatureForm(const IceSolver &ice, const PetscScalar *c, PetscInt idx, PetscInt m, PetscReal *cold_L)
{
  const GasEOS   &eos   = *ice.materials[m].eos;
  const PetscReal theta = c[ice.Offset(m, icef::theta)], rho = c[ice.Offset(m, icef::rho)], rho_L = c[ice.Offset(m, icef::rho_L)];
  const PetscReal dp_dil = c[ice.CellOffset(icef::dp_dil)];
  const PetscReal dr     = ice.has_mass_source ? ice.mass_source[idx * ice.nmat + m] : 0;
  const PetscReal de     = ice.has_mass_source ? ice.energy_source[idx * ice.nmat + m] : 0;
  const PetscReal pdv    = theta * c[ice.Offset(m, icef::kappa)] * (c[ice.Offset(m, icef::work_p)] + dp_dil) * dp_dil;
  if (cold_L && eos.HasColdEnergy()) {
    // the volume change that the pressure change dp_dil gives, -theta kappa dp_dil, and the
    // converted mass's
    const PetscReal theta_L = theta * (1 - c[ice.Offset(m, icef::kappa)] * dp_dil) + (dr > 0 ? dr * c[ice.Offset(m, icef::spvol)] : 0);
    *cold_L                 = eos.ColdEnergy(theta_L > 0 ? rho_L / theta_L : 1 / c[ice.Offset(m, icef::spvol)]);
  }
  return (rho * eos.cv * c[ice.Offset(m, icef::temp)] + pdv + de) / (rho_L * eos.cv);
}

const char *const IceFallbackClassNames[] = {"burning", "solid_filled", "solid_surface", "open"};

void IceCountFallback(IceSolver &ice, const PetscScalar *c, PetscInt idx)
{
  PetscReal solid   = 0; // the solids' volume fraction
  bool      burning = false;
  for (PetscInt m = ice.ngas; m < ice.nmat; ++m) solid += c[ice.Offset(m, icef::theta)];
  for (PetscInt m = 0; m < ice.ngas && ice.has_mass_source; ++m) burning = burning || ice.mass_source[idx * ice.nmat + m] > 0;
  const IceFallbackClass k = burning ? IceFallbackClass::Burning : solid >= 0.9 ? IceFallbackClass::SolidFilled : solid > ice.trace_fraction ? IceFallbackClass::SolidSurface : IceFallbackClass::Open;
  ++ice.energy_fallbacks;
  ++ice.energy_fallbacks_class[(int)k];
}

PetscReal IceFacePressure(const IceSolver &ice, const PetscScalar *a, PetscInt L, PetscInt R)
{
  const PetscScalar *cL = a + L * ice.stride, *cR = a + R * ice.stride;
  PetscReal          rL = 0, rR = 0;
  for (PetscInt m = 0; m < ice.nmat; ++m) {
    rL += cL[ice.Offset(m, icef::rho)];
    rR += cR[ice.Offset(m, icef::rho)];
  }
  return (cR[ice.CellOffset(icef::press)] * rL + cL[ice.CellOffset(icef::press)] * rR) / (rL + rR);
}

// A gas in a cell that holds a solid moves with the solid: the drag (exchange.cxx) holds it to the
// cell's centre-of-mass velocity u_cm, which the exchange keeps. The pressure source's work on it is
// then F . u_cm, and its internal energy changes by its own compression work (the temperature form)
// and the heat of its initial slip. The conservative form gives it instead the face pressures' work
// on its upwind face volumes, whose difference from those two terms is the discretisation's defect at
// the solid: a pocket of gas in the steel (volume fraction 0.02-0.06 beside cells of less) books the
// steel's GPa face pressures on the volume the advection moves, which can exceed its whole thermal
// energy (the exploding cylinder's energy fallbacks, doc/gas.md). Here each gas gets those two terms,
// and the defect, sum_gases (conservative total - that), goes as heat to the cell's solids by their
// heat capacity (their particles receive it, coupling.cxx): total energy is conserved, and the
// solids' share per kelvin is some thousand times the gas's. Off by default (-ice_solid_cell_energy):
// in the exploding cylinder the defect is not a pocket's alone but positive in every class of solid
// cell, 12.5 % of the chemical energy by 30 us, most of which stays in the particles as heat, and the
// wall's kinetic energy falls by 9.5 %; the gas gun (tests/decks/gas_gun.opts) moves by 0.1 % with
// it (doc/gas.md, "Energy fallbacks").
static void IceSolidCellEnergy(IceSolver &ice, PetscScalar *c, PetscInt idx)
{
  const PetscInt n = ice.nmat, dim = ice.dim;
  PetscReal      mass = 0, momentum[3] = {0, 0, 0}, u_cm[3] = {0, 0, 0};
  for (PetscInt m = 0; m < n; ++m) {
    mass += c[ice.Offset(m, icef::rho_L)];
    for (PetscInt d = 0; d < dim; ++d) momentum[d] += c[ice.Offset(m, icef::rho_L)] * c[ice.Offset(m, icef::vel_L + d)];
  }
  for (PetscInt d = 0; d < dim; ++d) u_cm[d] = momentum[d] / mass;
  PetscReal defect = 0, capacity = 0; // J/m^3, J/(m^3 K)
  for (PetscInt m = 0; m < ice.ngas; ++m) {
    if (IceIsTrace(ice, c, m)) continue;
    const IceMaterial &mat = ice.materials[m];
    const PetscReal    rho = c[ice.Offset(m, icef::rho)], rho_L = c[ice.Offset(m, icef::rho_L)];
    const bool         cold  = mat.eos->HasColdEnergy();
    PetscReal          slip0 = 0, slipL = 0, uL2 = 0;
    for (PetscInt d = 0; d < dim; ++d) {
      const PetscReal u = c[ice.Offset(m, icef::vel + d)], uL = c[ice.Offset(m, icef::vel_L + d)];
      slip0 += (u - u_cm[d]) * (u - u_cm[d]);
      slipL += (uL - u_cm[d]) * (uL - u_cm[d]);
      uL2 += uL * uL;
    }
    // what IceSources gave it (the conservative form, or a fallback)
    const PetscReal total   = rho_L * (mat.eos->cv * (c[ice.Offset(m, icef::temp_L)] + (cold ? c[ice.Offset(m, icef::energy_L)] : 0)) + 0.5 * uL2);
    PetscReal       cold_tf = 0;
    const PetscReal T_tf    = IceTemperatureForm(ice, c, idx, m, cold ? &cold_tf : nullptr);
    // after the exchange (exchange.cxx adds rho |u_L - u_cm|^2 / 2): rho_L (c_v T_tf + e_cold) + rho |u - u_cm|^2 / 2
    const PetscReal internal_L = rho_L * (mat.eos->cv * T_tf + cold_tf) + 0.5 * rho * slip0 - 0.5 * rho_L * slipL;
    defect += total - (internal_L + 0.5 * rho_L * uL2);
    c[ice.Offset(m, icef::temp_L)] = (internal_L / rho_L - cold_tf) / mat.eos->cv;
    if (cold) c[ice.Offset(m, icef::energy_L)] = cold_tf / mat.eos->cv;
  }
  for (PetscInt m = ice.ngas; m < n; ++m) capacity += c[ice.Offset(m, icef::rho_L)] * ice.materials[m].eos->cv;
  for (PetscInt m = ice.ngas; m < n; ++m) c[ice.Offset(m, icef::temp_L)] += defect / capacity;
  ice.solid_cell_energy_transfer += defect * ice.CellVolume();
}

PetscErrorCode IceSources(IceSolver &ice)
{
  PetscScalar   *a;
  const PetscInt S = ice.stride, n = ice.nmat, dim = ice.dim;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ice.ev_sources, 0, 0, 0, 0));
  PetscCall(IceGetLocalArray(ice, &a));
  const bool viscous = ice.viscosity[0] > 0 || ice.viscosity[1] > 0;
  // each face's pressure and shock viscosity once (every face of the owned cells, local index of its
  // upper cell); IceBudgetFaces reads them again
  for (PetscInt d = 0; d < dim; ++d) {
    PetscReal     *p_f = ice.face_pressure[d].data(), *q_f = ice.face_viscosity[d].data();
    const PetscInt st = ice.lstride[d];
    for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2] + (d == 2); ++k)
      for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1] + (d == 1); ++j)
        for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0] + (d == 0); ++i) {
          const PetscInt R = ice.LocalIndex(i, j, k);
          p_f[R]           = IceFacePressure(ice, a, R - st, R);
          q_f[R]           = viscous ? IceFaceViscosity(ice, a, d, R) : 0;
        }
  }
  // the cell exchange follows and gives each material the kinetic energy its drag removes
  const bool drag_settles      = ice.conservative_energy && ice.drag_heating && ice.nmat > 1;
  const bool solid_cell_energy = drag_settles && ice.solid_cell_energy && ice.ngas < ice.nmat;
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        const PetscInt idx = ice.LocalIndex(i, j, k);
        PetscScalar   *c   = a + idx * S;
        // lower, upper face of each direction: pressure, and the shock viscosity the gases feel
        PetscReal grad_p[3] = {0, 0, 0}, p_face[3][2] = {{0, 0}, {0, 0}, {0, 0}}, q_face[3][2] = {{0, 0}, {0, 0}, {0, 0}}, grad_q[3] = {0, 0, 0};
        for (PetscInt d = 0; d < dim; ++d) {
          p_face[d][0] = ice.face_pressure[d][idx];
          p_face[d][1] = ice.face_pressure[d][idx + ice.lstride[d]];
          grad_p[d]    = (p_face[d][1] - p_face[d][0]) / ice.h[d];
          if (viscous) {
            q_face[d][0] = ice.face_viscosity[d][idx];
            q_face[d][1] = ice.face_viscosity[d][idx + ice.lstride[d]];
            grad_q[d]    = (q_face[d][1] - q_face[d][0]) / ice.h[d];
          }
        }
        if (!ice.solid_pressure_dv.empty()) // the pressure source's velocity change of each solid (its work: src/coupling/pressure_work.cxx)
          for (PetscInt m = ice.ngas; m < n; ++m)
            for (PetscInt d = 0; d < 3; ++d) ice.solid_pressure_dv[(idx * (n - ice.ngas) + m - ice.ngas) * 3 + d] = d < dim ? -ice.dt * c[ice.Offset(m, icef::theta)] * grad_p[d] / c[ice.Offset(m, icef::rho)] : 0;
        // several gases in the cell (-ice_mixed_cell_energy): the conservative totals, for the split below
        PetscInt  gases_here = 0;
        PetscReal conservative_total[kIceMaxMaterials];
        bool      split[kIceMaxMaterials];
        if (ice.mixed_cell_energy && ice.conservative_energy)
          for (PetscInt m = 0; m < ice.ngas; ++m) gases_here += !IceIsTrace(ice, c, m);
        const bool mixed = gases_here > 1;
        for (PetscInt m = 0; m < n; ++m) {
          const IceMaterial &mat   = ice.materials[m];
          const PetscReal    rho   = c[ice.Offset(m, icef::rho)];
          const PetscReal    theta = c[ice.Offset(m, icef::theta)];
          if (mixed) split[m] = false;
          // mass conversion (burning, ice.md 2.4): the mass, its momentum and its energy
          const PetscReal  dr           = ice.has_mass_source ? ice.mass_source[idx * n + m] : 0;
          const PetscReal *dmv          = ice.has_mass_source ? &ice.momentum_source[(idx * n + m) * 3] : nullptr;
          const PetscReal  de           = ice.has_mass_source ? ice.energy_source[idx * n + m] : 0;
          const PetscReal  rho_L        = dr < 0 ? PetscMax(rho + dr, ice.rho_tiny / c[ice.Offset(m, icef::spvol)]) : rho + dr;
          c[ice.Offset(m, icef::rho_L)] = rho_L;
          PetscReal u2 = 0, uL2 = 0, ke_in = 0;
          for (PetscInt d = 0; d < 3; ++d) {
            const PetscReal source = d < dim ? -ice.dt * theta * (grad_p[d] + (mat.solid ? 0 : grad_q[d])) + ice.dt * rho * ice.gravity[d] : 0;
            const PetscReal u      = c[ice.Offset(m, icef::vel + d)];
            // mass lost (a burning solid) leaves at the material's own velocity and takes its share
            // of the force: the rest keeps the acceleration of the whole. (With the loss's own
            // momentum, a burnt-out particle's mass taken from a cell that holds less of it left a
            // floored rho_L with a finite momentum: 1e9 m/s on the solid's nodes.)
            const PetscReal uL                = dr < 0 ? (rho > 0 ? u + source / rho : u) : (rho * u + source + (dmv ? dmv[d] : 0)) / rho_L;
            c[ice.Offset(m, icef::vel_L + d)] = uL;
            u2 += u * u;
            uL2 += uL * uL;
            if (dmv && dr > 0) ke_in += 0.5 * dmv[d] * dmv[d] / dr;
          }
          PetscReal  T_L, cold_L = 0; // cold_L: e_cold at the Lagrangian specific volume, J/kg
          bool       cold_from_faces = false, deferred = false;
          const bool cold = !mat.solid && mat.eos->HasColdEnergy();
          if (mat.solid) T_L = c[ice.Offset(m, icef::temp)]; // MPM computes the solid's own work
          else if (IceIsTrace(ice, c, m)) {
            // a trace of gas (a cell the solids fill): no compression work, which would heat a
            // mass of rho_tiny by the solids' pressure changes to absurd temperatures
            T_L = (rho * mat.eos->cv * c[ice.Offset(m, icef::temp)] + de) / (rho_L * mat.eos->cv);
          } else if (ice.conservative_energy) {
            // total energy from the work of the face pressures on the face volume fluxes, plus what
            // the converted mass brings, minus the kinetic energy: conservative, so shocks move at
            // the Rankine-Hugoniot speed
            PetscReal work = 0, expansion = 0; // expansion: the material's volume change over V
            for (PetscInt d = 0; d < dim; ++d) {
              const PetscInt faces[2] = {idx, idx + ice.lstride[d]};
              for (int s = 0; s < 2; ++s) {
                const PetscInt  R = faces[s], L = R - ice.lstride[d];
                const PetscReal u       = ice.face_vel[d][R * n + m];
                const PetscReal theta_f = u > 0 ? a[L * S + ice.Offset(m, icef::theta)] : a[R * S + ice.Offset(m, icef::theta)];
                const PetscReal volume  = (s ? 1 : -1) * ice.dt / ice.h[d] * theta_f * u;
                work -= (p_face[d][s] + q_face[d][s]) * volume;
                expansion += volume;
              }
            }
            if (cold) {
              // e = c_v T + e_cold(rho_micro) (gas_eos.hpp): the work changes e, and the cold part
              // follows the material's own volume, theta + the face volumes (+ the converted mass's)
              const PetscReal e_cold   = mat.eos->ColdEnergy(1 / c[ice.Offset(m, icef::spvol)]);
              const PetscReal theta_L  = theta + expansion + (dr > 0 ? dr * c[ice.Offset(m, icef::spvol)] : 0);
              const PetscReal e_cold_L = theta_L > 0 ? mat.eos->ColdEnergy(rho_L / theta_L) : e_cold;
              const PetscReal total    = rho * (mat.eos->cv * c[ice.Offset(m, icef::temp)] + e_cold + 0.5 * u2) + work + de + ke_in;
              T_L                      = (total / rho_L - 0.5 * uL2 - e_cold_L) / mat.eos->cv;
              cold_L                   = e_cold_L;
              cold_from_faces          = true;
              if (mixed) conservative_total[m] = total, split[m] = true;
            } else {
              const PetscReal total = rho * (mat.eos->cv * c[ice.Offset(m, icef::temp)] + 0.5 * u2) + work + de + ke_in;
              T_L                   = (total / rho_L - 0.5 * uL2) / mat.eos->cv;
              if (mixed) conservative_total[m] = total, split[m] = true;
            }
            // T_L <= 0: the pressure gradient gave the gas more kinetic energy than it holds. In a
            // cell that the momentum exchange settles (a gas in a solid's cell, pushed by the
            // solid's pressure field) the drag gives that energy back (exchange.cxx), which then
            // checks; alone, keep the -p dV form here and count it
            if (!(T_L > 0) && !drag_settles) {
              T_L = IceTemperatureForm(ice, c, idx, m, nullptr);
              IceCountFallback(ice, c, idx);
              cold_from_faces = false;
              if (mixed) split[m] = false;
            }
            deferred = !(T_L > 0);
            if (mixed && deferred) split[m] = false;
          } else T_L = IceTemperatureForm(ice, c, idx, m, nullptr);
          PetscCheck((T_L > 0 || deferred) && std::isfinite(T_L), PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED,
                     "Gas step %" PetscInt_FMT ": the compression work makes the temperature of material %s in cell (%" PetscInt_FMT ", %" PetscInt_FMT ", %" PetscInt_FMT ") %g K; reduce -ice_cfl", ice.step, mat.name.c_str(), i, j, k, (double)T_L);
          if (cold && !cold_from_faces) IceTemperatureForm(ice, c, idx, m, &cold_L);
          c[ice.Offset(m, icef::temp_L)] = T_L;
          // the advection's total energy adds T_L and the kinetic energy to this (advection.cxx)
          if (cold) c[ice.Offset(m, icef::energy_L)] = cold_L / mat.eos->cv;
        }
        // gases in a cell that holds a solid (-ice_solid_cell_energy): see IceSolidCellEnergy
        bool solid_cell = false;
        if (solid_cell_energy) { // a solid that is not a trace, and no mass converted in the cell
          bool burning = false;
          for (PetscInt m = 0; m < n && ice.has_mass_source; ++m) burning = burning || ice.mass_source[idx * n + m] != 0;
          for (PetscInt m = ice.ngas; m < n && !burning; ++m) solid_cell = solid_cell || c[ice.Offset(m, icef::theta)] > ice.trace_fraction;
        }
        if (solid_cell) IceSolidCellEnergy(ice, c, idx);
        else if (mixed) {
          // Several gases: each one's face work follows its own upwind face fractions, which at a
          // contact can be 1e-16 for a gas that holds half the cell and takes theta grad p of
          // momentum: its kinetic energy then comes out of its internal energy (a water-air tube's air
          // at 0.03 K). Instead each gas gets the kinetic energy of its own momentum source and its
          // own compression work (the temperature form), and what the cell's face works hold beyond
          // those, a conservation defect, is shared by heat capacity rho_L c_v: total energy stays
          // conservative, and a light gas is not charged a heavy one's defect.
          PetscReal defect = 0, capacity = 0, consistent[kIceMaxMaterials], cold_tf[kIceMaxMaterials], kinetic[kIceMaxMaterials];
          for (PetscInt m = 0; m < ice.ngas; ++m) {
            if (!split[m]) continue;
            const IceMaterial &mat   = ice.materials[m];
            const PetscReal    rho_L = c[ice.Offset(m, icef::rho_L)];
            PetscReal          uL2   = 0;
            for (PetscInt d = 0; d < dim; ++d) uL2 += c[ice.Offset(m, icef::vel_L + d)] * c[ice.Offset(m, icef::vel_L + d)];
            kinetic[m]           = 0.5 * uL2; // J/kg
            cold_tf[m]           = 0;
            const PetscReal T_tf = IceTemperatureForm(ice, c, idx, m, mat.eos->HasColdEnergy() ? &cold_tf[m] : nullptr);
            consistent[m]        = rho_L * (mat.eos->cv * T_tf + cold_tf[m] + kinetic[m]);
            defect += conservative_total[m] - consistent[m];
            capacity += rho_L * mat.eos->cv;
          }
          PetscReal T_split[kIceMaxMaterials];
          bool      valid = true;
          for (PetscInt m = 0; m < ice.ngas; ++m) {
            if (!split[m]) continue;
            const IceMaterial &mat   = ice.materials[m];
            const PetscReal    rho_L = c[ice.Offset(m, icef::rho_L)];
            const PetscReal    total = consistent[m] + defect * rho_L * mat.eos->cv / capacity;
            T_split[m]               = (total / rho_L - kinetic[m] - cold_tf[m]) / mat.eos->cv;
            valid                    = valid && T_split[m] > 0 && std::isfinite(T_split[m]);
          }
          for (PetscInt m = 0; valid && m < ice.ngas; ++m) { // else each keeps its own face work's (checked above)
            if (!split[m]) continue;
            c[ice.Offset(m, icef::temp_L)] = T_split[m];
            if (ice.materials[m].eos->HasColdEnergy()) c[ice.Offset(m, icef::energy_L)] = cold_tf[m] / ice.materials[m].eos->cv;
          }
        }
      }
  PetscCall(IceRestoreLocalArray(ice, &a));
  PetscCall(PetscLogEventEnd(ice.ev_sources, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
