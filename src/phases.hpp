// The phases of a run (src/phases.cxx): a container in a fire heats for seconds or minutes before its
// charge ignites, and bursts in microseconds after. No single time step serves both, so such a run
// goes through phases, each with its own step, switched by criteria that are printed as they fire:
//
//   heatup     the gas flows (semi-implicit pressure at the flow's CFL: -phase_heatup_sound_speed_knob)
//              around solids held still and stress-free (no MPM time step); the gas and the solids
//              exchange heat in the cells they share and heat conducts in the solids. Over the last
//              -phase_flux_window seconds each particle's heat from the gas is measured as a
//              conductance G_p = Q_p / integral (T_f - T_p) dt, with T_f the flame temperature
//              (-phase_flame_temperature; default the hottest gas at the window's end).
//   heat_only  the gas is held at its last state (a steady fire); only the solids' temperatures move:
//              conduction with steps of -phase_heat_only_dt and the surface heat G_p (T_f - T_p). This
//              is how burst compresses the minutes of a cook-off: it integrates them, with the fire's
//              measured surface heat, instead of lowering the ignition temperature.
//   mechanics  the full coupled step (the run as every other scene runs).
//
// From heatup or heat_only the run goes to mechanics once the burn model's ignition criterion holds
// in a cell (-phase_ignition burn_model, the default: the same test its burning starts with, on the
// cells projected from the particles), or once a particle of the ignition material
// (-phase_ignition_material; default the solid with a burn model) reaches the ignition temperature
// (-phase_ignition temperature; -phase_ignition_temperature, default the burn model's own: Simple
// Burn's T_th, Steady Burn's T_ign), or once a particle of it has reacted -phase_kinetics_fraction of
// its mass by its own one-step thermal decomposition, integrated with CVODE after each step with the
// reaction heat kept in the particle (-phase_ignition kinetics; models/burn/thermal_decomposition.hpp,
// options -<material>_decomposition_*; swarm field reacted_fraction); heatup goes to heat_only (or mechanics) at -phase_heatup_end_time. A checkpoint is written
// at each switch (-phase_checkpoint) and kept as phase_<phase>_<step>.h5 (pruning leaves it), so a
// run can be continued from the end of the heat-up with other options (-restart FILE
// -restart_allow_option_change).
#pragma once
#include "petsc_compat.hpp"
#include <memory>
#include <string>
#include <vector>

namespace burst {

struct Simulation;
class ThermalDecomposition;
struct ThermalDecompositionDeleter {
  void operator()(ThermalDecomposition *) const;
};

enum class RunPhase { HeatUp = 0, HeatOnly = 1, Mechanics = 2 };
inline const char *RunPhaseName(RunPhase p) { return p == RunPhase::HeatUp ? "heatup" : p == RunPhase::HeatOnly ? "heat_only" : "mechanics"; }

struct Phases {
  // Options
  std::vector<RunPhase>                                              order                   = {RunPhase::Mechanics}; // -phases, in the order heatup, heat_only, mechanics
  PetscReal                                                          heatup_end_time         = 0.05;                  // s
  PetscReal                                                          flux_window             = 0;                     // s; 0: the last fifth of the heat-up
  PetscReal                                                          heat_only_dt            = 0.05;                  // s
  PetscReal                                                          heatup_sound_speed_knob = 0;                     // k of the gas CFL during the heat-up
  PetscReal                                                          heatup_dt_max           = 1e-4;                  // s
  PetscReal                                                          flame_temperature       = 0;                     // K; 0: the hottest gas at the window's end
  PetscReal                                                          ignition_temperature    = 0;                     // K; 0: the burn model's
  PetscInt                                                           ignition_material       = -1;                    // material id
  PetscBool                                                          ignition_by_temperature = PETSC_FALSE;           // -phase_ignition temperature: a particle's temperature, not the burn model's cells
  PetscBool                                                          ignition_by_kinetics    = PETSC_FALSE;           // -phase_ignition kinetics: each charge particle's thermal decomposition
  PetscReal                                                          kinetics_fraction       = 0.01;                  // the reacted fraction that counts as runaway
  std::unique_ptr<ThermalDecomposition, ThermalDecompositionDeleter> kinetics;                                        // -<material>_decomposition_*
  PetscBool                                                          write_checkpoint   = PETSC_TRUE;
  PetscReal                                                          mechanics_duration = 0;          // s; > 0: the run ends this long after mechanics began
  PetscBool                                                          mechanics_explicit = PETSC_TRUE; // mechanics on the explicit gas pressure (the burst's own step, as the exploding scenes)

  // State (checkpointed: /run/phases)
  size_t    current           = 0;            // index into order
  PetscReal window_start      = -1;           // s; < 0: not measuring yet
  PetscReal window_length     = 0;            // s measured so far
  PetscReal switch_time[3]    = {-1, -1, -1}; // s: when heatup, heat_only, mechanics began (-1: not yet)
  PetscReal surface_heat_rate = 0;            // W (per metre of depth in 2-D): sum_p G_p (T_f - T_p) at the window's end
  PetscReal hottest_ignition  = 0;            // K: the criterion's temperature at the last check (particle or cell)
  bool      switched          = false;        // this step ended a phase (the driver writes an output then)
  // heat_only with the burn model's criterion: the lowest ignition temperature of the burning
  // solids (0: one has none, every step is checked), and whether this heat_only has checked once
  PetscReal cell_ignition_temperature = 0;
  bool      heat_only_checked         = false;

  PetscReal              mechanics_sound_speed_knob = 0;           // the gas's own k, restored for mechanics
  PetscBool              semi_implicit_gas          = PETSC_FALSE; // the gas's own pressure solver is the semi-implicit one
  std::vector<PetscReal> temperature_before;                       // per local particle, reused: the heat-up's measurement
  PetscLogEvent          ev_measure = 0, ev_heat_only = 0;

  bool     Enabled() const { return !(order.size() == 1 && order[0] == RunPhase::Mechanics); }
  RunPhase Current() const { return order[current]; }
};

// Reads -phases and -phase_*; before the swarm is created (it registers the measurement's fields).
PetscErrorCode PhasesSetUp(Simulation &sim);
// After the coupling is set up: the ignition material and temperature, the gas's CFL knob.
PetscErrorCode PhasesCheck(Simulation &sim);
// The heat-up's measurement, around CouplingHeatToParticles: before (marks the temperatures) and after.
PetscErrorCode PhasesMeasureHeatBefore(Simulation &sim);
PetscErrorCode PhasesMeasureHeatAfter(Simulation &sim);
// After each step: the criteria; a switch is printed, checkpointed and sets up the next phase's step;
// *stop when the run's last phase has ended.
PetscErrorCode PhasesAfterStep(Simulation &sim, PetscBool *stop);
// Per solid material: the hottest particle's temperature and the mass-weighted mean (K), global
// (monitor.csv's columns with -phases).
PetscErrorCode PhasesTemperatures(Simulation &sim, std::vector<PetscReal> &out);
// summary.json's "phases" entry (a line ending in ",\n"; empty without -phases).
std::string PhasesSummary(const Simulation &sim);
// The checkpoint's /run/phases record and its restore.
std::vector<PetscReal> PhasesState(const Simulation &sim);
PetscErrorCode         PhasesRestore(Simulation &sim, const std::vector<PetscReal> &state);
constexpr PetscInt     kPhasesStateSize = 9;

} // namespace burst
