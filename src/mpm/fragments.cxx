// Fragments: the connected sets of intact particles, found in parallel, and the Grady-Hightower
// estimate of their number (paper eqs. 25-26).
//
// Two intact particles are neighbours when |x_i - x_j| < factor (s_i + s_j)/2, with s = V^{1/dim} the
// current particle size (2-D volumes are per metre of thickness) and factor = -fragments_distance_factor,
// so the criterion follows the deformation. Algorithm:
//   1. each rank joins its own particles (union-find over a hash grid of cell size factor s_max);
//   2. particles within one cell of the rank's owned box are exchanged (MPI_Allgatherv) and every
//      rank records the joins between its particles and the other ranks' (label pairs);
//   3. rank 0 merges the labels of all ranks (union-find on the pairs) and broadcasts the fragment of
//      each label; fragment sums (mass, momentum, first and second moments) are reduced to rank 0.
// Each fragment's size (fragments.csv) comes from its inertia about the centroid: in 2-D the length of
// the uniform rod with the same largest principal moment, sqrt(12 lambda_max) (an arc of the wall:
// about its chord), in 3-D the area of the uniform plate with the same two largest moments,
// 12 sqrt(lambda_1 lambda_2) (a strip of the wall: about its outer surface).
// The counted fragments' masses are fitted, in summary.json, by least squares on ln N(>= m) with
// N(>= m_k) = k for the masses sorted largest first: Mott's N0 exp(-(m/mu)^(1/2)) and Grady-Kipp's
// N0 exp(-m/mu) (Grady, Fragmentation of Rings and Shells, 2006, ch. 2-3).
// The modelled region is what is counted: a fragment cut by a symmetry plane is one fragment of the
// quarter model. Failed particles (field `failed` != 0) are not part of any fragment.
#include "mpm/mpm.hpp"
#include "mpm/swarm_access.hpp"
#include "util.hpp"
#include "io/checkpoint_values.hpp"
#include "mpm/fragments.hpp"
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <unordered_map>

namespace burst {

namespace {

struct UnionFind {
  std::vector<PetscInt> parent;
  explicit UnionFind(PetscInt n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  PetscInt Find(PetscInt a)
  {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void Join(PetscInt a, PetscInt b)
  {
    a = Find(a), b = Find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

// Hash grid over points: key of the cell of x.
struct HashGrid {
  PetscReal                                            cell;
  PetscInt                                             dim;
  std::unordered_map<long long, std::vector<PetscInt>> cells;

  long long Key(const PetscInt c[3]) const { return ((long long)(c[0] + (1 << 20)) << 42) ^ ((long long)(c[1] + (1 << 20)) << 21) ^ (long long)(c[2] + (1 << 20)); }
  void      Cell(const PetscReal x[], PetscInt c[3]) const
  {
    for (int d = 0; d < 3; ++d) c[d] = d < dim ? (PetscInt)std::floor(x[d] / cell) : 0;
  }
  void Insert(const PetscReal x[], PetscInt id)
  {
    PetscInt c[3];
    Cell(x, c);
    cells[Key(c)].push_back(id);
  }
  // Calls f(id) for the points in the 3^dim cells around x.
  template <class Fn>
  void Near(const PetscReal x[], Fn &&f) const
  {
    PetscInt c[3], n[3];
    Cell(x, c);
    const int r2 = dim == 3 ? 1 : 0;
    for (int k = -r2; k <= r2; ++k)
      for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
          n[0]          = c[0] + i;
          n[1]          = c[1] + j;
          n[2]          = c[2] + k;
          const auto it = cells.find(Key(n));
          if (it != cells.end())
            for (PetscInt id : it->second) f(id);
        }
  }
};

// Least squares of ln k on f(m_k) over the masses sorted largest first (N(>= m_k) = k):
// ln N = ln N0 + slope f(m). Returns false with fewer than three masses or a slope >= 0.
bool FitCumulative(std::vector<PetscReal> masses, PetscReal (*f)(PetscReal), PetscReal *N0, PetscReal *slope)
{
  if (masses.size() < 3) return false;
  std::sort(masses.begin(), masses.end(), std::greater<PetscReal>());
  PetscReal       sx = 0, sy = 0, sxx = 0, sxy = 0;
  const PetscReal n = (PetscReal)masses.size();
  for (size_t k = 0; k < masses.size(); ++k) {
    const PetscReal x = f(masses[k]), y = std::log((PetscReal)(k + 1));
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const PetscReal det = n * sxx - sx * sx;
  if (!(det > 0)) return false;
  *slope = (n * sxy - sx * sy) / det;
  *N0    = std::exp((sy - *slope * sx) / n);
  return *slope < 0;
}
} // namespace

// What the fragment search remembers between steps, for the checkpoint.

PetscErrorCode FragmentsSetUp(MpmSolver &mpm)
{
  Fragments &frag = mpm.fragments;
  PetscFunctionBeginUser;
  PetscOptionsBegin(mpm.comm, "", "Fragments and the Grady-Hightower estimate", "Fragments");
  PetscCall(PetscOptionsBool("-fragments", "Find fragments (connected intact particles) at output steps and at the end", "", frag.options.enabled, &frag.options.enabled, nullptr));
  PetscCall(PetscOptionsReal("-fragments_distance_factor", "Neighbours: |x_i - x_j| < factor (s_i + s_j)/2, s = particle size V^(1/dim) (-), > 0", "", frag.options.distance_factor, &frag.options.distance_factor, nullptr));
  PetscCall(CheckRange(mpm.comm, "-fragments_distance_factor", frag.options.distance_factor, 0, 10, PETSC_TRUE));
  PetscCall(PetscOptionsInt("-fragments_min_particles", "Smallest fragment counted in fragment_count (particles); smaller ones are debris, still listed", "", frag.options.min_particles, &frag.options.min_particles, nullptr));
  PetscCall(
    PetscOptionsReal("-fragments_min_mass_fraction", "Smallest fragment counted, a fraction of the counted materials' mass at t = 0 (-); with -fragments_min_particles", "", frag.options.min_mass_fraction, &frag.options.min_mass_fraction, nullptr));
  PetscCall(CheckRange(mpm.comm, "-fragments_min_mass_fraction", frag.options.min_mass_fraction, 0, 1, PETSC_FALSE));
  {
    char     *names[32];
    PetscInt  n = 32;
    PetscBool set;
    PetscCall(PetscOptionsStringArray("-fragments_materials", "Materials whose particles make the fragments and the expansion velocity (e.g. the container, not its filling); default all", "", names, &n, &set));
    if (set) {
      frag.options.counted.assign(mpm.materials.size(), 0);
      for (PetscInt i = 0; i < n; ++i) {
        PetscInt    found = -1;
        std::string valid;
        for (size_t m = 0; m < mpm.materials.size(); ++m) {
          valid += (m ? ", " : "") + std::string(mpm.materials[m]->Name());
          if (mpm.materials[m]->Name() == std::string(names[i])) found = (PetscInt)m;
        }
        PetscCheck(found >= 0 || mpm.help, mpm.comm, PETSC_ERR_USER_INPUT, "Option -fragments_materials: '%s' is not one of -materials (%s)", names[i], valid.c_str());
        if (found >= 0) frag.options.counted[found] = 1;
        PetscCall(PetscFree(names[i]));
      }
    }
  }
  PetscCall(PetscOptionsBool("-grady", "Report the Grady-Hightower fragment counts (eqs. 25-26) for the expansion velocity measured at the first failure", "", frag.options.grady, &frag.options.grady, nullptr));
  PetscCall(OptionsRealVector(PetscOptionsObject, "-grady_center", "Axis of the cylinder or ring (m)", frag.options.center, mpm.grid.dim, nullptr));
  PetscCall(PetscOptionsReal("-grady_radius", "Initial mean radius R0 of eq. 25 (m)", "", frag.options.radius, &frag.options.radius, nullptr));
  PetscCall(PetscOptionsReal("-grady_sector", "Angle of the modelled sector (degrees; 90 for a quarter)", "", frag.options.sector, &frag.options.sector, nullptr));
  PetscCall(PetscOptionsReal("-grady_density", "Density rho (kg/m^3)", "", frag.options.density, &frag.options.density, nullptr));
  PetscCall(PetscOptionsReal("-grady_youngs_modulus", "Young's modulus E of Gamma_T = K_c^2/(2E) (Pa)", "", frag.options.youngs_modulus, &frag.options.youngs_modulus, nullptr));
  PetscCall(PetscOptionsReal("-grady_fracture_toughness", "Fracture toughness K_c (Pa m^1/2)", "", frag.options.toughness, &frag.options.toughness, nullptr));
  PetscCall(PetscOptionsReal("-grady_specific_heat", "Specific heat Cp of Gamma_S (J/(kg K))", "", frag.options.specific_heat, &frag.options.specific_heat, nullptr));
  PetscCall(PetscOptionsReal("-grady_thermal_expansion", "Thermal softening/expansion coefficient alpha of Gamma_S (1/K)", "", frag.options.expansion, &frag.options.expansion, nullptr));
  PetscCall(PetscOptionsReal("-grady_thermal_diffusivity", "Thermal diffusivity chi of Gamma_S (m^2/s)", "", frag.options.diffusivity, &frag.options.diffusivity, nullptr));
  PetscCall(PetscOptionsReal("-grady_yield_stress", "Yield stress Y of Gamma_S (Pa)", "", frag.options.yield_stress, &frag.options.yield_stress, nullptr));
  PetscCall(PetscOptionsReal("-grady_shear_rate", "Shear strain rate of Gamma_S (1/s)", "", frag.options.shear_rate, &frag.options.shear_rate, nullptr));
  PetscOptionsEnd();
  if (frag.options.grady) {
    const char     *names[] = {"-grady_radius", "-grady_density", "-grady_youngs_modulus", "-grady_fracture_toughness", "-grady_specific_heat", "-grady_thermal_expansion", "-grady_thermal_diffusivity", "-grady_yield_stress", "-grady_shear_rate"};
    const PetscReal v[]     = {frag.options.radius,    frag.options.density,     frag.options.youngs_modulus, frag.options.toughness, frag.options.specific_heat,
                               frag.options.expansion, frag.options.diffusivity, frag.options.yield_stress,   frag.options.shear_rate};
    for (int i = 0; i < 9; ++i) PetscCall(CheckRange(mpm.comm, names[i], v[i], 0, PETSC_MAX_REAL, PETSC_TRUE));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Does the swarm carry a model field `name`? (A material lists it in OutputFields.)
bool SwarmHasModelField(const MpmSolver &mpm, const char name[])
{
  for (const auto &m : mpm.materials)
    for (const OutputField &f : m->OutputFields())
      if (std::string(f.name) == name) return true;
  return false;
}

// The Grady-Hightower fragmentation energies (eq. 26): tension K_c^2/(2E); shear
// (rho Cp/alpha) (9 rho^3 Cp^2 chi^3 / (Y^3 alpha^2 gamma_dot))^(1/4).
static void GradyEnergies(const FragmentOptions &o, PetscReal &tension, PetscReal &shear)
{
  tension = o.toughness * o.toughness / (2 * o.youngs_modulus);
  shear   = o.density * o.specific_heat / o.expansion * std::pow(9 * std::pow(o.density, 3) * o.specific_heat * o.specific_heat * std::pow(o.diffusivity, 3) / (std::pow(o.yield_stress, 3) * o.expansion * o.expansion * o.shear_rate), 0.25);
}

// Eq. 25: N = 2 pi (rho R0 V^2 / (24 Gamma))^(1/3) for the whole cylinder.
static PetscReal GradyCount(const FragmentOptions &o, PetscReal gamma, PetscReal velocity) { return 2 * PETSC_PI * std::cbrt(o.density * o.radius * velocity * velocity / (24 * gamma)); }

// The mass-weighted mean radial velocity about the Grady axis of the counted materials, and the
// number of their particles where a failure criterion has been met: failed, or (crack band) softening
// since a criterion, so the Grady velocity means the same with every regularisation.
static PetscErrorCode MeanRadialVelocity(MpmSolver &mpm, PetscReal *velocity, PetscReal *failed_count)
{
  Fragments &frag = mpm.fragments;

  SwarmAccess      fields(mpm.swarm);
  const PetscInt  *failed = nullptr, *softening = nullptr, *material;
  const PetscReal *x, *v, *m;
  PetscInt         n, dim = mpm.grid.dim;
  PetscReal        local[3] = {0, 0, 0}, global[3];
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
  if (SwarmHasModelField(mpm, state_field::failed)) PetscCall(fields.Get(state_field::failed, &failed));
  if (SwarmHasModelField(mpm, state_field::softening_criteria)) PetscCall(fields.Get(state_field::softening_criteria, &softening));
  PetscCall(fields.Get(field::material, &material));
  PetscCall(fields.Get(DMSwarmPICField_coor, &x));
  PetscCall(fields.Get(field::velocity, &v));
  PetscCall(fields.Get(field::mass, &m));
  for (PetscInt p = 0; p < n; ++p) {
    if (!frag.options.Counts(material[p])) continue;
    if ((failed && failed[p]) || (softening && softening[p])) local[2] += 1;
    PetscReal r = 0, vr = 0;
    for (PetscInt d = 0; d < 2; ++d) r += (x[dim * p + d] - frag.options.center[d]) * (x[dim * p + d] - frag.options.center[d]);
    r = std::sqrt(r);
    if (r > 0)
      for (PetscInt d = 0; d < 2; ++d) vr += v[dim * p + d] * (x[dim * p + d] - frag.options.center[d]) / r;
    local[0] += m[p] * vr;
    local[1] += m[p];
  }
  PetscCall(fields.RestoreAll());
  PetscCallMPI(MPI_Allreduce(local, global, 3, MPIU_REAL, MPI_SUM, mpm.comm));
  *velocity = global[1] > 0 ? global[0] / global[1] : 0;
  if (failed_count) *failed_count = global[2];
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Records the mean radial velocity of the material (mass weighted) when a failure criterion is first
// met anywhere (a particle fails, or starts softening under the crack band).
PetscErrorCode FragmentsMonitor(MpmSolver &mpm)
{
  Fragments &frag = mpm.fragments;
  PetscReal  velocity, failed;
  PetscFunctionBeginUser;
  if (!frag.options.grady || frag.fracture_velocity >= 0 || !SwarmHasModelField(mpm, state_field::failed)) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(MeanRadialVelocity(mpm, &velocity, &failed));
  if (failed > 0) {
    frag.fracture_velocity = velocity;
    frag.fracture_time     = mpm.time;
    PetscCall(PetscInfo(mpm.swarm, "First failure at t = %g s: mean radial velocity %g m/s\n", (double)mpm.time, (double)frag.fracture_velocity));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FragmentsExpansionVelocity(MpmSolver &mpm, PetscBool *enabled, PetscReal *velocity)
{
  Fragments &frag = mpm.fragments;
  PetscFunctionBeginUser;
  *enabled  = frag.options.grady;
  *velocity = 0;
  if (frag.options.grady) PetscCall(MeanRadialVelocity(mpm, velocity, nullptr));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// The total mass of the counted materials at t = 0: -fragments_min_mass_fraction is a fraction of it,
// so the count does not depend on when the first search runs (-output_interval) nor on what burned.
PetscErrorCode FragmentsRecordInitialMass(MpmSolver &mpm)
{
  Fragments       &frag = mpm.fragments;
  SwarmAccess      fields(mpm.swarm);
  const PetscInt  *material;
  const PetscReal *m;
  PetscInt         n;
  PetscReal        mass_local = 0;
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
  PetscCall(fields.Get(field::material, &material));
  PetscCall(fields.Get(field::mass, &m));
  for (PetscInt p = 0; p < n; ++p)
    if (frag.options.Counts(material[p])) mass_local += m[p];
  PetscCall(fields.RestoreAll());
  PetscCallMPI(MPI_Allreduce(&mass_local, &frag.initial_mass, 1, MPIU_REAL, MPI_SUM, mpm.comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FindFragments(MpmSolver &mpm, const char table_path[])
{
  Fragments     &frag = mpm.fragments;
  const PetscInt dim  = mpm.grid.dim;
  PetscInt       n;
  PetscFunctionBeginUser;
  if (!frag.options.enabled) PetscFunctionReturn(PETSC_SUCCESS);
  const bool has_failed = SwarmHasModelField(mpm, state_field::failed);

  SwarmAccess      fields(mpm.swarm);
  const PetscReal *x, *v, *m, *V;
  const PetscInt  *failed = nullptr, *material;
  PetscInt        *fragment;
  PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
  PetscCall(fields.Get(field::material, &material));
  PetscCall(fields.Get(DMSwarmPICField_coor, &x));
  PetscCall(fields.Get(field::velocity, &v));
  PetscCall(fields.Get(field::mass, &m));
  PetscCall(fields.Get(field::volume, &V));
  PetscCall(fields.Get(field::fragment, &fragment));
  if (has_failed) PetscCall(fields.Get(state_field::failed, &failed));

  // 1. local components
  std::vector<PetscInt>  intact;
  std::vector<PetscReal> size(n);
  PetscReal              s_max = 0;
  for (PetscInt p = 0; p < n; ++p) {
    fragment[p] = -1;
    if ((failed && failed[p]) || !frag.options.Counts(material[p])) continue;
    intact.push_back(p);
    size[p] = std::pow(V[p], 1.0 / dim);
    s_max   = PetscMax(s_max, size[p]);
  }
  PetscReal s_global;
  PetscCallMPI(MPI_Allreduce(&s_max, &s_global, 1, MPIU_REAL, MPI_MAX, mpm.comm));
  const PetscReal factor = frag.options.distance_factor;
  HashGrid        grid{factor * PetscMax(s_global, 1e-300), dim, {}};
  const PetscInt  ni = (PetscInt)intact.size();
  for (PetscInt a = 0; a < ni; ++a) grid.Insert(x + dim * intact[a], a);
  UnionFind uf(ni);
  auto      close = [&](const PetscReal *xa, PetscReal sa, const PetscReal *xb, PetscReal sb) {
    PetscReal d2 = 0;
    for (PetscInt d = 0; d < dim; ++d) d2 += (xa[d] - xb[d]) * (xa[d] - xb[d]);
    const PetscReal limit = 0.5 * factor * (sa + sb);
    return d2 < limit * limit;
  };
  for (PetscInt a = 0; a < ni; ++a) {
    const PetscReal *xa = x + dim * intact[a];
    grid.Near(xa, [&](PetscInt b) {
      if (b > a && close(xa, size[intact[a]], x + dim * intact[b], size[intact[b]])) uf.Join(a, b);
    });
  }
  // local roots -> global labels
  std::vector<PetscInt> root_index(ni, -1);
  PetscInt              nroots = 0;
  for (PetscInt a = 0; a < ni; ++a)
    if (uf.Find(a) == a) root_index[a] = nroots++;
  PetscInt offset = 0;
  PetscCallMPI(MPI_Exscan(&nroots, &offset, 1, MPIU_INT, MPI_SUM, mpm.comm));
  if (!mpm.rank) offset = 0;
  auto label_of = [&](PetscInt a) { return offset + root_index[uf.Find(a)]; };

  // 2. halo exchange: particles within one hash cell of the owned box
  PetscInt xs[3], xm[3];
  PetscCall(DMDAGetCorners(mpm.grid.da_nodes, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscReal lo[3], hi[3];
  for (PetscInt d = 0; d < dim; ++d) {
    lo[d] = mpm.grid.lower[d] + xs[d] * mpm.grid.h[d];
    hi[d] = mpm.grid.lower[d] + PetscMin(xs[d] + xm[d], mpm.grid.cells[d]) * mpm.grid.h[d];
  }
  std::vector<PetscReal> halo; // x[dim], size, label per particle
  const PetscInt         stride = dim + 2;
  for (PetscInt a = 0; a < ni; ++a) {
    const PetscReal *xa   = x + dim * intact[a];
    bool             near = false;
    for (PetscInt d = 0; d < dim; ++d) near = near || xa[d] - lo[d] < grid.cell || hi[d] - xa[d] < grid.cell;
    if (!near) continue;
    for (PetscInt d = 0; d < dim; ++d) halo.push_back(xa[d]);
    halo.push_back(size[intact[a]]);
    halo.push_back((PetscReal)label_of(a));
  }
  std::vector<PetscInt> pairs; // (label here, label there)
  if (mpm.size > 1) {
    PetscMPIInt              count = (PetscMPIInt)halo.size();
    std::vector<PetscMPIInt> counts(mpm.size), displs(mpm.size, 0);
    PetscCallMPI(MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, mpm.comm));
    for (int r = 1; r < mpm.size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
    std::vector<PetscReal> all(displs[mpm.size - 1] + counts[mpm.size - 1]);
    PetscCallMPI(MPI_Allgatherv(halo.data(), count, MPIU_REAL, all.data(), counts.data(), displs.data(), MPIU_REAL, mpm.comm));
    for (int r = 0; r < mpm.size; ++r) {
      if (r == mpm.rank) continue;
      for (PetscMPIInt k = displs[r]; k < displs[r] + counts[r]; k += stride) {
        const PetscReal *xb = &all[k];
        const PetscReal  sb = all[k + dim];
        const PetscInt   lb = (PetscInt)all[k + dim + 1];
        grid.Near(xb, [&](PetscInt a) {
          if (close(x + dim * intact[a], size[intact[a]], xb, sb)) {
            pairs.push_back(label_of(a));
            pairs.push_back(lb);
          }
        });
      }
    }
  }
  // 3. merge the labels of all ranks on rank 0, broadcast label -> fragment
  PetscInt total_labels = 0;
  PetscCallMPI(MPI_Allreduce(&nroots, &total_labels, 1, MPIU_INT, MPI_SUM, mpm.comm));
  PetscMPIInt              npairs = (PetscMPIInt)pairs.size();
  std::vector<PetscMPIInt> pcounts(mpm.size), pdispls(mpm.size, 0);
  PetscCallMPI(MPI_Gather(&npairs, 1, MPI_INT, pcounts.data(), 1, MPI_INT, 0, mpm.comm));
  for (int r = 1; r < mpm.size; ++r) pdispls[r] = pdispls[r - 1] + pcounts[r - 1];
  std::vector<PetscInt> all_pairs(mpm.rank ? 0 : pdispls[mpm.size - 1] + pcounts[mpm.size - 1]);
  PetscCallMPI(MPI_Gatherv(pairs.data(), npairs, MPIU_INT, all_pairs.data(), pcounts.data(), pdispls.data(), MPIU_INT, 0, mpm.comm));
  std::vector<PetscInt> fragment_of(total_labels, 0);
  PetscInt              nfragments = 0;
  if (!mpm.rank) {
    UnionFind labels(total_labels);
    for (size_t k = 0; k + 1 < all_pairs.size(); k += 2) labels.Join(all_pairs[k], all_pairs[k + 1]);
    std::vector<PetscInt> id(total_labels, -1);
    for (PetscInt l = 0; l < total_labels; ++l) {
      const PetscInt r = labels.Find(l);
      if (id[r] < 0) id[r] = nfragments++;
      fragment_of[l] = id[r];
    }
  }
  PetscCallMPI(MPI_Bcast(&nfragments, 1, MPIU_INT, 0, mpm.comm));
  PetscCallMPI(MPI_Bcast(fragment_of.data(), total_labels, MPIU_INT, 0, mpm.comm));

  // fragment sums: particles, mass, momentum, first moment, second moment (xx, xy, xz, yy, yz, zz)
  const int              nsum = 2 + 2 * 3 + 6;
  std::vector<PetscReal> sums((size_t)nsum * nfragments, 0), total(mpm.rank ? 0 : (size_t)nsum * nfragments);
  for (PetscInt a = 0; a < ni; ++a) {
    const PetscInt p = intact[a], fr = fragment_of[label_of(a)];
    fragment[p]  = fr;
    PetscReal *s = &sums[(size_t)nsum * fr];
    s[0] += 1;
    s[1] += m[p];
    for (PetscInt d = 0; d < dim; ++d) {
      s[2 + d] += m[p] * v[dim * p + d];
      s[5 + d] += m[p] * x[dim * p + d];
    }
    for (PetscInt d = 0, l = 0; d < 3; ++d)
      for (PetscInt e = d; e < 3; ++e, ++l)
        if (d < dim && e < dim) s[8 + l] += m[p] * x[dim * p + d] * x[dim * p + e];
  }
  PetscCall(fields.RestoreAll());
  PetscCallMPI(MPI_Reduce(sums.data(), total.data(), nsum * nfragments, MPIU_REAL, MPI_SUM, 0, mpm.comm));
  if (!mpm.rank) {
    frag.last_count        = 0;
    frag.largest_mass      = 0;
    frag.total_intact_mass = 0;
    frag.counted_masses.clear();
    for (PetscInt fr = 0; fr < nfragments; ++fr) {
      const PetscReal *s = &total[(size_t)nsum * fr];
      if (s[0] >= frag.options.min_particles && s[1] >= frag.options.min_mass_fraction * frag.initial_mass) {
        ++frag.last_count;
        frag.counted_masses.push_back(s[1]);
      }
      frag.largest_mass = PetscMax(frag.largest_mass, s[1]);
      frag.total_intact_mass += s[1];
    }
    if (table_path) {
      const std::string path = table_path, tmp = path + ".tmp";
      {
        std::ofstream out(tmp);
        out << "fragment,particles,mass,centroid_x,centroid_y,centroid_z,velocity_x,velocity_y,velocity_z," << (dim == 3 ? "size_area" : "size_length") << "\n";
        out.precision(10);
        for (PetscInt fr = 0; fr < nfragments; ++fr) {
          const PetscReal *s = &total[(size_t)nsum * fr];
          out << fr << "," << (long long)s[0] << "," << s[1];
          for (int d = 0; d < 3; ++d) out << "," << s[5 + d] / s[1];
          for (int d = 0; d < 3; ++d) out << "," << s[2 + d] / s[1];
          // inertia about the centroid per unit mass, then its principal values (ascending)
          Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
          for (PetscInt d = 0, l = 0; d < 3; ++d)
            for (PetscInt e = d; e < 3; ++e, ++l) inertia(d, e) = inertia(e, d) = d < dim && e < dim ? s[8 + l] / s[1] - (s[5 + d] / s[1]) * (s[5 + e] / s[1]) : 0;
          const Eigen::Vector3d lambda = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia, Eigen::EigenvaluesOnly).eigenvalues().cwiseMax(0.0);
          out << "," << (dim == 3 ? 12 * std::sqrt(lambda[2] * lambda[1]) : std::sqrt(12 * lambda[2])) << "\n";
        }
      }
      PetscCheck(std::rename(tmp.c_str(), path.c_str()) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Could not write %s", path.c_str());
    }
  }
  PetscCallMPI(MPI_Bcast(&frag.last_count, 1, MPIU_INT64, 0, mpm.comm));
  PetscCall(PetscPrintf(mpm.comm, "Fragments at t = %g s: %" PetscInt64_FMT " with at least %" PetscInt_FMT " particles and %g of the mass (%" PetscInt_FMT " components in all), largest %.4g kg of %.4g kg intact\n", (double)mpm.time, frag.last_count,
                        frag.options.min_particles, (double)frag.options.min_mass_fraction, nfragments, (double)frag.largest_mass, (double)frag.total_intact_mass));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Adds the fragment and Grady entries to summary.json (rank 0; `out` is inside the JSON object).
PetscErrorCode FragmentsSummary(const MpmSolver &mpm, std::ostream &out)
{
  const Fragments &frag = mpm.fragments;
  PetscFunctionBeginUser;
  if (frag.options.enabled) {
    out << "  \"fragment_count\": " << frag.last_count << ",\n";
    out << "  \"fragment_min_particles\": " << frag.options.min_particles << ",\n";
    out << "  \"fragment_min_mass_fraction\": " << frag.options.min_mass_fraction << ",\n";
    out << "  \"initial_mass\": " << frag.initial_mass << ",\n";
    out << "  \"largest_fragment_mass\": " << frag.largest_mass << ",\n";
    out << "  \"intact_mass\": " << frag.total_intact_mass << ",\n";
    // the counted fragments' cumulative mass distribution fitted (fewer than three: null)
    PetscReal N0, slope;
    out << "  \"fragment_mass_fit\": {\"mott\": ";
    if (FitCumulative(
          frag.counted_masses, [](PetscReal m) { return std::sqrt(m); }, &N0, &slope))
      out << "{\"N0\": " << N0 << ", \"mu\": " << 1 / (slope * slope) << "}";
    else out << "null";
    out << ", \"grady_kipp\": ";
    if (FitCumulative(
          frag.counted_masses, [](PetscReal m) { return m; }, &N0, &slope))
      out << "{\"N0\": " << N0 << ", \"mu\": " << -1 / slope << "}";
    else out << "null";
    out << "},\n";
  }
  if (frag.options.grady) {
    PetscReal tension, shear;
    GradyEnergies(frag.options, tension, shear);
    const PetscReal V = frag.fracture_velocity;
    out << "  \"grady_gamma_tension\": " << tension << ",\n";
    out << "  \"grady_gamma_shear\": " << shear << ",\n";
    out << "  \"fracture_velocity\": " << V << ",\n";
    out << "  \"fracture_time\": " << frag.fracture_time << ",\n";
    if (V > 0) {
      const PetscReal fraction = frag.options.sector / 360.0;
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "Grady-Hightower for V = %.1f m/s at the first failure (t = %g s): %.2f (shear) to %.2f (tension) fragments on the modelled %g degrees; found %" PetscInt64_FMT "\n", (double)V, (double)frag.fracture_time,
                            (double)(fraction * GradyCount(frag.options, shear, V)), (double)(fraction * GradyCount(frag.options, tension, V)), (double)frag.options.sector, frag.last_count));
      out << "  \"grady_tension\": {\"whole\": " << GradyCount(frag.options, tension, V) << ", \"sector\": " << fraction * GradyCount(frag.options, tension, V) << "},\n";
      out << "  \"grady_shear\": {\"whole\": " << GradyCount(frag.options, shear, V) << ", \"sector\": " << fraction * GradyCount(frag.options, shear, V) << "},\n";
    } else {
      out << "  \"grady_tension\": null,\n  \"grady_shear\": null,\n";
    }
  }
  (void)mpm;
  PetscFunctionReturn(PETSC_SUCCESS);
}

void Fragments::Checkpoint(CheckpointValues &values)
{
  values.Global("fracture_velocity", &fracture_velocity);
  values.Global("fracture_time", &fracture_time);
  values.Global("last_count", &last_count);
  values.Global("initial_mass", &initial_mass);
  values.Global("largest_mass", &largest_mass);
  values.Global("total_intact_mass", &total_intact_mass);
}

} // namespace burst
