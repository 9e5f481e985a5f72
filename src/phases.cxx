// The phases of a run: options, the heat-up's measurement of the surface heat, the switches
// (src/phases.hpp says what each phase does and why).
#include "phases.hpp"
#include "simulation.hpp"
#include "coupling/coupling.hpp"
#include "ice/ice.hpp"
#include "io/checkpoint.hpp"
#include "mpm/swarm_access.hpp"
#include "../models/burn/thermal_decomposition.hpp"
#include "util.hpp"
#include <cmath>
#include <cstring>
#include <sstream>

namespace burst {

namespace {
const char *const kPhaseChoices = "heatup, heat_only, mechanics";

bool Has(const Phases &ph, RunPhase p)
{
  for (RunPhase q : ph.order)
    if (q == p) return true;
  return false;
}

// -phases: names in the order heatup, heat_only, mechanics, each at most once.
PetscErrorCode ParsePhases(MPI_Comm comm, const std::string &text, std::vector<RunPhase> &order)
{
  PetscFunctionBeginUser;
  order.clear();
  std::stringstream words(text);
  std::string       word;
  while (std::getline(words, word, ',')) {
    RunPhase p;
    if (word == "heatup") p = RunPhase::HeatUp;
    else if (word == "heat_only") p = RunPhase::HeatOnly;
    else if (word == "mechanics") p = RunPhase::Mechanics;
    else SETERRQ(comm, PETSC_ERR_USER_INPUT, "Option -phases: unknown phase '%s'; valid choices: %s (a comma-separated list in that order)", word.c_str(), kPhaseChoices);
    PetscCheck(order.empty() || (int)p > (int)order.back(), comm, PETSC_ERR_USER_INPUT, "Option -phases %s: the phases must come in the order %s, each at most once", text.c_str(), kPhaseChoices);
    order.push_back(p);
  }
  PetscCheck(!order.empty(), comm, PETSC_ERR_USER_INPUT, "Option -phases is empty; valid choices: %s (a comma-separated list in that order)", kPhaseChoices);
  PetscFunctionReturn(PETSC_SUCCESS);
}

// The particle of material `material` with the largest value of the swarm field `name` (global): the
// value, its id and position.
PetscErrorCode LargestParticle(Simulation &sim, const char name[], PetscInt material, PetscReal *largest, PetscInt64 *id, PetscReal x[3])
{
  PetscInt          n;
  const PetscReal  *value, *coor;
  const PetscInt   *mat;
  const PetscInt64 *pid;
  const PetscInt    dim = sim.mpm.grid.dim;
  struct {
    PetscReal   value;
    PetscMPIInt rank;
  } local       = {-PETSC_MAX_REAL, sim.rank}, global;
  PetscInt best = -1;
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(sim.mpm.swarm, &n));
  SwarmAccess fields(sim.mpm.swarm);
  PetscCall(fields.Get(name, &value));
  PetscCall(fields.Get(field::material, &mat));
  PetscCall(fields.Get(DMSwarmPICField_coor, &coor));
  PetscCall(fields.Get(DMSwarmField_pid, &pid));
  for (PetscInt p = 0; p < n; ++p)
    if (mat[p] == material && value[p] > local.value) {
      local.value = value[p];
      best        = p;
    }
  static_assert(sizeof(PetscReal) == sizeof(double), "MPI_DOUBLE_INT below");
  PetscCallMPI(MPI_Allreduce(&local, &global, 1, MPI_DOUBLE_INT, MPI_MAXLOC, sim.comm));
  PetscReal where[4] = {0, 0, 0, 0};
  if (sim.rank == global.rank && best >= 0) {
    for (PetscInt d = 0; d < dim; ++d) where[d] = coor[best * dim + d];
    where[3] = (PetscReal)pid[best];
  }
  PetscCall(fields.RestoreAll());
  PetscCallMPI(MPI_Bcast(where, 4, MPIU_REAL, global.rank, sim.comm));
  *largest = global.value;
  *id      = (PetscInt64)where[3];
  for (int d = 0; d < 3; ++d) x[d] = where[d];
  PetscFunctionReturn(PETSC_SUCCESS);
}

// The ignition material's particles decompose over the step just taken (sim.dt) at their own
// temperature, the reaction heat kept (operator split after the step's conduction). Where the rate
// Z exp(-T_a/T) dt is below 1e-10 the reacted fraction grows by it explicitly; else CVODE.
PetscErrorCode AdvanceKinetics(Simulation &sim)
{
  Phases               &ph = sim.phases;
  ThermalDecomposition &k  = *ph.kinetics;
  PetscInt              n;
  PetscReal            *T, *lambda;
  const PetscInt       *mat;
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(sim.mpm.swarm, &n));
  SwarmAccess fields(sim.mpm.swarm);
  PetscCall(fields.Get(field::temperature, &T));
  PetscCall(fields.Get(field::reacted_fraction, &lambda));
  PetscCall(fields.Get(field::material, &mat));
  for (PetscInt p = 0; p < n; ++p) {
    if (mat[p] != ph.ignition_material) continue;
    const PetscReal rate = k.par.Z * std::exp(-k.par.T_a / T[p]) * sim.dt;
    if (rate < 1e-10) lambda[p] += (1 - lambda[p]) * rate;
    else PetscCall(k.Advance(sim.dt, &lambda[p], &T[p]));
  }
  PetscCall(fields.RestoreAll());
  PetscFunctionReturn(PETSC_SUCCESS);
}

// The hottest gas (a gas filling at least half of its cell), K: the flame's temperature.
PetscErrorCode HottestGas(Simulation &sim, PetscReal *T_max)
{
  IceSolver   &ice = *sim.ice;
  PetscScalar *a;
  PetscReal    local = 0;
  PetscFunctionBeginUser;
  PetscCall(IceGetLocalArray(ice, &a));
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        const PetscScalar *cell = a + ice.LocalIndex(i, j, k) * ice.stride;
        for (PetscInt g = 0; g < ice.ngas; ++g)
          if (cell[ice.Offset(g, icef::theta)] >= 0.5) local = PetscMax(local, cell[ice.Offset(g, icef::temp)]);
      }
  PetscCall(IceRestoreLocalArray(ice, &a));
  PetscCallMPI(MPI_Allreduce(&local, T_max, 1, MPIU_REAL, MPI_MAX, sim.comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// What the current phase's step needs of the gas, the coupling and the conduction.
PetscErrorCode ApplyPhase(Simulation &sim)
{
  Phases        &ph = sim.phases;
  const RunPhase p  = ph.Current();
  PetscFunctionBeginUser;
  sim.ice->sound_speed_knob = p == RunPhase::HeatUp ? ph.heatup_sound_speed_knob : ph.mechanics_sound_speed_knob;
  if (ph.semi_implicit_gas) sim.ice->pressure_solver = p == RunPhase::Mechanics && ph.mechanics_explicit ? IcePressureSolver::Explicit : IcePressureSolver::SemiImplicit;
  if (p == RunPhase::Mechanics && ph.mechanics_explicit) sim.ice->sound_speed_knob = 1; // (explicit: the sound speed in full)
  PetscCall(CouplingMeasureSurfaceHeat(*sim.coupling, (PetscBool)(p == RunPhase::HeatUp && ph.window_start >= 0)));
  if (sim.mpm.heat) PetscCall(HeatSetSurfaceSource(sim.mpm, (PetscBool)(p == RunPhase::HeatOnly), ph.flame_temperature));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// The end of the heat-up's window: each particle's conductance G_p = Q_p / (T_f W - integral T_p dt)
// (zero where the gas gave no heat: inside the solids and on faces the fire does not reach), and the
// surface heat rate sum_p G_p (T_f - T_p) now.
PetscErrorCode FinishMeasurement(Simulation &sim)
{
  Phases          &ph = sim.phases;
  PetscInt         n;
  const PetscReal *Q, *Tt, *T;
  PetscReal       *G;
  PetscReal        sums[2] = {0, 0}, global[2]; // [rate now, heat received over the window]
  PetscFunctionBeginUser;
  PetscCheck(ph.window_length > 0, sim.comm, PETSC_ERR_USER_INPUT, "Phases: the heat-up ended at t = %g s before its measurement window began (-phase_flux_window %g s, -phase_heatup_end_time %g s)", (double)sim.time, (double)ph.flux_window,
             (double)ph.heatup_end_time);
  if (ph.flame_temperature <= 0) PetscCall(HottestGas(sim, &ph.flame_temperature));
  PetscCall(DMSwarmGetLocalSize(sim.mpm.swarm, &n));
  SwarmAccess fields(sim.mpm.swarm);
  PetscCall(fields.Get(field::surface_heat, &Q));
  PetscCall(fields.Get(field::surface_temperature_time, &Tt));
  PetscCall(fields.Get(field::temperature, &T));
  PetscCall(fields.Get(field::surface_conductance, &G));
  const PetscReal Tf = ph.flame_temperature, W = ph.window_length;
  for (PetscInt p = 0; p < n; ++p) {
    const PetscReal driving = Tf * W - Tt[p]; // integral of (T_f - T_p) dt, K s
    G[p]                    = Q[p] > 0 && driving > 0 ? Q[p] / driving : 0;
    sums[0] += G[p] * (Tf - T[p]);
    sums[1] += Q[p];
  }
  PetscCall(fields.RestoreAll());
  PetscCallMPI(MPI_Allreduce(sums, global, 2, MPIU_REAL, MPI_SUM, sim.comm));
  ph.surface_heat_rate = global[0];
  PetscCall(PetscPrintf(sim.comm, "  surface heat measured over [%g, %g] s: %g J from the gas, %g W now (flame temperature %g K%s)\n", (double)ph.window_start, (double)(ph.window_start + W), (double)global[1], (double)global[0], (double)Tf,
                        sim.mpm.grid.dim == 2 ? "; per metre of depth" : ""));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SwitchTo(Simulation &sim, RunPhase to, const std::string &why)
{
  Phases        &ph   = sim.phases;
  const RunPhase from = ph.Current();
  PetscFunctionBeginUser;
  ph.switched = true;
  PetscCall(PetscPrintf(sim.comm, "Phase %s -> %s at step %" PetscInt_FMT ", t = %g s: %s\n", RunPhaseName(from), RunPhaseName(to), sim.step, (double)sim.time, why.c_str()));
  if (from == RunPhase::HeatUp) PetscCall(FinishMeasurement(sim));
  while (ph.Current() != to) ph.current += 1;
  ph.switch_time[(int)to] = sim.time;
  PetscCall(ApplyPhase(sim));
  if (ph.write_checkpoint) {
    char name[64];
    std::snprintf(name, sizeof(name), "phase_%s_%06d.h5", RunPhaseName(to), (int)sim.step);
    PetscCall(CheckpointWrite(sim));
    PetscCall(CheckpointKeepAs(sim, name));
    PetscCall(PetscPrintf(sim.comm, "  wrote %s/%s (continue from it with -restart %s/%s)\n", sim.output.dir.c_str(), name, sim.output.dir.c_str(), name));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
} // namespace

PetscErrorCode PhasesSetUp(Simulation &sim)
{
  Phases   &ph        = sim.phases;
  char      text[256] = "mechanics", ignition[256] = "";
  PetscBool set = PETSC_FALSE, has_window = PETSC_FALSE, has_material = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscOptionsBegin(sim.comm, "", "Run phases: a container in a fire (src/phases.hpp)", "Phases");
  PetscCall(PetscOptionsString("-phases", "The run's phases, a comma-separated list in the order heatup,heat_only,mechanics (heatup: gas around solids held still; heat_only: conduction under the measured surface heat; mechanics: the full step)", "",
                               text, text, sizeof(text), &set));
  PetscCall(PetscOptionsReal("-phase_heatup_end_time", "heatup: the time at which it ends (s), > 0", "", ph.heatup_end_time, &ph.heatup_end_time, nullptr));
  PetscCall(PetscOptionsReal("-phase_flux_window", "heatup: the surface heat is measured over this last part of it (s), in (0, -phase_heatup_end_time]; default: its last fifth", "", ph.flux_window, &ph.flux_window, &has_window));
  PetscCall(PetscOptionsReal("-phase_heatup_sound_speed_knob", "heatup: k of the gas CFL, in [0, 1] (0: the flow's speed alone sets the step, as the reference's heat-up)", "", ph.heatup_sound_speed_knob, &ph.heatup_sound_speed_knob, nullptr));
  PetscCall(PetscOptionsReal("-phase_heatup_dt_max", "heatup: the largest time step (s), > 0", "", ph.heatup_dt_max, &ph.heatup_dt_max, nullptr));
  PetscCall(PetscOptionsReal("-phase_heat_only_dt", "heat_only: the time step (s), > 0 (conduction sub-steps within it as -mpm_heat_cfl asks)", "", ph.heat_only_dt, &ph.heat_only_dt, nullptr));
  PetscCall(PetscOptionsReal("-phase_flame_temperature", "T_f of the surface heat G_p (T_f - T_p) (K), >= 0; 0: the hottest gas at the end of the heat-up", "", ph.flame_temperature, &ph.flame_temperature, nullptr));
  PetscCall(PetscOptionsReal("-phase_ignition_temperature", "The run goes to mechanics once a particle of the ignition material is this hot (K), >= 0; 0: its burn model's ignition temperature", "", ph.ignition_temperature, &ph.ignition_temperature,
                             nullptr));
  {
    const char *const criteria[] = {"burn_model", "temperature", "kinetics"};
    int               choice     = ph.ignition_by_temperature ? 1 : ph.ignition_by_kinetics ? 2 : 0;
    PetscCall(OptionsChoice(PetscOptionsObject, "-phase_ignition",
                            "What ends the heat-up and heat_only: burn_model (its ignition criterion holds in a cell), temperature (a particle of the ignition material reaches -phase_ignition_temperature) or kinetics (one of them has decomposed "
                            "-phase_kinetics_fraction of its mass)",
                            criteria, 3, &choice, nullptr));
    ph.ignition_by_temperature = (PetscBool)(choice == 1);
    ph.ignition_by_kinetics    = (PetscBool)(choice == 2);
  }
  PetscCall(PetscOptionsReal("-phase_kinetics_fraction", "With -phase_ignition kinetics: the reacted mass fraction of a particle that counts as ignition, in (0, 1)", "", ph.kinetics_fraction, &ph.kinetics_fraction, nullptr));
  PetscCall(PetscOptionsString("-phase_ignition_material", "The solid whose temperature decides ignition; default: the one with a burn model (-<material>_burn_type)", "", ignition, ignition, sizeof(ignition), &has_material));
  PetscCall(PetscOptionsReal("-phase_mechanics_duration", "mechanics: the run ends this long after they began (s), >= 0; 0: at -final_time (an ignition time is not known before the run)", "", ph.mechanics_duration, &ph.mechanics_duration, nullptr));
  PetscCall(PetscOptionsBool("-phase_mechanics_explicit", "mechanics: the gas pressure explicit (the exploding scenes' step; the heat-up needs -ice_pressure_solver semi_implicit for its long steps), with the sound-speed knob 1", "",
                             ph.mechanics_explicit, &ph.mechanics_explicit, nullptr));
  PetscCall(PetscOptionsBool("-phase_checkpoint", "Write a checkpoint at each phase switch, kept as phase_<phase>_<step>.h5", "", ph.write_checkpoint, &ph.write_checkpoint, nullptr));
  PetscOptionsEnd();
  if (sim.help) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(ParsePhases(sim.comm, text, ph.order));
  PetscCall(CheckRange(sim.comm, "-phase_heatup_end_time", ph.heatup_end_time, 0, PETSC_MAX_REAL, PETSC_TRUE));
  if (!has_window) ph.flux_window = 0.2 * ph.heatup_end_time;
  PetscCheck(ph.flux_window > 0 && ph.flux_window <= ph.heatup_end_time, sim.comm, PETSC_ERR_USER_INPUT, "Option -phase_flux_window = %g s is out of range: it must be in (0, -phase_heatup_end_time = %g s]", (double)ph.flux_window,
             (double)ph.heatup_end_time);
  PetscCall(CheckRange(sim.comm, "-phase_heatup_sound_speed_knob", ph.heatup_sound_speed_knob, 0, 1, PETSC_FALSE));
  PetscCall(CheckRange(sim.comm, "-phase_heatup_dt_max", ph.heatup_dt_max, 0, PETSC_MAX_REAL, PETSC_TRUE));
  PetscCall(CheckRange(sim.comm, "-phase_heat_only_dt", ph.heat_only_dt, 0, PETSC_MAX_REAL, PETSC_TRUE));
  PetscCall(CheckRange(sim.comm, "-phase_flame_temperature", ph.flame_temperature, 0, 1e6, PETSC_FALSE));
  if (ph.ignition_by_kinetics) PetscCall(CheckRange(sim.comm, "-phase_kinetics_fraction", ph.kinetics_fraction, 0, 1, PETSC_TRUE));
  PetscCall(CheckRange(sim.comm, "-phase_mechanics_duration", ph.mechanics_duration, 0, PETSC_MAX_REAL, PETSC_FALSE));
  PetscCall(CheckRange(sim.comm, "-phase_ignition_temperature", ph.ignition_temperature, 0, 1e6, PETSC_FALSE));
  if (has_material) {
    std::string names;
    for (size_t m = 0; m < sim.mpm.materials.size(); ++m) {
      names += (m ? ", " : "") + std::string(sim.mpm.materials[m]->Name());
      if (!std::strcmp(sim.mpm.materials[m]->Name(), ignition)) ph.ignition_material = (PetscInt)m;
    }
    PetscCheck(ph.ignition_material >= 0, sim.comm, PETSC_ERR_USER_INPUT, "Option -phase_ignition_material %s is not a solid material; valid choices (-materials): %s", ignition, names.c_str());
  }
  if (ph.Enabled()) {
    PetscClassId id;
    PetscCall(PetscClassIdRegister("Phases", &id));
    PetscCall(PetscLogEventRegister("Phase_Measure", id, &ph.ev_measure));
    PetscCall(PetscLogEventRegister("Phase_HeatOnly", id, &ph.ev_heat_only));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PhasesCheck(Simulation &sim)
{
  Phases &ph = sim.phases;
  PetscFunctionBeginUser;
  if (!ph.Enabled()) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(sim.coupling, sim.comm, PETSC_ERR_USER_INPUT, "Option -phases: phases other than mechanics need solids and gas (-materials and -ice_materials)");
  PetscCheck(!Has(ph, RunPhase::HeatOnly) || sim.mpm.heat, sim.comm, PETSC_ERR_USER_INPUT, "Option -phases heat_only needs heat conduction in the solids (-mpm_heat_conduction)");
  PetscCheck(!Has(ph, RunPhase::HeatOnly) || Has(ph, RunPhase::HeatUp), sim.comm, PETSC_ERR_USER_INPUT, "Option -phases heat_only needs heatup before it (the surface heat is measured there)");
  std::string model;
  PetscReal   T_model = 0;
  if (ph.ignition_material < 0) {
    std::string burning;
    for (size_t m = 0; m < sim.mpm.materials.size(); ++m) {
      PetscCall(CouplingIgnition(*sim.coupling, (PetscInt)m, &model, &T_model));
      if (model == "none") continue;
      PetscCheck(ph.ignition_material < 0, sim.comm, PETSC_ERR_USER_INPUT, "Option -phase_ignition_material: both %s and %s burn; name the one whose temperature decides ignition", sim.mpm.materials[ph.ignition_material]->Name(),
                 sim.mpm.materials[m]->Name());
      ph.ignition_material = (PetscInt)m;
    }
    PetscCheck(ph.ignition_material >= 0, sim.comm, PETSC_ERR_USER_INPUT, "Option -phases: no solid burns (-<material>_burn_type); give -phase_ignition_material and -phase_ignition_temperature");
  }
  PetscCall(CouplingIgnition(*sim.coupling, ph.ignition_material, &model, &T_model));
  if (ph.ignition_temperature <= 0) ph.ignition_temperature = T_model;
  ph.cell_ignition_temperature = PETSC_MAX_REAL;
  for (size_t m = 0; m < sim.mpm.materials.size(); ++m) {
    std::string burns;
    PetscReal   T_burns = 0;
    PetscCall(CouplingIgnition(*sim.coupling, (PetscInt)m, &burns, &T_burns));
    if (burns != "none") ph.cell_ignition_temperature = PetscMin(ph.cell_ignition_temperature, T_burns);
  }
  if (ph.ignition_by_kinetics && !ph.kinetics) {
    ph.kinetics.reset(new ThermalDecomposition());
    PetscCall(ph.kinetics->SetFromOptions(sim.comm, sim.mpm.materials[ph.ignition_material]->Name()));
    ph.kinetics->par.h = 0; // the particle keeps its reaction heat; conduction carries it on
  }
  PetscCheck(ph.ignition_temperature > 0 || !ph.ignition_by_temperature, sim.comm, PETSC_ERR_USER_INPUT, "Option -phase_ignition_temperature: the burn model of %s (%s) has no ignition temperature; give one (K, > 0)",
             sim.mpm.materials[ph.ignition_material]->Name(), model.c_str());
  ph.mechanics_sound_speed_knob = sim.ice->sound_speed_knob;
  ph.semi_implicit_gas          = (PetscBool)(sim.ice->pressure_solver == IcePressureSolver::SemiImplicit);
  if (ph.switch_time[(int)ph.order[0]] < 0) ph.switch_time[(int)ph.order[0]] = sim.time;
  PetscCall(ApplyPhase(sim));
  std::string list;
  for (RunPhase p : ph.order) list += (list.empty() ? "" : " -> ") + std::string(RunPhaseName(p));
  if (ph.ignition_by_kinetics)
    PetscCall(
      PetscPrintf(sim.comm, "Phases: %s (now %s); ignition: a %s particle's thermal decomposition reaching %g of its mass\n", list.c_str(), RunPhaseName(ph.Current()), sim.mpm.materials[ph.ignition_material]->Name(), (double)ph.kinetics_fraction));
  else if (ph.ignition_by_temperature)
    PetscCall(PetscPrintf(sim.comm, "Phases: %s (now %s); ignition: a %s particle at %g K%s\n", list.c_str(), RunPhaseName(ph.Current()), sim.mpm.materials[ph.ignition_material]->Name(), (double)ph.ignition_temperature,
                          ph.ignition_temperature == T_model ? (" (" + model + "'s)").c_str() : ""));
  else PetscCall(PetscPrintf(sim.comm, "Phases: %s (now %s); ignition: %s's criterion in a cell of %s\n", list.c_str(), RunPhaseName(ph.Current()), model.c_str(), sim.mpm.materials[ph.ignition_material]->Name()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PhasesMeasureHeatBefore(Simulation &sim)
{
  Phases &ph = sim.phases;
  PetscFunctionBeginUser;
  if (ph.window_start >= 0 || sim.time < (ph.heatup_end_time - ph.flux_window) * (1 - 1e-12)) PetscFunctionReturn(PETSC_SUCCESS);
  PetscInt   n;
  PetscReal *Q, *Tt;
  PetscCall(DMSwarmGetLocalSize(sim.mpm.swarm, &n));
  SwarmAccess fields(sim.mpm.swarm);
  PetscCall(fields.Get(field::surface_heat, &Q));
  PetscCall(fields.Get(field::surface_temperature_time, &Tt));
  for (PetscInt p = 0; p < n; ++p) Q[p] = Tt[p] = 0;
  PetscCall(fields.RestoreAll());
  ph.window_start  = sim.time;
  ph.window_length = 0;
  PetscCall(CouplingMeasureSurfaceHeat(*sim.coupling, PETSC_TRUE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PhasesMeasureHeatAfter(Simulation &sim)
{
  Phases &ph = sim.phases;
  PetscFunctionBeginUser;
  if (ph.window_start < 0) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogEventBegin(ph.ev_measure, 0, 0, 0, 0));
  PetscInt         n;
  const PetscReal *T;
  PetscReal       *Tt;
  PetscCall(DMSwarmGetLocalSize(sim.mpm.swarm, &n));
  SwarmAccess fields(sim.mpm.swarm);
  PetscCall(fields.Get(field::temperature, &T));
  PetscCall(fields.Get(field::surface_temperature_time, &Tt));
  for (PetscInt p = 0; p < n; ++p) Tt[p] += T[p] * sim.dt;
  PetscCall(fields.RestoreAll());
  ph.window_length += sim.dt;
  PetscCall(PetscLogEventEnd(ph.ev_measure, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PhasesAfterStep(Simulation &sim, PetscBool *stop)
{
  Phases &ph = sim.phases;
  PetscFunctionBeginUser;
  *stop       = PETSC_FALSE;
  ph.switched = false;
  if (!ph.Enabled()) PetscFunctionReturn(PETSC_SUCCESS);
  if (ph.Current() == RunPhase::Mechanics) {
    const PetscReal began = ph.switch_time[(int)RunPhase::Mechanics];
    if (ph.mechanics_duration > 0 && began >= 0 && sim.time >= (began + ph.mechanics_duration) * (1 - 1e-12)) {
      PetscCall(PetscPrintf(sim.comm, "Stopping at step %" PetscInt_FMT ", t = %g s: %g s of mechanics (-phase_mechanics_duration), begun at %g s\n", sim.step, (double)sim.time, (double)ph.mechanics_duration, (double)began));
      *stop = PETSC_TRUE;
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  char why[512] = "";
  if (ph.ignition_by_kinetics) {
    PetscCall(AdvanceKinetics(sim));
    PetscReal  x[3] = {0, 0, 0}, x_hot[3];
    PetscInt64 id   = -1, id_hot;
    PetscReal  most = 0;
    PetscCall(LargestParticle(sim, field::reacted_fraction, ph.ignition_material, &most, &id, x));
    PetscCall(LargestParticle(sim, field::temperature, ph.ignition_material, &ph.hottest_ignition, &id_hot, x_hot));
    if (most >= ph.kinetics_fraction) {
      std::snprintf(why, sizeof(why), "ignition: %s particle %lld at (%g, %g, %g) m has decomposed %g of its mass (-phase_kinetics_fraction %g), at %g K", sim.mpm.materials[ph.ignition_material]->Name(), (long long)id, (double)x[0], (double)x[1],
                    (double)x[2], (double)most, (double)ph.kinetics_fraction, (double)ph.hottest_ignition);
    }
  } else if (ph.ignition_by_temperature) {
    PetscReal  x[3] = {0, 0, 0};
    PetscInt64 id   = -1;
    PetscCall(LargestParticle(sim, field::temperature, ph.ignition_material, &ph.hottest_ignition, &id, x));
    if (ph.hottest_ignition >= ph.ignition_temperature)
      std::snprintf(why, sizeof(why), "ignition: %s particle %lld at (%g, %g, %g) m is at %g K >= %g K", sim.mpm.materials[ph.ignition_material]->Name(), (long long)id, (double)x[0], (double)x[1], (double)x[2], (double)ph.hottest_ignition,
                    (double)ph.ignition_temperature);
  } else {
    // the burn model's own test on the cells: heat_only moves only the particles' temperatures, so
    // they are projected first (the heat-up's step projected them at its start)
    bool check = true;
    if (ph.Current() == RunPhase::HeatOnly) {
      // Only the particles' temperatures change and the gas is held, and a cell's material
      // temperature is a weighted mean of its particles' (the projection's weights are positive):
      // no cell can newly ignite while every solid particle is below the burn models' ignition
      // temperature. The projection and the cell test (a P2G and a pass over the cells, the most of
      // a 3-D heat_only step) then wait, but for the first heat_only step (the held gas) and the
      // output steps (the gas file's solid cells).
      const bool output_due = sim.output.IntervalDue(sim.step) || sim.run.Reached(sim.time, sim.step);
      if (ph.heat_only_checked && !output_due && ph.cell_ignition_temperature > 0) {
        std::vector<PetscReal> temperatures; // per material: the hottest particle, the mean
        PetscCall(PhasesTemperatures(sim, temperatures));
        PetscReal hottest = 0;
        for (size_t m = 0; m < sim.mpm.materials.size(); ++m) hottest = PetscMax(hottest, temperatures[2 * m]);
        check = !(hottest < ph.cell_ignition_temperature);
      }
      if (check) {
        PetscCall(ParticlesToGrid(sim.mpm, {PETSC_TRUE, PETSC_TRUE, PETSC_FALSE}));
        PetscCall(CouplingProjectSolids(*sim.coupling));
        ph.heat_only_checked = true;
      }
    }
    PetscInt64 cells = 0;
    PetscReal  x[3];
    if (check) PetscCall(CouplingIgnitingCells(*sim.coupling, &cells, x, &ph.hottest_ignition));
    if (cells > 0)
      std::snprintf(why, sizeof(why), "ignition: the burn model's criterion holds in %lld cell(s); the hottest reactant surface cell, at (%g, %g, %g) m, is at %g K", (long long)cells, (double)x[0], (double)x[1], (double)x[2],
                    (double)ph.hottest_ignition);
  }
  if (why[0]) {
    if (Has(ph, RunPhase::Mechanics)) PetscCall(SwitchTo(sim, RunPhase::Mechanics, why));
    else {
      PetscCall(PetscPrintf(sim.comm, "Stopping at step %" PetscInt_FMT ", t = %g s: %s (-phases has no mechanics)\n", sim.step, (double)sim.time, why));
      ph.switch_time[(int)RunPhase::Mechanics] = sim.time; // the ignition time, for the summary
      *stop                                    = PETSC_TRUE;
      if (ph.write_checkpoint) { // (continued with -phases ...,mechanics, it goes on from the ignition)
        char name[64];
        std::snprintf(name, sizeof(name), "phase_ignition_%06d.h5", (int)sim.step);
        PetscCall(CheckpointWrite(sim));
        PetscCall(CheckpointKeepAs(sim, name));
        PetscCall(PetscPrintf(sim.comm, "  wrote %s/%s\n", sim.output.dir.c_str(), name));
      }
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (ph.Current() == RunPhase::HeatUp && sim.time >= ph.heatup_end_time * (1 - 1e-12)) {
    if (ph.current + 1 < ph.order.size()) PetscCall(SwitchTo(sim, ph.order[ph.current + 1], "the heat-up's end time (-phase_heatup_end_time)"));
    else {
      PetscCall(FinishMeasurement(sim));
      PetscCall(PetscPrintf(sim.comm, "Stopping at step %" PetscInt_FMT ", t = %g s: the heat-up's end time, the last of -phases\n", sim.step, (double)sim.time));
      *stop = PETSC_TRUE;
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PhasesTemperatures(Simulation &sim, std::vector<PetscReal> &out)
{
  const size_t           nm = sim.mpm.materials.size();
  PetscInt               n;
  const PetscReal       *T, *mass;
  const PetscInt        *mat;
  std::vector<PetscReal> hottest(nm, 0), sums(2 * nm, 0), global_sums(2 * nm, 0);
  PetscFunctionBeginUser;
  out.assign(2 * nm, 0);
  PetscCall(DMSwarmGetLocalSize(sim.mpm.swarm, &n));
  SwarmAccess fields(sim.mpm.swarm);
  PetscCall(fields.Get(field::temperature, &T));
  PetscCall(fields.Get(field::mass, &mass));
  PetscCall(fields.Get(field::material, &mat));
  for (PetscInt p = 0; p < n; ++p) {
    hottest[mat[p]] = PetscMax(hottest[mat[p]], T[p]);
    sums[2 * mat[p]] += mass[p] * T[p];
    sums[2 * mat[p] + 1] += mass[p];
  }
  PetscCall(fields.RestoreAll());
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, hottest.data(), (int)nm, MPIU_REAL, MPI_MAX, sim.comm));
  PetscCallMPI(MPI_Allreduce(sums.data(), global_sums.data(), (int)(2 * nm), MPIU_REAL, MPI_SUM, sim.comm));
  for (size_t m = 0; m < nm; ++m) {
    out[2 * m]     = hottest[m];
    out[2 * m + 1] = global_sums[2 * m + 1] > 0 ? global_sums[2 * m] / global_sums[2 * m + 1] : 0;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::string PhasesSummary(const Simulation &sim)
{
  const Phases &ph = sim.phases;
  if (!ph.Enabled()) return "";
  char buf[1024];
  std::snprintf(buf, sizeof(buf),
                "  \"phases\": {\"current\": \"%s\", \"heatup_start\": %.12g, \"heat_only_start\": %.12g, \"mechanics_start\": %.12g, \"flux_window\": [%.12g, %.12g], \"flame_temperature\": %.12g, \"surface_heat_rate\": %.12g, "
                "\"ignition_material\": \"%s\", \"ignition_temperature\": %.12g, \"hottest_ignition_material\": %.12g},\n",
                RunPhaseName(ph.Current()), (double)ph.switch_time[0], (double)ph.switch_time[1], (double)ph.switch_time[2], (double)ph.window_start, (double)(ph.window_start + ph.window_length), (double)ph.flame_temperature,
                (double)ph.surface_heat_rate, ph.ignition_material >= 0 ? sim.mpm.materials[ph.ignition_material]->Name() : "", (double)ph.ignition_temperature, (double)ph.hottest_ignition);
  return buf;
}

std::vector<PetscReal> PhasesState(const Simulation &sim)
{
  const Phases &ph = sim.phases;
  return {(PetscReal)(int)ph.Current(), ph.window_start, ph.window_length, ph.switch_time[0], ph.switch_time[1], ph.switch_time[2], ph.surface_heat_rate, ph.flame_temperature, ph.hottest_ignition};
}

PetscErrorCode PhasesRestore(Simulation &sim, const std::vector<PetscReal> &s)
{
  Phases &ph = sim.phases;
  PetscFunctionBeginUser;
  PetscCheck((PetscInt)s.size() == kPhasesStateSize, sim.comm, PETSC_ERR_FILE_UNEXPECTED, "Checkpoint: the phases record has %d values, expected %d", (int)s.size(), (int)kPhasesStateSize);
  const RunPhase saved = (RunPhase)(int)s[0];
  PetscCheck(Has(ph, saved), sim.comm, PETSC_ERR_USER_INPUT, "Option -phases: the checkpoint was written in phase %s, which this run's -phases does not list", RunPhaseName(saved));
  ph.current = 0;
  while (ph.Current() != saved) ph.current += 1;
  ph.window_start = s[1], ph.window_length = s[2];
  for (int k = 0; k < 3; ++k) ph.switch_time[k] = s[3 + k];
  ph.surface_heat_rate = s[6];
  if (saved != RunPhase::HeatUp) ph.flame_temperature = s[7]; // the conductances were measured against it
  ph.hottest_ignition = s[8];
  PetscFunctionReturn(PETSC_SUCCESS);
}

void ThermalDecompositionDeleter::operator()(ThermalDecomposition *object) const { delete object; }

} // namespace burst
