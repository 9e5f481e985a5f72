// The MPM solver: the background grid's nodes, the particles (DMSwarm), their materials, the method
// and contact options, counters, diagnostics and log events (src/mpm/). It is IceSolver's shape: it
// owns its state and its options; the driver sets its step, time and dt at every step (as it does
// the gas's), and each phase of the particle step (src/step.cxx) is a function of it.
#pragma once
#include "petsc_compat.hpp"
#include "mpm/shape.hpp"
#include "mpm/fragments.hpp"
#include "../models/material.hpp"
#include <petscdmda.h>
#include <petscdmswarm.h>
#include <array>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace burst {

enum class StepScheme : int { USL = 0, USF = 1, MUSL = 2 };
// MUSL's velocity gradient in a step with gas (-mpm_coupled_musl_gradient; src/step.cxx).
enum class MuslGradient : int { Remap = 0, VNew = 1 };
enum class FUpdate : int { Linear = 0, Exponential = 1 };
enum class FaceBC : int { Free = 0, Fixed = 1, Symmetry = 2 };
enum class OutsidePolicy : int { Error = 0, Remove = 1 };
enum class ContactType : int { NoSlip = 0, Friction = 1 };
// Particle velocity transfer (g2p.cxx): the FLIP/PIC blend of -mpm_flip_fraction, APIC (Jiang et al.
// 2015: an affine velocity matrix per particle) or XPIC(m) (Hammerquist & Nairn 2017).
enum class Transfer : int { FlipPic = 0, APIC = 1, XPIC = 2 };

extern const char *const StepSchemeNames[];
extern const char *const MuslGradientNames[];
extern const char *const FUpdateNames[];
extern const char *const FaceBCNames[];
extern const char *const OutsidePolicyNames[];
extern const char *const ContactTypeNames[];
extern const char *const ShapeTypeNames[];
extern const char *const TransferNames[];

// Names of the swarm fields registered by the core.
namespace field {
inline constexpr const char *velocity                 = "velocity";                 // m/s, bs dim
inline constexpr const char *mass                     = "mass";                     // kg
inline constexpr const char *volume                   = "volume";                   // m^3 (2-D: per metre of thickness)
inline constexpr const char *volume0                  = "volume0";                  // m^3, at seeding
inline constexpr const char *position0                = "position0";                // m, bs dim (reference position X)
inline constexpr const char *half_width0              = "half_width0";              // m, bs dim (GIMP particle half-widths)
inline constexpr const char *F                        = "F";                        // deformation gradient, bs 9
inline constexpr const char *stress                   = "stress";                   // Cauchy stress, Pa, bs 9
inline constexpr const char *L                        = "velocity_gradient";        // 1/s, bs 9
inline constexpr const char *temperature              = "temperature";              // K
inline constexpr const char *wave_speed               = "wave_speed";               // m/s
inline constexpr const char *internal_energy          = "internal_energy";          // J (stress work)
inline constexpr const char *external_force           = "external_force";           // N, bs dim (body + traction)
inline constexpr const char *traction_area0           = "traction_area0";           // m^2, bs dim: outward normal x area at seeding
inline constexpr const char *load_curve               = "load_curve";               // int: index of the pressure load curve, -1 none
inline constexpr const char *material                 = "material";                 // int: material id
inline constexpr const char *bulk_viscosity           = "bulk_viscosity";           // Pa, artificial bulk viscosity pressure q
inline constexpr const char *fragment                 = "fragment";                 // int: fragment id of intact particles, -1 otherwise
inline constexpr const char *ambient_pressure         = "ambient_pressure";         // Pa: pressure of a surrounding gas less its reference (only with gas)
inline constexpr const char *surface_heat             = "surface_heat";             // J: heat from the gas over the phases' window (only with -phases)
inline constexpr const char *surface_temperature_time = "surface_temperature_time"; // K s: integral of T over that window (only with -phases)
inline constexpr const char *surface_conductance      = "surface_conductance";      // W/K: G_p of the surface heat G_p (T_f - T_p) (only with -phases)
inline constexpr const char *reacted_fraction         = "reacted_fraction";         // -: a charge particle's thermally decomposed fraction (only with -phases)
inline constexpr const char *affine                   = "affine";                   // 1/s, bs 9: APIC affine velocity matrix B D^-1 (only with -mpm_transfer apic)
inline constexpr const char *deformation_heat         = "deformation_heat";         // J: m c_v dT of the stress updates, heat that internal_energy also holds (only for a solid that burns)
} // namespace field

// A piecewise-linear function of time (pressure histories), Pa.
struct LoadCurve {
  std::string            name;
  std::vector<PetscReal> time, value;

  PetscReal Evaluate(PetscReal t) const;
};

// A geometry object from which particles are seeded (src/mpm/seed.cxx).
struct Geometry;

// Heat conduction in the solids (src/mpm/heat_conduction.cxx), null unless -mpm_heat_conduction.
struct HeatConduction;
struct HeatDeleter {
  void operator()(HeatConduction *heat) const; // src/mpm/heat_conduction.cxx
};

struct Grid {
  PetscInt  dim      = 2;
  PetscReal lower[3] = {0, 0, 0}, upper[3] = {1, 1, 1};
  PetscInt  cells[3] = {10, 10, 10};
  PetscReal h[3]     = {0.1, 0.1, 0.1};
  Axis      axes[3];
  FaceBC    bc[3][2]    = {{FaceBC::Free, FaceBC::Free}, {FaceBC::Free, FaceBC::Free}, {FaceBC::Free, FaceBC::Free}};
  DM        da_nodes    = nullptr; // node DMDA, dof = nodal layout below
  DM        da_velocity = nullptr; // node DMDA for the velocity fields [v_old, v_new] per velocity field
  // Nodal layout per velocity field: [mass, momentum(dim), force(dim)], plus the mass gradient(dim)
  // for the contact normals when there are several fields (failed particles converted to their own
  // field). Fields are stacked: dof = num_velocity_fields * NodeStride().
  PetscInt num_velocity_fields = 1;
  PetscInt NodeStride() const { return 1 + 2 * dim + (num_velocity_fields > 1 ? dim : 0); }
  // Ownership of node indices per direction, for owner-rank computation (petsc.md 3).
  PetscMPIInt           procs[3] = {1, 1, 1};
  std::vector<PetscInt> start[3]; // start[d][r] = first node owned by slot r, with start[d][procs] = M
  // Local ghosted box of the node DMDA.
  PetscInt   gxs[3] = {0, 0, 0}, gxm[3] = {1, 1, 1};
  Vec        nodal = nullptr, nodal_local = nullptr;       // global / local nodal sums
  VecScatter ghost_sums = nullptr;                         // the ghost nodes of nodal_local onto their owners' entries of nodal (null without ghost nodes; p2g.cxx)
  Vec        velocity = nullptr, velocity_local = nullptr; // global / local [v_old, v_new]
  VecScatter velocity_ghosts = nullptr;                    // the owners' velocities onto the ghost nodes of velocity_local (reverse; null without ghost nodes)
  // Owned nodes whose velocities the last grid update (or the coupling) wrote non-zero, per owned node
  // (grid_update.cxx): an empty node that was empty before is zero in both vectors already. Empty
  // after a new layout: the first update writes every node.
  std::vector<unsigned char> velocity_written;
  // Load balance (grid.cxx): ownership ranges from the particle work, at start-up and every
  // balance_interval steps (0: start-up only).
  PetscBool balance              = PETSC_FALSE;
  PetscInt  balance_interval     = 0;
  PetscReal balance_rigid_weight = 0.5, balance_node_weight = 0.002, balance_plastic_weight = 2.0;
  PetscReal balance_gas_weight = 1.0;                                                         // work of a gas cell relative to a particle
  bool      balance_with_gas   = false;                                                       // the scene has gases: the start-up balance counts their cells
  PetscInt  balanced_at        = -1;                                                          // step of the last balance, -1: none yet
  bool      ranges_copied      = false;                                                       // another grid (the gas's) copied the node ranges at its set-up: they cannot change
  Vec       xpic_star = nullptr, xpic_w = nullptr, xpic_sum = nullptr, xpic_global = nullptr; // XPIC work vectors (only with -mpm_transfer xpic)
  // Nodes that can hold mass in step `reached_step`, per ghosted local node (p2g.cxx: the P2G of the
  // masses marks them): the grid updates skip the others without reading their sums.
  std::vector<unsigned char> reached;
  PetscInt                   reached_step = -1;

  PetscReal CellVolume() const { return dim == 2 ? h[0] * h[1] : h[0] * h[1] * h[2]; }
};

class CheckpointValues; // src/io/checkpoint_values.hpp

struct Diagnostics {
  PetscReal external_work       = 0;           // J, work of body forces and tractions (this rank)
  PetscReal removed_energy      = 0;           // J, kinetic + internal energy of removed particles (this rank)
  PetscReal viscous_work        = 0;           // J, work of the artificial bulk viscosity (this rank)
  PetscReal removed_mass        = 0;           // kg (this rank)
  PetscReal removed_momentum[3] = {0, 0, 0};   // kg m/s of the removed particles and of what burning took from particles (this rank)
  PetscReal bc_impulse[3]       = {0, 0, 0};   // N s the fixed and symmetry faces gave the particles through the nodes (this rank; grid update, gas coupling)
  PetscInt  removed_particles   = 0;           // this rank
  PetscReal initial_energy      = 0;           // J, global
  PetscReal initial_kinetic     = 0;           // J, global, at the start of the run
  PetscBool kinetic_stop        = PETSC_FALSE; // the run ended on -stop_kinetic_fraction
  // The budgets of a run with gas (monitor.cxx): the conserved sums at the start (mass, momentum (3),
  // energy) and the largest term seen (mass, momentum, energy), global.
  PetscReal budget_initial[5]       = {0, 0, 0, 0, 0};
  PetscReal budget_scale[3]         = {0, 0, 0};
  PetscReal max_error_displacement  = 0; // analytic solutions: max over monitor steps of the L2 error
  PetscReal last_error_displacement = 0;

  void Checkpoint(CheckpointValues &values); // its part of a checkpoint (src/io/monitor.cxx)
};

// Sharing the stress update between ranks (src/mpm/stress_share.cxx).
struct StressShare {
  PetscBool  enabled     = PETSC_TRUE; // -mpm_stress_share
  PetscReal  threshold   = 0.1;        // -mpm_stress_share_threshold: share above (1 + this) times the mean work
  PetscInt   min_points  = 256;        // -mpm_stress_share_min: and at least this many points' work above the mean
  PetscInt64 point_steps = 0;          // sum over steps of the points updated on another rank than their own (all ranks)
  PetscReal  overhead    = 0.3;        // a sender's cost of sending a point, as a fraction of updating it (measured, smoothed)
  enum class Balance { Time, Count };
  Balance   balance           = Balance::Time; // -mpm_stress_share_balance: what the plan evens out
  PetscReal seconds_per_point = 0;             // this rank's update time per point of its own (measured, smoothed; 0 before the first)
  PetscReal receive_factor    = 1;             // a received point's time here over its sender's time per point, waits included (measured, smoothed)
  struct Transfer {
    PetscMPIInt peer;
    PetscInt    count;
  };
  struct Chunk { // one message: count points of one material
    PetscMPIInt peer;
    PetscInt    material, first, count; // first: into selected (a sender's own messages)
    PetscInt    index;                  // its place among the messages of its transfer
  };
  std::vector<Transfer>              sends, receives;           // this step's plan for this rank
  std::vector<PetscInt>              spread, selected;          // the local points to send; the same, message by message
  std::vector<Chunk>                 chunks, incoming;          // the messages this rank sends, receives
  std::vector<std::vector<PetscInt>> headers, received_headers; // (material, count) of each message of a transfer
  std::vector<std::vector<int>>      material_fields;           // per material, the state fields its messages carry
  std::vector<std::vector<char>>     out, results, in;          // message buffers, kept between steps
  PetscLogEvent                      ev_share = 0;
};

struct MpmSolver {
  MPI_Comm    comm = PETSC_COMM_WORLD;
  PetscMPIInt rank = 0, size = 1;
  PetscBool   help = PETSC_FALSE; // -help: read and list every option, create nothing
  // The clock, set by the driver at every step (src/step.cxx), as the gas's.
  PetscInt  step = 0;
  PetscReal time = 0, dt = 0; // s

  // Method options (-mpm_*; read in src/options.cxx)
  PetscReal     cfl = 0.4, dt_max = PETSC_MAX_REAL, dt_fixed = 0;
  StepScheme    scheme                = StepScheme::USL;
  MuslGradient  coupled_musl_gradient = MuslGradient::Remap; // -mpm_coupled_musl_gradient (src/step.cxx)
  PetscReal     flip_fraction         = 1.0;                 // 1 = FLIP, 0 = PIC
  Transfer      transfer              = Transfer::FlipPic;
  PetscInt      xpic_order            = 2;           // m of XPIC(m); m = 1 is PIC
  PetscBool     axisymmetric          = PETSC_FALSE; // -dim 2 -axisymmetric: x is the radius r, y the axis z, masses and volumes per radian
  FUpdate       f_update              = FUpdate::Linear;
  ShapeType     shape                 = ShapeType::Linear;
  StencilCache  stencil_cache; // this step's particle stencils, shared by the transfers (shape.hpp)
  OutsidePolicy outside              = OutsidePolicy::Error;
  PetscReal     gravity[3]           = {0, 0, 0};
  PetscReal     mass_cutoff_fraction = 1e-9;        // nodes lighter than this fraction of a full cell's mass are void
  PetscReal     mass_cutoff          = 0;           // kg, from the fraction and the densest material
  PetscReal     densest              = 0;           // kg/m^3, largest material density
  PetscReal     viscosity[2]         = {0, 0};      // artificial bulk viscosity coefficients A1 (linear), A2 (quadratic)
  PetscBool     convert_failed       = PETSC_FALSE; // failed particles move in a velocity field of their own
  std::string   contact_material_name;              // -mpm_contact_material: this material moves in a field of its own
  PetscInt      contact_material    = -1;           // its material id, -1 if none
  PetscBool     ambient_pressure    = PETSC_FALSE;  // particles carry a surrounding gas's pressure (the coupling sets it)
  PetscBool     surface_heat_fields = PETSC_FALSE;  // particles carry the surface heat of a run in phases (-phases)
  PetscBool     deformation_heat    = PETSC_FALSE;  // particles carry field::deformation_heat (the coupling sets it for a solid that burns)
  ContactType   contact             = ContactType::Friction;
  PetscReal     friction            = 0;  // Coulomb coefficient of the contact between fields
  PetscInt      rigid_material      = -1; // material id of the rigid body, -1 if none
  PetscReal     rigid_velocity[3]   = {0, 0, 0};
  PetscInt      sort_interval       = 0; // -mpm_sort_interval: steps between sorts of the particles by cell (swarm.cxx)

  // A burning solid's heat from its stress updates (stress_loop.cxx): per material the c_v of the
  // tracked heat (J/(kg K); 0: not tracked; set by the coupling's burn set-up), and the
  // temperatures before this step's update (scratch)
  std::vector<PetscReal> deformation_heat_cv, temperature_before;

  // Velocity fields: 0 intact deformable, 1 converted (failed) particles if -mpm_convert_failed or
  // the material of -mpm_contact_material, last the rigid body if any.
  PetscInt VelocityField(PetscInt material, PetscInt failed) const
  {
    if (material == rigid_material) return grid.num_velocity_fields - 1;
    if (material == contact_material) return 1;
    return (convert_failed && failed) ? 1 : 0;
  }
  bool TwoDeformableFields() const { return convert_failed || contact_material >= 0; }

  // Objects
  Grid                                         grid;
  DM                                           swarm = nullptr;
  std::vector<std::unique_ptr<Material>>       materials;
  std::vector<std::unique_ptr<Geometry>>       geometries;
  std::vector<LoadCurve>                       load_curves;
  std::unique_ptr<HeatConduction, HeatDeleter> heat;      // null unless -mpm_heat_conduction
  Fragments                                    fragments; // the fragment search and the Grady estimate (fragments.cxx)
  // A body force per unit mass b(X, t), m/s^2, at the reference position X (an analytic solution's), or empty.
  std::function<void(const PetscReal X[], PetscReal t, PetscReal b[])> body_force;
  // The driver's picture of the particles as they are, written when a check finds an invalid state
  // (src/mpm/stress_loop.cxx), under the given step's name.
  std::function<PetscErrorCode(PetscInt step)> write_snapshot;
  bool                                         HasParticles() const { return swarm != nullptr; }

  // Counters
  PetscInt64  total_particles = 0; // global count, checked after every migration
  PetscInt64  next_pid        = 0; // next unused particle id (global)
  PetscInt64  particle_steps  = 0; // global sum over steps of the particle count
  PetscInt    swarm_bytes     = 0; // bytes of swarm storage per particle (all registered fields)
  Diagnostics diag;
  StressShare stress_share;

  // Events for -log_view
  PetscLogEvent ev_p2g, ev_ghost_sums, ev_grid, ev_g2p, ev_xpic, ev_remap, ev_stress, ev_migrate, ev_dt, ev_loads;
  PetscLogEvent ev_sort = 0, ev_balance = 0; // registered by CreateSwarm and CreateGrid

  ~MpmSolver();
};

// Set-up (one file each in src/mpm/)
PetscErrorCode CreateGrid(MpmSolver &mpm);
// The grid velocities [v_old, v_new] from the global vector to the ghosted local one (a no-op on a
// rank without ghost nodes, where the two are one vector).
PetscErrorCode GridVelocityToLocal(Grid &g); // the whole owned part and the ghost nodes (DMGlobalToLocal)
PetscErrorCode GridVelocityGhosts(Grid &g);  // the ghost nodes only (the grid update writes the owned part of both vectors)
PetscErrorCode CreateMaterials(MpmSolver &mpm);
PetscErrorCode ReadLoadCurves(MpmSolver &mpm);
PetscErrorCode ReadGeometries(MpmSolver &mpm);
PetscErrorCode CreateSwarm(MpmSolver &mpm);
PetscErrorCode SwarmSetFromOptions(MpmSolver &mpm); // -mpm_sort_interval, -mpm_stress_share*
PetscErrorCode SeedParticles(MpmSolver &mpm);
// Axisymmetric MPM (src/mpm/axisymmetric.cxx): checks the grid (-dim 2, r >= 0, the axis a symmetry
// face) and the features that do not support it; a no-op without -axisymmetric.
PetscErrorCode AxisymmetricSetUp(MpmSolver &mpm);
PetscErrorCode HeatConductionSetUp(MpmSolver &mpm); // reads -mpm_heat_* and -<mat>_thermal_conductivity/_heat_capacity

// The phases of a particle step
// mpm.dt = cfl min_p min_d h_d / (c_p + |v_p,d|) (or -mpm_dt), capped by -mpm_dt_max and cut so that
// the step ends at final_time.
PetscErrorCode ComputeTimeStep(MpmSolver &mpm, PetscReal final_time);
PetscErrorCode ComputeInitialWaveSpeed(MpmSolver &mpm);
PetscErrorCode StressShareSetUp(MpmSolver &mpm); // reads -mpm_stress_share*
// Runs every material's stress update on f (the local particles), sharing the points of crowded
// ranks with the others when -mpm_stress_share allows; collective.
PetscErrorCode UpdateStressShared(MpmSolver &mpm, const MaterialPointFields &f);
PetscErrorCode ComputeExternalForces(MpmSolver &mpm);
bool           HasExternalForces(const MpmSolver &mpm); // gravity, a body force or a load curve: external_force may be nonzero

struct P2GRequest {
  PetscBool mass, momentum, force;
};
PetscErrorCode ParticlesToGrid(MpmSolver &mpm, P2GRequest what);
// MUSL's remap: the particle velocities from the grid and their momentum back onto it, in one pass.
PetscErrorCode RemapMomentum(MpmSolver &mpm);
PetscErrorCode GridUpdate(MpmSolver &mpm);
PetscErrorCode GridVelocityFromMomentum(MpmSolver &mpm);

// kinematics: L = grad v_new, then F <- (I + L dt) F (or exp(L dt) F) and V = V0 det F, fused in one pass.
struct G2PRequest {
  PetscBool velocity, position, kinematics;
};
PetscErrorCode GridToParticles(MpmSolver &mpm, G2PRequest what);
PetscErrorCode UpdateStress(MpmSolver &mpm);
// Stops the run, naming the step, particle and field, on a non-finite state or a non-positive
// density (after writing mpm.write_snapshot's picture of it).
PetscErrorCode CheckParticleState(MpmSolver &mpm, const char phase[]);
PetscErrorCode MigrateParticles(MpmSolver &mpm);
PetscErrorCode SortParticlesByCell(MpmSolver &mpm);
PetscErrorCode BalanceGrid(MpmSolver &mpm, PetscBool *changed);
// Removes the local particles flagged in `remove` (their mass and energy go to the diagnostics);
// *removed is the global count.
PetscErrorCode RemoveParticles(MpmSolver &mpm, const std::vector<char> &remove, PetscInt64 *removed);
PetscErrorCode ComputeOwnerRanks(MpmSolver &mpm, PetscInt *num_outside, bool need_cells = true, PetscInt *num_leaving = nullptr);
PetscErrorCode ConductHeat(MpmSolver &mpm); // no-op unless -mpm_heat_conduction
// Adds G_p (T_source - T_p) to each conducting particle in every conduction sub-step (G_p: the swarm
// field surface_conductance, W/K), or stops doing so.
PetscErrorCode HeatSetSurfaceSource(MpmSolver &mpm, PetscBool on, PetscReal source_temperature);
PetscErrorCode NonlocalAverage(MpmSolver &mpm); // src/mpm/nonlocal.cxx: no-op unless a material has -MAT_regularization nonlocal

// Fragments (src/mpm/fragments.cxx)
PetscErrorCode FragmentsSetUp(MpmSolver &mpm);
PetscErrorCode FragmentsMonitor(MpmSolver &mpm);
// The mean radial velocity of the fragments' materials about the -grady axis (enabled: -grady is on).
PetscErrorCode FragmentsExpansionVelocity(MpmSolver &mpm, PetscBool *enabled, PetscReal *velocity);
PetscErrorCode FragmentsRecordInitialMass(MpmSolver &mpm); // at t = 0: the base of -fragments_min_mass_fraction
// table_path: where to write the fragment table (fragments.csv), or null.
PetscErrorCode FindFragments(MpmSolver &mpm, const char table_path[]);
PetscErrorCode FragmentsSummary(const MpmSolver &mpm, std::ostream &out);
bool           SwarmHasModelField(const MpmSolver &mpm, const char name[]);

} // namespace burst
