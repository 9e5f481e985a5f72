// Heat conduction in the solids: an explicit grid step at the end of every MPM time step, off unless
// -mpm_heat_conduction (then every scene is adiabatic, as before).
//
// The standard explicit MPM heat step (Uintah SerialMPM without thermal contact; Tao et al. 2016),
// with a node DMDA of its own, dof 3 = [C, T, Tdot]:
//   1. C_I = sum_p m_p c_p N_Ip,  T_I = sum_p m_p c_p T_p N_Ip / C_I          (P2G, ADD_VALUES)
//   2. grad T_p = sum_I T_I grad N_I(x_p);  Qdot_I = -sum_p V_p k_p grad N_I(x_p) . grad T_p
//      (nodes of a fixed-temperature face enter the gradient with the face temperature)
//   3. Tdot_I = Qdot_I / C_I; a node of a fixed-temperature face is held: its rate is zero (the rate
//      of a constant face value), so particles next to it move with the interior nodes only
//   4. T_p += dt sum_I N_Ip Tdot_I                                             (G2P)
// With every face insulated (the default) the step conserves sum_p m_p c_p T_p exactly (partition
// of unity), and the mechanics are untouched: only the swarm field "temperature" changes.
//
// Stability: the explicit limit dt_h = 1 / (2 alpha_max sum_d 1/h_d^2), alpha = k V_p / (m_p c_p)
// with the current particle density. The step is sub-cycled (n = ceil(dt / (cfl dt_h)) equal
// sub-steps) instead of cutting the MPM time step: in the impact problems burst is for, the
// conduction limit (~h^2/alpha, 1e-2 s for steel on a mm grid) is orders of magnitude above the
// wave-speed step, so n = 1 and the step costs four particle passes (a diffusivity scan and three
// transfers); when it does bind (slow problems, the verification bar) the mechanics keep their own
// step and -mpm_dt stays honoured.
//
// Fixed faces, the choice: Uintah instead sets the face node's rate to (T_face - T_I)/dt with T_I
// the particles' projection, relaxing the particles next to the face onto T_face. On the 1-D bar
// (tests/verify_heat.py) that kicks those particles by O(h) every sub-step: L2 order 1.5, max error
// order 1, 30x larger at 100 cells than the held node (order 2.0-2.3). The price of holding: a
// particle temperature that starts off the face value is not pulled onto it (the within-cell
// particle differences are the null space of the projection, as everywhere in MPM).
//
// Particles must be on their owning rank for the ghosted stencil, so the step runs after the
// migration, i.e. "at the end of a time step" as in the paper.
//
// Between materials (-mpm_heat_interface laminate, the default): the particle quadrature above gives
// a cell that two materials share their volume-weighted (arithmetic) mean conductivity in every
// direction. Across a steel-explosive interface (k 44.5 against 0.45 W/(m K)) that makes the charge's
// part of the cell conduct like steel: the charge within a cell of the wall heats with the wall, an
// O(h) error (the fire scene's charge band 38 % too fast at 2.5 mm cells). Instead each particle of a
// cell holding particles of different conductivity takes the layered-composite tensor of its cell,
//   K = k_a (I - n n) + k_h n n,   k_a = sum V k / sum V,   1/k_h = sum (V/k) / sum V,
// the harmonic mean across the interface and the arithmetic one along it, with n the direction in
// which log k grows over the cell's particles (the regression of log k on position). A cell of one
// conductivity is untouched. The cell is the one that holds the particle's centre; all of a cell's
// particles live on the rank that owns its lower node (petsc.md 3), so the sums need no messages.
//
// c_p here is the constant -<mat>_heat_capacity of this step; a constitutive model's own specific
// heat model (plastic-work heating) is separate and not read. Rigid materials do not conduct.
#include "grid_index.hpp"
#include "mpm/swarm_access.hpp"
#include "util.hpp"
#include <cmath>
#include <cstdio>
#include <string>

namespace burst {

const char *const HeatInterfaceNames[] = {"arithmetic", "laminate"};
enum class HeatInterface : int { Arithmetic = 0, Laminate = 1 };

struct HeatConduction {
  DM                     da     = nullptr; // node DMDA, dof 3: [C, T, Tdot]
  Vec                    global = nullptr, local = nullptr, scratch = nullptr;
  std::vector<PetscReal> k, c;                  // per material id; k < 0: does not conduct (rigid)
  PetscReal              cfl           = 0.5;   // fraction of the explicit stability limit
  PetscInt               max_substeps  = 10000; // refuse a step that would need more sub-steps
  PetscBool              fixed[3][2]   = {};    // fixed-temperature faces
  PetscReal              face_T[3][2]  = {};    // K
  PetscInt               last_substeps = 0;
  HeatInterface          interface     = HeatInterface::Laminate;
  bool                   several_k     = false; // conducting materials of different conductivity
  // laminate: per ghosted local node, the sums of the cell it is the lower node of; per local
  // particle, [k along, k across - k along, n (3)] (k along < 0: a cell of one conductivity)
  std::vector<PetscReal> cell_sums, particle_k;
  PetscLogEvent          event = 0;
  // A surface heat source per particle, G_p (T_source - T_p) with G_p the swarm field
  // surface_conductance (W/K; src/phases.cxx measures it from the gas): added in every sub-step
  PetscBool surface_source     = PETSC_FALSE;
  PetscReal source_temperature = 0; // K
  ~HeatConduction()
  {
    (void)VecDestroy(&global);
    (void)VecDestroy(&local);
    (void)VecDestroy(&scratch);
    (void)DMDestroy(&da);
  }
  // Temperature of a fixed face that node (i, j, k) lies on, first of x, y, z order; false if none.
  inline bool FaceTemperature(const Grid &g, PetscInt dim, const PetscInt ijk[3], PetscReal *T) const
  {
    for (PetscInt d = 0; d < dim; ++d) {
      if (fixed[d][0] && ijk[d] == 0) {
        *T = face_T[d][0];
        return true;
      }
      if (fixed[d][1] && ijk[d] == g.axes[d].nodes - 1) {
        *T = face_T[d][1];
        return true;
      }
    }
    return false;
  }
};

PetscErrorCode HeatConductionSetUp(MpmSolver &mpm)
{
  PetscBool   on             = PETSC_FALSE;
  auto        heat           = std::unique_ptr<HeatConduction, HeatDeleter>(new HeatConduction());
  const char *face_opt[3][2] = {{"-mpm_heat_bc_xmin", "-mpm_heat_bc_xmax"}, {"-mpm_heat_bc_ymin", "-mpm_heat_bc_ymax"}, {"-mpm_heat_bc_zmin", "-mpm_heat_bc_zmax"}};
  PetscFunctionBeginUser;
  PetscOptionsBegin(mpm.comm, "", "Heat conduction in the solids", "Heat");
  PetscCall(PetscOptionsBool("-mpm_heat_conduction", "Conduct heat between particles (explicit grid step at the end of each step, needs -<mat>_thermal_conductivity and -<mat>_heat_capacity); false: adiabatic", "", on, &on, nullptr));
  PetscCall(PetscOptionsReal("-mpm_heat_cfl", "Conduction sub-step as a fraction of the explicit limit 1/(2 alpha sum 1/h^2), in (0, 1]", "", heat->cfl, &heat->cfl, nullptr));
  {
    int choice = (int)heat->interface;
    PetscCall(OptionsChoice(PetscOptionsObject, "-mpm_heat_interface",
                            "Conductivity of a cell that materials of different conductivity share: laminate, the layered-composite tensor (harmonic mean across the interface, arithmetic along it); arithmetic, the particles' volume-weighted mean in "
                            "every direction",
                            HeatInterfaceNames, 2, &choice, nullptr));
    heat->interface = (HeatInterface)choice;
  }
  PetscCall(PetscOptionsInt("-mpm_heat_max_substeps", "Most conduction sub-steps in one time step, >= 1: a step that needs more (a high -<mat>_thermal_conductivity, a fine grid, a long -mpm_dt) stops the run with the count it would need", "",
                            heat->max_substeps, &heat->max_substeps, nullptr));
  for (PetscInt d = 0; d < mpm.grid.dim; ++d)
    for (int s = 0; s < 2; ++s) PetscCall(PetscOptionsReal(face_opt[d][s], "Fixed temperature (K) held on this domain face by the conduction step; unset: insulated (zero flux)", "", heat->face_T[d][s], &heat->face_T[d][s], &heat->fixed[d][s]));
  PetscOptionsEnd();
  if (!on && !mpm.help) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(CheckRange(mpm.comm, "-mpm_heat_cfl", heat->cfl, 0, 1, PETSC_TRUE));
  PetscCheck(heat->max_substeps >= 1, mpm.comm, PETSC_ERR_USER_INPUT, "Option -mpm_heat_max_substeps = %" PetscInt_FMT " is out of range: it must be >= 1", heat->max_substeps);
  for (PetscInt d = 0; d < mpm.grid.dim; ++d)
    for (int s = 0; s < 2; ++s)
      if (heat->fixed[d][s]) PetscCall(CheckRange(mpm.comm, face_opt[d][s], heat->face_T[d][s], 0, PETSC_MAX_REAL, PETSC_TRUE));

  // Material parameters, one options block per material.
  const PetscInt nmat = (PetscInt)mpm.materials.size();
  heat->k.assign(nmat, -1);
  heat->c.assign(nmat, -1);
  for (PetscInt m = 0; m < nmat; ++m) {
    Material         &mat = *mpm.materials[m];
    PetscReal         v[3];
    const bool        rigid = mat.IsRigid(v);
    const std::string pre   = mat.name_ + "_";
    PetscBool         has_k = PETSC_FALSE, has_c = PETSC_FALSE;
    PetscReal         k = -1, c = -1;
    PetscOptionsBegin(mpm.comm, pre.c_str(), "Heat conduction: material parameters", "Heat");
    PetscCall(PetscOptionsReal("-thermal_conductivity", "Thermal conductivity k (W/(m K)), >= 0; read with -mpm_heat_conduction", "", k, &k, &has_k));
    PetscCall(PetscOptionsReal("-heat_capacity", "Specific heat c_p (J/(kg K)), > 0, constant, of the conduction step only (a model's own specific heat model, if any, is separate)", "", c, &c, &has_c));
    PetscOptionsEnd();
    if (mpm.help || rigid) continue;
    PetscCheck(has_k, mpm.comm, PETSC_ERR_USER_INPUT, "-mpm_heat_conduction needs -%sthermal_conductivity (W/(m K), >= 0) for material %s", pre.c_str(), mat.Name());
    PetscCheck(has_c, mpm.comm, PETSC_ERR_USER_INPUT, "-mpm_heat_conduction needs -%sheat_capacity (J/(kg K), > 0) for material %s", pre.c_str(), mat.Name());
    PetscCall(CheckRange(mpm.comm, Prefixed(pre.c_str(), "thermal_conductivity").c_str(), k, 0, PETSC_MAX_REAL, PETSC_FALSE));
    PetscCall(CheckRange(mpm.comm, Prefixed(pre.c_str(), "heat_capacity").c_str(), c, 0, PETSC_MAX_REAL, PETSC_TRUE));
    heat->k[m] = k;
    heat->c[m] = c;
  }
  if (mpm.help || !on) PetscFunctionReturn(PETSC_SUCCESS);
  for (PetscInt m = 0; m < nmat; ++m)
    for (PetscInt l = 0; l < nmat; ++l) heat->several_k = heat->several_k || (heat->k[m] >= 0 && heat->k[l] >= 0 && heat->k[m] != heat->k[l]);

  PetscCall(DMDACreateCompatibleDMDA(mpm.grid.da_nodes, 3, &heat->da));
  PetscCall(DMCreateGlobalVector(heat->da, &heat->global));
  PetscCall(DMCreateLocalVector(heat->da, &heat->local));
  PetscCall(VecDuplicate(heat->local, &heat->scratch));
  PetscCall(PetscLogEventRegister("MPM_Heat", DM_CLASSID, &heat->event));
  PetscCall(PetscInfo(heat->da, "Heat conduction on, cfl %g\n", (double)heat->cfl));
  mpm.heat = std::move(heat);
  PetscFunctionReturn(PETSC_SUCCESS);
}

namespace {
// One pass over the conducting particles; what = 0: P2G of [C, C T]; 1: grad T and Qdot into
// `out`; 2: T_p += dt sum N Tdot.
struct HeatKernel {
  MpmSolver            &mpm;
  const HeatConduction &heat;
  int                   what;
  const PetscScalar    *in;  // ghosted [C, T, Tdot] (passes 1, 2)
  PetscScalar          *out; // ghosted sums (passes 0, 1)
  PetscReal             dt;
  template <int DIM, ShapeType S>
  PetscErrorCode operator()()
  {
    const Grid          &g = mpm.grid;
    const LocalNodeIndex index(g);
    PetscInt             n;
    const PetscReal     *x, *hw, *F, *m, *vol;
    const PetscInt      *mat;
    PetscReal           *T;
    PetscFunctionBeginUser;
    PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
    SwarmAccess fields(mpm.swarm);
    PetscCall(fields.Get(DMSwarmPICField_coor, &x));
    PetscCall(fields.Get(field::half_width0, &hw));
    PetscCall(fields.Get(field::F, &F));
    PetscCall(fields.Get(field::mass, &m));
    PetscCall(fields.Get(field::volume, &vol));
    PetscCall(fields.Get(field::material, &mat));
    PetscCall(fields.Get(field::temperature, &T));
    const PetscReal *G = nullptr;
    if (what == 2 && heat.surface_source) PetscCall(fields.Get(field::surface_conductance, &G));
    const PetscReal *laminate = what == 1 && !heat.particle_k.empty() ? heat.particle_k.data() : nullptr;
    Stencil<DIM, S>  st;
    for (PetscInt p = 0; p < n; ++p) {
      const PetscReal kp = heat.k[mat[p]], cp = heat.c[mat[p]];
      if (kp < 0) continue; // rigid: not part of the thermal problem
      st.Evaluate(g.axes, x + DIM * p, hw + DIM * p, F + 9 * p);
      if (what == 0) {
        const PetscReal C = m[p] * cp, CT = C * T[p];
        ForEachNode(st, [&](PetscInt i, PetscInt j, PetscInt k, PetscReal N, const PetscReal dN[]) {
          (void)dN;
          PetscScalar *node = out + 3 * index(i, j, k);
          node[0] += N * C;
          node[1] += N * CT;
        });
      } else if (what == 1) {
        PetscReal grad[DIM] = {};
        ForEachNode(st, [&](PetscInt i, PetscInt j, PetscInt k, PetscReal N, const PetscReal dN[]) {
          (void)N;
          const PetscInt ijk[3] = {i, j, k};
          PetscReal      TI     = in[3 * index(i, j, k) + 1];
          (void)heat.FaceTemperature(g, DIM, ijk, &TI);
          for (int a = 0; a < DIM; ++a) grad[a] += TI * dN[a];
        });
        const PetscReal *lam = laminate ? laminate + 5 * p : nullptr;
        if (lam && lam[0] >= 0) { // a cell shared by conductivities: the layered tensor K grad T
          PetscReal along_n = 0, flux[DIM];
          for (int a = 0; a < DIM; ++a) along_n += lam[2 + a] * grad[a];
          for (int a = 0; a < DIM; ++a) flux[a] = vol[p] * (lam[0] * grad[a] + lam[1] * along_n * lam[2 + a]);
          ForEachNode(st, [&](PetscInt i, PetscInt j, PetscInt k, PetscReal N, const PetscReal dN[]) {
            (void)N;
            PetscReal dot = 0;
            for (int a = 0; a < DIM; ++a) dot += dN[a] * flux[a];
            out[3 * index(i, j, k) + 2] -= dot;
          });
          continue;
        }
        const PetscReal Vk = vol[p] * kp;
        ForEachNode(st, [&](PetscInt i, PetscInt j, PetscInt k, PetscReal N, const PetscReal dN[]) {
          (void)N;
          PetscReal dot = 0;
          for (int a = 0; a < DIM; ++a) dot += dN[a] * grad[a];
          out[3 * index(i, j, k) + 2] -= Vk * dot;
        });
      } else {
        PetscReal rate = 0;
        ForEachNode(st, [&](PetscInt i, PetscInt j, PetscInt k, PetscReal N, const PetscReal dN[]) {
          (void)dN;
          rate += N * in[3 * index(i, j, k) + 2];
        });
        if (G) rate += G[p] * (heat.source_temperature - T[p]) / (m[p] * cp);
        T[p] += dt * rate;
      }
    }
    PetscCall(fields.RestoreAll());
    PetscFunctionReturn(PETSC_SUCCESS);
  }
};

// -mpm_heat_interface laminate: each conducting particle's conductivity tensor (heat.particle_k),
// from the sums over the particles of its cell (the header's formula).
PetscErrorCode LaminateConductivities(MpmSolver &mpm, HeatConduction &heat)
{
  const Grid          &g   = mpm.grid;
  const PetscInt       dim = g.dim;
  const LocalNodeIndex index(g);
  // per cell: V, V k, V/k, V psi, V x (3), V psi x (3), the first k seen, whether another differs
  // (psi = ln k, whose regression on x gives the normal)
  constexpr int    NSUM  = 13;
  const PetscInt   nodes = g.gxm[0] * g.gxm[1] * g.gxm[2];
  PetscInt         n;
  const PetscReal *x, *vol;
  const PetscInt  *mat;
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
  SwarmAccess fields(mpm.swarm);
  PetscCall(fields.Get(DMSwarmPICField_coor, &x));
  PetscCall(fields.Get(field::volume, &vol));
  PetscCall(fields.Get(field::material, &mat));
  heat.cell_sums.assign((size_t)nodes * NSUM, 0);
  heat.particle_k.resize(5 * (size_t)n);
  auto cell_of = [&](PetscInt p) -> PetscInt {
    PetscInt c[3] = {0, 0, 0};
    for (PetscInt d = 0; d < dim; ++d) {
      c[d] = PetscMin((PetscInt)std::floor((x[p * dim + d] - g.axes[d].origin) / g.axes[d].h), g.axes[d].nodes - 2);
      if (c[d] < g.gxs[d] || c[d] >= g.gxs[d] + g.gxm[d]) return -1; // not on this rank's box
    }
    return index(c[0], c[1], c[2]);
  };
  for (PetscInt p = 0; p < n; ++p) {
    const PetscReal k = heat.k[mat[p]];
    const PetscInt  c = k >= 0 ? cell_of(p) : -1;
    if (c < 0) continue;
    PetscReal      *s = heat.cell_sums.data() + (size_t)c * NSUM;
    const PetscReal V = vol[p], psi = std::log(k + 1e-300);
    if (s[0] == 0) s[11] = k;
    else if (k != s[11]) s[12] = 1;
    s[0] += V;
    s[1] += V * k;
    s[2] += k > 0 ? V / k : PETSC_INFINITY;
    s[3] += V * psi;
    for (PetscInt d = 0; d < dim; ++d) {
      s[4 + d] += V * x[p * dim + d];
      s[7 + d] += V * psi * x[p * dim + d];
    }
  }
  for (PetscInt p = 0; p < n; ++p) {
    PetscReal       *lam = heat.particle_k.data() + 5 * p;
    const PetscInt   c   = heat.k[mat[p]] >= 0 ? cell_of(p) : -1;
    const PetscReal *s   = c >= 0 ? heat.cell_sums.data() + (size_t)c * NSUM : nullptr;
    lam[0]               = -1; // one conductivity in the cell: the particle's own
    if (!s || s[12] == 0) continue;
    const PetscReal along = s[1] / s[0], across = s[0] / s[2]; // arithmetic, harmonic
    PetscReal       normal[3] = {0, 0, 0}, norm = 0;
    for (PetscInt d = 0; d < dim; ++d) {
      normal[d] = s[7 + d] - s[3] * s[4 + d] / s[0];
      norm += normal[d] * normal[d];
    }
    norm   = std::sqrt(norm);
    lam[0] = along;
    lam[1] = norm > 0 ? across - along : 0; // no direction (particles at one point): the mean alone
    for (PetscInt d = 0; d < 3; ++d) lam[2 + d] = norm > 0 ? normal[d] / norm : 0;
  }
  PetscCall(fields.RestoreAll());
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Largest diffusivity k V / (m c) over the conducting particles (global), m^2/s, and the material
// that has it (-1: none conducts).
PetscErrorCode MaxDiffusivity(MpmSolver &mpm, const HeatConduction &heat, PetscReal *alpha, PetscInt *which)
{
  PetscInt         n;
  const PetscReal *m, *vol;
  const PetscInt  *mat;
  PetscReal        local     = 0;
  PetscInt         local_mat = -1;
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
  SwarmAccess fields(mpm.swarm);
  PetscCall(fields.Get(field::mass, &m));
  PetscCall(fields.Get(field::volume, &vol));
  PetscCall(fields.Get(field::material, &mat));
  const PetscReal *laminate = heat.particle_k.empty() ? nullptr : heat.particle_k.data();
  for (PetscInt p = 0; p < n; ++p) {
    // in a shared cell the largest conductivity of the particle's tensor, the arithmetic mean
    const PetscReal k = laminate && heat.k[mat[p]] >= 0 && laminate[5 * p] >= 0 ? laminate[5 * p] : heat.k[mat[p]];
    if (k > 0 && m[p] > 0) {
      const PetscReal a = k * vol[p] / (m[p] * heat.c[mat[p]]);
      if (!(a <= local)) { // (a NaN or inf diffusivity wins)
        local     = std::isnan(a) ? PETSC_INFINITY : a;
        local_mat = mat[p];
      }
    }
  }
  PetscCall(fields.RestoreAll());
  PetscCallMPI(MPI_Allreduce(&local, alpha, 1, MPIU_REAL, MPI_MAX, mpm.comm));
  PetscInt mine = local == *alpha ? local_mat : -1;
  PetscCallMPI(MPI_Allreduce(&mine, which, 1, MPIU_INT, MPI_MAX, mpm.comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Visits the owned nodes of the heat DMDA: f(ijk, node) with node the 3 dofs of the global array.
template <class Fn>
PetscErrorCode ForOwnedNodes(const HeatConduction &heat, PetscScalar *array, Fn &&f)
{
  PetscInt xs[3], xm[3];
  PetscFunctionBeginUser;
  PetscCall(DMDAGetCorners(heat.da, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscInt l = 0;
  for (PetscInt k = xs[2]; k < xs[2] + xm[2]; ++k)
    for (PetscInt j = xs[1]; j < xs[1] + xm[1]; ++j)
      for (PetscInt i = xs[0]; i < xs[0] + xm[0]; ++i, ++l) {
        const PetscInt ijk[3] = {i, j, k};
        f(ijk, array + 3 * l);
      }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode HeatSubStep(MpmSolver &mpm, HeatConduction &heat, PetscReal dt)
{
  const Grid        &g   = mpm.grid;
  const PetscInt     dim = g.dim;
  PetscScalar       *arr;
  const PetscScalar *in;
  PetscFunctionBeginUser;
  // 1. C_I and T_I
  PetscCall(VecZeroEntries(heat.local));
  PetscCall(VecGetArray(heat.local, &arr));
  {
    HeatKernel kernel{mpm, heat, 0, nullptr, arr, dt};
    PetscCall(DispatchShape(dim, mpm.shape, kernel));
  }
  PetscCall(VecRestoreArray(heat.local, &arr));
  PetscCall(VecZeroEntries(heat.global));
  PetscCall(DMLocalToGlobal(heat.da, heat.local, ADD_VALUES, heat.global));
  PetscCall(VecGetArray(heat.global, &arr));
  PetscCall(ForOwnedNodes(heat, arr, [&](const PetscInt ijk[3], PetscScalar *node) {
    (void)ijk;
    node[1] = node[0] > 0 ? node[1] / node[0] : 0; // T_I without the face values (gTemperatureNoBC)
  }));
  PetscCall(VecRestoreArray(heat.global, &arr));
  PetscCall(DMGlobalToLocal(heat.da, heat.global, INSERT_VALUES, heat.local));
  // 2. Qdot_I
  PetscCall(VecZeroEntries(heat.scratch));
  PetscCall(VecGetArrayRead(heat.local, &in));
  PetscCall(VecGetArray(heat.scratch, &arr));
  {
    HeatKernel kernel{mpm, heat, 1, in, arr, dt};
    PetscCall(DispatchShape(dim, mpm.shape, kernel));
  }
  PetscCall(VecRestoreArray(heat.scratch, &arr));
  PetscCall(VecRestoreArrayRead(heat.local, &in));
  PetscCall(DMLocalToGlobal(heat.da, heat.scratch, ADD_VALUES, heat.global)); // only dof 2 is non-zero
  // 3. Tdot_I
  PetscCall(VecGetArray(heat.global, &arr));
  PetscCall(ForOwnedNodes(heat, arr, [&](const PetscInt ijk[3], PetscScalar *node) {
    PetscReal Tface;
    if (node[0] <= 0) node[2] = 0;
    else if (heat.FaceTemperature(g, dim, ijk, &Tface)) node[2] = 0; // held: the rate of a constant face temperature
    else node[2] = node[2] / node[0];
  }));
  PetscCall(VecRestoreArray(heat.global, &arr));
  PetscCall(DMGlobalToLocal(heat.da, heat.global, INSERT_VALUES, heat.local));
  // 4. T_p
  PetscCall(VecGetArrayRead(heat.local, &in));
  {
    HeatKernel kernel{mpm, heat, 2, in, nullptr, dt};
    PetscCall(DispatchShape(dim, mpm.shape, kernel));
  }
  PetscCall(VecRestoreArrayRead(heat.local, &in));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// After the sub-steps: every conducting particle's temperature is a finite number.
PetscErrorCode CheckTemperatures(MpmSolver &mpm, const HeatConduction &heat, PetscInt which)
{
  PetscInt         n, bad = -1;
  const PetscReal *T;
  const PetscInt  *mat;
  PetscInt64      *pid;
  PetscInt64       bad_id = -1, global_id;
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
  SwarmAccess fields(mpm.swarm);
  PetscCall(fields.Get(field::temperature, &T));
  PetscCall(fields.Get(field::material, &mat));
  PetscCall(fields.Get(DMSwarmField_pid, &pid));
  for (PetscInt p = 0; p < n && bad < 0; ++p)
    if (heat.k[mat[p]] >= 0 && !std::isfinite(T[p])) {
      bad    = mat[p];
      bad_id = pid[p];
    }
  PetscCall(fields.RestoreAll());
  PetscCallMPI(MPI_Allreduce(&bad_id, &global_id, 1, MPIU_INT64, MPI_MAX, mpm.comm));
  if (global_id < 0) PetscFunctionReturn(PETSC_SUCCESS);
  const std::string name = mpm.materials[which >= 0 ? which : 0]->name_;
  SETERRQ(mpm.comm, PETSC_ERR_USER_INPUT,
          "Heat conduction, step %" PetscInt_FMT ": the temperature of particle id %" PetscInt64_FMT " is not finite after %" PetscInt_FMT
          " conduction sub-step(s); check -%s_thermal_conductivity and -%s_heat_capacity (bounded physical values) and the initial temperatures (-<geometry>_temperature)",
          mpm.step + 1, global_id, heat.last_substeps, name.c_str(), name.c_str());
}
} // namespace

// The sub-step count is computed before any sub-step runs and bounded by -mpm_heat_max_substeps,
// so that one time step's conduction work is bounded: a stop signal (SIGTERM/SIGUSR1) or the
// wall-clock budget, acted on between time steps, then waits at most that many sub-steps.
PetscErrorCode ConductHeat(MpmSolver &mpm)
{
  PetscFunctionBeginUser;
  if (!mpm.heat) PetscFunctionReturn(PETSC_SUCCESS);
  HeatConduction &heat = *mpm.heat;
  PetscCall(PetscLogEventBegin(heat.event, 0, 0, 0, 0));
  PetscReal alpha, inv_h2 = 0;
  PetscInt  which;
  if (heat.interface == HeatInterface::Laminate && heat.several_k) PetscCall(LaminateConductivities(mpm, heat));
  PetscCall(MaxDiffusivity(mpm, heat, &alpha, &which));
  for (PetscInt d = 0; d < mpm.grid.dim; ++d) inv_h2 += 1.0 / (mpm.grid.h[d] * mpm.grid.h[d]);
  if (alpha > 0 && mpm.dt > 0) {
    const PetscReal limit  = heat.cfl / (2 * alpha * inv_h2);
    const PetscReal needed = std::ceil(mpm.dt / limit * (1 - 1e-12)); // inf or NaN for an unbounded input
    if (!(needed <= (PetscReal)heat.max_substeps)) {
      const Material &m = *mpm.materials[which >= 0 ? which : 0];

      auto g = [](PetscReal v) { // C's %g (PETSc's adds a trailing point to whole numbers)
        char buf[32];
        std::snprintf(buf, sizeof(buf), "%g", (double)v);
        return std::string(buf);
      };
      SETERRQ(mpm.comm, PETSC_ERR_USER_INPUT,
              "Heat conduction, step %" PetscInt_FMT ": the time step %s s would need %s conduction sub-steps (explicit limit %s s at -mpm_heat_cfl %s), more than -mpm_heat_max_substeps %" PetscInt_FMT
              "; it is driven by material %s: -%s_thermal_conductivity %s W/(m K) with -%s_heat_capacity %s J/(kg K) (diffusivity %s m^2/s). "
              "Lower the conductivity, use a smaller time step (-mpm_dt, -mpm_dt_max) or coarser grid, or raise -mpm_heat_max_substeps",
              mpm.step + 1, g(mpm.dt).c_str(), g(needed).c_str(), g(limit).c_str(), g(heat.cfl).c_str(), heat.max_substeps, m.Name(), m.Name(), g(heat.k[which >= 0 ? which : 0]).c_str(), m.Name(), g(heat.c[which >= 0 ? which : 0]).c_str(),
              g(alpha).c_str());
    }
    const PetscInt nsub = PetscMax(1, (PetscInt)needed);
    heat.last_substeps  = nsub;
    for (PetscInt s = 0; s < nsub; ++s) PetscCall(HeatSubStep(mpm, heat, mpm.dt / nsub));
    PetscCall(CheckTemperatures(mpm, heat, which));
  }
  PetscCall(PetscLogEventEnd(heat.event, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode HeatSetSurfaceSource(MpmSolver &mpm, PetscBool on, PetscReal source_temperature)
{
  PetscFunctionBeginUser;
  PetscCheck(mpm.heat, mpm.comm, PETSC_ERR_USER_INPUT, "A surface heat source needs -mpm_heat_conduction");
  mpm.heat->surface_source     = on;
  mpm.heat->source_temperature = source_temperature;
  PetscFunctionReturn(PETSC_SUCCESS);
}

void HeatDeleter::operator()(HeatConduction *object) const { delete object; }

} // namespace burst
