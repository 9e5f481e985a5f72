// MPM-ICE coupling: projections between particles, nodes and cells (ice.md 2.1-2.3).
//
// Node -> cell weights: a cell averages its 2^dim corner nodes (1/4 in 2-D, 1/8 in 3-D); a node on
// a domain face has only half the cells around it, so its weight is doubled there (ice.md 7.10),
// and every node's mass reaches the cells in full. Cell -> node: the same weights back (a node
// takes sum_c w_ci dX_c of the cells' increments per unit mass), so the nodes receive exactly the
// momentum and heat that the cells gave their solids (CouplingIncrementsToNodes).
#include "coupling_impl.hpp"
#include "../mpm/grid_index.hpp"
#include "../mpm/swarm_access.hpp"
#include "util.hpp"
#include "io/checkpoint_values.hpp"
#include <cmath>

namespace burst {

// The solid's volume as the gas sees it (ice.md 2.2): p = p_ref + K/2 (rho/rho0 - rho0/rho) in
// compression and the reference's modified form p = p_ref (rho/rho0)^(K/p_ref) below rho0, which
// stays positive so that a solid in tension lets go of the gas. No thermal part.
class SolidCouplingEOS final : public GasEOS {
public:
  PetscReal      K = 0, rho0 = 0, p_ref = 101325, T_ref = 300;
  PetscErrorCode SetFromOptions(PetscOptionItems *, const char[]) override { return PETSC_SUCCESS; }
  PetscErrorCode View(PetscViewer viewer) const override
  {
    return PetscViewerASCIIPrintf(viewer, "solid coupling EOS: bulk modulus %g Pa, density %g kg/m^3, reference pressure %g Pa, c_v %g J/(kg K)\n", (double)K, (double)rho0, (double)p_ref, (double)cv);
  }
  GasEOSPoint Evaluate(PetscReal rho, PetscReal) const override
  {
    if (rho >= rho0) return {p_ref + 0.5 * K * (rho / rho0 - rho0 / rho), 0.5 * K * (1 / rho0 + rho0 / (rho * rho)), 0};
    const PetscReal p = p_ref * std::pow(rho / rho0, K / p_ref);
    return {p, K / rho * p / p_ref, 0};
  }
  PetscReal Density(PetscReal p, PetscReal) const override
  {
    if (p >= p_ref) {
      const PetscReal g = (p - p_ref) / K;
      return rho0 * (g + std::sqrt(g * g + 1));
    }
    return p > 0 ? rho0 * std::pow(p / p_ref, p_ref / K) : -1;
  }
  // (below p_ref the slope K p/(p_ref rho) from p itself: one pow instead of two)
  PetscReal DensityAndSlope(PetscReal p, PetscReal T, PetscReal *dp_drho) const override
  {
    const PetscReal rho = Density(p, T);
    *dp_drho            = rho >= rho0 ? 0.5 * K * (1 / rho0 + rho0 / (rho * rho)) : K / rho * p / p_ref;
    return rho;
  }
  PetscReal Temperature(PetscReal, PetscReal) const override { return T_ref; }
};

PetscErrorCode CouplingSolidMaterials(MpmSolver &mpm, std::vector<IceSolidSpec> &solids, Coupling **coupling)
{
  PetscFunctionBeginUser;
  auto c = std::make_unique<Coupling>();
  c->mpm = &mpm;
  PetscOptionsBegin(mpm.comm, "", "Gas-solid coupling", "Coupling");
  PetscCall(PetscOptionsReal("-coupling_reference_pressure", "Reference pressure p_ref of the solids' coupling equation of state and of the stress the gas adds to the particles (Pa), > 0", "", c->p_ref, &c->p_ref, nullptr));
  PetscCall(CheckRange(mpm.comm, "-coupling_reference_pressure", c->p_ref, 0, PETSC_MAX_REAL, PETSC_TRUE));
  PetscCall(PetscOptionsReal("-coupling_surface_heat_transfer", "Convective heat transfer coefficient h between the solids' surfaces and the gas two cells out (W/(m^2 K)), >= 0; 0: off (src/coupling/surface_heat.cxx)", "", c->surface_h,
                             &c->surface_h, nullptr));
  PetscCall(CheckRange(mpm.comm, "-coupling_surface_heat_transfer", c->surface_h, 0, 1e8, PETSC_FALSE));
  PetscCall(
    PetscOptionsBool("-coupling_charge_pressure_work",
                     "The gases pay the work their pressure does on the solids (taken at the nodes, moved toward the gas and shared as -coupling_pressure_work_spread and _share say; total energy conserved); 0: the solids gain it from nothing", "",
                     c->charge_pressure_work, &c->charge_pressure_work, nullptr));
  PetscCall(PetscOptionsEnum("-coupling_pressure_work_share", "Who among the gases around a node pays its pressure work: energy (in proportion to M c_v T: one temperature factor for all) or heat_capacity (M c_v: one temperature difference)", "",
                             kWorkShareNames, (PetscEnum)c->work_share, (PetscEnum *)&c->work_share, nullptr));
  PetscCall(PetscOptionsInt("-coupling_pressure_work_spread",
                            "Sweeps that move the pressure work of nodes in or at a solid toward its neighbours, in proportion to the gas energy around them (p times open gas fraction), so the residue of the two discretisations of the gas pressure "
                            "is paid where the gas is; >= 0; 0: each node's work is paid by the gases of its own cells",
                            "", c->work_spread_sweeps, &c->work_spread_sweeps, nullptr));
  PetscCall(CheckRange(mpm.comm, "-coupling_pressure_work_spread", (PetscReal)c->work_spread_sweeps, 0, 64, PETSC_FALSE));
  PetscCall(PetscOptionsReal("-coupling_pressure_work_open_fraction",
                             "Each sweep, a node passes on 1 - min(1, f / this) of its pressure work, f the mean open gas fraction of its cells (a gas is open in proportion to its own pressure over the cell's), in (0, 1]", "", c->work_open_fraction,
                             &c->work_open_fraction, nullptr));
  PetscCall(CheckRange(mpm.comm, "-coupling_pressure_work_open_fraction", c->work_open_fraction, 0, 1, PETSC_TRUE));
  PetscCall(PetscOptionsReal("-coupling_pressure_work_closed_fraction",
                             "Mean open gas fraction of a node's cells below which the pressure work left there after the sweeps is held (counted in the budget) rather than paid by gas pockets, in [0, 1); 0: always paid", "", c->work_closed_fraction,
                             &c->work_closed_fraction, nullptr));
  PetscCall(CheckRange(mpm.comm, "-coupling_pressure_work_closed_fraction", c->work_closed_fraction, 0, 1, PETSC_FALSE, PETSC_TRUE));
  PetscOptionsEnd();
  c->solid_of.assign(mpm.materials.size(), -1);
  for (size_t m = 0; m < mpm.materials.size(); ++m) {
    const Material &mat = *mpm.materials[m];
    PetscReal       v[3];
    PetscCheck(!mat.IsRigid(v), mpm.comm, PETSC_ERR_SUP, "Material %s: a rigid body in a scene with gas is not supported yet", mat.Name());
    PetscCheck(mat.BulkModulus() > 0, mpm.comm, PETSC_ERR_SUP, "Material %s (model %s) reports no bulk modulus, which the gas coupling needs", mat.Name(), mat.Model());
    auto eos        = std::make_unique<SolidCouplingEOS>();
    eos->K          = mat.BulkModulus();
    eos->rho0       = mat.Density();
    eos->p_ref      = c->p_ref;
    PetscBool   set = PETSC_FALSE;
    std::string pre = std::string(mat.Name()) + "_";
    PetscOptionsBegin(mpm.comm, pre.c_str(), "Solid as the gas sees it", "Coupling");
    PetscCall(PetscOptionsReal("-heat_capacity", "Specific heat of the solid for the heat exchange with the gas (J/(kg K)), > 0; required with gas", "", eos->cv, &eos->cv, &set));
    PetscOptionsEnd();
    // a solid that burns (its model and product are read in burn.cxx): its particles keep the heat
    // of their stress updates, so that its products take its internal energy once
    char      burn_type[64] = "none";
    PetscBool burn_set      = PETSC_FALSE;
    PetscCall(PetscOptionsGetString(nullptr, pre.c_str(), "-burn_type", burn_type, sizeof(burn_type), &burn_set));
    if (burn_set && std::string(burn_type) != "none") c->burn_energy = true;
    PetscCheck(set || mpm.help, mpm.comm, PETSC_ERR_USER_INPUT, "Material %s: a scene with gas needs -%sheat_capacity (J/(kg K), > 0) for the heat exchange", mat.Name(), pre.c_str());
    PetscCall(CheckRange(mpm.comm, ("-" + pre + "heat_capacity").c_str(), eos->cv, 0, PETSC_MAX_REAL, PETSC_TRUE));
    c->solid_of[m] = c->nsolid++;
    c->rho0.push_back(mat.Density());
    eos->name_ = "solid_coupling";
    solids.push_back({mat.Name(), eos.release(), 300});
  }
  mpm.deformation_heat = c->burn_energy ? PETSC_TRUE : PETSC_FALSE;
  *coupling            = c.release();
  mpm.ambient_pressure = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

namespace {
// Particles -> nodes, per solid material: mass, mass T, momentum; with burning, the mass times the
// energy a particle's products take beyond c_v T (burn.cxx): (internal energy - deformation heat)/m
// + |v|^2/2, projected with the weights that then take the burnt mass from the particles.
struct ProjectKernel {
  MpmSolver   &mpm;
  Coupling    &c;
  PetscScalar *out;
  template <int DIM, ShapeType S>
  PetscErrorCode operator()()
  {
    const Grid          &g = mpm.grid;
    const LocalNodeIndex index(g);
    const PetscInt       stride = 2 + DIM, dof = c.mass_stride;
    PetscInt             n;
    const PetscReal     *x, *v, *m, *T, *hw, *F, *energy = nullptr, *heat = nullptr;
    const PetscInt      *mat;
    PetscFunctionBeginUser;
    PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
    SwarmAccess fields(mpm.swarm);
    PetscCall(fields.Get(DMSwarmPICField_coor, &x));
    PetscCall(fields.Get(field::velocity, &v));
    PetscCall(fields.Get(field::mass, &m));
    PetscCall(fields.Get(field::temperature, &T));
    PetscCall(fields.Get(field::half_width0, &hw));
    PetscCall(fields.Get(field::F, &F));
    PetscCall(fields.Get(field::material, &mat));
    if (c.burn_energy) {
      PetscCall(fields.Get(field::internal_energy, &energy));
      PetscCall(fields.Get(field::deformation_heat, &heat));
    }
    Stencil<DIM, S> st;
    for (PetscInt p = 0; p < n; ++p) {
      st.Evaluate(g.axes, x + DIM * p, hw + DIM * p, F + 9 * p);
      const PetscInt s = c.solid_of[mat[p]];
      PetscReal      e = 0; // J: what the products of the whole particle would take beyond m c_v T
      if (c.burn_energy) {
        e = energy[p] - heat[p];
        for (int a = 0; a < DIM; ++a) e += 0.5 * m[p] * v[DIM * p + a] * v[DIM * p + a];
      }
      ForEachNode(st, [&](PetscInt i, PetscInt j, PetscInt k, PetscReal N, const PetscReal[]) {
        PetscScalar *node = out + index(i, j, k) * dof + s * stride;
        node[0] += N * m[p];
        node[1] += N * m[p] * T[p];
        for (int a = 0; a < DIM; ++a) node[2 + a] += N * m[p] * v[DIM * p + a];
        if (c.burn_energy) out[index(i, j, k) * dof + c.BurnEnergyOffset(DIM, s)] += N * e;
      });
    }
    PetscCall(fields.RestoreAll());
    PetscFunctionReturn(PETSC_SUCCESS);
  }
};

// Nodal values -> particles: ambient pressure (p_n - p_ref) and the temperature increment (whose
// heat m c_v,s dT the budget counts).
struct ParticleKernel {
  MpmSolver         &mpm;
  Coupling          &c;
  const PetscScalar *inc;
  bool               pressure; // else temperature
  template <int DIM, ShapeType S>
  PetscErrorCode operator()()
  {
    const Grid          &g = mpm.grid;
    const LocalNodeIndex index(g);
    const PetscInt       dof = c.IncDof(DIM);
    PetscInt             n;
    const PetscReal     *x, *hw, *F, *m = nullptr;
    const PetscInt      *mat = nullptr;
    PetscReal           *out, heat = 0, *received = nullptr;
    PetscFunctionBeginUser;
    PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
    SwarmAccess fields(mpm.swarm);
    PetscCall(fields.Get(DMSwarmPICField_coor, &x));
    PetscCall(fields.Get(field::half_width0, &hw));
    PetscCall(fields.Get(field::F, &F));
    PetscCall(fields.Get(pressure ? field::ambient_pressure : field::temperature, &out));
    if (!pressure) {
      PetscCall(fields.Get(field::material, &mat));
      PetscCall(fields.Get(field::mass, &m));
      if (c.measure_surface_heat) PetscCall(fields.Get(field::surface_heat, &received));
    }
    bool             fill; // the pressure: this step's stencils from P2G(m, mv); the heat: after G2P moved them
    Stencil<DIM, S> *stencils = mpm.stencil_cache.Prepare<DIM, S>(n, mpm.step, &fill);
    for (PetscInt p = 0; p < n; ++p) {
      Stencil<DIM, S> &st = stencils[p];
      if (fill) st.Evaluate(g.axes, x + DIM * p, hw + DIM * p, F + 9 * p);
      // the pressure, or the temperature increment of the particle's own velocity field
      const PetscInt q     = pressure ? 0 : 1 + c.field_of[c.solid_of[mat[p]]] * (DIM + 1) + DIM;
      PetscReal      value = 0;
      ForEachNode(st, [&](PetscInt i, PetscInt j, PetscInt k, PetscReal N, const PetscReal[]) { value += N * inc[index(i, j, k) * dof + q]; });
      if (pressure) out[p] = value - c.p_ref;
      else {
        // The increments are the cells' (per unit of the solid's mass there); a particle colder than
        // a cell's solid can be handed more cooling than it holds (a trace of solid at the gas's
        // temperature relaxed in one step): it keeps at least half its temperature. What is held
        // back shows in the budget as heat the particles did not receive.
        value = PetscMax(value, -0.5 * out[p]);
        out[p] += value;
        const PetscReal Q = m[p] * c.ice->materials[c.first + c.solid_of[mat[p]]].eos->cv * value;
        heat += Q;
        if (received) received[p] += Q;
      }
    }
    c.counters[kHeatToParticles] += heat;
    PetscCall(fields.RestoreAll());
    PetscFunctionReturn(PETSC_SUCCESS);
  }
};

} // namespace

PetscErrorCode CouplingProjectSolids(Coupling &c)
{
  MpmSolver   &mpm = *c.mpm;
  IceSolver   &ice = *c.ice;
  PetscScalar *nodes, *a;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(c.ev_project, 0, 0, 0, 0));
  PetscCall(VecZeroEntries(c.mass_local));
  PetscCall(VecGetArray(c.mass_local, &nodes));
  ProjectKernel kernel{mpm, c, nodes};
  PetscCall(DispatchShape(mpm.grid.dim, mpm.shape, kernel));
  PetscCall(VecRestoreArray(c.mass_local, &nodes));
  PetscCall(VecZeroEntries(c.mass_global));
  PetscCall(DMLocalToGlobal(c.da_mass, c.mass_local, ADD_VALUES, c.mass_global));
  PetscCall(DMGlobalToLocal(c.da_mass, c.mass_global, INSERT_VALUES, c.mass_local));
  // nodes -> cells
  const LocalNodeIndex index(mpm.grid);
  const PetscInt       dim = ice.dim, stride = 2 + dim, S = ice.stride;
  const PetscReal      V = ice.CellVolume();
  PetscCall(VecGetArray(c.mass_local, &nodes));
  PetscCall(IceGetLocalArray(ice, &a));
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        PetscScalar *cell = a + ice.LocalIndex(i, j, k) * S;
        for (PetscInt s = 0; s < c.nsolid; ++s) {
          const PetscInt m = c.first + s;
          PetscReal      M = 0, MT = 0, P[3] = {0, 0, 0};
          ForEachCorner(ice, i, j, k, [&](const PetscInt node[3], PetscReal w) {
            const PetscScalar *nd = nodes + index(node[0], node[1], node[2]) * c.mass_stride + s * stride;
            M += w * nd[0];
            MT += w * nd[1];
            for (PetscInt d = 0; d < dim; ++d) P[d] += w * nd[2 + d];
          });
          const PetscReal M_tiny = ice.rho_tiny * c.rho0[s] * V;
          const PetscReal T_old  = cell[ice.Offset(m, icef::temp)];
          // an (almost) empty cell keeps its last temperature (ice.md 2.1)
          const PetscReal share           = M / (M + M_tiny);
          cell[ice.Offset(m, icef::rho)]  = (M + M_tiny) / V;
          cell[ice.Offset(m, icef::temp)] = M > 0 ? share * (MT / M) + (1 - share) * T_old : T_old;
          for (PetscInt d = 0; d < 3; ++d) cell[ice.Offset(m, icef::vel + d)] = d < dim ? P[d] / (M + M_tiny) : 0;
        }
      }
  PetscCall(IceRestoreLocalArray(ice, &a));
  PetscCall(VecRestoreArray(c.mass_local, &nodes));
  PetscCall(IceUpdateGhosts(ice));
  PetscCall(PetscLogEventEnd(c.ev_project, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CouplingPressureToParticles(Coupling &c)
{
  MpmSolver         &mpm = *c.mpm;
  IceSolver         &ice = *c.ice;
  const PetscScalar *a;
  PetscScalar       *inc;
  PetscInt           xs[3], xm[3];
  const PetscInt     dim = ice.dim, dof = c.IncDof(dim);
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(c.ev_pressure, 0, 0, 0, 0));
  // nodal pressure: the mean of the cells around each owned node (ghost cells carry the boundary
  // conditions), then to the ghost nodes
  PetscCall(DMDAGetCorners(c.da_inc, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(VecGetArrayRead(ice.local, &a));
  PetscCall(VecGetArray(c.inc_global, &inc));
  PetscInt l = 0;
  for (PetscInt k = xs[2]; k < xs[2] + xm[2]; ++k)
    for (PetscInt j = xs[1]; j < xs[1] + xm[1]; ++j)
      for (PetscInt i = xs[0]; i < xs[0] + xm[0]; ++i, ++l) {
        PetscReal p = 0;
        ForEachCellAroundNode(ice, i, j, k, [&](PetscInt idx, bool) { p += a[idx * ice.stride + ice.CellOffset(icef::press)]; });
        inc[l * dof] = p / (dim == 3 ? 8 : 4);
      }
  PetscCall(VecRestoreArray(c.inc_global, &inc));
  PetscCall(VecRestoreArrayRead(ice.local, &a));
  PetscCall(DMGlobalToLocal(c.da_inc, c.inc_global, INSERT_VALUES, c.inc_local));
  PetscCall(VecGetArrayRead(c.inc_local, &a));
  ParticleKernel kernel{mpm, c, a, true};
  PetscCall(DispatchShape(mpm.grid.dim, mpm.shape, kernel));
  PetscCall(VecRestoreArrayRead(c.inc_local, &a));
  PetscCall(CouplingAmbientImpulse(c)); // its work is the gases' to pay (pressure_work.cxx)
  PetscCall(PetscLogEventEnd(c.ev_pressure, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CouplingSolidVelocity(Coupling &c)
{
  MpmSolver           &mpm = *c.mpm;
  IceSolver           &ice = *c.ice;
  const PetscScalar   *nodes, *vel;
  PetscScalar         *a;
  const LocalNodeIndex index(mpm.grid);
  const PetscInt       dim = ice.dim, stride = 2 + dim, vdof = mpm.grid.num_velocity_fields * 2 * dim;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(c.ev_solid_velocity, 0, 0, 0, 0));
  PetscCall(VecGetArrayRead(c.mass_local, &nodes));
  PetscCall(VecGetArrayRead(mpm.grid.velocity_local, &vel));
  PetscCall(IceGetLocalArray(ice, &a));
  const PetscReal V = ice.CellVolume();
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        PetscScalar *cell = a + ice.LocalIndex(i, j, k) * ice.stride;
        for (PetscInt s = 0; s < c.nsolid; ++s) {
          const PetscInt m    = c.first + s;
          PetscReal      P[3] = {0, 0, 0};
          ForEachCorner(ice, i, j, k, [&](const PetscInt node[3], PetscReal w) {
            const PetscInt n = index(node[0], node[1], node[2]);
            for (PetscInt d = 0; d < dim; ++d) P[d] += w * nodes[n * c.mass_stride + s * stride] * vel[n * vdof + c.field_of[s] * 2 * dim + dim + d];
          });
          for (PetscInt d = 0; d < dim; ++d) cell[ice.Offset(m, icef::vel + d)] = P[d] / (cell[ice.Offset(m, icef::rho)] * V);
        }
      }
  PetscCall(IceRestoreLocalArray(ice, &a));
  PetscCall(VecRestoreArrayRead(mpm.grid.velocity_local, &vel));
  PetscCall(VecRestoreArrayRead(c.mass_local, &nodes));
  PetscCall(IceUpdateGhosts(ice)); // the increments of ghost cells are taken against these
  PetscCall(PetscLogEventEnd(c.ev_solid_velocity, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CouplingIncrementsToNodes(Coupling &c)
{
  MpmSolver         &mpm = *c.mpm;
  IceSolver         &ice = *c.ice;
  Grid              &g   = mpm.grid;
  const PetscScalar *a;
  PetscScalar       *inc, *vel;
  PetscInt           xs[3], xm[3];
  const PetscInt     dim = ice.dim, dof = c.IncDof(dim), vdof = g.num_velocity_fields * 2 * dim;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(c.ev_increments, 0, 0, 0, 0));
  // per owned node and velocity field: the increments of the cells around it, with the weights of
  // the projection (below)
  PetscCall(DMDAGetCorners(c.da_inc, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  const PetscScalar *nodal; // the nodal masses of the P2G, for the impulse of the face conditions
  const PetscInt     node_dof = g.num_velocity_fields * g.NodeStride();
  PetscCall(VecGetArrayRead(ice.local, &a));
  PetscCall(VecGetArray(c.inc_global, &inc));
  PetscCall(VecGetArray(g.velocity, &vel));
  PetscCall(VecGetArrayRead(g.nodal, &nodal));
  PetscCheck((PetscInt)g.velocity_written.size() == xm[0] * xm[1] * xm[2], PETSC_COMM_SELF, PETSC_ERR_PLIB, "The coupling's increments come after a grid update on the node DMDA's layout");
  const PetscReal V = ice.CellVolume();
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k) // the heat the cells gave their solids (the budgets' view of the gas side)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        const PetscScalar *cl = a + ice.LocalIndex(i, j, k) * ice.stride;
        for (PetscInt s = 0; s < c.nsolid; ++s) {
          const PetscInt  m = c.first + s;
          const PetscReal M = cl[ice.Offset(m, icef::rho)] * V;
          c.counters[kHeatToSolidCells] += M * ice.materials[m].eos->cv * (cl[ice.Offset(m, icef::temp_L)] - cl[ice.Offset(m, icef::temp)]);
          for (PetscInt d = 0; d < dim; ++d) {
            const PetscReal u = cl[ice.Offset(m, icef::vel + d)], uL = cl[ice.Offset(m, icef::vel_L + d)];
            c.counters[kMomentumToSolidCells + d] += M * (uL - u);
            c.counters[kKineticToSolidCells] += 0.5 * M * (uL * uL - u * u);
          }
        }
      }
  // Conservative transfer: cell c gives its solid s the increment dX_c per unit of its mass
  // M_c = sum_i w_ci m_i,s (the projection's node weights), and node i's share of that mass is
  // w_ci m_i,s, so node i takes dX_i,s = sum_c w_ci dX_c with w_ci its node weight (1/4 inside in
  // 2-D, more on the domain faces: the weights of a node sum to 1). Then what the nodes (and
  // through them the particles, sum_p m_p sum_i N_ip dX_i = sum_i m_i dX_i) receive is what the
  // cells gave. A field that carries several solids takes their nodal-mass-weighted mean.
  const LocalNodeIndex index(mpm.grid);
  const PetscInt       mstride = 2 + dim;
  const PetscScalar   *solid_mass;
  PetscCall(VecGetArrayRead(c.mass_local, &solid_mass));
  PetscInt l = 0;
  for (PetscInt k = xs[2]; k < xs[2] + xm[2]; ++k)
    for (PetscInt j = xs[1]; j < xs[1] + xm[1]; ++j)
      for (PetscInt i = xs[0]; i < xs[0] + xm[0]; ++i, ++l) {
        PetscReal       weight[2] = {0, 0}, dv[2][3] = {{0, 0, 0}, {0, 0, 0}}, dT[2] = {0, 0};
        const PetscInt  node_ijk[3] = {i, j, k};
        const PetscReal w_node      = NodeWeight(ice, node_ijk);
        for (PetscInt s = 0; s < c.nsolid; ++s) {
          const PetscReal ms = solid_mass[index(i, j, k) * c.mass_stride + s * mstride];
          if (!(ms > 0)) continue;
          const PetscInt m = c.first + s, f = c.field_of[s];
          PetscReal      sum_v[3] = {0, 0, 0}, sum_T = 0;
          ForEachCellAroundNode(ice, i, j, k, [&](PetscInt idx, bool inside) {
            if (!inside) return;
            const PetscScalar *cl = a + idx * ice.stride;
            for (PetscInt d = 0; d < dim; ++d) sum_v[d] += cl[ice.Offset(m, icef::vel_L + d)] - cl[ice.Offset(m, icef::vel + d)];
            sum_T += cl[ice.Offset(m, icef::temp_L)] - cl[ice.Offset(m, icef::temp)];
          });
          weight[f] += ms;
          for (PetscInt d = 0; d < dim; ++d) dv[f][d] += ms * w_node * sum_v[d];
          dT[f] += ms * w_node * sum_T;
        }
        const PetscInt node[3] = {i, j, k};
        for (PetscInt f = 0; f < c.nfield; ++f) {
          PetscScalar *ni = inc + l * dof + 1 + f * (dim + 1);
          for (PetscInt d = 0; d < dim; ++d) {
            PetscReal       value = weight[f] > 0 ? dv[f][d] / weight[f] : 0;
            const PetscReal given = value;
            // the boundary conditions of the grid hold: no normal change on a symmetry face, none on a fixed one
            for (int side = 0; side < 2; ++side) {
              const bool on_face = side == 0 ? node[d] == 0 : node[d] == g.cells[d];
              if (on_face && g.bc[d][side] == FaceBC::Symmetry) value = 0;
            }
            for (PetscInt e = 0; e < dim; ++e)
              for (int side = 0; side < 2; ++side)
                if ((side == 0 ? node[e] == 0 : node[e] == g.cells[e]) && g.bc[e][side] == FaceBC::Fixed) value = 0;
            // what the face held back is the face's impulse on the particles (their momentum changes by m_I dv_I)
            const PetscReal m_node = nodal[l * node_dof + f * g.NodeStride()];
            c.counters[kMomentumToNodes + d] += m_node * given;
            if (value != given) mpm.diag.bc_impulse[d] += m_node * (value - given);
            ni[d] = value;
            c.counters[kKineticToNodes] += m_node * (vel[l * vdof + f * 2 * dim + dim + d] + 0.5 * value) * value;
            vel[l * vdof + f * 2 * dim + dim + d] += value; // v_new of field f
            if (value != 0) g.velocity_written[l] = 1;      // (the next grid update must zero it if the node is empty)
          }
          ni[dim] = weight[f] > 0 ? dT[f] / weight[f] : 0;
        }
      }
  PetscCall(VecRestoreArrayRead(c.mass_local, &solid_mass));
  PetscCall(VecRestoreArrayRead(g.nodal, &nodal));
  PetscCall(VecRestoreArray(g.velocity, &vel));
  PetscCall(VecRestoreArray(c.inc_global, &inc));
  PetscCall(VecRestoreArrayRead(ice.local, &a));
  PetscCall(GridVelocityToLocal(g));
  PetscCall(DMGlobalToLocal(c.da_inc, c.inc_global, INSERT_VALUES, c.inc_local));
  PetscCall(PetscLogEventEnd(c.ev_increments, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CouplingHeatToParticles(Coupling &c)
{
  const PetscScalar *inc;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(c.ev_heat, 0, 0, 0, 0));
  PetscCall(VecGetArrayRead(c.inc_local, &inc));
  ParticleKernel kernel{*c.mpm, c, inc, false};
  PetscCall(DispatchShape(c.mpm->grid.dim, c.mpm->shape, kernel));
  PetscCall(VecRestoreArrayRead(c.inc_local, &inc));
  PetscCall(PetscLogEventEnd(c.ev_heat, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CouplingMeasureSurfaceHeat(Coupling &c, PetscBool on)
{
  PetscFunctionBeginUser;
  c.measure_surface_heat = on;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CouplingSetUp(Coupling &c, IceSolver &ice)
{
  MpmSolver &mpm = *c.mpm;
  PetscFunctionBeginUser;
  c.ice = &ice;
  PetscClassId id;
  PetscCall(PetscClassIdRegister("Coupling", &id));
  PetscCall(PetscLogEventRegister("Cpl_Project", id, &c.ev_project));
  PetscCall(PetscLogEventRegister("Cpl_Burn", id, &c.ev_burn));
  PetscCall(PetscLogEventRegister("Cpl_BurnParticles", id, &c.ev_burn_particles));
  PetscCall(PetscLogEventRegister("Cpl_PressureToPart", id, &c.ev_pressure));
  PetscCall(PetscLogEventRegister("Cpl_SolidVelocity", id, &c.ev_solid_velocity));
  PetscCall(PetscLogEventRegister("Cpl_IncrementsToNode", id, &c.ev_increments));
  PetscCall(PetscLogEventRegister("Cpl_HeatToParticles", id, &c.ev_heat));
  PetscCall(PetscLogEventRegister("Cpl_PressureWork", id, &c.ev_work));
  PetscCall(PetscLogEventRegister("Cpl_SurfaceHeat", id, &c.ev_surface));
  PetscCheck(!mpm.convert_failed, mpm.comm, PETSC_ERR_SUP, "Option -mpm_convert_failed is not supported with gas yet (use -mpm_contact_material for a second velocity field)");
  PetscCheck(mpm.scheme != StepScheme::USF, mpm.comm, PETSC_ERR_SUP, "Option -mpm_scheme usf is not supported with gas: use usl or musl");
  c.first       = ice.ngas;
  c.mass_stride = c.MassDof(mpm.grid.dim);
  c.nfield      = mpm.TwoDeformableFields() ? 2 : 1;
  c.field_of.assign(c.nsolid, 0);
  for (size_t m = 0; m < mpm.materials.size(); ++m)
    if (c.solid_of[m] >= 0) c.field_of[c.solid_of[m]] = mpm.VelocityField((PetscInt)m, 0);
  PetscCall(DMDACreateCompatibleDMDA(mpm.grid.da_nodes, c.mass_stride, &c.da_mass));
  PetscCall(DMCreateGlobalVector(c.da_mass, &c.mass_global));
  PetscCall(DMCreateLocalVector(c.da_mass, &c.mass_local));
  PetscCall(DMDACreateCompatibleDMDA(mpm.grid.da_nodes, c.IncDof(mpm.grid.dim), &c.da_inc));
  PetscCall(DMCreateGlobalVector(c.da_inc, &c.inc_global));
  PetscCall(DMCreateLocalVector(c.da_inc, &c.inc_local));
  // the first projection, then the gases give up the volume the solids take at the cell pressure
  PetscCall(CouplingProjectSolids(c));
  std::vector<PetscReal> fraction((size_t)ice.gxm[0] * ice.gxm[1] * ice.gxm[2], 0);
  PetscScalar           *a;
  PetscCall(IceGetLocalArray(ice, &a));
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        const PetscInt idx  = ice.LocalIndex(i, j, k);
        PetscScalar   *cell = a + idx * ice.stride;
        for (PetscInt s = 0; s < c.nsolid; ++s) {
          const PetscInt m = c.first + s;
          fraction[idx] += cell[ice.Offset(m, icef::rho)] / ice.materials[m].eos->Density(cell[ice.CellOffset(icef::press)], cell[ice.Offset(m, icef::temp)]);
        }
      }
  PetscCall(IceRestoreLocalArray(ice, &a));
  PetscCall(IceMakeRoomForSolids(ice, fraction));
  PetscCall(CouplingBurnSetUp(c));
  PetscCall(CouplingSurfaceHeatSetUp(c));
  if (c.charge_pressure_work) {
    ice.solid_pressure_dv.assign((size_t)ice.gxm[0] * ice.gxm[1] * ice.gxm[2] * c.nsolid * 3, 0);
    PetscCall(DMDACreateCompatibleDMDA(ice.da, c.nsolid * 3, &c.da_dv));
    PetscCall(DMCreateLocalVector(c.da_dv, &c.dv_local));
    PetscCall(VecCreateSeqWithArray(PETSC_COMM_SELF, c.nsolid * 3, (PetscInt)ice.solid_pressure_dv.size(), ice.solid_pressure_dv.data(), &c.dv_owned));
    PetscCall(DMDACreateCompatibleDMDA(mpm.grid.da_nodes, c.nfield * mpm.grid.dim, &c.da_impulse));
    PetscCall(DMCreateGlobalVector(c.da_impulse, &c.impulse_global));
    PetscCall(DMCreateLocalVector(c.da_impulse, &c.impulse_local));
    PetscCall(DMDACreateCompatibleDMDA(mpm.grid.da_nodes, 1, &c.da_work));
    PetscCall(DMCreateGlobalVector(c.da_work, &c.work_global));
    PetscCall(DMCreateLocalVector(c.da_work, &c.work_local));
    PetscCall(DMDACreateCompatibleDMDA(mpm.grid.da_nodes, 2, &c.da_spread));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

void CouplingCheckpointValues(Coupling &c, CheckpointValues &values)
{
  values.Global("burnt_particles", &c.burnt_particles);
  values.PerRank("burnt_mass", &c.burnt_mass);
  values.PerRank("counters", c.counters, kNumCouplingCounters);
}

void CouplingDeleter::operator()(Coupling *coupling) const { delete coupling; }

} // namespace burst
