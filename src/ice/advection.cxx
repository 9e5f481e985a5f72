// Advection of the gas (ice.md 1.9, step 17) and the advection operator that the pressure
// equation also uses for its upwind volume fractions.
//
// Slab volumes, directionally unsplit, no corner fluxes: the volume leaving cell c through face f
// in one step is |u_f| dt A_f when u_f points out of c. First order carries the donor cell's value;
// second order carries the value at the slab's centroid from a limited linear reconstruction
// (central differences, Barth-Jespersen limiter on the cell's vertices with the bounds of its face
// neighbours). Compatible fluxes (VanderHeyden & Kashiwa 1998) reconstruct a mass-specific q
// (velocity, temperature, specific volume) as rho_slab q_c + rho_c grad q . r, which keeps q
// bounded across steep density jumps. Each face flux is one number used by both of its cells, so
// mass, momentum and energy are conserved to round-off.
#include "ice.hpp"
#include <cmath>

namespace burst {

namespace {

// The box of donor cells: owned cells and one layer around them.
void DonorBox(const IceSolver &ice, PetscInt lo[3], PetscInt hi[3])
{
  for (PetscInt d = 0; d < 3; ++d) {
    if (d < ice.dim) {
      lo[d] = PetscMax(ice.xs[d] - 1, ice.gxs[d] + 1);
      hi[d] = PetscMin(ice.xs[d] + ice.xm[d] + 1, ice.gxs[d] + ice.gxm[d] - 1);
    } else {
      lo[d] = ice.xs[d];
      hi[d] = ice.xs[d] + ice.xm[d];
    }
  }
}

// Limited gradient of value(idx) at every donor cell, into grad[3 idx + d].
template <int DIM, class Value>
void LimitedGradient(const IceSolver &ice, Value value, PetscReal *grad)
{
  PetscInt lo[3], hi[3];
  DonorBox(ice, lo, hi);
  for (PetscInt k = lo[2]; k < hi[2]; ++k)
    for (PetscInt j = lo[1]; j < hi[1]; ++j)
      for (PetscInt i = lo[0]; i < hi[0]; ++i) {
        const PetscInt  idx  = ice.LocalIndex(i, j, k);
        const PetscReal q    = value(idx);
        PetscReal       qmax = q, qmin = q, g[3] = {0, 0, 0}, reach = 0;
        for (PetscInt d = 0; d < DIM; ++d) {
          const PetscReal qm = value(idx - ice.lstride[d]), qp = value(idx + ice.lstride[d]);
          g[d] = (qp - qm) / (2 * ice.h[d]);
          qmax = PetscMax(qmax, PetscMax(qm, qp));
          qmin = PetscMin(qmin, PetscMin(qm, qp));
          reach += std::fabs(g[d]) * 0.5 * ice.h[d]; // largest vertex deviation
        }
        PetscReal alpha = 1;
        if (reach > 0) alpha = PetscMin(1.0, PetscMin((qmax - q) / reach, (q - qmin) / reach));
        for (PetscInt d = 0; d < 3; ++d) grad[3 * idx + d] = alpha * g[d];
      }
}

// Compatible-flux limiter (VanderHeyden & Kashiwa 1998): the slab carries rho_v q_c + rho_c grad q
// . r, so the mass-specific value it delivers is q_c + (rho_c/rho_v) grad q . r. The gradient of q is
// limited so that this value stays within the face neighbours' bounds at every vertex, rho_v being
// the (already limited) density reconstruction there; without the density ratio a steep density
// drop (a trace material beside its own interface) lets q overshoot by the ratio and turn negative.
template <int DIM, class Value>
void CompatibleGradient(const IceSolver &ice, Value value, PetscInt density, const PetscScalar *a, const PetscReal *grad_rho, PetscReal *grad)
{
  PetscInt lo[3], hi[3];
  DonorBox(ice, lo, hi);
  constexpr PetscInt nvert = DIM == 3 ? 8 : 4;
  for (PetscInt k = lo[2]; k < hi[2]; ++k)
    for (PetscInt j = lo[1]; j < hi[1]; ++j)
      for (PetscInt i = lo[0]; i < hi[0]; ++i) {
        const PetscInt  idx = ice.LocalIndex(i, j, k);
        const PetscReal q = value(idx), rho = a[idx * ice.stride + density];
        PetscReal       qmax = q, qmin = q, g[3] = {0, 0, 0};
        for (PetscInt d = 0; d < DIM; ++d) {
          const PetscReal qm = value(idx - ice.lstride[d]), qp = value(idx + ice.lstride[d]);
          g[d] = (qp - qm) / (2 * ice.h[d]);
          qmax = PetscMax(qmax, PetscMax(qm, qp));
          qmin = PetscMin(qmin, PetscMin(qm, qp));
        }
        PetscReal alpha = 1;
        for (PetscInt v = 0; v < nvert; ++v) {
          PetscReal dq = 0, drho = 0;
          for (PetscInt d = 0; d < DIM; ++d) {
            const PetscReal r = ((v >> d) & 1 ? 0.5 : -0.5) * ice.h[d];
            dq += g[d] * r;
            drho += grad_rho[3 * idx + d] * r;
          }
          const PetscReal dv = dq * rho / (rho + drho);
          if (dv > 0) alpha = PetscMin(alpha, (qmax - q) / dv);
          else if (dv < 0) alpha = PetscMin(alpha, (qmin - q) / dv);
        }
        alpha = PetscMax(alpha, 0.0);
        for (PetscInt d = 0; d < 3; ++d) grad[3 * idx + d] = alpha * g[d];
      }
}

// An inflow face's first ghost layer, the donor of what flows in, holds the prescribed state of its
// face cell (boundary.cxx): its reconstruction is flat, so the face carries that state exactly
// (rho u A dt of the jet or the coflow, cell by cell). A uniform inflow's limiter flattens it anyway
// (the outer ghost equals it); along a jet's edge it would not.
void FlattenInflowGhosts(const IceSolver &ice, PetscReal *grad)
{
  PetscInt lo[3], hi[3];
  DonorBox(ice, lo, hi);
  for (PetscInt d = 0; d < ice.dim; ++d)
    for (int s = 0; s < 2; ++s) {
      const bool touches = s == 0 ? ice.xs[d] == 0 : ice.xs[d] + ice.xm[d] == ice.cells[d];
      if (!touches || ice.bc[d][s].type != IceBC::Inflow) continue;
      PetscInt flo[3] = {lo[0], lo[1], lo[2]}, fhi[3] = {hi[0], hi[1], hi[2]};
      flo[d] = s == 0 ? -1 : ice.cells[d];
      fhi[d] = flo[d] + 1;
      for (PetscInt k = flo[2]; k < fhi[2]; ++k)
        for (PetscInt j = flo[1]; j < fhi[1]; ++j)
          for (PetscInt i = flo[0]; i < fhi[0]; ++i)
            for (PetscInt e = 0; e < 3; ++e) grad[3 * ice.LocalIndex(i, j, k) + e] = 0;
    }
}

// The dimension and the number of advected quantities are compile-time constants so that the
// per-face loops over them unroll (IceAdvectionIncrement dispatches).
template <int DIM, int NQ>
void AdvectionIncrement(IceSolver &ice, const PetscScalar *a, PetscInt m, PetscInt density, const PetscInt q_fields[], PetscReal *const out[])
{
  constexpr PetscInt nq = NQ;
  const PetscInt     S = ice.stride, n = ice.nmat, nlocal = ice.gxm[0] * ice.gxm[1] * ice.gxm[2];
  const bool         second = ice.advection_order == 2;
  const PetscReal    dt     = ice.dt;
  ice.work_grad.resize((size_t)nlocal * 3 * (nq + 1));
  ice.work_adv.resize((size_t)nlocal * (nq + 1));
  PetscReal *grad_rho = ice.work_grad.data();

  auto grad_q = [&](PetscInt q) { return ice.work_grad.data() + (size_t)nlocal * 3 * (q + 1); };
  // Gradients: density, then q (compatible) or density * q
  if (second) {
    LimitedGradient<DIM>(
      ice, [&](PetscInt idx) { return a[idx * S + density]; }, grad_rho);
    for (PetscInt q = 0; q < nq; ++q) {
      const PetscInt f = q_fields[q];
      if (ice.compatible_fluxes)
        CompatibleGradient<DIM>(
          ice, [&](PetscInt idx) { return a[idx * S + f]; }, density, a, grad_rho, grad_q(q));
      else
        LimitedGradient<DIM>(
          ice, [&](PetscInt idx) { return a[idx * S + density] * a[idx * S + f]; }, grad_q(q));
    }
    FlattenInflowGhosts(ice, grad_rho);
    for (PetscInt q = 0; q < nq; ++q) FlattenInflowGhosts(ice, grad_q(q));
  }
  // Out-flux distance of face (d, side) of cell idx for material m
  auto out_distance = [&](PetscInt idx, PetscInt d, int side) {
    const PetscReal u = side > 0 ? ice.face_vel[d][(idx + ice.lstride[d]) * n + m] : ice.face_vel[d][idx * n + m];
    return side > 0 ? PetscMax(0.0, u * dt) : PetscMax(0.0, -u * dt);
  };
  // Flux of [density, density * q...] per unit slab volume leaving donor cell idx through (d, side)
  auto slab = [&](PetscInt idx, PetscInt d, int side, PetscReal values[]) {
    const PetscScalar *c   = a + idx * S;
    const PetscReal    rho = c[density];
    if (!second) {
      values[0] = rho;
      for (PetscInt q = 0; q < nq; ++q) values[1 + q] = rho * c[q_fields[q]];
      return;
    }
    PetscReal r[3] = {0, 0, 0};
    for (PetscInt e = 0; e < DIM; ++e) {
      if (e == d) r[e] = side * (0.5 * ice.h[e] - 0.5 * out_distance(idx, e, side));
      else r[e] = 0.5 * (out_distance(idx, e, -1) - out_distance(idx, e, +1));
    }
    const PetscReal *gr       = grad_rho + 3 * idx;
    const PetscReal  rho_slab = rho + gr[0] * r[0] + gr[1] * r[1] + gr[2] * r[2];
    values[0]                 = rho_slab;
    for (PetscInt q = 0; q < nq; ++q) {
      const PetscReal *g  = grad_q(q) + 3 * idx;
      const PetscReal  dq = g[0] * r[0] + g[1] * r[1] + g[2] * r[2];
      values[1 + q]       = ice.compatible_fluxes ? rho_slab * c[q_fields[q]] + rho * dq : rho * c[q_fields[q]] + dq;
    }
  };
  // Accumulate face fluxes into work_adv for the owned cells
  PetscReal *acc = ice.work_adv.data();
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        const PetscInt idx = ice.LocalIndex(i, j, k);
        for (PetscInt q = 0; q <= nq; ++q) acc[(size_t)q * nlocal + idx] = 0;
      }
  PetscReal values[NQ + 1];
  for (PetscInt d = 0; d < DIM; ++d) {
    const PetscReal courant = dt / ice.h[d]; // slab volume / V per unit velocity
    PetscInt        hi[3]   = {ice.xs[0] + ice.xm[0], ice.xs[1] + ice.xm[1], ice.xs[2] + ice.xm[2]};
    hi[d] += 1; // the upper face of the last owned cell
    for (PetscInt k = ice.xs[2]; k < hi[2]; ++k)
      for (PetscInt j = ice.xs[1]; j < hi[1]; ++j)
        for (PetscInt i = ice.xs[0]; i < hi[0]; ++i) {
          const PetscInt  R = ice.LocalIndex(i, j, k), L = R - ice.lstride[d];
          const PetscReal u = ice.face_vel[d][R * n + m];
          if (u == 0) continue;
          const PetscReal volume = std::fabs(u) * courant;
          if (u > 0) slab(L, d, +1, values);
          else slab(R, d, -1, values);
          const PetscReal sign    = u > 0 ? 1 : -1; // flux from L to R
          const PetscInt  ijk[3]  = {i, j, k};
          const bool      R_owned = ijk[d] < ice.xs[d] + ice.xm[d];
          const bool      L_owned = ijk[d] > ice.xs[d];
          for (PetscInt q = 0; q <= nq; ++q) {
            const PetscReal F = sign * volume * values[q];
            if (R_owned) acc[(size_t)q * nlocal + R] += F;
            if (L_owned) acc[(size_t)q * nlocal + L] -= F;
          }
          if (ice.boundary_flux_sink && (ijk[d] == 0 || ijk[d] == ice.cells[d])) { // a domain face: the same fluxes, out positive, for the budgets (diagnostics.cxx)
            for (PetscInt q = 0; q <= nq; ++q) ice.boundary_flux_sink[q] += (ijk[d] == 0 ? -sign : sign) * volume * values[q];
            ice.boundary_face_mass_flux[2 * d + (ijk[d] == 0 ? 0 : 1)] += (ijk[d] == 0 ? -sign : sign) * volume * values[0];
          }
        }
  }
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        const PetscInt idx = ice.LocalIndex(i, j, k);
        for (PetscInt q = 0; q <= nq; ++q) out[q][idx] = acc[(size_t)q * nlocal + idx];
      }
}

template <int DIM>
void AdvectionIncrementDim(IceSolver &ice, const PetscScalar *a, PetscInt m, PetscInt density, const PetscInt q_fields[], PetscInt nq, PetscReal *const out[])
{
  switch (nq) { // the volume alone; velocity and energy; with the dual-energy temperature; with the specific volume
  case 0: AdvectionIncrement<DIM, 0>(ice, a, m, density, q_fields, out); break;
  case DIM + 1: AdvectionIncrement<DIM, DIM + 1>(ice, a, m, density, q_fields, out); break;
  case DIM + 2: AdvectionIncrement<DIM, DIM + 2>(ice, a, m, density, q_fields, out); break;
  case DIM + 3: AdvectionIncrement<DIM, DIM + 3>(ice, a, m, density, q_fields, out); break;
  default: PetscCheckAbort(false, PETSC_COMM_SELF, PETSC_ERR_PLIB, "advection of %" PetscInt_FMT " quantities is not instantiated", nq);
  }
}
} // namespace

void IceAdvectionIncrement(IceSolver &ice, const PetscScalar *a, PetscInt m, PetscInt density, const PetscInt q_fields[], PetscInt nq, PetscReal *const out[])
{
  if (ice.dim == 2) AdvectionIncrementDim<2>(ice, a, m, density, q_fields, nq, out);
  else AdvectionIncrementDim<3>(ice, a, m, density, q_fields, nq, out);
}

PetscErrorCode IceVolumeOutflow(IceSolver &ice, const PetscScalar *a, std::vector<PetscReal> &out)
{
  const PetscInt nlocal = ice.gxm[0] * ice.gxm[1] * ice.gxm[2];
  PetscFunctionBeginUser;
  out.assign(nlocal, 0);
  std::vector<PetscReal> &inc = ice.work_increment;
  inc.resize(nlocal);
  PetscReal *outs[1] = {inc.data()};
  for (PetscInt m = 0; m < ice.nmat; ++m) {
    IceAdvectionIncrement(ice, a, m, ice.Offset(m, icef::theta), nullptr, 0, outs);
    for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
      for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
        for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
          const PetscInt idx = ice.LocalIndex(i, j, k);
          out[idx] -= inc[idx];
        }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Advects M, M u and M E (or M c_v T) of every gas with the Lagrangian values of this step, then
// recovers the primitive state; a non-positive density or temperature, or a non-finite velocity,
// stops the run with the step, cell, material and field (ice.md 7.6).
PetscErrorCode IceAdvect(IceSolver &ice)
{
  PetscScalar   *a;
  const PetscInt S = ice.stride, n = ice.nmat, nlocal = ice.gxm[0] * ice.gxm[1] * ice.gxm[2], dim = ice.dim;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ice.ev_advect, 0, 0, 0, 0));
  PetscCall(IceGetLocalArray(ice, &a));
  // The out-flux volume of a cell cannot exceed the cell (ice.md 1.9)
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        const PetscInt idx = ice.LocalIndex(i, j, k);
        for (PetscInt m = 0; m < ice.ngas; ++m) {
          PetscReal fraction = 0;
          for (PetscInt d = 0; d < dim; ++d) {
            fraction += PetscMax(0.0, -ice.face_vel[d][idx * n + m]) * ice.dt / ice.h[d];
            fraction += PetscMax(0.0, ice.face_vel[d][(idx + ice.lstride[d]) * n + m]) * ice.dt / ice.h[d];
          }
          PetscCheck(fraction <= 1, PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED,
                     "Gas step %" PetscInt_FMT ": material %s leaves cell (%" PetscInt_FMT ", %" PetscInt_FMT ", %" PetscInt_FMT ") with %g of its volume in one step (more than the cell); reduce -ice_cfl", ice.step, ice.materials[m].name.c_str(), i,
                     j, k, (double)fraction);
        }
      }
  // Total energy: advect c_v T + |u|^2/2 instead of c_v T, so the kinetic energy that the remap
  // averages away becomes heat (the reference advects c_v T only, ice.md 1.7). A trace material
  // (theta < 1e-6, mass ~ rho_tiny), whose energy is meaningless, keeps its Lagrangian temperature.
  const bool total = ice.advect_total_energy;
  if (total)
    for (PetscInt idx = 0; idx < nlocal; ++idx)
      for (PetscInt m = 0; m < ice.ngas; ++m) {
        PetscScalar *c  = a + idx * S;
        PetscReal    u2 = 0;
        for (PetscInt d = 0; d < dim; ++d) u2 += c[ice.Offset(m, icef::vel_L + d)] * c[ice.Offset(m, icef::vel_L + d)];
        // with a cold energy, energy_L holds e_cold/c_v at the Lagrangian state (sources.cxx)
        const PetscReal cold             = ice.materials[m].eos->HasColdEnergy() ? c[ice.Offset(m, icef::energy_L)] : 0;
        c[ice.Offset(m, icef::energy_L)] = c[ice.Offset(m, icef::temp_L)] + cold + 0.5 * u2 / ice.materials[m].eos->cv;
      }
  // velocity components, then energy (or temperature); with total energy also the temperature, the
  // dual-energy fallback where the kinetic energy is nearly all of it (Bryan et al., Comput. Phys.
  // Commun. 89 (1995) 149): there E - |u|^2/2 is a small difference of large numbers
  // The gases' specific volume, where the equilibration takes it as their state (the normalized
  // form, equilibration.cxx): its Lagrangian value v (1 - kappa dp_dil) plus what the converted mass
  // brings, v dm, per unit Lagrangian mass, is remapped with the mass (Uintah's M v).
  const bool transport_volume = ice.equilibration_form == IceEquilibrationForm::Normalized && ice.nmat > ice.ngas;
  if (transport_volume)
    for (PetscInt idx = 0; idx < nlocal; ++idx)
      for (PetscInt m = 0; m < ice.ngas; ++m) {
        PetscScalar    *c = a + idx * S;
        const PetscReal v = c[ice.Offset(m, icef::spvol)], rho_L = c[ice.Offset(m, icef::rho_L)];
        const PetscReal dr    = ice.has_mass_source ? PetscMax(ice.mass_source[idx * n + m], 0.0) : 0;
        const PetscReal vol_L = (rho_L - dr) * v * (1 - c[ice.Offset(m, icef::kappa)] * c[ice.CellOffset(icef::dp_dil)]) + dr * v;
        if (vol_L > 0 && rho_L > 0) c[ice.Offset(m, icef::spvol)] = vol_L / rho_L;
      }
  const PetscInt nq = dim + (total ? 2 : 1) + (transport_volume ? 1 : 0);
  ice.work_advect.resize((size_t)nlocal * (nq + 1));
  PetscReal *outs[8];
  for (PetscInt q = 0; q <= nq; ++q) outs[q] = ice.work_advect.data() + (size_t)q * nlocal;
  for (PetscInt m = 0; m < ice.ngas; ++m) { // solids are not advected: the particles carry them
    PetscInt q_fields[7];
    for (PetscInt d = 0; d < dim; ++d) q_fields[d] = ice.Offset(m, icef::vel_L + d);
    q_fields[dim] = ice.Offset(m, total ? icef::energy_L : icef::temp_L);
    if (total) q_fields[dim + 1] = ice.Offset(m, icef::temp_L);
    if (transport_volume) q_fields[nq - 1] = ice.Offset(m, icef::spvol);
    ice.boundary_flux_sink = ice.boundary_flux[m]; // (booked by IceBudgetOpenFaces)
    IceAdvectionIncrement(ice, a, m, ice.Offset(m, icef::rho_L), q_fields, nq, outs);
    ice.boundary_flux_sink = nullptr;
    const PetscReal cv     = ice.materials[m].eos->cv;
    // A cold energy (gas_eos.hpp): the temperature is e - e_cold at a specific volume that the next
    // equilibration keeps e with (it solves at fixed e): one material fills the cell, so its density;
    // else this step's equilibrated specific volume.
    const GasEOS &eos  = *ice.materials[m].eos;
    const bool    cold = eos.HasColdEnergy() && total;
    for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
      for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
        for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
          const PetscInt  idx   = ice.LocalIndex(i, j, k);
          PetscScalar    *c     = a + idx * S;
          const PetscReal rho_L = c[ice.Offset(m, icef::rho_L)];
          const PetscReal rho   = rho_L + outs[0][idx];
          const char     *bad   = nullptr;
          if (!(rho > 0)) bad = "density";
          if (transport_volume && !bad) {
            const PetscReal v = (rho_L * c[ice.Offset(m, icef::spvol)] + outs[nq][idx]) / rho;
            if (v > 0 && std::isfinite(v)) c[ice.Offset(m, icef::spvol)] = v;
          }
          PetscReal u[3] = {0, 0, 0}, u2 = 0;
          for (PetscInt d = 0; d < dim; ++d) {
            u[d] = (rho_L * c[ice.Offset(m, icef::vel_L + d)] + outs[1 + d][idx]) / rho;
            u2 += u[d] * u[d];
          }
          PetscReal T = (rho_L * c[q_fields[dim]] + outs[1 + dim][idx]) / rho;
          if (total) {
            const PetscReal E = T; // specific total energy / c_v
            T -= 0.5 * u2 / cv;
            if (!(T > ice.dual_energy_fraction * E)) { // the internal-energy remap instead
              T = (rho_L * c[q_fields[dim + 1]] + outs[2 + dim][idx]) / rho;
              IceCountFallback(ice, c, idx);
              ++ice.energy_fallbacks_remap;
            } else if (cold) {
              if (n == 1) c[ice.Offset(m, icef::spvol)] = 1 / rho;
              T -= eos.ColdEnergy(1 / c[ice.Offset(m, icef::spvol)]) / cv;
            }
          }
          // a trace (ice.hpp IceIsTrace) remapped to a non-positive temperature keeps its Lagrangian
          // one, or takes the heaviest gas's of its cell: its mass is round-off next to its cell's,
          // and its energy with it. A gas the advection has just emptied to a trace counts too (the
          // fire scene's burst: air at 1e-12 kg/m^3 left at 0 K by the cancellation of its fluxes)
          if (!(T > 0) && (IceIsTrace(ice, c, m) || IceIsTraceMass(ice, c, rho))) {
            PetscReal heaviest = 0, T_heaviest = 0;
            for (PetscInt g = 0; g < ice.ngas; ++g)
              if (c[ice.Offset(g, icef::rho)] > heaviest && c[ice.Offset(g, icef::temp_L)] > 0) {
                heaviest   = c[ice.Offset(g, icef::rho)];
                T_heaviest = c[ice.Offset(g, icef::temp_L)];
              }
            T = c[ice.Offset(m, icef::temp_L)] > 0 ? c[ice.Offset(m, icef::temp_L)] : T_heaviest;
          }
          if (!bad && !(T > 0) && !cold) bad = "temperature"; // with a cold energy the equilibration checks it
          if (!bad && !std::isfinite(T)) bad = "temperature";
          for (PetscInt d = 0; d < dim && !bad; ++d)
            if (!std::isfinite(u[d])) bad = "velocity";
          PetscCheck(!bad, PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED,
                     "Gas step %" PetscInt_FMT ": after advection the %s of material %s in cell (%" PetscInt_FMT ", %" PetscInt_FMT ", %" PetscInt_FMT ") is not positive and finite (density %g kg/m^3, temperature %g K); reduce -ice_cfl", ice.step,
                     bad, ice.materials[m].name.c_str(), i, j, k, (double)rho, (double)T);
          c[ice.Offset(m, icef::rho)] = rho;
          for (PetscInt d = 0; d < dim; ++d) c[ice.Offset(m, icef::vel + d)] = u[d];
          c[ice.Offset(m, icef::temp)] = T;
        }
  }
  PetscCall(IceRestoreLocalArray(ice, &a));
  PetscCall(IceUpdateGhosts(ice));
  PetscCall(PetscLogEventEnd(ice.ev_advect, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
