// Convective heat transfer at the solids' surfaces (-coupling_surface_heat_transfer h, W/(m^2 K)).
//
// Why: the gas is inviscid and does not conduct, and the drag holds the gas of a solid's surface
// cells to the solid's velocity, so those cells keep the gas they started with and the cell exchange
// (-ice_exchange_heat_solid) only equilibrates the solid with that trapped gas: a 1800 K jet gives a
// 300 K container under 1 % of the heat a convective correlation predicts (the fire scene,
// options/scenes/pool_fire2d.opts). The reference code has the same cure (MPMICE
// do_convective_heat_transfer: a solid surface cell exchanges heat with the gas one cell outward).
//
// Here, per cell c holding solid (theta_s = sum of the solids' volume fractions):
//   the surface in the cell   A_c = V |g|, g_d = the drops of theta_s to the lower neighbours along d
//                             over h_d (a monotone profile telescopes: the surfaces sum to the
//                             outline; a trace of solid beside a body takes none; in 2-D per metre)
//   the outward normal        n = -grad theta_s / |grad theta_s| (central differences)
//   the gas it faces          the cell two cells out along n (c + round(2 n)), its gases' M c_v-weighted
//                             Lagrangian temperature T_g; only where the solid thins along the way
//                             (a dip between two solids is no outer surface)
//   the heat                  Q_c = h A_c (T_g - T_s,c) dt, capped at half of what would equalise
//                             the two heat capacities (an explicit exchange cannot overshoot)
// The solids of c share Q_c as they make up the solid one cell out along n (the solid the gas meets;
// their Lagrangian temperatures, which reach the particles through CouplingIncrementsToNodes and
// CouplingHeatToParticles); the gases of the far
// cell lose it by M c_v (temperature and total energy), summed over the ranks through a cell DMDA.
// Total energy is conserved to round-off. Runs after the cell exchange, before its budget mark.
#include "coupling_impl.hpp"
#include "util.hpp"
#include <cmath>

namespace burst {

PetscErrorCode CouplingSurfaceHeatSetUp(Coupling &c)
{
  MpmSolver &mpm = *c.mpm;
  PetscFunctionBeginUser;
  if (c.surface_h > 0) {
    PetscCheck(!mpm.axisymmetric, mpm.comm, PETSC_ERR_SUP, "Option -coupling_surface_heat_transfer is not supported with -axisymmetric yet");
    PetscCall(DMDACreateCompatibleDMDA(c.ice->da, 1, &c.da_surface));
    PetscCall(DMCreateGlobalVector(c.da_surface, &c.surface_global));
    PetscCall(DMCreateLocalVector(c.da_surface, &c.surface_local));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CouplingSurfaceHeat(Coupling &c)
{
  IceSolver   &ice = *c.ice;
  PetscScalar *a, *sink;
  PetscFunctionBeginUser;
  if (c.surface_h <= 0) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogEventBegin(c.ev_surface, 0, 0, 0, 0));
  const PetscInt  S = ice.stride, dim = ice.dim;
  const PetscReal V = ice.CellVolume();

  auto solid_fraction = [&](const PetscScalar *cell) {
    PetscReal theta = 0;
    for (PetscInt s = 0; s < c.nsolid; ++s) theta += cell[ice.Offset(c.first + s, icef::theta)];
    return theta;
  };
  PetscCall(VecZeroEntries(c.surface_local));
  PetscCall(VecGetArray(c.surface_local, &sink));
  PetscCall(IceGetLocalArray(ice, &a));
  PetscReal given = 0;
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        const PetscInt  idx   = ice.LocalIndex(i, j, k);
        PetscScalar    *cell  = a + idx * S;
        const PetscReal theta = solid_fraction(cell);
        if (!(theta > 0)) continue;
        const PetscInt ijk[3]  = {i, j, k};
        PetscReal      grad[3] = {0, 0, 0}, drop[3] = {0, 0, 0}, norm = 0;
        for (PetscInt d = 0; d < dim; ++d) {
          // the direction from central differences (one-sided at a domain face); the size from the
          // drops to lower neighbours, so the surface sums to the body's outline (a 1-D profile
          // telescopes) and a cell with a mere trace of solid beside a body takes none of it
          const bool      lo = ijk[d] > 0, hi = ijk[d] < ice.cells[d] - 1;
          const PetscReal up = hi ? solid_fraction(a + (idx + ice.lstride[d]) * S) : theta;
          const PetscReal dn = lo ? solid_fraction(a + (idx - ice.lstride[d]) * S) : theta;
          grad[d]            = (up - dn) / (((lo ? 1 : 0) + (hi ? 1 : 0)) * ice.h[d]);
          drop[d]            = (PetscMax(0, theta - up) + PetscMax(0, theta - dn)) / ice.h[d];
          norm += drop[d] * drop[d];
        }
        norm            = std::sqrt(norm);
        PetscReal gnorm = 0;
        for (PetscInt d = 0; d < dim; ++d) gnorm += grad[d] * grad[d];
        gnorm = std::sqrt(gnorm);
        if (!(norm > 0 && gnorm > 0)) continue;
        PetscInt far[3] = {i, j, k}, mid[3] = {i, j, k};
        bool     inside = true;
        for (PetscInt d = 0; d < dim; ++d) {
          far[d] += (PetscInt)std::lround(-2 * grad[d] / gnorm);
          mid[d] += (PetscInt)std::lround(-grad[d] / gnorm);
          inside = inside && far[d] >= 0 && far[d] < ice.cells[d];
        }
        if (!inside) continue;
        const PetscInt     fidx = ice.LocalIndex(far[0], far[1], far[2]);
        const PetscScalar *fc   = a + fidx * S;
        // an outer surface only: the solid thins along the ray (a dip between two solids, e.g. the
        // gas pockets between wall and charge, is not one, though the gas beyond a thin wall is hot)
        const PetscReal theta_mid = solid_fraction(a + ice.LocalIndex(mid[0], mid[1], mid[2]) * S);
        if (theta_mid > theta + 0.01 || solid_fraction(fc) > theta_mid + 0.01) continue; // (0.01: the fractions' small ripples)
        PetscReal Cg = 0, CgT = 0, Cs = 0, CsT = 0;
        for (PetscInt g = 0; g < ice.ngas; ++g) {
          const PetscReal C = fc[ice.Offset(g, icef::rho_L)] * V * ice.materials[g].eos->cv;
          Cg += C;
          CgT += C * fc[ice.Offset(g, icef::temp_L)];
        }
        for (PetscInt s = 0; s < c.nsolid; ++s) {
          const PetscInt  m = c.first + s;
          const PetscReal C = cell[ice.Offset(m, icef::rho)] * V * ice.materials[m].eos->cv; // (the mass the nodes convert its temperature change with)
          Cs += C;
          CsT += C * cell[ice.Offset(m, icef::temp_L)];
        }
        if (!(Cg > 0 && Cs > 0)) continue;
        const PetscReal Tg = CgT / Cg, Ts = CsT / Cs;
        PetscReal       Q = c.surface_h * V * norm * (Tg - Ts) * ice.dt;
        // (a quarter: several surface cells may face the same gas cell)
        const PetscReal cap = 0.25 * std::fabs(Tg - Ts) * Cg * Cs / (Cg + Cs);
        Q                   = PetscMax(-cap, PetscMin(cap, Q));
        // The solids share it as they make up the solid one cell further out (the one the gas meets;
        // on a coarse grid a thin wall's surface cells also hold the charge behind it, which must not
        // take the fire's heat), or this cell's solid if that cell holds none of them.
        // Only the particles' part of a cell's solid mass carries heat to them (the projection adds
        // a floor of rho_tiny rho0 V that no particle holds).
        const PetscScalar *mc = a + ice.LocalIndex(mid[0], mid[1], mid[2]) * S;
        PetscReal          weight[kIceMaxMaterials], carried[kIceMaxMaterials], total = 0;
        for (PetscInt s = 0; s < c.nsolid; ++s) carried[s] = cell[ice.Offset(c.first + s, icef::rho)] * V - ice.rho_tiny * c.rho0[s] * V;
        for (int pass = 0; pass < 2 && !(total > 0); ++pass)
          for (PetscInt s = 0; s < c.nsolid; ++s) {
            weight[s] = carried[s] > ice.rho_tiny * c.rho0[s] * V ? (pass ? cell : mc)[ice.Offset(c.first + s, icef::theta)] : 0;
            total += weight[s];
          }
        if (!(total > 0)) continue;
        for (PetscInt s = 0; s < c.nsolid; ++s) {
          const PetscInt m = c.first + s;
          if (weight[s] > 0) cell[ice.Offset(m, icef::temp_L)] += weight[s] / total * Q / (carried[s] * ice.materials[m].eos->cv);
        }
        sink[fidx] += Q;
        given += Q;
      }
  PetscCall(VecRestoreArray(c.surface_local, &sink));
  PetscCall(VecZeroEntries(c.surface_global));
  PetscCall(DMLocalToGlobal(c.da_surface, c.surface_local, ADD_VALUES, c.surface_global));
  const PetscScalar *owned;
  PetscCall(VecGetArrayRead(c.surface_global, &owned));
  PetscInt l = 0;
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i, ++l) {
        if (owned[l] == 0) continue;
        PetscScalar *cell = a + ice.LocalIndex(i, j, k) * S;
        PetscReal    Cg   = 0;
        for (PetscInt g = 0; g < ice.ngas; ++g) Cg += cell[ice.Offset(g, icef::rho_L)] * V * ice.materials[g].eos->cv;
        const PetscReal dT = owned[l] / Cg; // every gas of the cell by the same temperature: M c_v shares
        for (PetscInt g = 0; g < ice.ngas; ++g) {
          cell[ice.Offset(g, icef::temp_L)] -= dT;
          cell[ice.Offset(g, icef::energy_L)] -= dT;
        }
      }
  PetscCall(VecRestoreArrayRead(c.surface_global, &owned));
  PetscCall(IceRestoreLocalArray(ice, &a));
  PetscCall(IceUpdateGhosts(ice));
  c.surface_heat += given;
  PetscCall(PetscLogEventEnd(c.ev_surface, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CouplingSurfaceHeatTotal(Coupling &c, PetscReal *total)
{
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(&c.surface_heat, total, 1, MPIU_REAL, MPI_SUM, c.mpm->comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
