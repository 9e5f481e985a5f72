// Burning: a reactant solid turns into a product gas (ice.md 2.4, 3).
//
// A solid material burns when it names a model, -<mat>_burn_type simple_burn|steady_burn (models/
// burn/), and its product, -<mat>_burn_product <gas>. Per cell, after the equilibration, the model
// gives the mass dm that burns in this step from the cell pressure, the solid's temperature and the
// burning surface (from the gradient of the solid's nodal mass, ice.md 3.1). The gas gains dm, its
// momentum dm u_s and the energy dm (c_v,s T_s + Q); the solid loses the mass, its momentum and its
// energy; the pressure equation sees the volume that the conversion creates. On the particle side
// each reactant particle loses the burnt fraction of its cell's solid (through the nodes), and a
// particle below -coupling_burnout_fraction of its seeded mass, or one crushed below
// -coupling_burnout_volume_ratio of its volume (det F), burns out: what is left of it goes to the
// product gas of its cell and the particle is removed and counted.
#include "coupling_impl.hpp"
#include "../mpm/grid_index.hpp"
#include "../mpm/swarm_access.hpp"
#include "util.hpp"
#include "../../models/elastic/tensor.hpp"
#include <cmath>

namespace burst {

// The burn-out thresholds (set-up and -help read the same options).
static PetscErrorCode BurnoutOptions(MPI_Comm comm, PetscReal *fraction, PetscReal *volume_ratio)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "", "Burning", "Coupling");
  PetscCall(PetscOptionsReal("-coupling_burnout_fraction", "A burning particle is removed (and counted) below this fraction of its seeded mass, in (0, 1)", "", *fraction, fraction, nullptr));
  PetscCall(CheckRange(comm, "-coupling_burnout_fraction", *fraction, 0, 1, PETSC_TRUE, PETSC_TRUE));
  PetscCall(PetscOptionsReal("-coupling_burnout_volume_ratio", "A reactant particle crushed below this ratio of its volume (det F) burns out: the rest of it becomes product gas, in [0, 1)", "", *volume_ratio, volume_ratio, nullptr));
  PetscCall(CheckRange(comm, "-coupling_burnout_volume_ratio", *volume_ratio, 0, 1, PETSC_FALSE, PETSC_TRUE));
  PetscOptionsEnd();
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Adds a converted mass (per cell volume, dr > 0 gained, < 0 lost) with its velocity u and specific
// energy e to material m's sources in local cell idx.
static inline void AddConversion(IceSolver &ice, PetscInt idx, PetscInt m, PetscReal dr, const PetscReal u[], PetscReal e)
{
  const PetscInt n = ice.nmat;
  ice.mass_source[idx * n + m] += dr;
  for (PetscInt d = 0; d < ice.dim; ++d) ice.momentum_source[(idx * n + m) * 3 + d] += dr * u[d];
  ice.energy_source[idx * n + m] += dr * e;
}

PetscErrorCode CouplingBurnSetUp(Coupling &c)
{
  MpmSolver &mpm = *c.mpm;
  IceSolver &ice = *c.ice;
  PetscFunctionBeginUser;
  c.burn.resize(c.nsolid);
  c.product.assign(c.nsolid, -1);
  c.seed_mass.assign(c.nsolid, 0);
  PetscCall(BurnoutOptions(mpm.comm, &c.burnout, &c.burnout_volume_ratio));
  bool any = false;
  for (size_t m = 0; m < mpm.materials.size(); ++m) {
    const PetscInt s = c.solid_of[m];
    if (s < 0) continue;
    const Material &mat = *mpm.materials[m];
    BurnModel      *model;
    PetscCall(BurnModelCreate(mpm.comm, mat.Name(), &model));
    c.burn[s].reset(model);
    if (model->name_ == "none") continue;
    char              product[256] = "";
    PetscBool         set          = PETSC_FALSE;
    const std::string pre          = std::string(mat.Name()) + "_";
    PetscOptionsBegin(mpm.comm, pre.c_str(), "Burning", "Coupling");
    PetscCall(PetscOptionsString("-burn_product", "The gas material (one of -ice_materials) that the burnt solid becomes", "", product, product, sizeof(product), &set));
    PetscOptionsEnd();
    std::string names;
    for (PetscInt g = 0; g < ice.ngas; ++g) {
      names += (g ? ", " : "") + ice.materials[g].name;
      if (ice.materials[g].name == product) c.product[s] = g;
    }
    PetscCheck(c.product[s] >= 0, mpm.comm, PETSC_ERR_USER_INPUT, "Material %s burns (-%sburn_type %s): -%sburn_product must name its product gas; valid choices (-ice_materials): %s", mat.Name(), pre.c_str(), model->name_.c_str(), pre.c_str(),
               names.c_str());
    any = true;
  }
  PetscCheck(any == c.burn_energy, mpm.comm, PETSC_ERR_PLIB, "The burning solids (%s) and the particles' deformation heat (%s) disagree", any ? "some" : "none", c.burn_energy ? "tracked" : "not tracked");
  if (any) {
    // the heat of a burning solid's stress updates, which its stress work holds, counted once (stress_loop.cxx)
    mpm.deformation_heat_cv.assign(mpm.materials.size(), 0);
    for (size_t m = 0; m < mpm.materials.size(); ++m)
      if (c.solid_of[m] >= 0 && c.product[c.solid_of[m]] >= 0) mpm.deformation_heat_cv[m] = ice.materials[c.first + c.solid_of[m]].eos->cv;
    // the seeded particle masses (burnt-out threshold)
    PetscInt               n;
    const PetscReal       *mass;
    const PetscInt        *material;
    std::vector<PetscReal> local(c.nsolid, 0);
    PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
    SwarmAccess fields(mpm.swarm);
    PetscCall(fields.Get(field::mass, &mass));
    PetscCall(fields.Get(field::material, &material));
    for (PetscInt p = 0; p < n; ++p) local[c.solid_of[material[p]]] = PetscMax(local[c.solid_of[material[p]]], mass[p]);
    PetscCall(fields.RestoreAll());
    PetscCallMPI(MPI_Allreduce(local.data(), c.seed_mass.data(), (int)c.nsolid, MPIU_REAL, MPI_MAX, mpm.comm));
    const size_t nlocal = (size_t)ice.gxm[0] * ice.gxm[1] * ice.gxm[2];
    ice.mass_source.assign(nlocal * ice.nmat, 0);
    ice.momentum_source.assign(nlocal * ice.nmat * 3, 0);
    ice.energy_source.assign(nlocal * ice.nmat, 0);
    c.burnt_fraction.assign(nlocal * c.nsolid, 0);
    PetscCall(DMDACreateCompatibleDMDA(mpm.grid.da_nodes, c.nsolid, &c.da_phi));
    PetscCall(DMDACreateCompatibleDMDA(ice.da, 5 * ice.nmat + c.nsolid, &c.da_source));
    PetscCall(DMCreateGlobalVector(c.da_source, &c.source_global));
    PetscCall(DMCreateLocalVector(c.da_source, &c.source_local));
    PetscCall(DMCreateGlobalVector(c.da_phi, &c.phi_global));
    PetscCall(DMCreateLocalVector(c.da_phi, &c.phi_local));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscReal *CouplingCounters(Coupling &c) { return c.counters; }

PetscErrorCode CouplingIgnition(Coupling &c, PetscInt material, std::string *model, PetscReal *temperature)
{
  PetscFunctionBeginUser;
  const PetscInt s = c.solid_of[material];
  *model           = s >= 0 && c.burn[s] ? c.burn[s]->name_ : "none";
  *temperature     = s >= 0 && c.burn[s] ? c.burn[s]->IgnitionTemperature() : 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CouplingSummary(Coupling &c, PetscReal *burnt_mass, PetscInt64 *burnt_particles)
{
  const MpmSolver &mpm = *c.mpm;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(&c.burnt_mass, burnt_mass, 1, MPIU_REAL, MPI_SUM, mpm.comm));
  *burnt_particles = c.burnt_particles;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CouplingBurnHelp(Coupling &c)
{
  const MpmSolver &mpm     = *c.mpm;
  PetscReal        burnout = 1e-3, volume_ratio = 0.5;
  char             product[256] = "";
  PetscFunctionBeginUser;
  PetscCall(BurnoutOptions(mpm.comm, &burnout, &volume_ratio));
  for (const auto &mat : mpm.materials) {
    BurnModel        *model;
    const std::string pre = std::string(mat->Name()) + "_";
    PetscCall(BurnModelCreate(mpm.comm, mat->Name(), &model));
    delete model;
    PetscOptionsBegin(mpm.comm, pre.c_str(), "Burning", "Coupling");
    PetscCall(PetscOptionsString("-burn_product", "The gas material (one of -ice_materials) that the burnt solid becomes", "", product, product, sizeof(product), nullptr));
    PetscOptionsEnd();
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

// The volume fraction of the gases in local cell idx (from this step's equilibration).
static PetscReal GasRoom(const IceSolver &ice, const PetscScalar *a, PetscInt idx)
{
  PetscReal room = 0;
  for (PetscInt g = 0; g < ice.ngas; ++g) room += a[idx * ice.stride + ice.Offset(g, icef::theta)];
  return room;
}

// What the burn model of solid s reads about local cell (i, j, k) (ice.md 3.1-3.3), and the gradient
// of the reactant's nodal mass (the burning surface's normal is -grad).
static void CellBurnInput(Coupling &c, const PetscScalar *a, const PetscScalar *nodes, PetscInt i, PetscInt j, PetscInt k, PetscInt s, BurnInput *in, PetscReal grad[3])
{
  MpmSolver           &mpm = *c.mpm;
  IceSolver           &ice = *c.ice;
  const LocalNodeIndex index(mpm.grid);
  const PetscInt       dim = ice.dim, stride = 2 + dim, n = ice.nmat;
  const PetscReal      V    = ice.CellVolume();
  const PetscScalar   *cell = a + ice.LocalIndex(i, j, k) * ice.stride;
  // the hottest material that fills at least a fifth of the cell (Simple Burn's ignition)
  PetscReal T_hot = 0;
  for (PetscInt m = 0; m < n; ++m)
    if (cell[ice.Offset(m, icef::theta)] > 0.2) T_hot = PetscMax(T_hot, cell[ice.Offset(m, icef::temp)]);
  // the gases together: the products that a burning surface puts into air share the air's room,
  // and neither alone may fill a fifth of the cell where together they do (doc/fire.md, 3-D)
  const PetscReal gas_theta = GasRoom(ice, a, ice.LocalIndex(i, j, k));
  PetscReal       gas_heat = 0, gas_capacity = 0;
  for (PetscInt g = 0; g < ice.ngas; ++g) {
    const PetscReal capacity = cell[ice.Offset(g, icef::rho)] * ice.materials[g].eos->cv;
    gas_heat += capacity * cell[ice.Offset(g, icef::temp)];
    gas_capacity += capacity;
  }
  const PetscInt  m = c.first + s, g = c.product[s];
  const PetscReal M = cell[ice.Offset(m, icef::rho)] * V;
  // nodal mass of the reactant around the cell: contrast and gradient (ice.md 3.1). A node on a
  // domain face holds the mass of half a neighbourhood: it counts double (ice.md 7.10), or
  // every symmetry plane through a reactant would look like a burning surface.
  PetscReal Mmax = 0, Mmin = PETSC_MAX_REAL;
  grad[0] = grad[1] = grad[2] = 0;
  ForEachCorner(ice, i, j, k, [&](const PetscInt node[3], PetscReal w) {
    const PetscReal mn      = nodes[index(node[0], node[1], node[2]) * c.mass_stride + s * stride] * w * (dim == 3 ? 8 : 4);
    Mmax                    = PetscMax(Mmax, mn);
    Mmin                    = PetscMin(Mmin, mn);
    const PetscInt local[3] = {node[0] - i, node[1] - j, node[2] - k};
    for (PetscInt d = 0; d < dim; ++d) grad[d] += (local[d] ? 1.0 : -1.0) * mn / (ice.h[d] * (dim == 3 ? 4 : 2));
  });
  in->p      = cell[ice.CellOffset(icef::press_eq)];
  in->T_s    = cell[ice.Offset(m, icef::temp)];
  in->T_g    = cell[ice.Offset(g, icef::temp)];
  in->rho_s  = 1 / cell[ice.Offset(m, icef::spvol)];
  in->area   = BurnSurfaceArea(dim, ice.h, grad, V);
  in->dt     = ice.dt;
  in->M_s    = M;
  in->M_tiny = ice.rho_tiny * c.rho0[s] * V; // the projection's floor (CouplingProjectSolids): M - M_tiny is the particles'
  // a corner below 1e-9 of the largest holds no reactant: a particle domain whose edge meets
  // the node gives it a round-off weight, and Simple Burn's contrast < 1 would flip on it
  if (Mmin < 1e-9 * Mmax) Mmin = 0;
  in->mass_contrast = Mmax > 0 ? (Mmax - Mmin) / Mmax : 0;
  in->T_hot         = T_hot;
  in->T_gases       = gas_theta > 0.2 && gas_capacity > 0 ? gas_heat / gas_capacity : 0;
  in->n_particles   = M > 2 * in->M_tiny ? 1 : 0;
}

PetscErrorCode CouplingIgnitingCells(Coupling &c, PetscInt64 *count, PetscReal where[3], PetscReal *T_hot)
{
  MpmSolver         &mpm = *c.mpm;
  IceSolver         &ice = *c.ice;
  const PetscScalar *nodes, *a;
  PetscInt64         local = 0;
  struct {
    PetscReal   value;
    PetscMPIInt rank;
  } hottest       = {-1, mpm.rank}, global;
  PetscReal at[3] = {0, 0, 0};
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(c.mass_local, &nodes));
  PetscCall(VecGetArrayRead(ice.local, &a));
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i)
        for (PetscInt s = 0; s < c.nsolid; ++s) {
          if (!c.burn[s] || c.product[s] < 0) continue;
          BurnInput in;
          PetscReal grad[3];
          CellBurnInput(c, a, nodes, i, j, k, s, &in, grad);
          if (!(in.M_s > 2 * in.M_tiny)) continue; // (a cell without the reactant's particles)
          const bool ignites = c.burn[s]->Ignites(in);
          if (ignites) local += 1;
          // the closest to igniting: the hottest reactant-bearing cell that the criterion sees
          const PetscReal hot = PetscMax(in.T_hot, in.T_gases);
          if (in.mass_contrast > 0 && hot > hottest.value) {
            hottest.value         = hot;
            const PetscInt ijk[3] = {i, j, k};
            for (PetscInt d = 0; d < ice.dim; ++d) at[d] = ice.lower[d] + (ijk[d] + 0.5) * ice.h[d];
          }
        }
  PetscCall(VecRestoreArrayRead(ice.local, &a));
  PetscCall(VecRestoreArrayRead(c.mass_local, &nodes));
  PetscCallMPI(MPI_Allreduce(&local, count, 1, MPIU_INT64, MPI_SUM, mpm.comm));
  static_assert(sizeof(PetscReal) == sizeof(double), "MPI_DOUBLE_INT below");
  PetscCallMPI(MPI_Allreduce(&hottest, &global, 1, MPI_DOUBLE_INT, MPI_MAXLOC, mpm.comm));
  PetscCallMPI(MPI_Bcast(at, 3, MPIU_REAL, global.rank, mpm.comm));
  for (int d = 0; d < 3; ++d) where[d] = at[d];
  *T_hot = global.value;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CouplingBurn(Coupling &c)
{
  IceSolver         &ice = *c.ice;
  const PetscScalar *nodes, *a;
  PetscFunctionBeginUser;
  ice.has_mass_source = !c.burnt_fraction.empty();
  if (!ice.has_mass_source) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogEventBegin(c.ev_burn, 0, 0, 0, 0));
  std::fill(ice.mass_source.begin(), ice.mass_source.end(), 0);
  std::fill(ice.momentum_source.begin(), ice.momentum_source.end(), 0);
  std::fill(ice.energy_source.begin(), ice.energy_source.end(), 0);
  std::fill(c.burnt_fraction.begin(), c.burnt_fraction.end(), 0);
  const PetscInt       dim = ice.dim, n = ice.nmat;
  const PetscReal      V = ice.CellVolume();
  const LocalNodeIndex index(c.mpm->grid);
  PetscCall(VecGetArrayRead(c.mass_local, &nodes));
  PetscCall(VecGetArrayRead(ice.local, &a));
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        const PetscInt     idx  = ice.LocalIndex(i, j, k);
        const PetscScalar *cell = a + idx * ice.stride;
        for (PetscInt s = 0; s < c.nsolid; ++s) {
          if (!c.burn[s] || c.product[s] < 0) continue;
          const PetscInt m = c.first + s, g = c.product[s];
          BurnInput      in;
          PetscReal      grad[3];
          CellBurnInput(c, a, nodes, i, j, k, s, &in, grad);
          const PetscReal M = in.M_s;
          BurnOutput      out;
          PetscCall(c.burn[s]->Evaluate(in, &out));
          if (!(out.dm > 0)) continue;
          const PetscReal dr = out.dm / V, cv = ice.materials[m].eos->cv, Ts = in.T_s, *u = cell + ice.Offset(m, icef::vel);
          AddConversion(ice, idx, m, -dr, u, cv * Ts);
          // The products take the reactant's energy: c_v T_s, the stored part of its stress work and
          // its kinetic energy (the particles' projection per unit mass: what the burnt particles
          // lose, BurnParticles), of which the momentum source brings |u|^2/2.
          PetscReal stored = 0;
          if (c.burn_energy) {
            const PetscInt extra = c.BurnEnergyOffset(dim, s);
            ForEachCorner(ice, i, j, k, [&](const PetscInt node[3], PetscReal w) { stored += w * nodes[index(node[0], node[1], node[2]) * c.mass_stride + extra]; });
            stored /= M - in.M_tiny;
            for (PetscInt d = 0; d < dim; ++d) stored -= 0.5 * u[d] * u[d];
          }
          // The products leave the burning surface on its gas side: into the neighbours across the
          // faces the outward normal -grad M points through, in proportion to |n_d| and to the room
          // the gases have there (their volume fraction), the rest into the burning cell itself.
          // (Released inside a cell that the reactant fills next to open gas, the gas would have no
          // room: its volume would compress the solid there, sum kappa being the solid's, by orders
          // of magnitude; released into a neighbour that another solid fills, e.g. the container
          // wall, it would be trapped there at the wall's pressure.)
          PetscReal norm = 0, weight[4], total = 0;
          PetscInt  target[4];
          for (PetscInt d = 0; d < dim; ++d) norm += std::fabs(grad[d]);
          target[dim] = idx;
          weight[dim] = GasRoom(ice, a, idx);
          for (PetscInt d = 0; d < dim; ++d) {
            const PetscReal share  = norm > 0 ? std::fabs(grad[d]) / norm : (d == 0 ? 1.0 : 0.0);
            PetscInt        ijk[3] = {i, j, k};
            ijk[d] += grad[d] > 0 ? -1 : 1;
            if (ijk[d] < 0 || ijk[d] >= ice.cells[d]) ijk[d] = d == 0 ? i : d == 1 ? j : k; // at a domain face: here
            target[d] = ice.LocalIndex(ijk[0], ijk[1], ijk[2]);
            weight[d] = share * GasRoom(ice, a, target[d]);
          }
          for (PetscInt d = 0; d <= dim; ++d) total += weight[d];
          for (PetscInt d = 0; d <= dim; ++d) {
            const PetscReal share = total > 0 ? weight[d] / total : (d == dim ? 1.0 : 0.0); // no room anywhere: here
            if (share == 0) continue;
            AddConversion(ice, target[d], g, share * dr, u, cv * Ts + out.Q + stored);
          }
          // of the particles' mass in the cell, M - M_tiny: they lose exactly dm
          c.burnt_fraction[idx * c.nsolid + s] = out.dm / (M - in.M_tiny);
          c.burnt_mass += out.dm;
          c.counters[kChemicalEnergy] += out.dm * out.Q; // the products' energy beyond the reactant's c_v,s T_s
          c.counters[kReactantEnergyCells] += out.dm * (cv * Ts + stored);
          for (PetscInt d = 0; d < dim; ++d) c.counters[kReactantEnergyCells] += 0.5 * out.dm * u[d] * u[d];
        }
      }
  PetscCall(VecRestoreArrayRead(ice.local, &a));
  PetscCall(VecRestoreArrayRead(c.mass_local, &nodes));
  // sources put in ghost cells belong to the neighbour ranks: add them there, then refresh ghosts
  {
    PetscScalar   *src;
    const PetscInt nlocal = ice.gxm[0] * ice.gxm[1] * ice.gxm[2], q = 5 * n + c.nsolid;
    PetscCall(VecGetArray(c.source_local, &src));
    for (PetscInt idx = 0; idx < nlocal; ++idx)
      for (PetscInt m = 0; m < n; ++m) {
        src[idx * q + 5 * m] = ice.mass_source[idx * n + m];
        for (PetscInt d = 0; d < 3; ++d) src[idx * q + 5 * m + 1 + d] = ice.momentum_source[(idx * n + m) * 3 + d];
        src[idx * q + 5 * m + 4] = ice.energy_source[idx * n + m];
      }
    // the burnt fractions travel along (set on owned cells only, so the add leaves them as they are),
    // and come back in the ghost cells, which the nodes at a rank boundary need
    for (PetscInt idx = 0; idx < nlocal; ++idx)
      for (PetscInt s = 0; s < c.nsolid; ++s) src[idx * q + 5 * n + s] = c.burnt_fraction[idx * c.nsolid + s];
    PetscCall(VecRestoreArray(c.source_local, &src));
    PetscCall(VecZeroEntries(c.source_global));
    PetscCall(DMLocalToGlobal(c.da_source, c.source_local, ADD_VALUES, c.source_global));
    PetscCall(DMGlobalToLocal(c.da_source, c.source_global, INSERT_VALUES, c.source_local));
    PetscCall(VecGetArray(c.source_local, &src));
    for (PetscInt idx = 0; idx < nlocal; ++idx)
      for (PetscInt m = 0; m < n; ++m) {
        ice.mass_source[idx * n + m] = src[idx * q + 5 * m];
        for (PetscInt d = 0; d < 3; ++d) ice.momentum_source[(idx * n + m) * 3 + d] = src[idx * q + 5 * m + 1 + d];
        ice.energy_source[idx * n + m] = src[idx * q + 5 * m + 4];
      }
    for (PetscInt idx = 0; idx < nlocal; ++idx)
      for (PetscInt s = 0; s < c.nsolid; ++s) c.burnt_fraction[idx * c.nsolid + s] = src[idx * q + 5 * n + s];
    PetscCall(VecRestoreArray(c.source_local, &src));
  }
  PetscCall(PetscLogEventEnd(c.ev_burn, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

namespace {
// Nodal burnt fraction -> reactant particles: mass, volumes and energy scale with the mass left.
struct BurnParticles {
  MpmSolver         &mpm;
  Coupling          &c;
  IceSolver         &ice;
  const PetscScalar *phi; // per node, per solid
  std::vector<char> &remove;
  template <int DIM, ShapeType S>
  PetscErrorCode operator()()
  {
    const Grid          &g = mpm.grid;
    const LocalNodeIndex index(g);
    PetscInt             n;
    const PetscReal     *x, *hw, *F;
    PetscReal           *mass, *vol, *vol0, *energy, *heat;
    const PetscReal     *v, *T;
    const PetscInt      *material;
    PetscFunctionBeginUser;
    PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
    remove.assign(n, 0);
    SwarmAccess fields(mpm.swarm);
    PetscCall(fields.Get(DMSwarmPICField_coor, &x));
    PetscCall(fields.Get(field::half_width0, &hw));
    PetscCall(fields.Get(field::F, &F));
    PetscCall(fields.Get(field::mass, &mass));
    PetscCall(fields.Get(field::volume, &vol));
    PetscCall(fields.Get(field::volume0, &vol0));
    PetscCall(fields.Get(field::internal_energy, &energy));
    PetscCall(fields.Get(field::deformation_heat, &heat));
    PetscCall(fields.Get(field::material, &material));
    PetscCall(fields.Get(field::velocity, &v));
    PetscCall(fields.Get(field::temperature, &T));
    const PetscReal V = ice.CellVolume();
    Stencil<DIM, S> st;
    for (PetscInt p = 0; p < n; ++p) {
      const PetscInt s = c.solid_of[material[p]];
      if (s < 0 || !c.burn[s] || c.product[s] < 0) continue;
      st.Evaluate(g.axes, x + DIM * p, hw + DIM * p, F + 9 * p);
      PetscReal f = 0;
      ForEachNode(st, [&](PetscInt i, PetscInt j, PetscInt k, PetscReal N, const PetscReal[]) { f += N * phi[index(i, j, k) * c.nsolid + s]; });
      const PetscReal J = Mat3CMap(F + 9 * p).determinant(); // a crushed reactant burns out, burning this step or not
      if (f <= 0 && J >= c.burnout_volume_ratio) continue;
      const PetscReal keep = PetscMax(1 - f, 0.0), cv = ice.materials[c.first + s].eos->cv;
      PetscReal       v2 = 0;
      for (int a = 0; a < DIM; ++a) v2 += v[DIM * p + a] * v[DIM * p + a];
      // what leaves the particles goes to the gas: it leaves the solids' energy balance
      const PetscReal burnt = (1 - keep) * mass[p];
      mpm.diag.removed_mass += burnt;
      mpm.diag.removed_energy += (1 - keep) * (0.5 * mass[p] * v2 + energy[p]);
      c.counters[kBurntParticleMass] += burnt;
      c.counters[kBurntParticleEnergy] += (1 - keep) * (0.5 * mass[p] * v2 + energy[p]);
      // (the heat of its stress updates is in energy[p]: counted there, not in c_v T)
      c.counters[kBurntParticleThermal] += burnt * cv * T[p] - (1 - keep) * heat[p];
      for (int a = 0; a < DIM; ++a) {
        mpm.diag.removed_momentum[a] += burnt * v[DIM * p + a];
        c.counters[kBurntParticleMomentum + a] += burnt * v[DIM * p + a];
      }
      mass[p] *= keep;
      vol[p] *= keep;
      vol0[p] *= keep;
      energy[p] *= keep;
      heat[p] *= keep;
      if (mass[p] < c.burnout * c.seed_mass[s] || J < c.burnout_volume_ratio) {
        // burnt out: the rest burns into the product in the particle's cell (ice.md 2.4's bookkeeping)
        remove[p]       = 1;
        PetscInt ijk[3] = {0, 0, 0};
        for (int d = 0; d < DIM; ++d) ijk[d] = PetscMin(PetscMax((PetscInt)std::floor((x[DIM * p + d] - ice.lower[d]) / ice.h[d]), ice.xs[d]), ice.xs[d] + ice.xm[d] - 1);
        const PetscInt  idx = ice.LocalIndex(ijk[0], ijk[1], ijk[2]), m = c.first + s;
        const PetscReal dr = mass[p] / V, stored = (energy[p] - heat[p]) / mass[p]; // (the momentum brings |v|^2/2)
        AddConversion(ice, idx, m, -dr, v + DIM * p, cv * T[p]);
        AddConversion(ice, idx, c.product[s], dr, v + DIM * p, cv * T[p] + c.burn[s]->HeatOfReaction() + stored);
        c.burnt_mass += mass[p]; // RemoveParticles books its mass, momentum and energy as removed
        c.counters[kBurntParticleMass] += mass[p];
        c.counters[kBurntParticleEnergy] += 0.5 * mass[p] * v2 + energy[p];
        c.counters[kBurntParticleThermal] += mass[p] * cv * T[p] - heat[p];
        for (int a = 0; a < DIM; ++a) c.counters[kBurntParticleMomentum + a] += mass[p] * v[DIM * p + a];
        c.counters[kChemicalEnergy] += mass[p] * c.burn[s]->HeatOfReaction();
        c.counters[kReactantEnergyCells] += mass[p] * (cv * T[p] + stored + 0.5 * v2); // (a remnant's product takes the particle's own)
      }
    }
    PetscCall(fields.RestoreAll());
    PetscFunctionReturn(PETSC_SUCCESS);
  }
};
} // namespace

PetscErrorCode CouplingBurnParticles(Coupling &c)
{
  MpmSolver &mpm = *c.mpm;
  IceSolver &ice = *c.ice;
  PetscFunctionBeginUser;
  if (c.burnt_fraction.empty()) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogEventBegin(c.ev_burn_particles, 0, 0, 0, 0));
  // nodal fraction: phi_n = w_n sum of the burnt fractions of the node's cells, with the node ->
  // cell weights of the projection. A particle then loses sum_c W_pc phi_c of its mass, W_pc its
  // projection weight to cell c, and the particles of a cell lose exactly the mass that burnt
  // there, phi_c M_c (the start-of-step positions, before G2P moves them).
  DM           da     = c.da_phi;
  Vec          global = c.phi_global, local = c.phi_local;
  PetscScalar *phi;
  PetscInt     xs[3], xm[3];
  PetscCall(DMDAGetCorners(da, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(VecGetArray(global, &phi));
  PetscInt l = 0;
  for (PetscInt k = xs[2]; k < xs[2] + xm[2]; ++k)
    for (PetscInt j = xs[1]; j < xs[1] + xm[1]; ++j)
      for (PetscInt i = xs[0]; i < xs[0] + xm[0]; ++i, ++l)
        for (PetscInt s = 0; s < c.nsolid; ++s) {
          PetscReal      sum     = 0;
          const PetscInt node[3] = {i, j, k};
          ForEachCellAroundNode(ice, i, j, k, [&](PetscInt idx, bool inside) {
            if (inside) sum += c.burnt_fraction[idx * c.nsolid + s];
          });
          phi[l * c.nsolid + s] = NodeWeight(ice, node) * sum;
        }
  PetscCall(VecRestoreArray(global, &phi));
  PetscCall(DMGlobalToLocal(da, global, INSERT_VALUES, local));
  std::vector<char> &remove = c.burnt_out;
  const PetscScalar *phil;
  PetscCall(VecGetArrayRead(local, &phil));
  BurnParticles kernel{mpm, c, ice, phil, remove};
  PetscCall(DispatchShape(mpm.grid.dim, mpm.shape, kernel));
  PetscCall(VecRestoreArrayRead(local, &phil));
  PetscInt64 removed = 0;
  PetscCall(RemoveParticles(mpm, remove, &removed));
  c.burnt_particles += removed;
  if (removed) PetscCall(PetscInfo(mpm.swarm, "Step %" PetscInt_FMT ": %" PetscInt64_FMT " reactant particle(s) burnt out and removed\n", mpm.step, removed));
  PetscCall(PetscLogEventEnd(c.ev_burn_particles, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
