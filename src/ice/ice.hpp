// The gas half of burst: multi-material ICE (Kashiwa & Rauenzahn 1994; ice.md 1) on a cell-centred
// DMDA that shares the ownership of the MPM node DMDA (petsc.md 5.5).
//
// One step (ice.md 1.2, the rows without MPM) is, in order, one file each in src/ice/:
//   equilibration.cxx   per-cell pressure with sum(theta) = 1 (Newton, bisection fallback)
//   face_velocity.cxx   face velocities from the pressure gradient, then face momentum exchange
//   pressure.cxx        explicit pressure update, or the semi-implicit KSP solve (outer iteration)
//   sources.cxx         face pressure, momentum and energy sources, Lagrangian values
//   exchange.cxx        implicit cell exchange of momentum and heat, Lagrangian specific volume
//   advection.cxx       first- or second-order limited advection, conserved -> primitive
//   boundary.cxx        ghost cells: wall, symmetry, outflow, inflow; ghost exchange
//   timestep.cxx        the ICE CFL condition
// and setup.cxx (options, materials, initial state) and diagnostics.cxx (totals, profile.csv).
//
// All state is cell-centred and every material lives in every cell (a tiny mass where absent,
// ice.md 7.1). This header knows nothing of MPM: the driver passes the node DMDA for its ownership.
#pragma once
#include "petsc_compat.hpp"
#include "ice_fwd.hpp"
#include "../../models/gas_eos/gas_eos.hpp"
#include <petscdmda.h>
#include <petscksp.h>
#include <array>
#include <memory>
#include <string>
#include <vector>

namespace burst {

enum class IceBC : int { Wall = 0, Symmetry = 1, Outflow = 2, Inflow = 3 };
enum class IcePressureSolver : int { Explicit = 0, SemiImplicit = 1 };
enum class RiemannShape : int { Planar = 0, Cylinder = 1, Sphere = 2 };
enum class IceEquilibrationForm : int { Mass = 0, Normalized = 1 };
extern const char *const IceBCNames[];
extern const char *const IceEquilibrationFormNames[];
extern const char *const IcePressureSolverNames[];
extern const char *const RiemannShapeNames[];

// Most materials a cell holds (small dense exchange solves on the stack).
inline constexpr int kIceMaxMaterials = 8;

// The cells where a gas's energy falls back to a non-conservative form (IceCountFallback; summary.json's
// gas block): a gas gains burnt mass there this step (the burning surface); the solids fill at least
// 90 % of the cell (a pocket of gas in the steel or the charge); the solids hold part of it (a solid's
// surface, a gap between fragments); no solid (open gas).
enum class IceFallbackClass : int { Burning = 0, SolidFilled = 1, SolidSurface = 2, Open = 3 };
inline constexpr int     kIceFallbackClasses = 4;
extern const char *const IceFallbackClassNames[];

struct IceMaterial {
  std::string             name;
  std::unique_ptr<GasEOS> eos;
  PetscReal               density         = -1; // initial material density, kg/m^3
  PetscReal               temperature     = -1; // initial temperature, K
  PetscReal               velocity[3]     = {0, 0, 0};
  PetscReal               volume_fraction = -1; // -ice_uniform_volume_fraction (else 1 where present)
  // A solid (MPM) material as the gas sees it (ice.md 2): its mass, velocity and temperature come
  // from the particles every step (src/coupling/); it takes part in the equilibration, the face
  // velocities, the pressure and the exchange, but is not advected and gets no energy source.
  bool solid = false;
};

// Field offsets in the cell DMDA: a block of kMatFields per material, then the cell fields.
namespace icef {
inline constexpr int rho        = 0;  // bulk density M_m/V, kg/m^3
inline constexpr int vel        = 1;  // velocity, 3 components (unused ones 0), m/s
inline constexpr int temp       = 4;  // temperature, K
inline constexpr int spvol      = 5;  // specific volume of the material, 1/rho_micro, m^3/kg (equilibration)
inline constexpr int theta      = 6;  // volume fraction
inline constexpr int kappa      = 7;  // isentropic compressibility v/c^2, 1/Pa
inline constexpr int work_p     = 8;  // T (dP/dT)_rho: the pressure that does compression work, Pa
inline constexpr int rho_L      = 9;  // Lagrangian bulk density, kg/m^3
inline constexpr int vel_L      = 10; // Lagrangian (after sources and exchange) velocity, 3 components
inline constexpr int temp_L     = 13; // Lagrangian temperature, K
inline constexpr int energy_L   = 14; // Lagrangian total energy over c_v, T + |u|^2/(2 c_v), K
inline constexpr int kMatFields = 15;
// cell fields after the material blocks
inline constexpr int press       = 0; // pressure at the end of the step (p^{n+1}), Pa
inline constexpr int press_eq    = 1; // equilibration pressure of this step, Pa
inline constexpr int dp_dil      = 2; // dilatational pressure change of this step, Pa
inline constexpr int sum_kappa   = 3; // sum_m theta_m kappa_m, 1/Pa
inline constexpr int kCellFields = 4;
} // namespace icef

// The state an inflow face prescribes in one of its cells.
struct IceInflowState {
  PetscInt  material = 0;               // the material that flows in (the others at their tiny mass)
  PetscReal state[5] = {0, 0, 0, 0, 0}; // density (kg/m^3), velocity (3, m/s), temperature (K)
};

// An inflow face holds `inflow` in every cell, or with a jet (-ice_inflow_<face>_jet) `jet` in the
// face cells whose centre lies within jet_radius of jet_center along the face (a slot of half-width
// jet_radius in 2-D, a disc in 3-D) and `inflow` (the coflow) in the others: IceInflowAt.
struct IceFaceBC {
  IceBC          type = IceBC::Wall;
  IceInflowState inflow;
  bool           has_jet = false;
  IceInflowState jet;
  PetscReal      jet_center[3] = {0, 0, 0}; // m; the component normal to the face is not used
  PetscReal      jet_radius    = 0;         // m
  PetscReal      pressure      = 0;         // outflow: the far-field pressure its ghost cells hold (Pa); 0: zero gradient
};

struct IceTotals {
  PetscReal mass = 0, momentum[3] = {0, 0, 0}, internal_energy = 0, kinetic_energy = 0;
  PetscReal max_pressure    = 0; // Pa, over the cells
  PetscReal max_temperature = 0; // K, the hottest gas over the cells (traces excluded)
};

// What crossed the domain faces since the start, this rank's faces (the budgets of monitor.csv,
// diagnostics.cxx). Open (outflow, inflow) faces: the gases' mass, momentum and advected total energy
// out of the domain, the very face fluxes the advection gives the cells (net, out positive), and the
// work p theta_f u A dt the gas at those faces does on the outside (the conservative energy form's
// face work). Every face: the impulse of the face pressure on the cells' materials, gas and solid,
// theta_m p_f A dt (the sources' momentum term at a domain face, towards the inside).
struct IceBoundaryBudget {
  PetscReal mass = 0, momentum[3] = {0, 0, 0}, energy = 0; // kg, kg m/s, J
  PetscReal work            = 0;                           // J
  PetscReal impulse[3]      = {0, 0, 0};                   // N s
  PetscReal face_mass[3][2] = {{0, 0}, {0, 0}, {0, 0}};    // kg: of `mass`, each face's (xmin, xmax, ymin, ...)
};
// Values per material that the advection's face loop adds for the domain faces: the flux of the
// density and of the nq advected quantities (at most dim + 3: velocity, energy, the dual-energy
// temperature, the transported specific volume), per unit cell volume.
inline constexpr int kIceBoundaryFluxes = 7;

struct IceSolver {
  MPI_Comm                 comm     = PETSC_COMM_WORLD;
  PetscInt                 dim      = 2;
  PetscInt                 cells[3] = {1, 1, 1};
  PetscReal                lower[3] = {0, 0, 0}, h[3] = {1, 1, 1};
  std::vector<IceMaterial> materials;
  PetscInt                 nmat                                           = 0; // gases first, then solids
  PetscInt                 ngas                                           = 0;
  PetscReal                exchange_K[kIceMaxMaterials][kIceMaxMaterials] = {}; // momentum exchange, kg/(m^3 s)
  PetscReal                exchange_H[kIceMaxMaterials][kIceMaxMaterials] = {}; // heat exchange, W/(m^3 K)
  IceFaceBC                bc[3][2];

  // Options
  IcePressureSolver pressure_solver = IcePressureSolver::Explicit;
  // In cells that hold a solid: the materials' volumes from their masses (Mass), or rescaled to fill
  // the cell at the old pressure, the gases' from their transported specific volume (Normalized,
  // equilibration.cxx)
  IceEquilibrationForm equilibration_form  = IceEquilibrationForm::Mass;
  PetscInt             advection_order     = 2;
  PetscBool            compatible_fluxes   = PETSC_TRUE;
  PetscBool            conservative_energy = PETSC_TRUE; // Lagrangian energy from face-pressure work (total energy)
  PetscBool            drag_heating        = PETSC_TRUE; // with conservative_energy: the drag's dissipated kinetic energy becomes heat
  PetscBool solid_cell_energy    = PETSC_FALSE; // with conservative_energy and drag heating: a gas in a solid's cell gets its compression work and the work at the centre-of-mass velocity; the face work's excess goes to the solids (sources.cxx)
  PetscBool mixed_cell_energy    = PETSC_TRUE;  // with conservative_energy: in a cell of several gases each gets its own kinetic and compression energy, and their face works' excess is shared by heat capacity (sources.cxx)
  PetscBool advect_total_energy  = PETSC_TRUE;  // remap total energy (kinetic energy lost becomes heat)
  PetscReal viscosity[2]         = {0.5, 1};    // shock viscosity c1 (linear), c2 (quadratic), viscosity.cxx
  PetscReal cfl                  = 0.25;
  PetscReal sound_speed_knob     = -1;    // k_c of the CFL; default 1 explicit, 0.5 semi-implicit
  PetscReal dt_fixed             = 0;     // -ice_dt
  PetscReal rho_tiny             = 1e-12; // fraction of the material density kept where it is absent
  PetscReal trace_fraction       = 1e-6;  // a gas below this volume fraction is a trace: no compression work, not in the CFL
  PetscReal trace_mass           = 0;     // a gas below this share of the cell's mass is a trace too (0: the volume fraction alone)
  PetscReal cfl_min_fraction     = 0;     // a gas below this volume fraction sets the step by its speed, not its sound speed
  PetscReal outer_tolerance      = 1e-8;  // semi-implicit: max |residual| / V over cells
  PetscInt  outer_max_iterations = 20;
  PetscInt  equilibration_max_iterations = 100;
  PetscReal gravity[3]                   = {0, 0, 0};

  // Grid objects
  DM  da    = nullptr; // cell DMDA, BOX, width 2, dof = nmat * kMatFields + kCellFields
  DM  da_p  = nullptr; // pressure DMDA, STAR, width 1, dof 1, same ownership
  Vec state = nullptr, local = nullptr;
  Mat A   = nullptr;
  KSP ksp = nullptr;
  // Semi-implicit pressure KSP (pressure_implicit.cxx, setup.cxx): ksp_jacobi (CG + Jacobi, prefix
  // -ice_pressure_jacobi_) takes a step's solves while the matrix is diagonally dominant, max over
  // rows of sum |offdiag| / diag below jacobi_below (-ice_pressure_jacobi_below; with the default
  // preconditioner only; 0: never); ksp's
  // preconditioner is built at a step's first solve and reused by its later outer iterations, and
  // rebuilt every pc_lag steps only (1: every step).
  KSP           ksp_jacobi    = nullptr;
  PetscReal     jacobi_below  = 0.5;
  PetscInt      pc_lag        = 1;
  PetscInt      pc_built_step = -1;               // gas step of the last preconditioner set-up
  PetscBool     matrix_aij    = PETSC_FALSE;      // A is (MPI/Seq)AIJ: refill without zeroing
  PetscReal     dominance = 0, dominance_max = 0; // of the last step's first matrix, and the largest seen
  PetscInt64    jacobi_solves = 0, pc_setups = 0;
  PetscLogEvent ev_p_assemble = 0, ev_p_solve = 0;
  Vec           dp = nullptr, rhs = nullptr;
  PetscInt      stride = 0;
  PetscInt      xs[3] = {0, 0, 0}, xm[3] = {1, 1, 1};   // owned cells
  PetscInt      gxs[3] = {0, 0, 0}, gxm[3] = {1, 1, 1}; // local (ghosted) box
  PetscInt      lstride[3] = {1, 1, 1};                 // index stride of the local box per direction

  // Per-step face data for the local box: value of the LOWER face of each local cell, per
  // direction and material: velocity after exchange, before exchange, effective specific volume.
  std::vector<PetscReal> face_vel[3], face_vel_star[3], face_spvol[3], face_spvol_eff[3];
  // the sources' face pressure and shock viscosity (sources.cxx), per face (local index of its upper
  // cell), filled on the owned cells' faces each step and read again by the budget (diagnostics.cxx)
  std::vector<PetscReal> face_pressure[3], face_viscosity[3];
  // Work arrays for advection (gradients, fluxes) and the semi-implicit solve.
  std::vector<PetscReal> work_grad, work_adv, work_outflow, work_increment, work_advect, work_pressure;

  // Mass conversion of this step (burning, ice.md 2.4), per local cell index and material: bulk
  // density change (kg/m^3; negative for the reactant), momentum (kg/(m^2 s)) and energy (J/m^3)
  // that come with it. Filled by the coupling after the equilibration; empty when nothing burns.
  std::vector<PetscReal> mass_source, momentum_source, energy_source;
  bool                   has_mass_source = false;
  // Per local cell and solid material (when the coupling asks for it, else empty): the velocity
  // change du (3 values) that this step's pressure source -dt theta_s grad p gives the solid, whose
  // work the gases pay (src/coupling/pressure_work.cxx). Filled by IceSources.
  std::vector<PetscReal> solid_pressure_dv;

  // Step state
  PetscReal         dt = 0, time = 0;
  PetscInt          step           = 0;
  PetscInt          ksp_iterations = 0, outer_iterations = 0; // of the last step
  PetscInt64        ksp_iterations_total = 0, pressure_solves = 0;
  PetscInt64        energy_fallbacks                            = 0;  // cells and materials that fell back to the -p dV energy or the internal-energy remap (this rank)
  PetscInt64        energy_fallbacks_remap                      = 0;  // of those, the internal-energy remap's (advection.cxx; the rest are the sources')
  PetscInt64        energy_fallbacks_exchange                   = 0;  // of those, the exchange's (exchange.cxx: a total-energy temperature the drag heat left negative)
  PetscInt64        energy_fallbacks_class[kIceFallbackClasses] = {}; // of all, by the class of their cell (IceCountFallback)
  PetscReal         peak_pressure = 0, peak_pressure_time = 0;        // the largest cell pressure seen by the monitor, and when
  PetscReal         peak_temperature = 0, peak_temperature_time = 0;  // the hottest gas (traces excluded) seen by the monitor, and when
  PetscReal         dual_energy_fraction = 1e-3;                      // below this share of the total energy the remap takes the internal energy
  IceTotals         initial;
  IceBoundaryBudget boundary;                         // cumulative (this rank), see IceBoundaryBudget
  PetscReal         exchange_energy_change      = 0;  // J, this rank: the total energy of every material the cell exchange changed (cells' view; IceBudgetAfterExchange)
  PetscReal         exchange_energy_mark        = 0;  // J, this rank: that energy before the exchange (IceBudgetFaces)
  PetscReal         drag_energy_change          = 0;  // J, this rank: of it, the kinetic energy the drag removes that no material gets as heat (exchange.cxx)
  PetscReal         exchange_fallback_energy    = 0;  // J, this rank: of it, what its temperature-form fallbacks changed (exchange.cxx)
  PetscReal         solid_pressure_work         = 0;  // J, this rank: the kinetic energy the momentum source -theta_s grad p gives the solids' cell materials (IceBudgetFaces)
  PetscReal         gas_interface_work          = 0;  // J, this rank: the gases' face work booked on one side of an interior face only (a trace on the other; IceBudgetFaces)
  PetscReal         advection_energy_change     = 0;  // J, this rank: the gases' total energy the advection made (its dual-energy fallbacks and trace resets; IceBudgetOpenFaces)
  PetscReal         fallback_energy_change      = 0;  // J, this rank: the gases' total energy IceSources made beyond its conservative terms where it books the face work (-p dV fallbacks; IceBudgetFaces)
  PetscReal         solid_cell_energy_transfer  = 0;  // J, this rank: what IceSolidCellEnergy moved from the gases of solids' cells to the solids (sources.cxx; IceBudgetFaces sees it in fallback_energy_change, and the monitor adds it back there)
  PetscReal         trace_energy_change         = 0;  // J, this rank: the same where a gas is a trace (its pressure acceleration without work)
  PetscReal         equilibration_energy_change = 0;  // J, this rank: the gases' total energy the phases before the sources changed (equilibration: e at the new specific volume)
  PetscReal         gas_energy_mark             = 0;  // J, this rank: the gases' total energy at the step's start (IceBudgetStepStart)
  PetscReal         gas_energy_after            = 0;  // J, this rank: the same sum after the last advection (IceBudgetOpenFaces) ...
  PetscInt          gas_energy_after_step       = -1; // ... for the gas step it starts (-1: none), which takes it as its mark
  // The ten energy diagnostics above in one fixed order, for the monitor's reduction and the
  // checkpoint (both keep them in this order).
  static constexpr int                        kEnergyDiagnostics = 10;
  std::array<PetscReal *, kEnergyDiagnostics> EnergyDiagnostics()
  {
    return {&drag_energy_change,  &solid_pressure_work,         &gas_interface_work,     &advection_energy_change,  &fallback_energy_change,
            &trace_energy_change, &equilibration_energy_change, &exchange_energy_change, &exchange_fallback_energy, &solid_cell_energy_transfer};
  }
  // The advection's face loop adds its domain-face fluxes here while IceAdvect advects a gas (null
  // otherwise: the pressure's volume fluxes are not a budget); IceBudgetOpenFaces books them.
  PetscReal *boundary_flux_sink                                  = nullptr;
  PetscReal  boundary_flux[kIceMaxMaterials][kIceBoundaryFluxes] = {};
  // The gases' density flux of each domain face (index 2 d + side, out positive, per unit cell
  // volume) that the same loop adds while boundary_flux_sink is set: the budget per face.
  PetscReal boundary_face_mass_flux[6] = {};

  PetscLogEvent ev_equilibrate, ev_face, ev_pressure, ev_sources, ev_exchange, ev_advect, ev_bc, ev_dt, ev_budget;

  PetscInt  Offset(PetscInt m, PetscInt f) const { return m * icef::kMatFields + f; }
  PetscInt  CellOffset(PetscInt f) const { return nmat * icef::kMatFields + f; }
  PetscInt  LocalIndex(PetscInt i, PetscInt j, PetscInt k) const { return ((k - gxs[2]) * gxm[1] + (j - gxs[1])) * gxm[0] + (i - gxs[0]); }
  PetscReal CellVolume() const { return dim == 2 ? h[0] * h[1] : h[0] * h[1] * h[2]; }
  ~IceSolver();
};

// The inflow state of face (d, s) in the cell (i, j, k) of the face's layer (a ghost or a domain
// cell; only the indices along the face matter): the jet's where the cell centre is within the jet's
// radius of its centre, else the face's own (IceFaceBC).
inline const IceInflowState &IceInflowAt(const IceSolver &ice, PetscInt d, int s, PetscInt i, PetscInt j, PetscInt k)
{
  const IceFaceBC &bc = ice.bc[d][s];
  if (!bc.has_jet) return bc.inflow;
  const PetscInt ijk[3] = {i, j, k};
  PetscReal      r2     = 0;
  for (PetscInt e = 0; e < ice.dim; ++e) {
    if (e == d) continue;
    const PetscReal x = ice.lower[e] + (ijk[e] + 0.5) * ice.h[e] - bc.jet_center[e];
    r2 += x * x;
  }
  return r2 <= bc.jet_radius * bc.jet_radius ? bc.jet : bc.inflow;
}

// Set-up (setup.cxx). `nodes` is the MPM node DMDA whose ownership the cell DMDA copies;
// grid_* describe the box. Reads every -ice_ option and the gas materials; *ice = null when the
// scene lists no gas materials (-ice_materials).
// A solid material for the equilibration: its name and the equation of state that gives its
// density at the cell pressure (ownership passes to the solver).
struct IceSolidSpec {
  std::string name;
  GasEOS     *eos;
  PetscReal   temperature; // K, until the particles give one
};
struct IceGridSpec {
  PetscInt                  dim;
  PetscInt                  cells[3];
  PetscReal                 lower[3], h[3];
  PetscReal                 gravity[3]; // m/s^2
  DM                        nodes;
  std::vector<IceSolidSpec> solids;               // after the gases in material order
  bool                      axisymmetric = false; // the grid is (r, z): the gas cells cannot be (they are Cartesian)
};
// *ice is null without gas materials (or with -help); the caller owns it (IceSolverDeleter).
PetscErrorCode IceCreate(MPI_Comm comm, const IceGridSpec &grid, PetscBool help, IceSolver **ice);
// Whether the options list gas materials (-ice_materials), before the solver is created.
bool           IceMaterialsRequested(MPI_Comm comm);
PetscErrorCode IceSetInitialState(IceSolver &ice);
// -ice_perturbation acoustic|entropy: a smooth Gaussian over the uniform initial state
// (perturbation.cxx; the acoustic and low_mach verification problems). Call after IceCreate.
PetscErrorCode IceApplyPerturbation(IceSolver &ice);
PetscErrorCode IceView(const IceSolver &ice, PetscViewer viewer);

// The phases of one step, in order (src/step.cxx calls them).
PetscErrorCode IceComputeTimeStep(IceSolver &ice, PetscReal *dt);
PetscErrorCode IceEquilibrate(IceSolver &ice);
PetscErrorCode IceFaceVelocities(IceSolver &ice);
PetscErrorCode IceUpdatePressure(IceSolver &ice);
PetscErrorCode IceSources(IceSolver &ice);
PetscErrorCode IceCellExchange(IceSolver &ice);
PetscErrorCode IceAdvect(IceSolver &ice);
// The semi-implicit pressure (pressure_implicit.cxx), called by IceUpdatePressure.
PetscErrorCode IceSolvePressureSemiImplicit(IceSolver &ice);

// Helpers shared by the phases.
PetscErrorCode IceUpdateGhosts(IceSolver &ice); // owned -> ghosts, then boundary ghosts
PetscErrorCode IceSyncGlobal(IceSolver &ice);   // the global vector from the local one (output)
PetscErrorCode IceApplyBoundaryGhosts(IceSolver &ice, PetscScalar *a);
void           IceBoundaryFaceVelocities(IceSolver &ice); // wall/symmetry/inflow face values
PetscErrorCode IceGetLocalArray(IceSolver &ice, PetscScalar **a);
PetscErrorCode IceRestoreLocalArray(IceSolver &ice, PetscScalar **a);
// Face exchange of one face (ice.md 1.4) for the face at local index `idx` in direction d, from
// u* (face_vel_star) and v-bar (face_spvol): writes face_vel and face_spvol_eff.
void IceFaceExchange(IceSolver &ice, const PetscScalar *a, PetscInt d, PetscInt idx);
// Net outflow volume of every material through the faces of each owned cell relative to the
// cell volume, sum_m sum_f theta_hat u_f A_f dt / V (theta_hat from the advection operator);
// out[local index].
PetscErrorCode IceVolumeOutflow(IceSolver &ice, const PetscScalar *a, std::vector<PetscReal> &out);
// Advection increments (1/V) sum_f (in - out) for every owned cell of material m (face velocities
// of this step): out[0][local index] for the density field `density` (bulk density, or theta),
// out[1 + q][...] for density * a[q_fields[q]] (mass-specific quantities: velocity components,
// temperature, specific volume). The arrays are overwritten for owned cells.
void IceAdvectionIncrement(IceSolver &ice, const PetscScalar *a, PetscInt m, PetscInt density, const PetscInt q_fields[], PetscInt nq, PetscReal *const out[]);
// The Lagrangian temperature of gas m in the cell c (local index idx) from the temperature form,
// c_v dT = theta kappa (T dP/dT + dp_dil) dp_dil, with the converted mass's energy (sources.cxx; the
// total-energy form's fallback); *cold_L (if not null, for a cold energy) its e_cold, J/kg.
PetscReal IceTemperatureForm(const IceSolver &ice, const PetscScalar *c, PetscInt idx, PetscInt m, PetscReal *cold_L);
// Whether gas m is a trace in the cell c: below -ice_trace_fraction of its volume, or below
// -ice_trace_mass of the cell's mass (a remnant at the rho_tiny level that has expanded past the
// volume bound: doc/gas.md, the water-air tube)
// Whether a gas of bulk density rho is below -ice_trace_mass of the cell c's mass
inline bool IceIsTraceMass(const IceSolver &ice, const PetscScalar *c, PetscReal rho)
{
  if (!(ice.trace_mass > 0)) return false;
  PetscReal mass = 0;
  for (PetscInt l = 0; l < ice.nmat; ++l) mass += c[ice.Offset(l, icef::rho)];
  return rho < ice.trace_mass * mass;
}
inline bool IceIsTrace(const IceSolver &ice, const PetscScalar *c, PetscInt m) { return c[ice.Offset(m, icef::theta)] < ice.trace_fraction || IceIsTraceMass(ice, c, c[ice.Offset(m, icef::rho)]); }
// Counts one energy fallback of a gas in the cell c (local index idx) in ice.energy_fallbacks and in the
// class of the cell (IceFallbackClass; sources.cxx).
void IceCountFallback(IceSolver &ice, const PetscScalar *c, PetscInt idx);
// Face pressure from continuity of acceleration between local cells L and R (sources.cxx):
// (p_R rho_L + p_L rho_R)/(rho_L + rho_R), rho the sum of the bulk densities, Pa.
PetscReal IceFacePressure(const IceSolver &ice, const PetscScalar *a, PetscInt L, PetscInt R);
// Shock viscosity (viscosity.cxx) of the face between local cells R - lstride[d] and R, Pa.
PetscReal IceFaceViscosity(const IceSolver &ice, const PetscScalar *a, PetscInt d, PetscInt R);
// Gases only; internal energy rho_m V e(rho_micro = 1/spvol, T) with the cold energy of the EOS.
PetscErrorCode IceComputeTotals(IceSolver &ice, IceTotals &t);
// The budget of the domain faces (diagnostics.cxx, IceBoundaryBudget): after IceSources (before the
// advection changes the densities the face pressures are weighted with), the face work at open faces
// and the face-pressure impulse, and with several materials the work of the pressure source on the
// solids (solid_pressure_work) and the face work booked on one side only (gas_interface_work), and
// the energy IceSources did not conserve (fallback_energy_change, trace_energy_change); after
// IceAdvect, the open faces' fluxes of that advection and the energy it did not conserve
// (advection_energy_change).
// IceBudgetStepStart, first in the step, marks the gases' total energy that the equilibration
// (equilibration_energy_change) is measured against.
PetscErrorCode IceBudgetStepStart(IceSolver &ice);
PetscErrorCode IceBudgetFaces(IceSolver &ice);
PetscErrorCode IceBudgetAfterExchange(IceSolver &ice); // the exchange's change (exchange_energy_change)
PetscErrorCode IceBudgetOpenFaces(IceSolver &ice);
// Scales every gas's bulk density by (1 - solid_fraction) per owned cell (local index), so that
// the gases fill what the solids leave at the start (ice.md 8).
PetscErrorCode IceMakeRoomForSolids(IceSolver &ice, const std::vector<PetscReal> &solid_fraction);
PetscErrorCode IceWriteProfile(IceSolver &ice, const std::string &file, PetscReal time, PetscInt step);

// The gas solver's part of a checkpoint (checkpoint.cxx): its counters and accumulators by name,
// and its cell state, /gas/state in natural ordering.
class CheckpointValues;

void           IceCheckpointValues(IceSolver &ice, CheckpointValues &values);
PetscErrorCode IceCheckpointWrite(IceSolver &ice, PetscViewer viewer);
PetscErrorCode IceCheckpointRead(IceSolver &ice, PetscViewer viewer, const std::string &file);

} // namespace burst
