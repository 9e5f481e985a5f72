// One time step: the ordered list of phases, MPM and ICE (ice.md 1.2).
//
// MPM (a scene with solids):
//   USL  (update stress last, the default; Uintah's order, Wallstedt & Guilkey 2008):
//        P2G(m, mv, f) -> grid update + BCs -> G2P(v, x, L, F) -> stress -> migrate
//   MUSL (modified USL, Sulsky et al. 1995): after the velocity G2P, momentum goes back to the grid
//        (both in one particle pass, RemapMomentum) and the position and L come from that remapped
//        velocity.
//   USF  (update stress first): P2G(m, mv) -> grid velocity -> G2P(L, F) -> stress -> P2G(f) ->
//        grid update -> G2P(v, x)
// ICE (a scene with gases), rows 4 and 7-17 of ice.md 1.2:
//   equilibration pressure -> face velocities + face exchange -> pressure (explicit or KSP) ->
//   face pressure, momentum and energy sources, Lagrangian values -> cell exchange, Lagrangian
//   specific volume -> advection, conserved to primitive; the budgets mark the gases' energy at the
//   start, book the domain faces after the sources (face work, face-pressure impulse), the exchange's
//   change after it, and the open faces after the advection (their fluxes)
//
// Solids and gas together (ice.md 1.2, the full table; USL or MUSL for the particles):
//   P2G(m, mv) -> solids to cells -> equilibration -> burning (gas sources, particle masses) ->
//   face velocities -> pressure -> pressure to the
//   particles -> P2G(f, with sigma + (p - p_ref) I) -> grid update -> the solids' nodal velocity to
//   cells -> gas sources -> cell exchange -> surface heat -> pressure force and exchange back to the nodes -> the
//   gases pay the pressure's work on the solids -> G2P -> exchange heat to the particles -> stress ->
//   migrate -> heat conduction -> gas advection
//   MUSL takes L and the positions from the remapped velocity; with -mpm_coupled_musl_gradient v_new,
//   L from v_new, the nodal velocity whose divergence the gas's pressure solve and sources were given:
//   L from the remap deforms a solid by another velocity than the one the gas sharing its cells saw,
//   and the cell a solid leaves goes unstable once -mpm_cfl c_solid / c_gas exceeds about 7; v_new
//   is stable there but the fire scene's energy budget misses (doc/coupling.md, the gas gun).
//
// A run in phases (src/phases.hpp; a container in a fire) takes two more steps before its mechanics:
//   heatup:    P2G(m, mv) -> nodal velocities (zero: the solids are held still) -> solids to cells
//              -> equilibration -> face velocities -> pressure -> solids' velocity to cells -> gas
//              sources -> cell exchange -> surface heat -> increments to the nodes -> exchange heat to the particles
//              (measured) -> heat conduction -> gas advection; no stress, no MPM time step
//   heat_only: heat conduction with the measured surface heat; the gas is held
//
// Every phase is a named function with its own PetscLogEvent; the two solvers meet only through
// src/coupling/.
#include "simulation.hpp"
#include "step.hpp"
#include "ice/ice.hpp"
#include "coupling/coupling.hpp"

namespace burst {

static PetscErrorCode MPMStep(MpmSolver &mpm)
{
  PetscFunctionBeginUser;
  PetscCall(ComputeExternalForces(mpm));
  switch (mpm.scheme) {
  case StepScheme::USL:
    PetscCall(ParticlesToGrid(mpm, {PETSC_TRUE, PETSC_TRUE, PETSC_TRUE}));
    PetscCall(GridUpdate(mpm));
    PetscCall(GridToParticles(mpm, {PETSC_TRUE, PETSC_TRUE, PETSC_TRUE}));
    PetscCall(UpdateStress(mpm));
    break;
  case StepScheme::MUSL:
    PetscCall(ParticlesToGrid(mpm, {PETSC_TRUE, PETSC_TRUE, PETSC_TRUE}));
    PetscCall(GridUpdate(mpm));
    PetscCall(RemapMomentum(mpm)); // G2P(v) and P2G(mv) in one particle pass
    PetscCall(GridVelocityFromMomentum(mpm));
    PetscCall(GridToParticles(mpm, {PETSC_FALSE, PETSC_TRUE, PETSC_TRUE}));
    PetscCall(UpdateStress(mpm));
    break;
  case StepScheme::USF:
    PetscCall(ParticlesToGrid(mpm, {PETSC_TRUE, PETSC_TRUE, PETSC_FALSE}));
    PetscCall(GridVelocityFromMomentum(mpm));
    PetscCall(GridToParticles(mpm, {PETSC_FALSE, PETSC_FALSE, PETSC_TRUE}));
    PetscCall(UpdateStress(mpm));
    PetscCall(ParticlesToGrid(mpm, {PETSC_FALSE, PETSC_FALSE, PETSC_TRUE}));
    PetscCall(GridUpdate(mpm));
    PetscCall(GridToParticles(mpm, {PETSC_TRUE, PETSC_TRUE, PETSC_FALSE}));
    break;
  }
  PetscCall(MigrateParticles(mpm));
  PetscCall(ConductHeat(mpm));     // after migration: the stencil needs every particle on its owner rank
  PetscCall(NonlocalAverage(mpm)); // likewise; no-op unless a material regularises nonlocally
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode ICEStep(IceSolver &ice, PetscReal dt)
{
  PetscFunctionBeginUser;
  ice.dt = dt;
  PetscCall(IceBudgetStepStart(ice));
  PetscCall(IceEquilibrate(ice));
  PetscCall(IceFaceVelocities(ice));
  PetscCall(IceUpdatePressure(ice));
  PetscCall(IceSources(ice));
  PetscCall(IceBudgetFaces(ice));
  PetscCall(IceCellExchange(ice));
  PetscCall(IceBudgetAfterExchange(ice));
  PetscCall(IceAdvect(ice));
  PetscCall(IceBudgetOpenFaces(ice));
  ice.time += dt;
  ice.step += 1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Solids and gas in one step (ice.md 1.2).
static PetscErrorCode CoupledStep(Simulation &sim)
{
  MpmSolver &mpm      = sim.mpm;
  Coupling  &coupling = *sim.coupling;
  IceSolver &ice      = *sim.ice;
  PetscFunctionBeginUser;
  ice.dt = sim.dt;
  PetscCall(ComputeExternalForces(mpm));
  PetscCall(ParticlesToGrid(mpm, {PETSC_TRUE, PETSC_TRUE, PETSC_FALSE}));
  PetscCall(CouplingProjectSolids(coupling));
  PetscCall(IceBudgetStepStart(ice));
  PetscCall(IceEquilibrate(ice));
  PetscCall(CouplingBurn(coupling));
  PetscCall(CouplingBurnParticles(coupling));
  PetscCall(IceFaceVelocities(ice));
  PetscCall(IceUpdatePressure(ice));
  PetscCall(CouplingPressureToParticles(coupling));
  PetscCall(ParticlesToGrid(mpm, {PETSC_FALSE, PETSC_FALSE, PETSC_TRUE}));
  PetscCall(GridUpdate(mpm));
  PetscCall(CouplingSolidVelocity(coupling));
  PetscCall(IceSources(ice));
  PetscCall(IceBudgetFaces(ice));
  PetscCall(IceCellExchange(ice));
  PetscCall(CouplingSurfaceHeat(coupling)); // no-op unless -coupling_surface_heat_transfer
  PetscCall(IceBudgetAfterExchange(ice));
  PetscCall(CouplingIncrementsToNodes(coupling));
  PetscCall(CouplingChargePressureWork(coupling));
  if (mpm.scheme == StepScheme::MUSL) {
    const PetscBool gradient_from_v_new = mpm.coupled_musl_gradient == MuslGradient::VNew ? PETSC_TRUE : PETSC_FALSE;
    PetscCall(RemapMomentum(mpm));
    if (gradient_from_v_new) PetscCall(GridToParticles(mpm, {PETSC_FALSE, PETSC_FALSE, PETSC_TRUE})); // L from v_new: the velocity the gas saw
    PetscCall(GridVelocityFromMomentum(mpm));
    PetscCall(GridToParticles(mpm, {PETSC_FALSE, PETSC_TRUE, gradient_from_v_new ? PETSC_FALSE : PETSC_TRUE}));
  } else PetscCall(GridToParticles(mpm, {PETSC_TRUE, PETSC_TRUE, PETSC_TRUE}));
  PetscCall(CouplingHeatToParticles(coupling));
  PetscCall(UpdateStress(mpm));
  PetscCall(MigrateParticles(mpm));
  PetscCall(ConductHeat(mpm));
  PetscCall(NonlocalAverage(mpm));
  PetscCall(IceAdvect(ice));
  PetscCall(IceBudgetOpenFaces(ice));
  ice.time += sim.dt;
  ice.step += 1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

// The heat-up: the gas flows around solids held still; they take its heat and conduct it.
static PetscErrorCode HeatUpStep(Simulation &sim)
{
  MpmSolver &mpm      = sim.mpm;
  Coupling  &coupling = *sim.coupling;
  IceSolver &ice      = *sim.ice;
  PetscFunctionBeginUser;
  ice.dt = sim.dt;
  PetscCall(ParticlesToGrid(mpm, {PETSC_TRUE, PETSC_TRUE, PETSC_FALSE}));
  PetscCall(GridVelocityFromMomentum(mpm)); // the particles are at rest: every nodal velocity is zero
  PetscCall(CouplingProjectSolids(coupling));
  PetscCall(IceBudgetStepStart(ice));
  PetscCall(IceEquilibrate(ice));
  PetscCall(IceFaceVelocities(ice));
  PetscCall(IceUpdatePressure(ice));
  PetscCall(CouplingSolidVelocity(coupling));
  PetscCall(IceSources(ice));
  PetscCall(IceBudgetFaces(ice));
  PetscCall(IceCellExchange(ice));
  PetscCall(CouplingSurfaceHeat(coupling)); // no-op unless -coupling_surface_heat_transfer
  PetscCall(IceBudgetAfterExchange(ice));
  PetscCall(CouplingIncrementsToNodes(coupling)); // the heat increments; no velocity reaches the particles
  PetscCall(PhasesMeasureHeatBefore(sim));
  PetscCall(CouplingHeatToParticles(coupling));
  PetscCall(PhasesMeasureHeatAfter(sim));
  PetscCall(ConductHeat(mpm));
  PetscCall(IceAdvect(ice));
  PetscCall(IceBudgetOpenFaces(ice));
  ice.time += sim.dt;
  ice.step += 1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Heat only: the solids conduct under the surface heat measured in the heat-up; the gas is held.
static PetscErrorCode HeatOnlyStep(Simulation &sim)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(sim.phases.ev_heat_only, 0, 0, 0, 0));
  PetscCall(ConductHeat(sim.mpm));
  sim.ice->time += sim.dt;
  PetscCall(PetscLogEventEnd(sim.phases.ev_heat_only, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// The step size: the smaller of the MPM and gas limits, ending exactly at -final_time. In the
// heat-up the gas alone sets it (and the heat-up ends on a step); heat only takes its own.
static PetscErrorCode StableTimeStep(Simulation &sim)
{
  const RunPhase phase = sim.phases.Current();
  PetscFunctionBeginUser;
  sim.dt = PETSC_MAX_REAL;
  if (sim.HasParticles() && phase == RunPhase::Mechanics) {
    PetscCall(ComputeTimeStep(sim.mpm, sim.run.final_time));
    sim.dt = sim.mpm.dt;
  }
  if (sim.ice) {
    PetscReal dt_gas;
    PetscCall(IceComputeTimeStep(*sim.ice, &dt_gas));
    sim.dt = PetscMin(sim.dt, PetscMin(dt_gas, sim.mpm.dt_max));
    if (sim.mpm.dt_fixed > 0) sim.dt = sim.mpm.dt_fixed;
    if (phase == RunPhase::HeatUp) {
      const Phases   &ph   = sim.phases;
      const PetscReal left = ph.heatup_end_time - sim.time;
      sim.dt               = PetscMin(sim.dt, ph.heatup_dt_max);
      if (left > 0 && (sim.dt > left || left - sim.dt < 1e-6 * sim.dt)) sim.dt = left;
    } else if (phase == RunPhase::HeatOnly) sim.dt = sim.phases.heat_only_dt;
    PetscCheck(sim.dt > 0 && sim.dt < PETSC_MAX_REAL, sim.comm, PETSC_ERR_NOT_CONVERGED,
               "Step %" PetscInt_FMT
               ": time step %g s is not positive: a sound speed or velocity is not finite; check the gas materials' equation-of-state options (-<gas>_gamma, -<gas>_cv, ...), their -<gas>_density and -<gas>_temperature, and -ice_cfl / -ice_dt",
               sim.step, (double)sim.dt);
    const PetscReal remaining = sim.run.final_time - sim.time;
    if (sim.dt > remaining || remaining - sim.dt < 1e-6 * sim.dt) sim.dt = remaining;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

void SetMpmClock(Simulation &sim)
{
  sim.mpm.step = sim.step;
  sim.mpm.time = sim.time;
  sim.mpm.dt   = sim.dt;
}

PetscErrorCode TakeStep(Simulation &sim)
{
  PetscFunctionBeginUser;
  SetMpmClock(sim);
  PetscCall(StableTimeStep(sim));
  SetMpmClock(sim);
  if (sim.phases.Current() == RunPhase::HeatUp) PetscCall(HeatUpStep(sim));
  else if (sim.phases.Current() == RunPhase::HeatOnly) PetscCall(HeatOnlyStep(sim));
  else if (sim.coupling) PetscCall(CoupledStep(sim));
  else {
    if (sim.HasParticles()) PetscCall(MPMStep(sim.mpm));
    if (sim.ice) PetscCall(ICEStep(*sim.ice, sim.dt));
  }
  sim.time += sim.dt;
  sim.step += 1;
  sim.mpm.particle_steps += sim.mpm.total_particles;
  SetMpmClock(sim);
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
