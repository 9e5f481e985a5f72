// One explicit MPM time step: the ordered list of phases.
//
//   USL  (update stress last, the default; Uintah's order, Wallstedt & Guilkey 2008):
//        P2G(m, mv, f) -> grid update + BCs -> G2P(v, x, L, F) -> stress -> migrate
//   MUSL (modified USL, Sulsky et al. 1995): after the velocity G2P, momentum goes back to the grid
//        and the position and L come from that remapped velocity.
//   USF  (update stress first): P2G(m, mv) -> grid velocity -> G2P(L, F) -> stress -> P2G(f) ->
//        grid update -> G2P(v, x)
//
// Every phase is a named function with its own PetscLogEvent; a coupled solver (ICE) interleaves
// its phases between these calls (ice.md 1.2).
#include "simulation.hpp"

namespace burst {

PetscErrorCode TakeStep(Simulation &sim)
{
  PetscFunctionBeginUser;
  PetscCall(ComputeTimeStep(sim));
  PetscCall(ComputeExternalForces(sim));
  switch (sim.scheme) {
  case StepScheme::USL:
    PetscCall(ParticlesToGrid(sim, {PETSC_TRUE, PETSC_TRUE, PETSC_TRUE}));
    PetscCall(GridUpdate(sim));
    PetscCall(GridToParticles(sim, {PETSC_TRUE, PETSC_TRUE, PETSC_TRUE}));
    PetscCall(UpdateStress(sim));
    break;
  case StepScheme::MUSL:
    PetscCall(ParticlesToGrid(sim, {PETSC_TRUE, PETSC_TRUE, PETSC_TRUE}));
    PetscCall(GridUpdate(sim));
    PetscCall(GridToParticles(sim, {PETSC_TRUE, PETSC_FALSE, PETSC_FALSE}));
    PetscCall(ParticlesToGrid(sim, {PETSC_FALSE, PETSC_TRUE, PETSC_FALSE}));
    PetscCall(GridVelocityFromMomentum(sim));
    PetscCall(GridToParticles(sim, {PETSC_FALSE, PETSC_TRUE, PETSC_TRUE}));
    PetscCall(UpdateStress(sim));
    break;
  case StepScheme::USF:
    PetscCall(ParticlesToGrid(sim, {PETSC_TRUE, PETSC_TRUE, PETSC_FALSE}));
    PetscCall(GridVelocityFromMomentum(sim));
    PetscCall(GridToParticles(sim, {PETSC_FALSE, PETSC_FALSE, PETSC_TRUE}));
    PetscCall(UpdateStress(sim));
    PetscCall(ParticlesToGrid(sim, {PETSC_FALSE, PETSC_FALSE, PETSC_TRUE}));
    PetscCall(GridUpdate(sim));
    PetscCall(GridToParticles(sim, {PETSC_TRUE, PETSC_TRUE, PETSC_FALSE}));
    break;
  }
  PetscCall(MigrateParticles(sim));
  sim.time += sim.dt;
  sim.step += 1;
  sim.particle_steps += sim.total_particles;
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
