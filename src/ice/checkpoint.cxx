// The gas solver's part of a checkpoint (src/io/checkpoint.cxx writes the file): the step state,
// the run-wide counters, each rank's partial sums of the budgets, and the cell state.
#include "ice.hpp"
#include "io/checkpoint_values.hpp"
#include <petscviewerhdf5.h>

namespace burst {

void IceCheckpointValues(IceSolver &ice, CheckpointValues &values)
{
  values.Global("time", &ice.time);
  values.Global("step", &ice.step);
  values.Global("dt", &ice.dt);
  values.Global("ksp_iterations_total", &ice.ksp_iterations_total);
  values.Global("pressure_solves", &ice.pressure_solves);
  values.Global("ksp_iterations", &ice.ksp_iterations);
  values.Global("outer_iterations", &ice.outer_iterations);
  values.Global("initial_mass", &ice.initial.mass);
  values.Global("initial_momentum", ice.initial.momentum, 3);
  values.Global("initial_internal_energy", &ice.initial.internal_energy);
  values.Global("initial_kinetic_energy", &ice.initial.kinetic_energy);
  values.Global("peak_pressure", &ice.peak_pressure);
  values.Global("peak_pressure_time", &ice.peak_pressure_time);
  values.Global("peak_temperature", &ice.peak_temperature);
  values.Global("peak_temperature_time", &ice.peak_temperature_time);
  values.PerRank("energy_fallbacks", &ice.energy_fallbacks);
  values.PerRank("energy_fallbacks_remap", &ice.energy_fallbacks_remap);
  values.PerRank("energy_fallbacks_exchange", &ice.energy_fallbacks_exchange);
  values.PerRank("energy_fallbacks_class", ice.energy_fallbacks_class, kIceFallbackClasses);
  IceBoundaryBudget &f = ice.boundary;
  values.PerRank("boundary_mass", &f.mass);
  values.PerRank("boundary_momentum", f.momentum, 3);
  values.PerRank("boundary_energy", &f.energy);
  values.PerRank("boundary_work", &f.work);
  values.PerRank("boundary_impulse", f.impulse, 3);
  values.PerRank("boundary_face_mass", &f.face_mass[0][0], 6);
  static const char *const names[IceSolver::kEnergyDiagnostics] = {"drag_energy_change",  "solid_pressure_work",         "gas_interface_work",     "advection_energy_change",  "fallback_energy_change",
                                                                   "trace_energy_change", "equilibration_energy_change", "exchange_energy_change", "exchange_fallback_energy", "solid_cell_energy_transfer"};
  const auto               diagnostics                          = ice.EnergyDiagnostics();
  for (int k = 0; k < IceSolver::kEnergyDiagnostics; ++k) values.PerRank(names[k], diagnostics[k]);
}

PetscErrorCode IceCheckpointWrite(IceSolver &ice, PetscViewer viewer)
{
  Vec v;
  PetscFunctionBeginUser;
  PetscCall(IceSyncGlobal(ice)); // the local vector is the solver's working copy
  PetscCall(VecDuplicate(ice.state, &v));
  PetscCall(VecCopy(ice.state, v));
  PetscCall(PetscObjectSetName((PetscObject)v, "state"));
  { // the file holds the natural ordering: the checksum adds the entries at their place there
    Vec natural;
    PetscCall(DMDACreateNaturalVector(ice.da, &natural));
    PetscCall(DMDAGlobalToNaturalBegin(ice.da, v, INSERT_VALUES, natural));
    PetscCall(DMDAGlobalToNaturalEnd(ice.da, v, INSERT_VALUES, natural));
    PetscCall(CheckpointChecksumVec(natural, "gas/state"));
    PetscCall(VecDestroy(&natural));
  }
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/gas"));
  PetscCall(VecView(v, viewer));
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscCall(VecDestroy(&v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IceCheckpointRead(IceSolver &ice, PetscViewer viewer, const std::string &file)
{
  Vec       v;
  PetscBool has;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5HasDataset(viewer, "/gas/state", &has));
  if (!has) {
    std::string gases;
    for (PetscInt m = 0; m < ice.ngas; ++m) gases += (m ? "," : "") + ice.materials[m].name;
    SETERRQ(ice.comm, PETSC_ERR_USER_INPUT, "Checkpoint %s has no gas state, but this run has gas (-ice_materials %s)", file.c_str(), gases.c_str());
  }
  PetscCall(VecDuplicate(ice.state, &v));
  PetscCall(PetscObjectSetName((PetscObject)v, "state"));
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/gas"));
  PetscCall(VecLoad(v, viewer));
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscCall(VecCopy(v, ice.state));
  PetscCall(VecDestroy(&v));
  PetscCall(DMGlobalToLocal(ice.da, ice.state, INSERT_VALUES, ice.local));
  PetscCall(IceUpdateGhosts(ice));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
