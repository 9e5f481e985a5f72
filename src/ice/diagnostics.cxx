// Gas totals for the monitor (mass, momentum, internal and kinetic energy), the budget of the domain
// faces (what the gas takes out through open faces, the face pressure's impulse) and the profile of
// a run along x (profile.csv), written atomically by rank 0.
#include "ice.hpp"
#include <algorithm>
#include <cstdio>

namespace burst {

PetscErrorCode IceComputeTotals(IceSolver &ice, IceTotals &t)
{
  PetscScalar *a;
  PetscReal    local[6] = {0, 0, 0, 0, 0, 0}, global[6], max[2] = {0, 0}, global_max[2]; // the largest pressure and gas temperature
  PetscFunctionBeginUser;
  PetscCall(IceGetLocalArray(ice, &a));
  const PetscReal V = ice.CellVolume();
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        const PetscScalar *c = a + ice.LocalIndex(i, j, k) * ice.stride;
        max[0]               = PetscMax(max[0], c[ice.CellOffset(icef::press)]);
        for (PetscInt m = 0; m < ice.ngas; ++m) {
          const PetscReal M  = c[ice.Offset(m, icef::rho)] * V;
          PetscReal       u2 = 0;
          local[0] += M;
          if (c[ice.Offset(m, icef::theta)] >= ice.trace_fraction) max[1] = PetscMax(max[1], c[ice.Offset(m, icef::temp)]);
          for (PetscInt d = 0; d < ice.dim; ++d) {
            const PetscReal u = c[ice.Offset(m, icef::vel + d)];
            local[1 + d] += M * u;
            u2 += u * u;
          }
          // e(rho_micro, T) = c_v T + e_cold(rho_micro), at the material density of the last equilibration
          local[4] += M * ice.materials[m].eos->InternalEnergy(1 / c[ice.Offset(m, icef::spvol)], c[ice.Offset(m, icef::temp)]);
          local[5] += 0.5 * M * u2;
        }
      }
  PetscCall(IceRestoreLocalArray(ice, &a));
  PetscCallMPI(MPI_Allreduce(local, global, 6, MPIU_REAL, MPI_SUM, ice.comm));
  PetscCallMPI(MPI_Allreduce(max, global_max, 2, MPIU_REAL, MPI_MAX, ice.comm));
  t.max_pressure    = global_max[0];
  t.max_temperature = global_max[1];
  t.mass            = global[0];
  for (int d = 0; d < 3; ++d) t.momentum[d] = global[1 + d];
  t.internal_energy = global[4];
  t.kinetic_energy  = global[5];
  PetscFunctionReturn(PETSC_SUCCESS);
}

// The Lagrangian total energy of every material in the owned cells, rho_L V (c_v T_L + e_cold,L +
// |u_L|^2/2) (the cells' view of the solids too), between the sources and the advection.
static PetscReal LagrangianEnergy(const IceSolver &ice, const PetscScalar *a)
{
  PetscReal       sum = 0, cv[kIceMaxMaterials];
  bool            cold[kIceMaxMaterials]; // IceSources leaves e_cold,L / c_v in energy_L
  const PetscReal V = ice.CellVolume();
  for (PetscInt m = 0; m < ice.nmat; ++m) {
    cv[m]   = ice.materials[m].eos->cv;
    cold[m] = !ice.materials[m].solid && ice.materials[m].eos->HasColdEnergy();
  }
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        const PetscScalar *c = a + ice.LocalIndex(i, j, k) * ice.stride;
        for (PetscInt m = 0; m < ice.nmat; ++m) {
          PetscReal uL2 = 0;
          for (PetscInt d = 0; d < ice.dim; ++d) uL2 += c[ice.Offset(m, icef::vel_L + d)] * c[ice.Offset(m, icef::vel_L + d)];
          sum += V * c[ice.Offset(m, icef::rho_L)] * (cv[m] * (c[ice.Offset(m, icef::temp_L)] + (cold[m] ? c[ice.Offset(m, icef::energy_L)] : 0)) + 0.5 * uL2);
        }
      }
  return sum;
}

// e(rho_micro, T) = c_v T + e_cold(rho_micro) of gas m in cell c (c_v T alone, exactly, without a cold energy)
static inline PetscReal CellInternalEnergy(const IceSolver &ice, const PetscScalar *c, PetscInt m, bool cold)
{
  const GasEOS &eos = *ice.materials[m].eos;
  return cold ? eos.InternalEnergy(1 / c[ice.Offset(m, icef::spvol)], c[ice.Offset(m, icef::temp)]) : eos.cv * c[ice.Offset(m, icef::temp)];
}

PetscErrorCode IceBudgetAfterExchange(IceSolver &ice)
{
  const PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ice.ev_budget, 0, 0, 0, 0));
  PetscCall(VecGetArrayRead(ice.local, &a));
  ice.exchange_energy_change += LagrangianEnergy(ice, a) - ice.exchange_energy_mark;
  PetscCall(VecRestoreArrayRead(ice.local, &a));
  PetscCall(PetscLogEventEnd(ice.ev_budget, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IceBudgetStepStart(IceSolver &ice)
{
  const PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ice.ev_budget, 0, 0, 0, 0));
  if (ice.gas_energy_after_step == ice.step) { // nothing changed the gases since the last advection summed them
    ice.gas_energy_mark = ice.gas_energy_after;
    PetscCall(PetscLogEventEnd(ice.ev_budget, 0, 0, 0, 0));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(VecGetArrayRead(ice.local, &a));
  ice.gas_energy_mark = 0;
  bool            cold[kIceMaxMaterials];
  const PetscReal V = ice.CellVolume();
  for (PetscInt m = 0; m < ice.ngas; ++m) cold[m] = ice.materials[m].eos->HasColdEnergy();
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        const PetscScalar *c = a + ice.LocalIndex(i, j, k) * ice.stride;
        for (PetscInt m = 0; m < ice.ngas; ++m) {
          PetscReal u2 = 0;
          for (PetscInt d = 0; d < ice.dim; ++d) u2 += c[ice.Offset(m, icef::vel + d)] * c[ice.Offset(m, icef::vel + d)];
          ice.gas_energy_mark += V * c[ice.Offset(m, icef::rho)] * (CellInternalEnergy(ice, c, m, cold[m]) + 0.5 * u2);
        }
      }
  PetscCall(VecRestoreArrayRead(ice.local, &a));
  PetscCall(PetscLogEventEnd(ice.ev_budget, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IceBudgetFaces(IceSolver &ice)
{
  const PetscScalar *a;
  const PetscInt     S = ice.stride, n = ice.nmat;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ice.ev_budget, 0, 0, 0, 0));
  PetscCall(VecGetArrayRead(ice.local, &a));
  // the face pressure of IceSources (sources.cxx), which kept it per face, and the shock viscosity
  // that the gases (not the solids) feel there
  const PetscReal V = ice.CellVolume();
  // One pass over the owned cells for the budgets' report (not their sums): the solids' kinetic energy
  // from IceSources' -dt theta_s grad p; the gases' face work that only one side of an interior face
  // books (IceSources leaves it out where the gas is a trace, as in a cell a solid fills: the
  // conservative form's face work cancels between two cells only where both book it); and what
  // IceSources gave each gas beyond its conservative terms, its total energy change M_L (c_v T_L +
  // e_cold,L + |u_L|^2/2) - M (c_v T + e_cold + |u|^2/2) less the converted mass's energy and kinetic
  // energy and less the face work it books: in a cell that books it, a -p dV fallback; elsewhere a
  // trace's pressure acceleration without work. (A total-energy temperature that stays negative for
  // the exchange is the exchange's fallback, exchange.cxx.)
  auto      booked = [&](const PetscScalar *c, PetscInt m) { return ice.conservative_energy && !IceIsTrace(ice, c, m); };
  PetscReal energy = 0; // the gases' total energy as IceSources found it, against the step's start
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        const PetscInt     idx          = ice.LocalIndex(i, j, k);
        const PetscScalar *c            = a + idx * S;
        const PetscInt     ijk[3]       = {i, j, k};
        PetscReal          p_face[3][2] = {{0, 0}, {0, 0}, {0, 0}}, q_face[3][2] = {{0, 0}, {0, 0}, {0, 0}};
        for (PetscInt d = 0; d < ice.dim; ++d) {
          p_face[d][0] = ice.face_pressure[d][idx];
          p_face[d][1] = ice.face_pressure[d][idx + ice.lstride[d]];
          q_face[d][0] = ice.face_viscosity[d][idx];
          q_face[d][1] = ice.face_viscosity[d][idx + ice.lstride[d]];
        }
        for (PetscInt m = 0; m < ice.ngas; ++m) {
          const bool here = booked(c, m);
          PetscReal  work = 0; // per volume, as IceSources
          for (PetscInt d = 0; d < ice.dim; ++d)
            for (int side = 0; side < 2; ++side) {
              const PetscInt  R = side ? idx + ice.lstride[d] : idx, L = R - ice.lstride[d];
              const PetscReal u = ice.face_vel[d][R * n + m], theta_f = u > 0 ? a[L * S + ice.Offset(m, icef::theta)] : a[R * S + ice.Offset(m, icef::theta)];
              const PetscReal dw = ice.dt / ice.h[d] * (p_face[d][side] + q_face[d][side]) * theta_f * u;
              if (here) work -= (side ? 1 : -1) * dw;
              if (!side && ijk[d] > 0 && booked(a + L * S, m) != here) ice.gas_interface_work += (here ? 1 : -1) * V * dw; // the lower face: every interior face once
            }
          const GasEOS &eos  = *ice.materials[m].eos;
          const bool    cold = eos.HasColdEnergy(); // IceSources leaves e_cold,L / c_v in energy_L
          PetscReal     u2 = 0, uL2 = 0, converted = 0;
          for (PetscInt d = 0; d < ice.dim; ++d) {
            u2 += c[ice.Offset(m, icef::vel + d)] * c[ice.Offset(m, icef::vel + d)];
            uL2 += c[ice.Offset(m, icef::vel_L + d)] * c[ice.Offset(m, icef::vel_L + d)];
          }
          if (ice.has_mass_source) { // as IceSources: the energy source and the kinetic energy of the mass gained
            const PetscReal  dr  = ice.mass_source[idx * n + m];
            const PetscReal *dmv = &ice.momentum_source[(idx * n + m) * 3];
            converted            = ice.energy_source[idx * n + m];
            for (PetscInt d = 0; d < 3 && dr > 0; ++d) converted += 0.5 * dmv[d] * dmv[d] / dr;
          }
          const PetscReal e   = eos.cv * c[ice.Offset(m, icef::temp)] + (cold ? eos.ColdEnergy(1 / c[ice.Offset(m, icef::spvol)]) : 0);
          const PetscReal e_L = eos.cv * (c[ice.Offset(m, icef::temp_L)] + (cold ? c[ice.Offset(m, icef::energy_L)] : 0));
          energy += V * c[ice.Offset(m, icef::rho)] * (e + 0.5 * u2);
          const PetscReal made = V * (c[ice.Offset(m, icef::rho_L)] * (e_L + 0.5 * uL2) - c[ice.Offset(m, icef::rho)] * (e + 0.5 * u2) - converted - work);
          if (here) ice.fallback_energy_change += made;
          else ice.trace_energy_change += made;
        }
        for (PetscInt m = ice.ngas; m < n; ++m) {
          const PetscReal rho = c[ice.Offset(m, icef::rho)], theta = c[ice.Offset(m, icef::theta)];
          for (PetscInt d = 0; d < ice.dim; ++d) {
            const PetscReal source = -ice.dt * theta * (p_face[d][1] - p_face[d][0]) / ice.h[d]; // momentum per volume
            ice.solid_pressure_work += V * source * (c[ice.Offset(m, icef::vel + d)] + 0.5 * source / rho);
          }
        }
      }
  // the equilibration (and the pressure) keep each gas's mass, velocity and, at its new specific
  // volume, its e: what they changed
  ice.equilibration_energy_change += energy - ice.gas_energy_mark;
  // the domain faces
  for (PetscInt d = 0; d < ice.dim; ++d)
    for (int s = 0; s < 2; ++s) {
      if (!(s == 0 ? ice.xs[d] == 0 : ice.xs[d] + ice.xm[d] == ice.cells[d])) continue; // not this rank's face
      const PetscReal A = V / ice.h[d], outward = s ? 1 : -1;
      PetscInt        lo[3], hi[3];
      for (PetscInt e = 0; e < 3; ++e) {
        lo[e] = ice.xs[e];
        hi[e] = ice.xs[e] + ice.xm[e];
      }
      lo[d] = s ? ice.cells[d] - 1 : 0;
      hi[d] = lo[d] + 1;
      for (PetscInt k = lo[2]; k < hi[2]; ++k)
        for (PetscInt j = lo[1]; j < hi[1]; ++j)
          for (PetscInt i = lo[0]; i < hi[0]; ++i) {
            const PetscInt  idx = ice.LocalIndex(i, j, k), ghost = s ? idx + ice.lstride[d] : idx - ice.lstride[d];
            const PetscInt  L = s ? idx : ghost, R = s ? ghost : idx;                  // the face's cells; its velocity is stored with R
            const PetscReal p = ice.face_pressure[d][R], q = ice.face_viscosity[d][R]; // (L, R)
            for (PetscInt m = 0; m < n; ++m) {
              const PetscReal theta = a[idx * S + ice.Offset(m, icef::theta)], p_felt = m < ice.ngas ? p + q : p;
              ice.boundary.impulse[d] -= outward * ice.dt * theta * p_felt * A; // -dt theta grad (p + q): the face's share
              // the face work of the conservative energy form (gases that are not a trace only, as IceSources)
              if (m >= ice.ngas || !ice.conservative_energy || IceIsTrace(ice, a + idx * S, m)) continue;
              const PetscReal u       = ice.face_vel[d][R * n + m];
              const PetscReal theta_f = u > 0 ? a[L * S + ice.Offset(m, icef::theta)] : a[R * S + ice.Offset(m, icef::theta)];
              ice.boundary.work += outward * ice.dt * A * p_felt * theta_f * u;
            }
          }
    }
  ice.exchange_energy_mark = LagrangianEnergy(ice, a); // (IceBudgetAfterExchange)
  PetscCall(VecRestoreArrayRead(ice.local, &a));
  PetscCall(PetscLogEventEnd(ice.ev_budget, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IceBudgetOpenFaces(IceSolver &ice)
{
  const PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ice.ev_budget, 0, 0, 0, 0));
  const PetscReal V     = ice.CellVolume();
  const bool      total = ice.advect_total_energy;
  PetscReal       out   = 0; // the energy this advection carried out
  for (PetscInt m = 0; m < ice.ngas; ++m) {
    PetscReal *f = ice.boundary_flux[m]; // density, momentum (dim), energy (or temperature) over c_v, ...
    ice.boundary.mass += V * f[0];
    for (PetscInt d = 0; d < ice.dim; ++d) ice.boundary.momentum[d] += V * f[1 + d];
    // total energy: c_v T + e_cold + |u|^2/2 is what the advection carries (with
    // -ice_advect_total_energy 0 the thermal energy c_v T only: that form does not conserve the total)
    out += V * ice.materials[m].eos->cv * f[1 + ice.dim];
    for (int q = 0; q < kIceBoundaryFluxes; ++q) f[q] = 0;
  }
  for (PetscInt d = 0; d < ice.dim; ++d)
    for (int s = 0; s < 2; ++s) {
      ice.boundary.face_mass[d][s] += V * ice.boundary_face_mass_flux[2 * d + s];
      ice.boundary_face_mass_flux[2 * d + s] = 0;
    }
  ice.boundary.energy += out;
  // what the advection did not conserve: the total energy M (c_v T + e_cold + |u|^2/2) after it (as
  // IceComputeTotals), plus what left, less the Lagrangian one it advected (the L fields are still
  // there); the conservative remap changes it by round-off, its dual-energy fallbacks and trace resets
  // by what they replace
  PetscReal change = out, after = 0; // after: the next step's mark (IceBudgetStepStart), summed as it sums it
  bool      cold[kIceMaxMaterials];
  for (PetscInt m = 0; m < ice.ngas; ++m) cold[m] = ice.materials[m].eos->HasColdEnergy();
  PetscCall(VecGetArrayRead(ice.local, &a));
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        const PetscScalar *c = a + ice.LocalIndex(i, j, k) * ice.stride;
        for (PetscInt m = 0; m < ice.ngas; ++m) {
          const GasEOS &eos = *ice.materials[m].eos;
          PetscReal     u2 = 0, uL2 = 0;
          for (PetscInt d = 0; d < ice.dim; ++d) {
            u2 += c[ice.Offset(m, icef::vel + d)] * c[ice.Offset(m, icef::vel + d)];
            uL2 += c[ice.Offset(m, icef::vel_L + d)] * c[ice.Offset(m, icef::vel_L + d)];
          }
          // energy_L: the advected (T_L + e_cold,L/c_v + |u_L|^2/(2 c_v)) with total energy, else e_cold,L/c_v (sources.cxx)
          const PetscReal E_L = total ? eos.cv * c[ice.Offset(m, icef::energy_L)] : eos.cv * (c[ice.Offset(m, icef::temp_L)] + (cold[m] ? c[ice.Offset(m, icef::energy_L)] : 0)) + 0.5 * uL2;
          const PetscReal E   = V * c[ice.Offset(m, icef::rho)] * (CellInternalEnergy(ice, c, m, cold[m]) + 0.5 * u2);
          change -= V * c[ice.Offset(m, icef::rho_L)] * E_L;
          change += E;
          after += E;
        }
      }
  PetscCall(VecRestoreArrayRead(ice.local, &a));
  ice.advection_energy_change += change;
  ice.gas_energy_after      = after;
  ice.gas_energy_after_step = ice.step + 1; // (the callers advance ice.step after this)
  PetscCall(PetscLogEventEnd(ice.ev_budget, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// profile.csv: x, pressure, then per material density (bulk, M/V), x-velocity, temperature and
// volume fraction, one row per cell of the first row of cells along x (j = k = 0).
PetscErrorCode IceWriteProfile(IceSolver &ice, const std::string &file, PetscReal time, PetscInt step)
{
  PetscScalar *a;
  PetscMPIInt  rank, size;
  const int    per_cell = 2 + 4 * (int)ice.nmat;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(ice.comm, &rank));
  PetscCallMPI(MPI_Comm_size(ice.comm, &size));
  std::vector<PetscReal> rows;
  PetscCall(IceGetLocalArray(ice, &a));
  if (ice.xs[1] == 0 && ice.xs[2] == 0)
    for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
      const PetscScalar *c = a + ice.LocalIndex(i, 0, 0) * ice.stride;
      rows.push_back(ice.lower[0] + (i + 0.5) * ice.h[0]);
      rows.push_back(c[ice.CellOffset(icef::press)]);
      for (PetscInt m = 0; m < ice.nmat; ++m) {
        rows.push_back(c[ice.Offset(m, icef::rho)]);
        rows.push_back(c[ice.Offset(m, icef::vel)]);
        rows.push_back(c[ice.Offset(m, icef::temp)]);
        rows.push_back(c[ice.Offset(m, icef::theta)]);
      }
    }
  PetscCall(IceRestoreLocalArray(ice, &a));
  int              count = (int)rows.size();
  std::vector<int> counts(size), displs(size);
  PetscCallMPI(MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, ice.comm));
  std::vector<PetscReal> all;
  if (!rank) {
    int total = 0;
    for (int r = 0; r < size; ++r) {
      displs[r] = total;
      total += counts[r];
    }
    all.resize(total);
  }
  PetscCallMPI(MPI_Gatherv(rows.data(), count, MPIU_REAL, all.data(), counts.data(), displs.data(), MPIU_REAL, 0, ice.comm));
  if (!rank) {
    const size_t        ncells = all.size() / per_cell;
    std::vector<size_t> order(ncells);
    for (size_t r = 0; r < ncells; ++r) order[r] = r;
    std::sort(order.begin(), order.end(), [&](size_t p, size_t q) { return all[p * per_cell] < all[q * per_cell]; });
    const std::string tmp = file + ".tmp";
    FILE             *fp  = std::fopen(tmp.c_str(), "w");
    PetscCheck(fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Could not write %s", tmp.c_str());
    std::fprintf(fp, "# time %.17g step %" PetscInt_FMT "\nx,pressure", (double)time, step);
    for (const IceMaterial &m : ice.materials) std::fprintf(fp, ",%s_density,%s_velocity,%s_temperature,%s_volume_fraction", m.name.c_str(), m.name.c_str(), m.name.c_str(), m.name.c_str());
    std::fprintf(fp, "\n");
    for (size_t r : order) {
      for (int q = 0; q < per_cell; ++q) std::fprintf(fp, q ? ",%.17g" : "%.17g", (double)all[r * per_cell + q]);
      std::fprintf(fp, "\n");
    }
    PetscCheck(std::fclose(fp) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Could not write %s", tmp.c_str());
    PetscCheck(std::rename(tmp.c_str(), file.c_str()) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Could not rename %s to %s", tmp.c_str(), file.c_str());
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IceMakeRoomForSolids(IceSolver &ice, const std::vector<PetscReal> &solid_fraction)
{
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(IceGetLocalArray(ice, &a));
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        const PetscInt  idx  = ice.LocalIndex(i, j, k);
        const PetscReal keep = PetscMax(1 - solid_fraction[idx], 0.0);
        PetscScalar    *c    = a + idx * ice.stride;
        for (PetscInt m = 0; m < ice.ngas; ++m) {
          const PetscReal floor       = ice.rho_tiny / c[ice.Offset(m, icef::spvol)];
          c[ice.Offset(m, icef::rho)] = PetscMax(c[ice.Offset(m, icef::rho)] * keep, floor);
        }
      }
  PetscCall(IceRestoreLocalArray(ice, &a));
  PetscCall(IceUpdateGhosts(ice));
  PetscCall(IceComputeTotals(ice, ice.initial));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
