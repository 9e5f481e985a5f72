// Run-control options: scene name, output, time stepping, MPM scheme, body force.
#include "simulation.hpp"
#include <cmath>
#include "util.hpp"

namespace burst {

const char *const StepSchemeNames[]    = {"usl", "usf", "musl"};
const char *const MuslGradientNames[]  = {"remap", "v_new"};
const char *const FUpdateNames[]       = {"linear", "exponential"};
const char *const FaceBCNames[]        = {"free", "fixed", "symmetry"};
const char *const OutsidePolicyNames[] = {"error", "remove"};
const char *const ShapeTypeNames[]     = {"linear", "ugimp", "cpgimp", "bspline2"};
const char *const ContactTypeNames[]   = {"no_slip", "friction"};
const char *const TransferNames[]      = {"flip_pic", "apic", "xpic"};

PetscErrorCode ReadRunOptions(Simulation &sim)
{
  char      buf[PETSC_MAX_PATH_LEN];
  PetscBool set;
  int       choice;
  PetscFunctionBeginUser;
  PetscOptionsBegin(sim.comm, "", "burst run control", "Run");
  PetscCall(PetscStrncpy(buf, sim.run.scene.c_str(), sizeof(buf)));
  PetscCall(PetscOptionsString("-scene", "Name of the scene, reported in the summary", "", buf, buf, sizeof(buf), &set));
  sim.run.scene = buf;
  PetscCall(PetscStrncpy(buf, sim.output.dir.c_str(), sizeof(buf)));
  PetscCall(PetscOptionsString("-output_dir", "Folder for HDF5/XDMF output, monitor.csv and summary.json", "", buf, buf, sizeof(buf), &set));
  sim.output.dir = buf;

  PetscCall(PetscOptionsReal("-final_time", "Final time (s), > 0", "", sim.run.final_time, &sim.run.final_time, nullptr));
  PetscCall(CheckRange(sim.comm, "-final_time", sim.run.final_time, 0, PETSC_MAX_REAL, PETSC_TRUE));
  PetscCall(PetscOptionsInt("-max_steps", "Stop after this many steps (default: no limit)", "", sim.run.max_steps, &sim.run.max_steps, nullptr));
  PetscCheck(sim.run.max_steps >= 0, sim.comm, PETSC_ERR_USER_INPUT, "Option -max_steps = %" PetscInt_FMT " is out of range: it must be >= 0", sim.run.max_steps);
  PetscCall(PetscOptionsReal("-mpm_cfl", "Courant number: dt = cfl min_p min_d h_d/(c_p + |v_p,d|), in (0, 1]", "", sim.mpm.cfl, &sim.mpm.cfl, nullptr));
  PetscCall(CheckRange(sim.comm, "-mpm_cfl", sim.mpm.cfl, 0, 1, PETSC_TRUE));
  PetscCall(PetscOptionsReal("-mpm_dt_max", "Largest time step (s), > 0 (default: none)", "", sim.mpm.dt_max, &sim.mpm.dt_max, nullptr));
  PetscCall(CheckRange(sim.comm, "-mpm_dt_max", sim.mpm.dt_max, 0, PETSC_MAX_REAL, PETSC_TRUE));
  PetscCall(PetscOptionsReal("-mpm_dt", "Fixed time step (s) instead of the CFL rule; 0 = use the CFL rule", "", sim.mpm.dt_fixed, &sim.mpm.dt_fixed, nullptr));
  PetscCall(CheckRange(sim.comm, "-mpm_dt", sim.mpm.dt_fixed, 0, PETSC_MAX_REAL, PETSC_FALSE));

  choice = (int)sim.mpm.scheme;
  PetscCall(OptionsChoice(PetscOptionsObject, "-mpm_scheme", "Order of stress update and grid update in a step", StepSchemeNames, 3, &choice, nullptr));
  sim.mpm.scheme = (StepScheme)choice;
  choice         = (int)sim.mpm.coupled_musl_gradient;
  PetscCall(OptionsChoice(PetscOptionsObject, "-mpm_coupled_musl_gradient",
                          "With gas and -mpm_scheme musl: the particles' velocity gradient from the remapped velocity (remap, Sulsky's MUSL) or from v_new, the nodal velocity the gas saw (v_new: stable at the cell a driven solid leaves, but the "
                          "fire scene's energy budget misses by 3 %; doc/coupling.md)",
                          MuslGradientNames, 2, &choice, nullptr));
  sim.mpm.coupled_musl_gradient = (MuslGradient)choice;
  PetscCall(PetscOptionsReal("-mpm_flip_fraction", "Particle velocity update: 1 = FLIP, 0 = PIC, between = blend", "", sim.mpm.flip_fraction, &sim.mpm.flip_fraction, nullptr));
  PetscCall(CheckRange(sim.comm, "-mpm_flip_fraction", sim.mpm.flip_fraction, 0, 1, PETSC_FALSE));
  choice = (int)sim.mpm.transfer;
  PetscCall(OptionsChoice(PetscOptionsObject, "-mpm_transfer", "Particle velocity transfer: flip_pic (the -mpm_flip_fraction blend), apic (affine PIC, Jiang et al. 2015) or xpic (XPIC(m), Hammerquist & Nairn 2017); default flip_pic", TransferNames,
                          3, &choice, nullptr));
  sim.mpm.transfer = (Transfer)choice;
  PetscCall(PetscOptionsInt("-mpm_xpic_order", "Order m of XPIC(m), in [1, 8] (m = 1 is PIC); default 2", "", sim.mpm.xpic_order, &sim.mpm.xpic_order, nullptr));
  PetscCheck(sim.mpm.xpic_order >= 1 && sim.mpm.xpic_order <= 8, sim.comm, PETSC_ERR_USER_INPUT, "Option -mpm_xpic_order = %" PetscInt_FMT " is out of range: it must be in [1, 8]", sim.mpm.xpic_order);
  PetscCall(PetscOptionsBool("-axisymmetric", "Axisymmetric MPM with -dim 2: x is the radius r >= 0, y the axis; hoop strain rate v_r/r and hoop stress in the internal force; masses and volumes per radian; default false", "", sim.mpm.axisymmetric,
                             &sim.mpm.axisymmetric, nullptr));
  PetscCall(PetscOptionsReal("-stop_kinetic_fraction", "Stop once the kinetic energy has fallen below this fraction of its initial value (checked at monitor steps), in [0, 1); 0 = never (default)", "", sim.run.stop_kinetic_fraction,
                             &sim.run.stop_kinetic_fraction, nullptr));
  PetscCheck(sim.run.stop_kinetic_fraction >= 0 && sim.run.stop_kinetic_fraction < 1, sim.comm, PETSC_ERR_USER_INPUT, "Option -stop_kinetic_fraction = %g is out of range: it must be in [0, 1)", (double)sim.run.stop_kinetic_fraction);
  PetscCall(PetscOptionsReal("-mpm_energy_growth_limit", "Stop with an error when the total energy has grown by more than this fraction of the largest energy seen (an unstable run: energy from nowhere), checked at monitor steps; 0 = off (default)",
                             "", sim.run.energy_growth_limit, &sim.run.energy_growth_limit, nullptr));
  PetscCall(CheckRange(sim.comm, "-mpm_energy_growth_limit", sim.run.energy_growth_limit, 0, PETSC_MAX_REAL, PETSC_FALSE));
  choice = (int)sim.mpm.f_update;
  PetscCall(OptionsChoice(PetscOptionsObject, "-mpm_F_update", "Deformation gradient update: F <- (I + L dt) F, or F <- exp(L dt) F", FUpdateNames, 2, &choice, nullptr));
  sim.mpm.f_update = (FUpdate)choice;
  choice           = (int)sim.mpm.shape;
  PetscCall(OptionsChoice(PetscOptionsObject, "-mpm_shape_type", "Interpolator (shape functions)", ShapeTypeNames, 4, &choice, nullptr));
  sim.mpm.shape = (ShapeType)choice;
  choice        = (int)sim.mpm.outside;
  PetscCall(OptionsChoice(PetscOptionsObject, "-mpm_outside_domain", "A particle leaving the domain: stop with an error, or remove it and count it", OutsidePolicyNames, 2, &choice, nullptr));
  sim.mpm.outside = (OutsidePolicy)choice;
  {
    PetscInt n = 3;
    PetscCall(PetscOptionsRealArray("-gravity", "Body acceleration gx,gy[,gz] (m/s^2); missing components are 0", "", sim.mpm.gravity, &n, &set));
    PetscInt dim = sim.mpm.grid.dim; // the grid reads -dim later; a gz in 2-D would be dropped without a word
    PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-dim", &dim, nullptr));
    PetscCheck(!set || n <= dim, sim.comm, PETSC_ERR_USER_INPUT, "Option -gravity has %" PetscInt_FMT " components; it takes at most one per dimension (%" PetscInt_FMT " with -dim %" PetscInt_FMT ")", n, dim, dim);
    for (PetscInt d = 0; set && d < n; ++d) PetscCheck(std::isfinite(sim.mpm.gravity[d]), sim.comm, PETSC_ERR_USER_INPUT, "Option -gravity: component %" PetscInt_FMT " is %g; it must be finite", d, (double)sim.mpm.gravity[d]);
  }
  PetscCall(OptionsRealVector(PetscOptionsObject, "-mpm_artificial_viscosity", "Artificial bulk viscosity A1,A2: q = rho (A1 c |tr D| dx + A2 (tr D dx)^2) in compression (Uintah's defaults 0.2,2.0); 0,0 = off", sim.mpm.viscosity, 2, nullptr));
  PetscCheck(sim.mpm.viscosity[0] >= 0 && sim.mpm.viscosity[1] >= 0, sim.comm, PETSC_ERR_USER_INPUT, "Option -mpm_artificial_viscosity: both coefficients must be >= 0");
  PetscCall(PetscOptionsBool("-mpm_convert_failed", "Failed particles join a velocity field of their own, meeting the intact material only through contact (the paper's conversion)", "", sim.mpm.convert_failed, &sim.mpm.convert_failed, nullptr));
  {
    char buf[256] = "";
    PetscCall(PetscOptionsString("-mpm_contact_material",
                                 "Name of a material (of -materials) that moves in a velocity field of its own and meets the others only through contact (-mpm_contact_type), e.g. an explosive that burns away from its container; default none", "",
                                 buf, buf, sizeof(buf), &set));
    if (set) sim.mpm.contact_material_name = buf;
    PetscCheck(!(set && sim.mpm.convert_failed), sim.comm, PETSC_ERR_SUP, "Options -mpm_contact_material and -mpm_convert_failed cannot be combined yet (each needs the second velocity field)");
  }
  choice = (int)sim.mpm.contact;
  PetscCall(OptionsChoice(PetscOptionsObject, "-mpm_contact_type", "Contact between velocity fields: no_slip (one velocity where both are present) or friction (Bardenhagen et al. 2001: only approaching fields interact, Coulomb friction)",
                          ContactTypeNames, 2, &choice, nullptr));
  sim.mpm.contact = (ContactType)choice;
  PetscCall(PetscOptionsReal("-mpm_contact_friction", "Coulomb friction coefficient of the friction contact (-), >= 0", "", sim.mpm.friction, &sim.mpm.friction, nullptr));
  PetscCall(CheckRange(sim.comm, "-mpm_contact_friction", sim.mpm.friction, 0, PETSC_MAX_REAL, PETSC_FALSE));
  PetscCall(PetscOptionsReal("-mpm_mass_cutoff", "Nodes with less mass than this fraction of a full cell of the densest material are treated as empty", "", sim.mpm.mass_cutoff_fraction, &sim.mpm.mass_cutoff_fraction, nullptr));
  PetscCall(CheckRange(sim.comm, "-mpm_mass_cutoff", sim.mpm.mass_cutoff_fraction, 0, 1, PETSC_FALSE));

  PetscCall(PetscOptionsInt("-output_interval", "Steps between HDF5/XDMF outputs; 0 = first and last step only", "", sim.output.interval, &sim.output.interval, nullptr));
  PetscCheck(sim.output.interval >= 0, sim.comm, PETSC_ERR_USER_INPUT, "Option -output_interval = %" PetscInt_FMT " is out of range: it must be >= 0", sim.output.interval);
  PetscCall(PetscOptionsInt("-monitor_interval", "Steps between monitor lines (energy, momentum) on screen and in monitor.csv; > 0", "", sim.output.monitor_interval, &sim.output.monitor_interval, nullptr));
  PetscCheck(sim.output.monitor_interval > 0, sim.comm, PETSC_ERR_USER_INPUT, "Option -monitor_interval = %" PetscInt_FMT " is out of range: it must be > 0", sim.output.monitor_interval);
  PetscCall(PetscOptionsBool("-output_grid", "Write grid fields (mass, velocity) with the particles", "", sim.output.write_grid, &sim.output.write_grid, nullptr));
  PetscCall(PetscOptionsBool("-progress", "Print a progress line for long runs", "", sim.output.progress, &sim.output.progress, nullptr));
  PetscCall(OptionsRealVector(PetscOptionsObject, "-monitor_track_point", "Trace the particle nearest to this point at the start (m, 3 values; in 2-D the last is ignored)", sim.output.track_point, 3, &sim.output.track_by_point));
  PetscCall(PetscOptionsInt("-monitor_track_pid", "Particle id whose position and displacement go into monitor.csv; -1 = none", "", sim.output.track_pid, &sim.output.track_pid, nullptr));
  PetscOptionsEnd();
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
