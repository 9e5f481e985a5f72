// MPM-ICE coupling (ice.md 1.2, 2): the only part of burst that knows both solvers.
//
// Each non-rigid MPM material is also a material of the gas cells: its mass, momentum and
// temperature are projected from the particles (through the nodes) to the cells, where the
// equilibration gives it a volume from its coupling equation of state at the cell pressure
// (never particle mass over volume, ice.md 2.2). The gas pressure reaches the solid two ways,
// as in the reference (ice.md 2.3): the cell momentum source -theta grad p and the cell exchange
// change the solid's cell velocity, and that change goes back to the nodes; and the MPM internal
// force uses sigma + (p - p_ref) I, which cancels the pressure gradient inside the solid where the
// first path counts it, so that only the pressure on the solid's surface acts.
#pragma once
#include "../mpm/mpm.hpp"
#include "../ice/ice.hpp"
#include "coupling_fwd.hpp"

namespace burst {

struct Coupling;

// Before the gas solver exists: one solid material per non-rigid MPM material, with its coupling
// equation of state (bulk-modulus form, the modified form in tension; ice.md 2.2).
PetscErrorCode CouplingSolidMaterials(MpmSolver &mpm, std::vector<IceSolidSpec> &solids, Coupling **coupling);
// After the particles and the gas exist: the projection objects, the first projection, and room
// for the solids in the gas.
PetscErrorCode CouplingSetUp(Coupling &c, IceSolver &ice);

// The coupling's part of a checkpoint: the burnt particles, and each rank's burnt mass and budget
// counters.
class CheckpointValues;
void CouplingCheckpointValues(Coupling &c, CheckpointValues &values);

// The coupled phases, in the order of src/step.cxx.
PetscErrorCode CouplingProjectSolids(Coupling &c);                      // particles -> nodes -> cells (M, u, T)
PetscErrorCode CouplingPressureToParticles(Coupling &c);                // cell p -> nodes -> particles
PetscErrorCode CouplingSolidVelocity(Coupling &c);                      // nodal v* after the MPM update -> cells
PetscErrorCode CouplingIncrementsToNodes(Coupling &c);                  // pressure force + exchange -> nodes
PetscErrorCode CouplingHeatToParticles(Coupling &c);                    // exchange heat -> particles
PetscErrorCode CouplingSurfaceHeatSetUp(Coupling &c);                   // -coupling_surface_heat_transfer
PetscErrorCode CouplingSurfaceHeat(Coupling &c);                        // convective heat from the gas to the solids' surfaces (after the cell exchange)
PetscErrorCode CouplingSurfaceHeatTotal(Coupling &c, PetscReal *total); // J so far, global
PetscErrorCode CouplingMeasureSurfaceHeat(Coupling &c, PetscBool on);   // CouplingHeatToParticles adds each particle's heat (J) to its surface_heat field
PetscErrorCode CouplingChargePressureWork(Coupling &c);                 // the gas pays the work its pressure did on the solids
// Burning (burn.cxx): the reactants' models and products; the mass, momentum and energy that burn
// in each cell (after the equilibration); the particles' share of it (right after, at the positions
// the cells were projected from, so that the particles lose exactly what the gas gains).
PetscErrorCode CouplingBurnSetUp(Coupling &c);
PetscErrorCode CouplingBurnHelp(Coupling &c); // -help: list the burning options
// summary.json: the mass burnt into gas and the burnt-out particles removed (collective).
// The burn model of solid material `material` (a material id): its name ("none" if inert) and the
// temperature its ignition criterion asks (K, 0 if none).
PetscErrorCode CouplingIgnition(Coupling &c, PetscInt material, std::string *model, PetscReal *temperature);
// The cells (global count) whose burn model's ignition criterion holds now, from this step's
// projection (CouplingProjectSolids); where and how hot (the criterion's T_hot, K) the hottest cell
// holding reactant particles on a reactant surface is. Burns nothing.
PetscErrorCode CouplingIgnitingCells(Coupling &c, PetscInt64 *count, PetscReal where[3], PetscReal *T_hot);
PetscErrorCode CouplingSummary(Coupling &c, PetscReal *burnt_mass, PetscInt64 *burnt_particles);
PetscErrorCode CouplingBurn(Coupling &c);
PetscErrorCode CouplingBurnParticles(Coupling &c);

// The coupling's budget counters (monitor.cxx, checkpoint.cxx), this rank's, cumulative since the
// start: what burning took from the particles (mass; kinetic energy and stress work; thermal energy
// m c_v,s T_p less the heat of the stress updates, which the stress work holds; momentum), the
// chemical energy the burn model released (dm Q: what the products receive beyond the reactant's own
// energy), and the heat the gas gave the
// particles (the cell exchange's and the drag's heat as the particles received it, m c_v,s dT_p).
// The same transfers as the cells saw them, which the budgets report beside the particles' view:
// the heat the exchange gave the solids' cell materials (M_s c_v,s (T_L - T)), the reactant's
// energy the products received (dm (c_v,s T_s + the projected stored and kinetic energy per mass)), and the
// momentum the cells' sources and exchange gave the solids (M_s (u_L - u)) against what the nodes
// received of it (m_I dv_I, before the face conditions hold it back), and the kinetic energy the same
// increments give the solids in the cells (M_s (|u_L|^2 - |u|^2)/2) and at the nodes (m_I (|v + dv|^2
// - |v|^2)/2 with the increments the nodes keep).
enum CouplingCounter : int {
  kBurntParticleMass,
  kBurntParticleEnergy,
  kBurntParticleThermal,
  kBurntParticleMomentum, // 3 values
  kChemicalEnergy = kBurntParticleMomentum + 3,
  kHeatToParticles,
  kHeatToSolidCells,
  kReactantEnergyCells,
  kMomentumToSolidCells,                            // 3 values
  kMomentumToNodes     = kMomentumToSolidCells + 3, // 3 values
  kKineticToSolidCells = kMomentumToNodes + 3,
  kKineticToNodes,
  kAmbientStressWork,   // the work of the (p - p_ref) I the particles carry in their stress (pressure_work.cxx)
  kPressureWorkCharged, // the work of the gas pressure on the solids that the gases paid (pressure_work.cxx)
  kPressureWorkHeld,    // of that work, what no gas paid (a node with no gas around it, or beyond half a gas's temperature in a step)
  kNumCouplingCounters
};
PetscReal *CouplingCounters(Coupling &c); // kNumCouplingCounters values

} // namespace burst
