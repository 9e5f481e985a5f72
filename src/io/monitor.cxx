// Conserved-quantity monitor (screen + monitor.csv) and the end-of-run summary.json.
//
// Energy balance of the solids: kinetic + internal (stress work) + removed - external work stays
// equal to its initial value for a conservative scheme; the relative balance error divides the drift
// by the largest energy seen (kinetic + internal + |external work|).
//
// A run with gas has the budgets of the whole system (Budget below): mass, momentum and total energy
// of particles and gases with what crossed the domain faces, what was removed and the chemical
// energy the burn released; its energy error is the run's balance error.
#include "../simulation.hpp"
#include "mpm/swarm_access.hpp"
#include "scenes/analytic.hpp"
#include "ice/ice.hpp"
#include "coupling/coupling.hpp"
#include "io/checkpoint_values.hpp"
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

namespace burst {

PetscErrorCode ComputeEnergies(Simulation &sim, EnergyReport &r)
{
  PetscInt         n, dim = sim.mpm.grid.dim;
  const PetscReal *v, *m, *e;
  PetscReal        local[8] = {0, 0, 0, 0, 0, 0, 0, 0}, global[8];
  PetscFunctionBeginUser;
  r = EnergyReport{};
  if (!sim.HasParticles()) PetscFunctionReturn(PETSC_SUCCESS); // a gas-only scene
  PetscCall(DMSwarmGetLocalSize(sim.mpm.swarm, &n));
  SwarmAccess fields(sim.mpm.swarm);
  PetscCall(fields.Get(field::velocity, &v));
  PetscCall(fields.Get(field::mass, &m));
  PetscCall(fields.Get(field::internal_energy, &e));
  for (PetscInt p = 0; p < n; ++p) {
    PetscReal v2 = 0;
    for (PetscInt d = 0; d < dim; ++d) {
      v2 += v[dim * p + d] * v[dim * p + d];
      local[3 + d] += m[p] * v[dim * p + d];
    }
    local[0] += 0.5 * m[p] * v2;
    local[1] += e[p];
    local[6] += m[p];
  }
  local[2] = sim.mpm.diag.external_work;
  local[7] = sim.mpm.diag.removed_energy;
  // parts of the internal energy kept by the models: failure energy, plastic work, heat
  PetscReal   parts_local[5] = {0, 0, 0, sim.mpm.diag.viscous_work, 0}, parts[5];
  const char *part_names[5]  = {"failure_energy", "plastic_work", "plastic_heat", nullptr, "elastic_energy"};
  const bool  elastic_known  = SwarmHasModelField(sim.mpm, "elastic_energy");
  for (int k = 0; k < 5; ++k)
    if (part_names[k] && SwarmHasModelField(sim.mpm, part_names[k])) {
      const PetscReal *values;
      PetscCall(fields.Get(part_names[k], &values));
      for (PetscInt p = 0; p < n; ++p) parts_local[k] += values[p];
    }
  if (!elastic_known) parts_local[4] = local[1]; // elastic materials store all their stress work
  PetscCall(fields.RestoreAll());
  PetscCallMPI(MPI_Allreduce(local, global, 8, MPIU_REAL, MPI_SUM, sim.comm));
  PetscCallMPI(MPI_Allreduce(parts_local, parts, 5, MPIU_REAL, MPI_SUM, sim.comm));
  r.failure_energy = parts[0];
  r.plastic_work   = parts[1];
  r.heat           = parts[2];
  r.viscous_work   = parts[3];
  r.kinetic        = global[0];
  r.internal       = global[1];
  r.external_work  = global[2];
  r.removed        = global[7];
  r.total          = r.kinetic + r.internal + r.removed;
  r.stored_elastic = parts[4];
  r.unaccounted    = r.internal - r.stored_elastic - r.plastic_work - r.viscous_work - r.failure_energy;
  for (int d = 0; d < 3; ++d) r.momentum[d] = global[3 + d];
  r.mass                  = global[6];
  sim.output.energy_scale = PetscMax(sim.output.energy_scale, r.kinetic + r.internal + PetscAbsReal(r.external_work));
  r.balance_error         = sim.output.energy_scale > 0 ? (r.total - r.external_work - sim.mpm.diag.initial_energy) / sim.output.energy_scale : 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Position, displacement and normal stresses of the tracked particle (-monitor_track_pid),
// gathered to every rank.
static PetscErrorCode TrackedParticle(Simulation &sim, PetscReal xu[9])
{
  PetscInt          n, dim = sim.mpm.grid.dim;
  const PetscReal  *x, *X0, *sigma;
  const PetscInt64 *pid;
  PetscReal         local[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0}, global[10];
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(sim.mpm.swarm, &n));
  SwarmAccess fields(sim.mpm.swarm);
  PetscCall(fields.Get(DMSwarmPICField_coor, &x));
  PetscCall(fields.Get(field::position0, &X0));
  PetscCall(fields.Get(DMSwarmField_pid, &pid));
  PetscCall(fields.Get(field::stress, &sigma));
  for (PetscInt p = 0; p < n; ++p)
    if (pid[p] == sim.output.track_pid) {
      for (PetscInt d = 0; d < dim; ++d) {
        local[d]     = x[dim * p + d];
        local[3 + d] = x[dim * p + d] - X0[dim * p + d];
      }
      for (int d = 0; d < 3; ++d) local[6 + d] = sigma[9 * p + 4 * d];
      local[9] = 1;
    }
  PetscCall(fields.RestoreAll());
  PetscCallMPI(MPI_Allreduce(local, global, 10, MPIU_REAL, MPI_SUM, sim.comm));
  PetscCheck(global[9] == 1, sim.comm, PETSC_ERR_USER_INPUT,
             "Option -monitor_track_pid %" PetscInt_FMT ": no particle has this id (lattice ids are ((cell x geometries + geometry) x sub-cells + sub-cell), polar ones follow them, all below %" PetscInt64_FMT "; see the id field of the output)",
             sim.output.track_pid, sim.mpm.next_pid);
  for (int k = 0; k < 9; ++k) xu[k] = global[k];
  PetscFunctionReturn(PETSC_SUCCESS);
}

// The id of the particle nearest to -monitor_track_point (the smallest id on a tie).
static PetscErrorCode NearestParticle(Simulation &sim)
{
  PetscInt          n, dim = sim.mpm.grid.dim;
  const PetscReal  *x;
  const PetscInt64 *pid;
  struct {
    PetscReal  d2;
    PetscInt64 id;
  } local = {PETSC_MAX_REAL, -1};
  PetscFunctionBeginUser;
  SwarmAccess fields(sim.mpm.swarm);
  PetscCall(DMSwarmGetLocalSize(sim.mpm.swarm, &n));
  PetscCall(fields.Get(DMSwarmPICField_coor, &x));
  PetscCall(fields.Get(DMSwarmField_pid, &pid));
  for (PetscInt p = 0; p < n; ++p) {
    PetscReal d2 = 0;
    for (PetscInt d = 0; d < dim; ++d) d2 += (x[dim * p + d] - sim.output.track_point[d]) * (x[dim * p + d] - sim.output.track_point[d]);
    if (d2 < local.d2 || (d2 == local.d2 && pid[p] < local.id)) local = {d2, pid[p]};
  }
  PetscCall(fields.RestoreAll());
  PetscReal  best;
  PetscInt64 id = PETSC_MAX_INT, candidate;
  PetscCallMPI(MPI_Allreduce(&local.d2, &best, 1, MPIU_REAL, MPI_MIN, sim.comm));
  candidate = local.d2 == best ? local.id : PETSC_MAX_INT;
  PetscCallMPI(MPI_Allreduce(&candidate, &id, 1, MPIU_INT64, MPI_MIN, sim.comm));
  sim.output.track_pid = (PetscInt)id;
  PetscCall(PetscInfo(sim.mpm.swarm, "Tracing particle %" PetscInt64_FMT " at %g m from -monitor_track_point\n", id, (double)std::sqrt(best)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

namespace {
// The budgets of a run with gas. Each conserved quantity is a sum of terms that stays at its initial
// value for a conservative step:
//   mass      particles + gases + out through open faces + particles removed (outside the domain)
//   momentum  particles + gases + out through open faces + removed particles - the impulse of the
//             face pressures on the cells' materials - the impulse of the grid's fixed and symmetry
//             faces on the particles
//   energy    particles' kinetic energy + stress work + heat from the gas - the thermal energy
//             m c_v,s T the burnt reactant took into the gas + gases' kinetic + internal energy +
//             advected energy and p theta u A dt work out through open faces + removed particles'
//             kinetic energy and stress work - external work - chemical energy released (dm Q)
// Burnt mass moves from the particles to the gas: it is in neither "out" term, and what the gas
// receives (dm (c_v,s T_s + Q) and dm u^2/2) against what the particles lose (m c_v,s T, kinetic
// energy, stress work) is measured by the sums. Each error is the sum's drift divided by the largest
// term seen so far (momentum: vector norms).
struct Budget {
  PetscReal solid_mass = 0, gas_mass = 0, open_mass = 0, removed_mass = 0;
  PetscReal open_mass_face[3][2] = {{0, 0}, {0, 0}, {0, 0}}; // of open_mass, each domain face's (not in the sums)
  PetscReal solid_momentum[3] = {0, 0, 0}, gas_momentum[3] = {0, 0, 0}, open_momentum[3] = {0, 0, 0};
  PetscReal face_impulse[3] = {0, 0, 0}, bc_impulse[3] = {0, 0, 0}, removed_momentum[3] = {0, 0, 0};
  PetscReal solid_kinetic = 0, solid_internal = 0, heat_to_particles = 0, reactant_thermal = 0, gas_kinetic = 0, gas_internal = 0;
  PetscReal open_energy = 0, open_work = 0, removed_energy = 0, external_work = 0, chemical = 0;
  PetscReal heat_to_solid_cells = 0, reactant_energy_cells = 0;                         // the cells' view of two transfers (not in the sums)
  PetscReal momentum_to_solid_cells[3] = {0, 0, 0}, momentum_to_nodes[3] = {0, 0, 0};   // the cells' and the nodes' view of the solids' momentum from the gas (not in the sums)
  PetscReal kinetic_to_solid_cells = 0, kinetic_to_nodes = 0;                           // and of the kinetic energy it brings
  PetscReal drag_energy_change         = 0;                                             // what the cell exchange's drag created (< 0: the dissipated kinetic energy dropped; not in the sums)
  PetscReal solid_pressure_work        = 0;                                             // the kinetic energy the cells' pressure source gives the solids (not in the sums)
  PetscReal gas_interface_work         = 0;                                             // the gases' face work booked on one side of a face only (not in the sums)
  PetscReal advection_energy_change    = 0;                                             // the gases' energy the advection did not conserve (not in the sums)
  PetscReal solid_cell_energy_transfer = 0;                                             // the gases of solids' cells to their solids (sources.cxx)
  PetscReal fallback_energy_change = 0, trace_energy_change = 0;                        // and the sources: -p dV fallbacks, traces (not in the sums)
  PetscReal equilibration_energy_change = 0;                                            // and the equilibration (not in the sums)
  PetscReal exchange_energy_change = 0, exchange_fallback_energy = 0;                   // and the exchange: all of it, its fallbacks' part (the drag's above)
  PetscReal burnt_particle_energy = 0;                                                  // the kinetic energy and stress work burning took from the particles (not in the sums)
  PetscReal ambient_stress_work = 0, pressure_work_charged = 0, pressure_work_held = 0; // the gas pressure's work on the solids: the particles' (p - p_ref) I part, what the gases paid of all of it, what they could not (not in the sums)
  PetscReal mass = 0, momentum[3] = {0, 0, 0}, energy = 0;                              // the sums
  PetscReal momentum_residual[3] = {0, 0, 0}, energy_residual = 0;                      // sums less their initial values (kg m/s, J)
  PetscReal mass_error = 0, momentum_error = 0, energy_error = 0;                       // relative to the largest term
};

PetscReal Norm3(const PetscReal v[3]) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// The terms from the solids' report r and the gas totals, with the counters of every rank; with
// `initial` the sums become the reference (set-up), else the largest terms grow and the errors follow.
PetscErrorCode ComputeBudget(Simulation &sim, const EnergyReport &r, const IceTotals &gas, bool initial, Budget &b)
{
  enum {
    kOpen             = 0,
    kRemovedMomentum  = 9,
    kBcImpulse        = 12,
    kRemovedMass      = 15,
    kDrag             = 16,
    kPressureWork     = 17,
    kInterfaceWork    = 18,
    kAdvection        = 19,
    kFallback         = 20,
    kTrace            = 21,
    kEquilibration    = 22,
    kExchange         = 23,
    kExchangeFallback = 24,
    kSolidCell        = 25,
    kCoupling         = 26,
    kFaceMass         = kCoupling + kNumCouplingCounters,
    kCount            = kFaceMass + 6
  };
  PetscReal local[kCount] = {0}, global[kCount];
  PetscFunctionBeginUser;
  const IceBoundaryBudget &f = sim.ice->boundary;
  local[kOpen]               = f.mass;
  for (int d = 0; d < 3; ++d) {
    local[kOpen + 1 + d]        = f.momentum[d];
    local[kOpen + 6 + d]        = f.impulse[d];
    local[kRemovedMomentum + d] = sim.mpm.diag.removed_momentum[d];
    local[kBcImpulse + d]       = sim.mpm.diag.bc_impulse[d];
  }
  local[kOpen + 4]    = f.energy;
  local[kOpen + 5]    = f.work;
  local[kRemovedMass] = sim.mpm.diag.removed_mass;
  for (int k = 0; k < 6; ++k) local[kFaceMass + k] = f.face_mass[k / 2][k % 2];
  const auto diagnostics = sim.ice->EnergyDiagnostics(); // kDrag .. kExchangeFallback, in its order
  for (int k = 0; k < IceSolver::kEnergyDiagnostics; ++k) local[kDrag + k] = *diagnostics[k];
  if (sim.coupling)
    for (int k = 0; k < kNumCouplingCounters; ++k) local[kCoupling + k] = CouplingCounters(*sim.coupling)[k];
  PetscCallMPI(MPI_Allreduce(local, global, kCount, MPIU_REAL, MPI_SUM, sim.comm));
  const PetscReal *counter = global + kCoupling; // the coupling's (coupling.hpp)
  b.solid_mass             = r.mass;
  b.gas_mass               = gas.mass;
  b.open_mass              = global[kOpen];
  for (int k = 0; k < 6; ++k) b.open_mass_face[k / 2][k % 2] = global[kFaceMass + k];
  b.removed_mass = global[kRemovedMass] - counter[kBurntParticleMass]; // burnt mass went to the gas
  for (int d = 0; d < 3; ++d) {
    b.solid_momentum[d]   = r.momentum[d];
    b.gas_momentum[d]     = gas.momentum[d];
    b.open_momentum[d]    = global[kOpen + 1 + d];
    b.face_impulse[d]     = global[kOpen + 6 + d];
    b.bc_impulse[d]       = global[kBcImpulse + d];
    b.removed_momentum[d] = global[kRemovedMomentum + d] - counter[kBurntParticleMomentum + d];
  }
  b.solid_kinetic           = r.kinetic;
  b.solid_internal          = r.internal;
  b.heat_to_particles       = counter[kHeatToParticles];
  b.reactant_thermal        = counter[kBurntParticleThermal];
  b.gas_kinetic             = gas.kinetic_energy;
  b.gas_internal            = gas.internal_energy;
  b.open_energy             = global[kOpen + 4];
  b.open_work               = global[kOpen + 5];
  b.removed_energy          = r.removed - counter[kBurntParticleEnergy];
  b.external_work           = r.external_work;
  b.chemical                = counter[kChemicalEnergy];
  b.heat_to_solid_cells     = counter[kHeatToSolidCells];
  b.reactant_energy_cells   = counter[kReactantEnergyCells];
  b.drag_energy_change      = global[kDrag];
  b.solid_pressure_work     = global[kPressureWork];
  b.gas_interface_work      = global[kInterfaceWork];
  b.advection_energy_change = global[kAdvection];
  // IceBudgetFaces counts what IceSolidCellEnergy moved from a gas to its cell's solids as made by
  // the sources; it is a transfer (the solids' heat_to_solid_cells has it)
  b.solid_cell_energy_transfer  = global[kSolidCell];
  b.fallback_energy_change      = global[kFallback] + global[kSolidCell];
  b.trace_energy_change         = global[kTrace];
  b.equilibration_energy_change = global[kEquilibration];
  b.exchange_energy_change      = global[kExchange];
  b.exchange_fallback_energy    = global[kExchangeFallback];
  b.burnt_particle_energy       = counter[kBurntParticleEnergy];
  b.kinetic_to_solid_cells      = counter[kKineticToSolidCells];
  b.kinetic_to_nodes            = counter[kKineticToNodes];
  b.ambient_stress_work         = counter[kAmbientStressWork];
  b.pressure_work_charged       = counter[kPressureWorkCharged];
  b.pressure_work_held          = counter[kPressureWorkHeld];
  for (int d = 0; d < 3; ++d) {
    b.momentum_to_solid_cells[d] = counter[kMomentumToSolidCells + d];
    b.momentum_to_nodes[d]       = counter[kMomentumToNodes + d];
  }
  b.mass = b.solid_mass + b.gas_mass + b.open_mass + b.removed_mass;
  for (int d = 0; d < 3; ++d) b.momentum[d] = b.solid_momentum[d] + b.gas_momentum[d] + b.open_momentum[d] + b.removed_momentum[d] - b.face_impulse[d] - b.bc_impulse[d];
  b.energy        = b.solid_kinetic + b.solid_internal + b.heat_to_particles - b.reactant_thermal + b.gas_kinetic + b.gas_internal + b.open_energy + b.open_work + b.removed_energy - b.external_work - b.chemical;
  PetscReal *init = sim.mpm.diag.budget_initial, *scale = sim.mpm.diag.budget_scale;
  if (initial) {
    init[0] = b.mass;
    for (int d = 0; d < 3; ++d) init[1 + d] = b.momentum[d];
    init[4]  = b.energy;
    scale[0] = scale[1] = scale[2] = 0;
  }
  const PetscReal mass_terms[] = {b.solid_mass, b.gas_mass, b.open_mass, b.removed_mass};
  for (PetscReal t : mass_terms) scale[0] = PetscMax(scale[0], PetscAbsReal(t));
  const PetscReal *momentum_terms[] = {b.solid_momentum, b.gas_momentum, b.open_momentum, b.face_impulse, b.bc_impulse, b.removed_momentum};
  for (const PetscReal *t : momentum_terms) scale[1] = PetscMax(scale[1], Norm3(t));
  const PetscReal energy_terms[] = {b.solid_kinetic, b.solid_internal, b.heat_to_particles, b.reactant_thermal, b.gas_kinetic, b.gas_internal, b.open_energy, b.open_work, b.removed_energy, b.external_work, b.chemical};
  for (PetscReal t : energy_terms) scale[2] = PetscMax(scale[2], PetscAbsReal(t));
  for (int d = 0; d < 3; ++d) b.momentum_residual[d] = b.momentum[d] - init[1 + d];
  b.energy_residual = b.energy - init[4];
  b.mass_error      = scale[0] > 0 ? (b.mass - init[0]) / scale[0] : 0;
  b.momentum_error  = scale[1] > 0 ? Norm3(b.momentum_residual) / scale[1] : 0;
  b.energy_error    = scale[2] > 0 ? b.energy_residual / scale[2] : 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}
} // namespace

// A restarted run continues monitor.csv: the rows up to the checkpoint's step are kept (a killed run
// may have written later ones), then new rows are appended.
static PetscErrorCode ContinueMonitorFile(Simulation &sim, const std::string &path, bool *continued)
{
  PetscFunctionBeginUser;
  *continued = false;
  std::ifstream in(path);
  if (!in) PetscFunctionReturn(PETSC_SUCCESS);
  std::string header, line, kept;
  if (!std::getline(in, header)) PetscFunctionReturn(PETSC_SUCCESS);
  while (std::getline(in, line))
    if (!line.empty() && std::atoll(line.c_str()) <= sim.step) kept += line + "\n";
  in.close();
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << header << "\n" << kept;
    PetscCheck(out.good(), PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Could not write %s", tmp.c_str());
  }
  PetscCheck(std::rename(tmp.c_str(), path.c_str()) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Could not rename %s", tmp.c_str());
  sim.output.monitor_csv = std::fopen(path.c_str(), "a");
  PetscCheck(sim.output.monitor_csv, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Could not open %s", path.c_str());
  *continued = true;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MonitorSetUp(Simulation &sim)
{
  EnergyReport r;
  PetscFunctionBeginUser;
  if (sim.output.track_by_point && !sim.restarted) PetscCall(NearestParticle(sim)); // a restart keeps the traced id
  if (!sim.restarted) {                                                             // a restart keeps the initial energy and the scale of the balance
    PetscCall(ComputeEnergies(sim, r));
    sim.mpm.diag.initial_energy  = r.total - r.external_work;
    sim.mpm.diag.initial_kinetic = r.kinetic;
    if (sim.ice) { // the budgets' initial sums (and the gas totals they are made of)
      IceTotals gas;
      Budget    b;
      PetscCall(IceComputeTotals(*sim.ice, gas));
      PetscCall(ComputeBudget(sim, r, gas, true, b));
    }
  }
  PetscBool expansion = PETSC_FALSE; // the -grady cylinder's mean radial velocity gets a column
  PetscReal velocity;
  if (sim.HasParticles()) PetscCall(FragmentsExpansionVelocity(sim.mpm, &expansion, &velocity));
  bool continued = false;
  if (!sim.rank && sim.restarted) PetscCall(ContinueMonitorFile(sim, sim.output.dir + "/monitor.csv", &continued));
  if (!sim.rank && !continued) {
    const std::string path = sim.output.dir + "/monitor.csv";
    sim.output.monitor_csv = std::fopen(path.c_str(), "w");
    PetscCheck(sim.output.monitor_csv, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Could not open %s", path.c_str());
    FILE *csv = sim.output.monitor_csv;
    std::fprintf(csv, "step,time,dt,kinetic,internal,external_work,removed,total,balance_error,momentum_x,momentum_y,momentum_z,mass,particles,failure_energy,plastic_work,heat,viscous_work,stored_elastic,unaccounted");
    if (sim.analytic) std::fprintf(csv, ",displacement_error_rms,displacement_error_max");
    if (sim.output.track_pid >= 0) std::fprintf(csv, ",track_x,track_y,track_z,track_ux,track_uy,track_uz,track_sxx,track_syy,track_szz");
    if (sim.ice) std::fprintf(csv, ",gas_mass,gas_momentum_x,gas_momentum_y,gas_momentum_z,gas_internal_energy,gas_kinetic_energy,gas_total_energy,ice_ksp_iterations,ice_outer_iterations,gas_max_pressure,gas_max_temperature");
    if (sim.ice) // the budgets (ComputeBudget); balance_error is the energy budget's
      std::fprintf(csv,
                   ",open_face_mass,removed_particle_mass,mass_budget_error"
                   ",open_face_momentum_x,open_face_momentum_y,open_face_momentum_z,face_pressure_impulse_x,face_pressure_impulse_y,face_pressure_impulse_z"
                   ",grid_face_impulse_x,grid_face_impulse_y,grid_face_impulse_z,removed_particle_momentum_x,removed_particle_momentum_y,removed_particle_momentum_z"
                   ",momentum_budget_residual_x,momentum_budget_residual_y,momentum_budget_residual_z,momentum_budget_error"
                   ",heat_to_particles,reactant_thermal_energy,open_face_energy,open_face_work,removed_particle_energy,chemical_energy"
                   ",budget_energy,energy_budget_residual,energy_budget_scale,solid_balance_error,heat_to_solid_cells,reactant_energy_cells,kinetic_to_solid_cells,kinetic_to_nodes,drag_energy_change,solid_pressure_work,gas_interface_work,advection_"
                   "energy_change,fallback_energy_change,trace_energy_change,equilibration_energy_change,exchange_energy_change,exchange_fallback_energy,solid_cell_energy_transfer,ambient_stress_work,pressure_work_charged,pressure_work_held");
    if (expansion) std::fprintf(csv, ",expansion_velocity");
    if (sim.phases.Enabled()) { // the fire's histories (src/phases.hpp)
      std::fprintf(csv, ",phase");
      for (const auto &m : sim.mpm.materials) std::fprintf(csv, ",temperature_max_%s,temperature_mean_%s", m->Name(), m->Name());
    }
    std::fprintf(csv, "\n");
  }
  if (sim.HasParticles()) PetscCall(PetscPrintf(sim.comm, "%8s %12s %11s %12s %12s %12s %11s %12s %12s\n", "step", "time", "dt", "kinetic", "internal", "total", "balance", "momentum_x", "momentum_y"));
  else PetscCall(PetscPrintf(sim.comm, "%8s %12s %11s %14s %12s %12s %14s %12s %12s %6s\n", "step", "time", "dt", "gas mass", "kinetic", "internal", "total energy", "momentum_x", "momentum_y", "KSP"));
  PetscCall(PetscTime(&sim.output.last_progress));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Monitor(Simulation &sim, PetscBool force)
{
  EnergyReport r;
  PetscFunctionBeginUser;
  if (sim.output.progress) {
    PetscLogDouble now;
    PetscCall(PetscTime(&now));
    if (now - sim.output.last_progress > 10.0) {
      const PetscReal fraction = sim.time / sim.run.final_time, elapsed = now - sim.wall_start;
      if (sim.phases.Enabled()) // (when a phase ends is not known ahead: no estimate of what is left)
        PetscCall(PetscPrintf(sim.comm, "  progress: phase %s, t = %g s, step %" PetscInt_FMT ", %.0f s elapsed\n", RunPhaseName(sim.phases.Current()), (double)sim.time, sim.step, elapsed));
      else PetscCall(PetscPrintf(sim.comm, "  progress: %5.1f%% of the final time, step %" PetscInt_FMT ", %.0f s elapsed, about %.0f s left\n", 100.0 * fraction, sim.step, elapsed, fraction > 0 ? elapsed * (1 - fraction) / fraction : 0.0));
      sim.output.last_progress = now;
    }
  }
  if (!force && sim.step % sim.output.monitor_interval) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogEventBegin(sim.output.ev_monitor, 0, 0, 0, 0));
  PetscCall(ComputeEnergies(sim, r));
  PetscReal rms = 0, max = 0, track[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  if (sim.analytic) {
    PetscCall(AnalyticDisplacementError(sim, &rms, &max));
    sim.mpm.diag.max_error_displacement  = PetscMax(sim.mpm.diag.max_error_displacement, rms);
    sim.mpm.diag.last_error_displacement = rms;
  }
  if (sim.output.track_pid >= 0) PetscCall(TrackedParticle(sim, track));
  IceTotals gas;
  Budget    b;
  if (sim.ice) PetscCall(IceComputeTotals(*sim.ice, gas));
  if (sim.ice) PetscCall(ComputeBudget(sim, r, gas, false, b));
  const PetscReal balance_error = sim.ice ? b.energy_error : r.balance_error; // with gas: the whole system's
  if (sim.ice && gas.max_pressure > sim.ice->peak_pressure) {
    sim.ice->peak_pressure      = gas.max_pressure;
    sim.ice->peak_pressure_time = sim.time;
  }
  if (sim.ice && gas.max_temperature > sim.ice->peak_temperature) {
    sim.ice->peak_temperature      = gas.max_temperature;
    sim.ice->peak_temperature_time = sim.time;
  }
  PetscBool expansion          = PETSC_FALSE;
  PetscReal expansion_velocity = 0;
  if (sim.HasParticles()) PetscCall(FragmentsExpansionVelocity(sim.mpm, &expansion, &expansion_velocity));
  std::vector<PetscReal> phase_temperatures; // per material: the hottest particle, the mass-weighted mean
  if (sim.phases.Enabled()) PetscCall(PhasesTemperatures(sim, phase_temperatures));
  if (sim.HasParticles())
    PetscCall(PetscPrintf(sim.comm, "%8" PetscInt_FMT " %12.5e %11.4e %12.5e %12.5e %12.5e %11.3e %12.5e %12.5e\n", sim.step, (double)sim.time, (double)sim.dt, (double)r.kinetic, (double)r.internal, (double)(r.total - r.external_work),
                          (double)balance_error, (double)r.momentum[0], (double)r.momentum[1]));
  else
    PetscCall(PetscPrintf(sim.comm, "%8" PetscInt_FMT " %12.5e %11.4e %14.7e %12.5e %12.5e %14.7e %12.5e %12.5e %6" PetscInt_FMT "\n", sim.step, (double)sim.time, (double)sim.dt, (double)gas.mass, (double)gas.kinetic_energy,
                          (double)gas.internal_energy, (double)(gas.kinetic_energy + gas.internal_energy), (double)gas.momentum[0], (double)gas.momentum[1], sim.ice->ksp_iterations));
  if (!sim.rank && sim.output.monitor_csv) {
    FILE *csv = sim.output.monitor_csv;
    std::fprintf(csv, "%d,%.12e,%.12e,%.12e,%.12e,%.12e,%.12e,%.12e,%.12e,%.12e,%.12e,%.12e,%.12e,%lld", (int)sim.step, (double)sim.time, (double)sim.dt, (double)r.kinetic, (double)r.internal, (double)r.external_work, (double)r.removed,
                 (double)r.total, (double)balance_error, (double)r.momentum[0], (double)r.momentum[1], (double)r.momentum[2], (double)r.mass, (long long)sim.mpm.total_particles);
    std::fprintf(csv, ",%.12e,%.12e,%.12e,%.12e,%.12e,%.12e", (double)r.failure_energy, (double)r.plastic_work, (double)r.heat, (double)r.viscous_work, (double)r.stored_elastic, (double)r.unaccounted);
    if (sim.analytic) std::fprintf(csv, ",%.12e,%.12e", (double)rms, (double)max);
    if (sim.output.track_pid >= 0)
      for (int k = 0; k < 9; ++k) std::fprintf(csv, ",%.12e", (double)track[k]);
    if (sim.ice)
      std::fprintf(csv, ",%.16e,%.16e,%.16e,%.16e,%.16e,%.16e,%.16e,%d,%d", (double)gas.mass, (double)gas.momentum[0], (double)gas.momentum[1], (double)gas.momentum[2], (double)gas.internal_energy, (double)gas.kinetic_energy,
                   (double)(gas.internal_energy + gas.kinetic_energy), (int)sim.ice->ksp_iterations, (int)sim.ice->outer_iterations);
    if (sim.ice) std::fprintf(csv, ",%.12e,%.12e", (double)gas.max_pressure, (double)gas.max_temperature);
    if (sim.ice) {
      std::fprintf(csv, ",%.16e,%.16e,%.6e", (double)b.open_mass, (double)b.removed_mass, (double)b.mass_error);
      for (const PetscReal *v : {b.open_momentum, b.face_impulse, b.bc_impulse, b.removed_momentum, b.momentum_residual})
        for (int d = 0; d < 3; ++d) std::fprintf(csv, ",%.12e", (double)v[d]);
      std::fprintf(csv, ",%.6e", (double)b.momentum_error);
      for (PetscReal v : {b.heat_to_particles, b.reactant_thermal, b.open_energy, b.open_work, b.removed_energy, b.chemical, b.energy}) std::fprintf(csv, ",%.16e", (double)v);
      std::fprintf(csv, ",%.12e,%.12e,%.12e,%.16e,%.16e", (double)b.energy_residual, (double)sim.mpm.diag.budget_scale[2], (double)r.balance_error, (double)b.heat_to_solid_cells, (double)b.reactant_energy_cells);
      std::fprintf(csv, ",%.16e,%.16e,%.16e,%.16e", (double)b.kinetic_to_solid_cells, (double)b.kinetic_to_nodes, (double)b.drag_energy_change, (double)b.solid_pressure_work);
      std::fprintf(csv, ",%.16e,%.16e,%.16e,%.16e", (double)b.gas_interface_work, (double)b.advection_energy_change, (double)b.fallback_energy_change, (double)b.trace_energy_change);
      std::fprintf(csv, ",%.16e,%.16e,%.16e,%.16e", (double)b.equilibration_energy_change, (double)b.exchange_energy_change, (double)b.exchange_fallback_energy, (double)b.solid_cell_energy_transfer);
      std::fprintf(csv, ",%.16e,%.16e,%.16e", (double)b.ambient_stress_work, (double)b.pressure_work_charged, (double)b.pressure_work_held);
    }
    if (expansion) std::fprintf(csv, ",%.12e", (double)expansion_velocity);
    if (sim.phases.Enabled()) {
      std::fprintf(csv, ",%d", (int)sim.phases.Current());
      for (PetscReal T : phase_temperatures) std::fprintf(csv, ",%.12e", (double)T);
    }
    std::fprintf(csv, "\n");
    std::fflush(csv);
  }
  PetscCall(PetscLogEventEnd(sim.output.ev_monitor, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode WriteSummary(Simulation &sim)
{
  EnergyReport r;
  PetscFunctionBeginUser;
  PetscCall(ComputeEnergies(sim, r));
  const PetscInt bytes = sim.mpm.swarm_bytes;
  PetscReal      rms = 0, max = 0;
  if (sim.analytic) PetscCall(AnalyticDisplacementError(sim, &rms, &max));
  PetscReal Trms = 0, Tmax = 0;
  if (sim.analytic && sim.analytic->HasTemperature()) PetscCall(AnalyticTemperatureError(sim, &Trms, &Tmax));
  IceTotals gas;
  Budget    b;
  if (sim.ice) PetscCall(IceComputeTotals(*sim.ice, gas));
  if (sim.ice) PetscCall(ComputeBudget(sim, r, gas, false, b));
  const PetscReal balance_error   = sim.ice ? b.energy_error : r.balance_error; // with gas: the whole system's
  PetscReal       burnt_mass      = 0;
  PetscInt64      burnt_particles = 0;
  if (sim.coupling) PetscCall(CouplingSummary(*sim.coupling, &burnt_mass, &burnt_particles));
  PetscReal surface_heat = 0; // J the solids took from the gas by -coupling_surface_heat_transfer
  if (sim.coupling) PetscCall(CouplingSurfaceHeatTotal(*sim.coupling, &surface_heat));
  PetscInt64 fallbacks       = 0; // cells that fell back to the -p dV energy form
  PetscInt64 fallbacks_remap = 0; // of those, the advection's internal-energy remap
  if (sim.ice) PetscCallMPI(MPI_Allreduce(&sim.ice->energy_fallbacks, &fallbacks, 1, MPIU_INT64, MPI_SUM, sim.comm));
  if (sim.ice) PetscCallMPI(MPI_Allreduce(&sim.ice->energy_fallbacks_remap, &fallbacks_remap, 1, MPIU_INT64, MPI_SUM, sim.comm));
  PetscInt64 fallbacks_exchange = 0, fallbacks_class[kIceFallbackClasses] = {}; // the exchange's; all by cell class (IceFallbackClass)
  if (sim.ice) PetscCallMPI(MPI_Allreduce(&sim.ice->energy_fallbacks_exchange, &fallbacks_exchange, 1, MPIU_INT64, MPI_SUM, sim.comm));
  if (sim.ice) PetscCallMPI(MPI_Allreduce(sim.ice->energy_fallbacks_class, fallbacks_class, kIceFallbackClasses, MPIU_INT64, MPI_SUM, sim.comm));
  PetscInt64 removed = sim.mpm.diag.removed_particles, removed_global = 0;
  PetscCallMPI(MPI_Allreduce(&removed, &removed_global, 1, MPIU_INT64, MPI_SUM, sim.comm));
  const PetscReal rate = sim.wall_stepping > 0 ? (PetscReal)sim.mpm.particle_steps / sim.wall_stepping : 0;
  // With logging on (-log_view) and several ranks: each rank's time in the stepping phases, so a
  // load-balance study sees which rank waits in which phase (-log_view prints only max and max/min).
  struct Phase {
    const char   *name;
    PetscLogEvent event;
  };
  const Phase         phases[]   = {{"p2g", sim.mpm.ev_p2g},     {"ghost_sums", sim.mpm.ev_ghost_sums}, {"grid_update", sim.mpm.ev_grid}, {"g2p", sim.mpm.ev_g2p},
                                    {"remap", sim.mpm.ev_remap}, {"stress", sim.mpm.ev_stress},         {"migrate", sim.mpm.ev_migrate},  {"time_step", sim.mpm.ev_dt}};
  constexpr int       num_phases = sizeof(phases) / sizeof(phases[0]);
  PetscBool           logging    = PETSC_FALSE;
  std::vector<double> rank_phase_seconds; // [rank][phase], on rank 0
  PetscCall(PetscLogIsActive(&logging));
  if (logging && sim.size > 1) {
    double mine[num_phases + 1];
    for (int i = 0; i < num_phases; ++i) {
      PetscEventPerfInfo info;
      PetscCall(PetscLogEventGetPerfInfo(sim.stage_step, phases[i].event, &info));
      mine[i] = info.time;
    }
    mine[num_phases] = sim.wall_stepping;
    if (!sim.rank) rank_phase_seconds.resize((size_t)(num_phases + 1) * sim.size);
    PetscCallMPI(MPI_Gather(mine, num_phases + 1, MPI_DOUBLE, rank_phase_seconds.data(), num_phases + 1, MPI_DOUBLE, 0, sim.comm));
  }
  if (sim.rank) PetscFunctionReturn(PETSC_SUCCESS);
  if (sim.output.monitor_csv) {
    std::fclose(sim.output.monitor_csv);
    sim.output.monitor_csv = nullptr;
  }
  std::ostringstream s;
  s.precision(17); // round-trip: the budgets are checked to 1e-12
  s << "{\n";
  s << "  \"scene\": \"" << sim.run.scene << "\",\n";
  s << "  \"dim\": " << sim.mpm.grid.dim << ",\n";
  s << "  \"ranks\": " << sim.size << ",\n";
  s << "  \"cells\": [" << sim.mpm.grid.cells[0] << ", " << sim.mpm.grid.cells[1] << ", " << (sim.mpm.grid.dim == 3 ? sim.mpm.grid.cells[2] : 1) << "],\n";
  s << "  \"grid_lower\": [" << sim.mpm.grid.lower[0] << ", " << sim.mpm.grid.lower[1] << ", " << sim.mpm.grid.lower[2] << "],\n";
  s << "  \"grid_upper\": [" << sim.mpm.grid.upper[0] << ", " << sim.mpm.grid.upper[1] << ", " << sim.mpm.grid.upper[2] << "],\n";
  s << "  \"shape\": \"" << ShapeTypeNames[(int)sim.mpm.shape] << "\",\n";
  s << "  \"scheme\": \"" << StepSchemeNames[(int)sim.mpm.scheme] << "\",\n";
  s << "  \"flip_fraction\": " << sim.mpm.flip_fraction << ",\n";
  s << "  \"particles\": " << sim.mpm.total_particles << ",\n";
  s << "  \"removed_particles\": " << removed_global << ",\n";
  s << "  \"steps\": " << sim.step << ",\n";
  s << "  \"final_time\": " << sim.time << ",\n";
  s << "  \"kinetic_energy\": " << r.kinetic << ",\n";
  s << "  \"internal_energy\": " << r.internal << ",\n";
  s << "  \"external_work\": " << r.external_work << ",\n";
  s << "  \"initial_energy\": " << sim.mpm.diag.initial_energy << ",\n";
  s << "  \"energy_balance_error\": " << balance_error << ",\n";
  if (sim.ice) s << "  \"solid_energy_balance_error\": " << r.balance_error << ",\n";
  s << "  \"momentum\": [" << r.momentum[0] << ", " << r.momentum[1] << ", " << r.momentum[2] << "],\n";
  s << "  \"mass\": " << r.mass << ",\n";
  if (sim.analytic) {
    s << "  \"analytic\": \"" << sim.analytic->Name() << "\",\n";
    s << "  \"displacement_error_rms\": " << rms << ",\n";
    s << "  \"displacement_error_max\": " << max << ",\n";
    s << "  \"displacement_error_rms_max_over_time\": " << PetscMax(sim.mpm.diag.max_error_displacement, rms) << ",\n";
    if (sim.analytic->HasTemperature()) s << "  \"temperature_error_rms\": " << Trms << ",\n  \"temperature_error_max\": " << Tmax << ",\n";
  }
  s << "  \"failure_energy\": " << r.failure_energy << ",\n";
  s << "  \"plastic_work\": " << r.plastic_work << ",\n";
  s << "  \"heat\": " << r.heat << ",\n";
  s << "  \"viscous_work\": " << r.viscous_work << ",\n";
  s << "  \"stored_elastic_energy\": " << r.stored_elastic << ",\n";
  s << "  \"unaccounted_internal_energy\": " << r.unaccounted << ",\n";
  if (sim.HasParticles()) PetscCall(FragmentsSummary(sim.mpm, s));
  if (sim.taylor) PetscCall(TaylorSummary(sim, s));
  if (sim.ice) {
    const IceTotals &g0 = sim.ice->initial;
    const PetscReal  e0 = g0.internal_energy + g0.kinetic_energy, e = gas.internal_energy + gas.kinetic_energy;
    s << "  \"gas\": {\"materials\": " << sim.ice->nmat << ", \"mass\": " << gas.mass << ", \"mass_change\": " << (gas.mass - g0.mass) / g0.mass;
    s << ", \"momentum\": [" << gas.momentum[0] << ", " << gas.momentum[1] << ", " << gas.momentum[2] << "]";
    s << ", \"internal_energy\": " << gas.internal_energy << ", \"kinetic_energy\": " << gas.kinetic_energy << ", \"total_energy\": " << e << ", \"total_energy_change\": " << (e - e0) / e0;
    s << ", \"pressure_solver\": \"" << IcePressureSolverNames[(int)sim.ice->pressure_solver] << "\", \"ksp_iterations_per_solve\": " << (sim.ice->pressure_solves ? (PetscReal)sim.ice->ksp_iterations_total / sim.ice->pressure_solves : 0.0);
    const PetscReal cells = (PetscReal)sim.mpm.grid.cells[0] * sim.mpm.grid.cells[1] * (sim.mpm.grid.dim == 3 ? sim.mpm.grid.cells[2] : 1);
    s << ", \"peak_pressure\": " << sim.ice->peak_pressure << ", \"peak_pressure_time\": " << sim.ice->peak_pressure_time << ", \"peak_temperature\": " << sim.ice->peak_temperature << ", \"peak_temperature_time\": " << sim.ice->peak_temperature_time;
    s << ", \"energy_fallbacks\": " << fallbacks << ", \"energy_fallbacks_remap\": " << fallbacks_remap << ", \"energy_fallbacks_exchange\": " << fallbacks_exchange << ", \"energy_fallbacks_by_class\": {";
    for (int k = 0; k < kIceFallbackClasses; ++k) s << (k ? ", " : "") << "\"" << IceFallbackClassNames[k] << "\": " << fallbacks_class[k];
    s << "}, \"burnt_mass\": " << burnt_mass << ", \"burnt_out_particles\": " << burnt_particles << ", \"surface_heat_to_solids\": " << surface_heat;
    s << ", \"cell_steps_per_second_per_core\": " << (sim.wall_stepping > 0 ? cells * sim.step / sim.wall_stepping / sim.size : 0.0) << "},\n";
  }
  if (sim.ice) { // the budgets (ComputeBudget)
    auto vec = [](const PetscReal v[3]) {
      std::ostringstream o;
      o.precision(17);
      o << "[" << v[0] << ", " << v[1] << ", " << v[2] << "]";
      return o.str();
    };
    const PetscReal *init = sim.mpm.diag.budget_initial, *scale = sim.mpm.diag.budget_scale;
    s << "  \"budget\": {\n";
    s << "    \"mass\": {\"particles\": " << b.solid_mass << ", \"gas\": " << b.gas_mass << ", \"open_faces\": " << b.open_mass << ", \"removed_particles\": " << b.removed_mass;
    s << ", \"open_faces_by_face\": {"; // out positive, per domain face
    const char *face_names[3][2] = {{"xmin", "xmax"}, {"ymin", "ymax"}, {"zmin", "zmax"}};
    for (int d = 0; d < sim.ice->dim; ++d)
      for (int side = 0; side < 2; ++side) s << (d || side ? ", " : "") << "\"" << face_names[d][side] << "\": " << b.open_mass_face[d][side];
    s << "}";
    s << ", \"initial\": " << init[0] << ", \"residual\": " << b.mass - init[0] << ", \"largest_term\": " << scale[0] << ", \"error\": " << b.mass_error << "},\n";
    const PetscReal p0[3] = {init[1], init[2], init[3]};
    s << "    \"momentum\": {\"particles\": " << vec(b.solid_momentum) << ", \"gas\": " << vec(b.gas_momentum) << ", \"open_faces\": " << vec(b.open_momentum);
    s << ", \"face_pressure_impulse\": " << vec(b.face_impulse) << ", \"grid_face_impulse\": " << vec(b.bc_impulse) << ", \"removed_particles\": " << vec(b.removed_momentum);
    s << ", \"initial\": " << vec(p0) << ", \"residual\": " << vec(b.momentum_residual) << ", \"largest_term\": " << scale[1] << ", \"error\": " << b.momentum_error;
    s << ", \"to_solid_cells\": " << vec(b.momentum_to_solid_cells) << ", \"to_nodes\": " << vec(b.momentum_to_nodes) << "},\n";
    s << "    \"energy\": {\"particles_kinetic\": " << b.solid_kinetic << ", \"particles_internal\": " << b.solid_internal << ", \"heat_to_particles\": " << b.heat_to_particles;
    s << ", \"reactant_thermal\": " << b.reactant_thermal << ", \"gas_kinetic\": " << b.gas_kinetic << ", \"gas_internal\": " << b.gas_internal;
    s << ", \"open_faces\": " << b.open_energy << ", \"open_face_work\": " << b.open_work << ", \"removed_particles\": " << b.removed_energy;
    s << ", \"external_work\": " << b.external_work << ", \"chemical\": " << b.chemical;
    s << ", \"initial\": " << init[4] << ", \"residual\": " << b.energy_residual << ", \"largest_term\": " << scale[2] << ", \"error\": " << b.energy_error;
    s << ", \"error_of_chemical\": " << (b.chemical > 0 ? b.energy_residual / b.chemical : 0.0);
    s << ", \"heat_to_solid_cells\": " << b.heat_to_solid_cells << ", \"reactant_energy_cells\": " << b.reactant_energy_cells;
    s << ", \"kinetic_to_solid_cells\": " << b.kinetic_to_solid_cells << ", \"kinetic_to_nodes\": " << b.kinetic_to_nodes << ", \"drag_energy_change\": " << b.drag_energy_change << ", \"solid_pressure_work\": " << b.solid_pressure_work
      << ", \"gas_interface_work\": " << b.gas_interface_work << ", \"advection_energy_change\": " << b.advection_energy_change << ", \"fallback_energy_change\": " << b.fallback_energy_change << ", \"trace_energy_change\": " << b.trace_energy_change
      << ", \"equilibration_energy_change\": " << b.equilibration_energy_change << ", \"exchange_energy_change\": " << b.exchange_energy_change << ", \"exchange_fallback_energy\": " << b.exchange_fallback_energy
      << ", \"solid_cell_energy_transfer\": " << b.solid_cell_energy_transfer << ", \"burnt_particles\": " << b.burnt_particle_energy;
    s << ", \"ambient_stress_work\": " << b.ambient_stress_work << ", \"pressure_work_charged\": " << b.pressure_work_charged << ", \"pressure_work_held\": " << b.pressure_work_held << "}\n";
    s << "  },\n";
  }
  if (!rank_phase_seconds.empty()) { // the phases' seconds on each rank, and the stepping wall time
    s << "  \"rank_phase_seconds\": {";
    for (int i = 0; i <= num_phases; ++i) {
      s << (i ? ", " : "") << "\"" << (i < num_phases ? phases[i].name : "stepping") << "\": [";
      for (int r = 0; r < sim.size; ++r) s << (r ? ", " : "") << rank_phase_seconds[(size_t)r * (num_phases + 1) + i];
      s << "]";
    }
    s << "},\n";
  }
  { // each rank slot's node count per direction (equal, or set by -grid_balance)
    const Grid &g = sim.mpm.grid;
    s << "  \"node_ranges\": {";
    for (PetscInt d = 0; d < 3; ++d) {
      s << (d ? ", " : "") << "\""
        << "xyz"[d] << "\": [";
      for (PetscMPIInt r = 0; r < g.procs[d]; ++r) s << (r ? ", " : "") << (g.start[d].size() > (size_t)r + 1 ? g.start[d][r + 1] - g.start[d][r] : 0);
      s << "]";
    }
    s << "},\n";
  }
  s << PhasesSummary(sim);
  s << "  \"bytes_per_particle\": " << bytes << ",\n";
  s << "  \"wall_time_s\": " << sim.wall_stepping << ",\n";
  s << "  \"stress_shared_point_steps\": " << sim.mpm.stress_share.point_steps << ",\n";
  s << "  \"particle_steps_per_second\": " << rate << ",\n";
  s << "  \"particle_steps_per_second_per_core\": " << rate / sim.size << "\n";
  s << "}\n";
  const std::string path = sim.output.dir + "/summary.json", tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << s.str();
    PetscCheck(out.good(), PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Could not write %s", tmp.c_str());
  }
  PetscCheck(std::rename(tmp.c_str(), path.c_str()) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Could not rename %s", tmp.c_str());
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "Summary: %s, %" PetscInt_FMT " steps to t = %g s, %lld particles on %d rank(s), energy balance error %.3e, %.3g particle-steps/s per core; wrote %s\n", sim.run.scene.c_str(), sim.step, (double)sim.time,
                        (long long)sim.mpm.total_particles, sim.size, (double)balance_error, (double)(rate / sim.size), path.c_str()));
  if (sim.ice)
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "Gas: mass change %.3e, total energy change %.3e (relative), %.3g cell-steps/s per core\n", (double)((gas.mass - sim.ice->initial.mass) / sim.ice->initial.mass),
                          (double)((gas.internal_energy + gas.kinetic_energy - sim.ice->initial.internal_energy - sim.ice->initial.kinetic_energy) / (sim.ice->initial.internal_energy + sim.ice->initial.kinetic_energy)),
                          (double)(sim.wall_stepping > 0 ? (PetscReal)sim.mpm.grid.cells[0] * sim.mpm.grid.cells[1] * (sim.mpm.grid.dim == 3 ? sim.mpm.grid.cells[2] : 1) * sim.step / sim.wall_stepping / sim.size : 0.0)));
  if (sim.ice) {
    char chemical[128] = "";
    if (b.chemical > 0) std::snprintf(chemical, sizeof(chemical), ", %.3e of the chemical energy released (%.4g J)", (double)(b.energy_residual / b.chemical), (double)b.chemical);
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "Budgets (particles, gases, open faces, removed particles, chemical energy): mass error %.3e, momentum %.3e, energy %.3e of the largest term (%.4g kg, %.4g kg m/s, %.4g J); energy residual %.4g J%s\n",
                          (double)b.mass_error, (double)b.momentum_error, (double)b.energy_error, (double)sim.mpm.diag.budget_scale[0], (double)sim.mpm.diag.budget_scale[1], (double)sim.mpm.diag.budget_scale[2], (double)b.energy_residual, chemical));
  }
  if (sim.analytic) PetscCall(PetscPrintf(PETSC_COMM_SELF, "Analytic %s: displacement error rms %.4e m, max %.4e m at t = %g s\n", sim.analytic->Name(), (double)rms, (double)max, (double)sim.time));
  if (sim.analytic && sim.analytic->HasTemperature()) PetscCall(PetscPrintf(PETSC_COMM_SELF, "Analytic %s: temperature error rms %.4e K, max %.4e K\n", sim.analytic->Name(), (double)Trms, (double)Tmax));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst

namespace burst {

void Diagnostics::Checkpoint(CheckpointValues &values)
{
  values.Global("initial_energy", &initial_energy);
  values.Global("initial_kinetic", &initial_kinetic);
  values.Global("max_error_displacement", &max_error_displacement);
  values.Global("last_error_displacement", &last_error_displacement);
  values.Global("budget_initial", budget_initial, 5);
  values.Global("budget_scale", budget_scale, 3);
  values.PerRank("external_work", &external_work);
  values.PerRank("removed_energy", &removed_energy);
  values.PerRank("viscous_work", &viscous_work);
  values.PerRank("removed_mass", &removed_mass);
  values.PerRank("removed_particles", &removed_particles);
  values.PerRank("removed_momentum", removed_momentum, 3);
  values.PerRank("bc_impulse", bc_impulse, 3);
}

} // namespace burst
