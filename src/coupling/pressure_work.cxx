// The work of the gas pressure on the solids, paid by the gases (ice.md 2.3).
//
// The gas pressure reaches a solid two ways (coupling.hpp): the cell momentum source -theta_s grad p,
// and the (p - p_ref) I that the particles' internal force adds to their stress. Both give the solid
// energy: the first kinetic energy in the cells (IceSources keeps it per cell, ice.solid_work), the
// second the power -V (p - p_ref) tr L of that stress on the particle's motion. Inside a solid the two
// cancel; what is left is the work of the pressure on the solid's surface. The gases' face work only
// moves energy between gas cells, so without a charge the solids gain this work from nothing (the
// main job's energy budget +32 % of the chemical energy released). Here each cell's gases pay it,
// shared by volume fraction, from their Lagrangian internal energy before the advection.
//
// The particles' share goes back the way the pressure came: particle -> nodes (N_ip) -> the cells
// around each node (the node's share of each, 1/2^dim inside; the transpose of the nodal pressure
// mean). A cell without gas above the trace fraction, or whose gases would cool below half their
// temperature, cannot pay: that part is counted (kPressureWorkHeld) and the budget shows it.
#include "coupling_impl.hpp"
#include "../mpm/grid_index.hpp"
#include "../mpm/swarm_access.hpp"

namespace burst {

namespace {
// Particles -> nodes: the work W_p = -dt V_p (p_p - p_ref) tr L_p of the ambient stress, V_p the
// volume at the start of the step (the one the internal force used).
struct AmbientWorkKernel {
  Simulation  &sim;
  PetscScalar *out;
  PetscReal    total = 0; // J, the work of all the particles
  template <int DIM, ShapeType S>
  PetscErrorCode operator()()
  {
    const Grid          &g = sim.grid;
    const LocalNodeIndex index(g);
    PetscInt             n;
    const PetscReal     *x, *hw, *F, *L, *vol, *ambient;
    PetscFunctionBeginUser;
    PetscCall(DMSwarmGetLocalSize(sim.swarm, &n));
    SwarmAccess fields(sim.swarm);
    PetscCall(fields.Get(DMSwarmPICField_coor, &x));
    PetscCall(fields.Get(field::half_width0, &hw));
    PetscCall(fields.Get(field::F, &F));
    PetscCall(fields.Get(field::L, &L));
    PetscCall(fields.Get(field::volume, &vol));
    PetscCall(fields.Get(field::ambient_pressure, &ambient));
    const PetscReal dt = sim.dt;
    Stencil<DIM, S> st;
    for (PetscInt p = 0; p < n; ++p) {
      if (ambient[p] == 0) continue;
      const PetscReal *l = L + 9 * p;
      // det(I + dt L): the volume ratio of the step (g2p.cxx)
      const PetscReal a00 = 1 + dt * l[0], a01 = dt * l[1], a02 = dt * l[2], a10 = dt * l[3], a11 = 1 + dt * l[4], a12 = dt * l[5], a20 = dt * l[6], a21 = dt * l[7], a22 = 1 + dt * l[8];
      const PetscReal ratio = a00 * (a11 * a22 - a12 * a21) - a01 * (a10 * a22 - a12 * a20) + a02 * (a10 * a21 - a11 * a20);
      const PetscReal work  = -dt * vol[p] / ratio * ambient[p] * (l[0] + l[4] + l[8]);
      total += work;
      st.Evaluate(g.axes, x + DIM * p, hw + DIM * p, F + 9 * p);
      ForEachNode(st, [&](PetscInt i, PetscInt j, PetscInt k, PetscReal N, const PetscReal[]) { out[index(i, j, k)] += N * work; });
    }
    PetscCall(fields.RestoreAll());
    PetscFunctionReturn(PETSC_SUCCESS);
  }
};
} // namespace

PetscErrorCode CouplingChargePressureWork(Simulation &sim)
{
  Coupling  &c   = *sim.coupling;
  IceSolver &ice = *sim.ice;
  PetscFunctionBeginUser;
  if (!c.charge_pressure_work) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogEventBegin(c.ev_work, 0, 0, 0, 0));
  PetscScalar *nodes;
  PetscCall(VecZeroEntries(c.work_local));
  PetscCall(VecGetArray(c.work_local, &nodes));
  AmbientWorkKernel kernel{sim, nodes};
  PetscCall(DispatchShape(sim.grid.dim, sim.shape, kernel));
  PetscCall(VecRestoreArray(c.work_local, &nodes));
  c.counters[kAmbientStressWork] += kernel.total;
  PetscCall(VecZeroEntries(c.work_global));
  PetscCall(DMLocalToGlobal(c.da_work, c.work_local, ADD_VALUES, c.work_global));
  PetscCall(DMGlobalToLocal(c.da_work, c.work_global, INSERT_VALUES, c.work_local));

  const LocalNodeIndex index(sim.grid);
  const PetscReal      V = ice.CellVolume();
  const PetscScalar   *node_work;
  PetscScalar         *a;
  PetscReal            charged = 0, held = 0;
  PetscCall(VecGetArrayRead(c.work_local, &node_work));
  PetscCall(IceGetLocalArray(ice, &a));
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        const PetscInt idx  = ice.LocalIndex(i, j, k);
        PetscScalar   *cell = a + idx * ice.stride;
        // a node's work goes to its cells in the shares NodeWeight gives (1/2^dim inside)
        PetscReal work = ice.solid_work[idx];
        ForEachCorner(ice, i, j, k, [&](const PetscInt node[3], PetscReal w) { work += w * node_work[index(node[0], node[1], node[2])]; });
        if (work == 0) continue;
        PetscReal gas_fraction = 0;
        for (PetscInt m = 0; m < ice.ngas; ++m)
          if (cell[ice.Offset(m, icef::theta)] >= ice.trace_fraction) gas_fraction += cell[ice.Offset(m, icef::theta)];
        if (!(gas_fraction > 0)) {
          held += work;
          continue;
        }
        for (PetscInt m = 0; m < ice.ngas; ++m) {
          const PetscReal theta = cell[ice.Offset(m, icef::theta)];
          if (theta < ice.trace_fraction) continue;
          const PetscReal share = work * theta / gas_fraction;
          const PetscReal heat  = cell[ice.Offset(m, icef::rho_L)] * V * ice.materials[m].eos->cv; // J/K
          PetscReal      &T_L   = cell[ice.Offset(m, icef::temp_L)];
          const PetscReal paid  = PetscMin(share, 0.5 * T_L * heat); // keeps at least half its temperature
          T_L -= paid / heat;
          charged += paid;
          held += share - paid;
        }
      }
  PetscCall(IceRestoreLocalArray(ice, &a));
  PetscCall(IceUpdateGhosts(ice)); // the advection reads the neighbours' Lagrangian values
  PetscCall(VecRestoreArrayRead(c.work_local, &node_work));
  c.counters[kPressureWorkCharged] += charged;
  c.counters[kPressureWorkHeld] += held;
  PetscCall(PetscLogEventEnd(c.ev_work, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
