// The work of the gas pressure on the solids, paid by the gases (ice.md 2.3).
//
// The gas pressure reaches a solid two ways (coupling.hpp): the cell momentum source -theta_s grad p,
// which reaches the nodes with the cells' increments, and the (p - p_ref) I the particles' internal
// force adds to their stress. Inside a solid the two impulses cancel; what is left at a node is the
// pressure on the solid's surface there. The gases' face work only moves energy between gas cells,
// so without a charge the solids gain the work of that surface pressure from nothing (the main job's
// energy budget +32 % of the chemical energy released). Here the work is taken where it is done:
// per node and velocity field, the sum of the two impulses times the node's mean velocity over the
// step, (v_old + v_new)/2. The nodes' works are moved toward the gas that can pay them (SpreadWorkToTheGas),
// then each is paid by the gases of the cells around it, shared by their thermal energies M c_v T, from
// their Lagrangian internal energy before the advection. (Taken per
// cell instead, the two parts do not cancel inside a solid: a heavy piston's cells held +705 J that
// no gas could pay and handed -682 J to a column of air that holds 66 J.)
//
// A node whose cells hold no gas above the trace fraction, a node still inside a solid after the
// sweeps, or the part that would change a gas's temperature by more than half in one step, is not
// paid for: it is counted (kPressureWorkHeld) and the budget shows it.
#include "coupling_impl.hpp"
#include "../mpm/grid_index.hpp"
#include "../mpm/swarm_access.hpp"

namespace burst {

namespace {
// Particles -> nodes: the impulse -dt V_p (p_p - p_ref) grad N_ip of the ambient stress, as P2G(f)
// will add it to the internal force (same positions, volumes and weights), per velocity field.
struct AmbientImpulseKernel {
  MpmSolver   &mpm;
  Coupling    &c;
  PetscScalar *out;
  template <int DIM, ShapeType S>
  PetscErrorCode operator()()
  {
    const Grid          &g = mpm.grid;
    const LocalNodeIndex index(g);
    PetscInt             n;
    const PetscReal     *x, *hw, *F, *vol, *ambient;
    const PetscInt      *mat;
    PetscFunctionBeginUser;
    PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
    SwarmAccess fields(mpm.swarm);
    PetscCall(fields.Get(DMSwarmPICField_coor, &x));
    PetscCall(fields.Get(field::half_width0, &hw));
    PetscCall(fields.Get(field::F, &F));
    PetscCall(fields.Get(field::volume, &vol));
    PetscCall(fields.Get(field::ambient_pressure, &ambient));
    PetscCall(fields.Get(field::material, &mat));
    const PetscReal  dt = mpm.dt;
    bool             fill; // this step's stencils, from P2G(m, mv) at the same positions
    Stencil<DIM, S> *stencils = mpm.stencil_cache.Prepare<DIM, S>(n, mpm.step, &fill);
    for (PetscInt p = 0; p < n; ++p) {
      Stencil<DIM, S> &st = stencils[p];
      if (fill) st.Evaluate(g.axes, x + DIM * p, hw + DIM * p, F + 9 * p);
      const PetscInt s = c.solid_of[mat[p]];
      if (ambient[p] == 0 || s < 0) continue;
      const PetscReal scale = -dt * vol[p] * ambient[p];
      PetscScalar    *field = out + c.field_of[s] * DIM;
      ForEachNode(st, [&](PetscInt i, PetscInt j, PetscInt k, PetscReal, const PetscReal dN[]) {
        PetscScalar *node = field + index(i, j, k) * c.nfield * DIM;
        for (int d = 0; d < DIM; ++d) node[d] += scale * dN[d];
      });
    }
    PetscCall(fields.RestoreAll());
    PetscFunctionReturn(PETSC_SUCCESS);
  }
};
} // namespace

PetscErrorCode CouplingAmbientImpulse(Coupling &c)
{
  MpmSolver   &mpm = *c.mpm;
  PetscScalar *nodes;
  PetscFunctionBeginUser;
  if (!c.charge_pressure_work) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogEventBegin(c.ev_work, 0, 0, 0, 0));
  PetscCall(VecZeroEntries(c.impulse_local));
  PetscCall(VecGetArray(c.impulse_local, &nodes));
  AmbientImpulseKernel kernel{mpm, c, nodes};
  PetscCall(DispatchShape(mpm.grid.dim, mpm.shape, kernel));
  PetscCall(VecRestoreArray(c.impulse_local, &nodes));
  PetscCall(VecZeroEntries(c.impulse_global));
  PetscCall(DMLocalToGlobal(c.da_impulse, c.impulse_local, ADD_VALUES, c.impulse_global)); // owned nodes: complete
  PetscCall(PetscLogEventEnd(c.ev_work, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// The volume fraction of a cell's gases that stand at its pressure: a gas below it (a near-vacuum
// pocket in a steel cell, 1e-5 kg/m^3 over a tenth of it) fills room but holds no energy to pay with.
static PetscReal OpenGasFraction(const IceSolver &ice, const PetscScalar *cell)
{
  const PetscReal p_cell = cell[ice.CellOffset(icef::press)];
  PetscReal       open   = 0;
  for (PetscInt m = 0; m < ice.ngas; ++m) {
    const PetscReal theta = cell[ice.Offset(m, icef::theta)];
    if (!(theta > 0)) continue;
    const PetscReal p_gas = ice.materials[m].eos->Evaluate(cell[ice.Offset(m, icef::rho_L)] / theta, cell[ice.Offset(m, icef::temp_L)]).pressure;
    open += p_cell > 0 ? theta * PetscMin(1.0, PetscMax(0.0, p_gas / p_cell)) : theta;
  }
  return open;
}

// Inside a solid the cells' pressure impulse and the particles' ambient stress cancel only to the
// accuracy of their two discretisations: across a wall that holds the charge's pressure back, the
// nodes inside and on its faces take residues that sum to about nothing over the wall. Paid where
// they fall, the inside's went to the gas pockets of the steel's cells and the outer face's to the
// thin air outside, and heated them to 1e5-1e9 K in the fire scene's burst, where they set the time
// step (a median 3e-8 s against 1.2e-7 s). Each sweep, a node passes on the part of its work its cells' open
// gas fraction does not hold (-coupling_pressure_work_open_fraction) to its face neighbours, in
// proportion to the gas energy around them (pressure times open fraction): the total is unchanged,
// and over a wall's thickness in sweeps the residues meet and what is left goes to the gas with the
// energy to pay it, the charge's products rather than the air outside.
static PetscErrorCode SpreadWorkToTheGas(Coupling &c)
{
  IceSolver           &ice = *c.ice;
  const Grid          &g   = c.mpm->grid;
  const LocalNodeIndex index(g);
  const PetscInt       dim = ice.dim;
  PetscInt             xs[3], xm[3];
  Vec                  gas_global, gas_local, reach_global, reach_local;
  PetscScalar         *cells, *gas, *reach, *work;
  const PetscScalar   *gas_l, *reach_l, *work_l;
  PetscFunctionBeginUser;
  if (c.work_spread_sweeps == 0) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(DMDAGetCorners(c.da_work, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(DMGetGlobalVector(c.da_spread, &gas_global));
  PetscCall(DMGetLocalVector(c.da_spread, &gas_local));
  PetscCall(DMGetGlobalVector(c.da_work, &reach_global));
  PetscCall(DMGetLocalVector(c.da_work, &reach_local));
  // per local cell (ghosts too), its open gas fraction and gas energy scale, p times that fraction;
  // then per node, their means over its cells
  PetscCall(IceGetLocalArray(ice, &cells));
  const PetscInt ncells = ice.gxm[0] * ice.gxm[1] * ice.gxm[2];
  c.cell_open.resize(2 * ncells);
  for (PetscInt idx = 0; idx < ncells; ++idx) {
    const PetscScalar *cell  = cells + idx * ice.stride;
    const PetscReal    open  = OpenGasFraction(ice, cell);
    c.cell_open[2 * idx]     = open;
    c.cell_open[2 * idx + 1] = open * PetscMax(cell[ice.CellOffset(icef::press)], 0.0);
  }
  PetscCall(IceRestoreLocalArray(ice, &cells));
  PetscCall(VecGetArray(gas_global, &gas));
  PetscInt l = 0;
  for (PetscInt k = xs[2]; k < xs[2] + xm[2]; ++k)
    for (PetscInt j = xs[1]; j < xs[1] + xm[1]; ++j)
      for (PetscInt i = xs[0]; i < xs[0] + xm[0]; ++i, ++l) {
        PetscReal open = 0, energy = 0;
        PetscInt  n = 0;
        ForEachCellAroundNode(ice, i, j, k, [&](PetscInt idx, bool inside) {
          if (!inside) return;
          open += c.cell_open[2 * idx];
          energy += c.cell_open[2 * idx + 1];
          ++n;
        });
        gas[2 * l]     = n ? open / n : 0;
        gas[2 * l + 1] = n ? energy / n : 0;
      }
  PetscCall(VecRestoreArray(gas_global, &gas));
  PetscCall(DMGlobalToLocal(c.da_spread, gas_global, INSERT_VALUES, gas_local));
  PetscCall(VecGetArrayRead(gas_local, &gas_l));
  auto open_of   = [&](PetscInt node) { return gas_l[2 * node]; };
  auto energy_of = [&](PetscInt node) { return gas_l[2 * node + 1]; };
  // the face neighbours of node (i, j, k) in the domain
  auto for_each_neighbour = [&](PetscInt i, PetscInt j, PetscInt k, auto &&f) {
    const PetscInt node[3] = {i, j, k};
    for (PetscInt d = 0; d < dim; ++d)
      for (PetscInt side = -1; side <= 1; side += 2) {
        PetscInt nb[3] = {node[0], node[1], node[2]};
        nb[d] += side;
        if (nb[d] < 0 || nb[d] > ice.cells[d]) continue;
        f(index(nb[0], nb[1], nb[2]));
      }
  };
  // reach: the gas energy around a node's neighbours, which share what it passes on
  PetscCall(VecGetArray(reach_global, &reach));
  l = 0;
  for (PetscInt k = xs[2]; k < xs[2] + xm[2]; ++k)
    for (PetscInt j = xs[1]; j < xs[1] + xm[1]; ++j)
      for (PetscInt i = xs[0]; i < xs[0] + xm[0]; ++i, ++l) {
        PetscReal sum = 0;
        for_each_neighbour(i, j, k, [&](PetscInt nb) { sum += energy_of(nb); });
        reach[l] = sum;
      }
  PetscCall(VecRestoreArray(reach_global, &reach));
  PetscCall(DMGlobalToLocal(c.da_work, reach_global, INSERT_VALUES, reach_local));
  PetscCall(VecGetArrayRead(reach_local, &reach_l));
  // the part of its work a node passes on: all of it when its cells hold no open gas, none when open
  auto passed = [&](PetscInt node) { return reach_l[node] > 0 ? 1 - PetscMin(1.0, open_of(node) / c.work_open_fraction) : 0.0; };
  for (PetscInt sweep = 0; sweep < c.work_spread_sweeps; ++sweep) {
    PetscCall(DMGlobalToLocal(c.da_work, c.work_global, INSERT_VALUES, c.work_local));
    PetscCall(VecGetArrayRead(c.work_local, &work_l));
    PetscCall(VecGetArray(c.work_global, &work));
    l = 0;
    for (PetscInt k = xs[2]; k < xs[2] + xm[2]; ++k)
      for (PetscInt j = xs[1]; j < xs[1] + xm[1]; ++j)
        for (PetscInt i = xs[0]; i < xs[0] + xm[0]; ++i, ++l) {
          const PetscInt me       = index(i, j, k);
          PetscReal      received = 0;
          for_each_neighbour(i, j, k, [&](PetscInt nb) {
            if (work_l[nb] != 0) received += passed(nb) * work_l[nb] * energy_of(me) / reach_l[nb];
          });
          work[l] = (1 - passed(me)) * work_l[me] + received;
        }
    PetscCall(VecRestoreArray(c.work_global, &work));
    PetscCall(VecRestoreArrayRead(c.work_local, &work_l));
  }
  // what is still inside a solid after the sweeps is not paid by its gas pockets: it is held
  PetscCall(VecGetArray(c.work_global, &work));
  l = 0;
  for (PetscInt k = xs[2]; k < xs[2] + xm[2]; ++k)
    for (PetscInt j = xs[1]; j < xs[1] + xm[1]; ++j)
      for (PetscInt i = xs[0]; i < xs[0] + xm[0]; ++i, ++l)
        if (work[l] != 0 && open_of(index(i, j, k)) < c.work_closed_fraction) {
          c.counters[kPressureWorkHeld] += work[l];
          work[l] = 0;
        }
  PetscCall(VecRestoreArray(c.work_global, &work));
  PetscCall(VecRestoreArrayRead(reach_local, &reach_l));
  PetscCall(VecRestoreArrayRead(gas_local, &gas_l));
  PetscCall(DMRestoreLocalVector(c.da_work, &reach_local));
  PetscCall(DMRestoreGlobalVector(c.da_work, &reach_global));
  PetscCall(DMRestoreLocalVector(c.da_spread, &gas_local));
  PetscCall(DMRestoreGlobalVector(c.da_spread, &gas_global));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CouplingChargePressureWork(Coupling &c)
{
  MpmSolver &mpm = *c.mpm;
  IceSolver &ice = *c.ice;
  Grid      &g   = mpm.grid;
  PetscFunctionBeginUser;
  if (!c.charge_pressure_work) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogEventBegin(c.ev_work, 0, 0, 0, 0));
  const PetscInt       dim = ice.dim, vdof = g.num_velocity_fields * 2 * dim, mstride = 2 + dim, ns = c.nsolid;
  const LocalNodeIndex index(g);
  PetscInt             xs[3], xm[3];
  const PetscScalar   *impulse, *vel, *solid_mass;
  PetscScalar         *work;
  PetscReal            ambient_work = 0;
  // the solids' pressure velocity changes of the owned cells (IceSources) -> with the ghost cells
  PetscCall(DMLocalToLocalBegin(c.da_dv, c.dv_owned, INSERT_VALUES, c.dv_local));
  PetscCall(DMLocalToLocalEnd(c.da_dv, c.dv_owned, INSERT_VALUES, c.dv_local));
  const PetscScalar *dv_cells;
  // the work at each owned node: (the cells' pressure impulse + the particles' ambient impulse) . (v_old + v_new)/2
  PetscCall(DMDAGetCorners(c.da_work, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(VecGetArrayRead(c.dv_local, &dv_cells));
  PetscCall(VecGetArrayRead(c.impulse_global, &impulse));
  PetscCall(VecGetArrayRead(g.velocity, &vel));
  PetscCall(VecGetArrayRead(c.mass_local, &solid_mass));
  PetscCall(VecGetArray(c.work_global, &work));
  PetscInt l = 0;
  for (PetscInt k = xs[2]; k < xs[2] + xm[2]; ++k)
    for (PetscInt j = xs[1]; j < xs[1] + xm[1]; ++j)
      for (PetscInt i = xs[0]; i < xs[0] + xm[0]; ++i, ++l) {
        PetscReal       J[2][3]     = {{0, 0, 0}, {0, 0, 0}}; // the cells' impulse per field
        const PetscInt  node_ijk[3] = {i, j, k};
        const PetscReal w_node      = NodeWeight(ice, node_ijk);
        for (PetscInt s = 0; s < ns; ++s) {
          const PetscReal ms = solid_mass[index(i, j, k) * c.mass_stride + s * mstride];
          if (!(ms > 0)) continue;
          ForEachCellAroundNode(ice, i, j, k, [&](PetscInt idx, bool inside) {
            if (!inside) return;
            for (PetscInt d = 0; d < dim; ++d) J[c.field_of[s]][d] += ms * w_node * dv_cells[(idx * ns + s) * 3 + d];
          });
        }
        PetscReal w = 0;
        for (PetscInt f = 0; f < c.nfield; ++f) {
          const PetscScalar *v = vel + l * vdof + f * 2 * dim; // v_old, v_new
          for (PetscInt d = 0; d < dim; ++d) {
            const PetscReal v_mid = 0.5 * (v[d] + v[dim + d]), amb = impulse[l * c.nfield * dim + f * dim + d];
            w += (J[f][d] + amb) * v_mid;
            ambient_work += amb * v_mid;
          }
        }
        work[l] = w;
      }
  PetscCall(VecRestoreArray(c.work_global, &work));
  PetscCall(VecRestoreArrayRead(c.mass_local, &solid_mass));
  PetscCall(VecRestoreArrayRead(g.velocity, &vel));
  PetscCall(VecRestoreArrayRead(c.impulse_global, &impulse));
  PetscCall(VecRestoreArrayRead(c.dv_local, &dv_cells));
  PetscCall(SpreadWorkToTheGas(c));
  PetscCall(DMGlobalToLocal(c.da_work, c.work_global, INSERT_VALUES, c.work_local));

  // each owned cell pays its share of the work of its corner nodes: a node's work is shared by the
  // gases of the cells around it in proportion to their thermal energy M c_v T (the default) or heat
  // capacity M c_v (-coupling_pressure_work_share). Ideal gases compressed together at one pressure
  // change their temperatures by one factor, which is the energy share; the heat-capacity share
  // changes them by one difference, so a cold gas paying for the products' expansion at a burning
  // surface reached a few kelvin. Traces are excluded: by volume fraction, an almost empty pocket in
  // the charge (1e-13 kg/m^3 over 1 % of the cell) took a node's work and reached 6e9 K.
  const PetscReal    V = ice.CellVolume();
  const PetscScalar *node_work;
  PetscScalar       *cells;
  PetscReal          charged = 0, held = 0;
  auto               heat_capacity = [&](const PetscScalar *cell, PetscInt m) { return cell[ice.Offset(m, icef::theta)] >= ice.trace_fraction ? cell[ice.Offset(m, icef::rho_L)] * ice.materials[m].eos->cv : 0.0; };
  auto               weight        = [&](const PetscScalar *cell, PetscInt m) { return heat_capacity(cell, m) * (c.work_share == WorkShare::Energy ? cell[ice.Offset(m, icef::temp_L)] : 1.0); };
  auto               gas_weight    = [&](const PetscScalar *cell) {
    PetscReal sum = 0;
    for (PetscInt m = 0; m < ice.ngas; ++m) sum += weight(cell, m);
    return sum;
  };
  PetscCall(VecGetArrayRead(c.work_local, &node_work));
  PetscCall(IceGetLocalArray(ice, &cells));
  // the bills first, from the temperatures before any is paid (the energy share reads them)
  c.cell_bill.resize(ice.xm[0] * ice.xm[1] * ice.xm[2]);
  PetscInt n = 0;
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i, ++n) {
        const PetscReal mine = gas_weight(cells + ice.LocalIndex(i, j, k) * ice.stride);
        PetscReal       bill = 0;
        ForEachCorner(ice, i, j, k, [&](const PetscInt node[3], PetscReal w) {
          const PetscReal W = node_work[index(node[0], node[1], node[2])];
          if (W == 0) return;
          PetscReal around = 0;
          ForEachCellAroundNode(ice, node[0], node[1], node[2], [&](PetscInt idx, bool inside) {
            if (inside) around += gas_weight(cells + idx * ice.stride);
          });
          if (around > 0) bill += W * mine / around;
          else held += w * W; // no gas around the node: each of its cells counts its weight's share
        });
        c.cell_bill[n] = bill;
      }
  n = 0;
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i, ++n) {
        const PetscReal bill = c.cell_bill[n];
        if (bill == 0) continue;
        PetscScalar    *cell = cells + ice.LocalIndex(i, j, k) * ice.stride;
        const PetscReal mine = gas_weight(cell);
        for (PetscInt m = 0; m < ice.ngas; ++m) {
          const PetscReal capacity = heat_capacity(cell, m);
          if (!(capacity > 0)) continue;
          const PetscReal share = bill * weight(cell, m) / mine;
          const PetscReal heat  = capacity * V; // J/K
          PetscReal      &T_L   = cell[ice.Offset(m, icef::temp_L)];
          // a step changes the gas's temperature by at most half of it either way; the rest is held
          const PetscReal paid = PetscMax(PetscMin(share, 0.5 * T_L * heat), -0.5 * T_L * heat);
          T_L -= paid / heat;
          charged += paid;
          held += share - paid;
        }
      }
  PetscCall(IceRestoreLocalArray(ice, &cells));
  PetscCall(IceUpdateGhosts(ice)); // the advection reads the neighbours' Lagrangian values
  PetscCall(VecRestoreArrayRead(c.work_local, &node_work));
  c.counters[kAmbientStressWork] += ambient_work;
  c.counters[kPressureWorkCharged] += charged;
  c.counters[kPressureWorkHeld] += held;
  PetscCall(PetscLogEventEnd(c.ev_work, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
