// ICE set-up: options, gas materials, the cell and pressure DMDAs, and the initial state.
//
// The cell DMDA copies the node DMDA's process grid, with one cell fewer on the last rank of each
// direction, so a cell and its lower node live on the same rank (petsc.md 5.5). Width 2 (BOX): the
// second-order advection needs the limited gradient of a donor cell one ghost layer out.
#include "ice.hpp"
#include "util.hpp"
#include "../memory.hpp"
#include <cmath>
#include <cstring>

namespace burst {

const char *const IceBCNames[]                = {"wall", "symmetry", "outflow", "inflow"};
const char *const IcePressureSolverNames[]    = {"explicit", "semi_implicit"};
const char *const IceEquilibrationFormNames[] = {"mass", "normalized"};
const char *const RiemannShapeNames[]         = {"planar", "cylinder", "sphere"};

// The Riemann (two-state) initial condition, ice.md 6.1-6.2.
struct RiemannSetup {
  PetscBool    set     = PETSC_FALSE;
  PetscReal    left[3] = {1, 0, 1}, right[3] = {0.125, 0, 0.1}; // rho, u, p
  PetscReal    position = 0.5, center[3] = {0, 0, 0};
  PetscInt     left_material = 0, right_material = 0;
  RiemannShape shape = RiemannShape::Planar;
};

static PetscErrorCode MaterialIndex(const IceSolver &ice, const char opt[], const char name[], PetscInt *index)
{
  PetscFunctionBeginUser;
  std::string names;
  for (PetscInt m = 0; m < ice.nmat; ++m) {
    if (ice.materials[m].name == name) {
      *index = m;
      PetscFunctionReturn(PETSC_SUCCESS);
    }
    names += (m ? ", " : "") + ice.materials[m].name;
  }
  SETERRQ(ice.comm, PETSC_ERR_USER_INPUT, "Option %s = %s is not a gas material; valid choices (-ice_materials): %s", opt, name, names.c_str());
}

static PetscErrorCode ReadExchange(IceSolver &ice, PetscOptionItems *PetscOptionsObject, const char opt[], const char help[], PetscReal upper, PetscReal K[kIceMaxMaterials][kIceMaxMaterials])
{
  const PetscInt pairs = ice.nmat * (ice.nmat - 1) / 2;
  PetscReal      values[kIceMaxMaterials * kIceMaxMaterials];
  PetscInt       n = kIceMaxMaterials * kIceMaxMaterials;
  PetscBool      set;
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < n; ++i) values[i] = 0;
  PetscCall(PetscOptionsRealArray(opt, help, "", values, &n, &set));
  if (set) PetscCheck(n == pairs || n == 1, ice.comm, PETSC_ERR_USER_INPUT, "Option %s needs %" PetscInt_FMT " values (the upper triangle in -ice_materials order: 12,13,...,23,...) or one for every pair; got %" PetscInt_FMT, opt, pairs, n);
  PetscInt k = 0;
  for (PetscInt a = 0; a < ice.nmat; ++a)
    for (PetscInt b = a + 1; b < ice.nmat; ++b, ++k) {
      const PetscReal v = set ? (n == 1 ? values[0] : values[k]) : K[a][b];
      PetscCall(CheckRange(ice.comm, opt, v, 0, upper, PETSC_FALSE));
      K[a][b] = K[b][a] = v;
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

// A jet on inflow face (d, s): -ice_inflow_<face>_jet (its state, as -ice_inflow_<face>), _jet_center
// (m, default the face's centre), _jet_radius (m) and _jet_material (default the face's material).
// The face cells whose centre lies within the radius of the centre along the face (a slot of that
// half-width in 2-D, a disc in 3-D) take the jet's state, the others the face's (the coflow; IceInflowAt).
static PetscErrorCode ReadInflowJet(IceSolver &ice, PetscOptionItems *PetscOptionsObject, PetscInt d, int s, const char face_opt[], const char inflow_opt[])
{
  IceFaceBC        &bc      = ice.bc[d][s];
  const std::string jet_opt = std::string(inflow_opt) + "_jet", center_opt = jet_opt + "_center", radius_opt = jet_opt + "_radius", material_opt = jet_opt + "_material";
  PetscReal         state[5] = {0, 0, 0, 0, 0}, center[3] = {0, 0, 0}, radius = 0;
  PetscInt          ns = 5, nc = 3;
  PetscBool         jet_set, center_set, radius_set, material_set;
  char              buf[256];
  PetscFunctionBeginUser;
  for (PetscInt e = 0; e < ice.dim; ++e) center[e] = ice.lower[e] + 0.5 * ice.cells[e] * ice.h[e];
  const std::string jet_help = "Jet on this inflow face: density (kg/m^3), velocity (m/s, dim values), temperature (K) in the face cells whose centre lies within " + radius_opt + " of " + center_opt + "; the face's other cells take " + inflow_opt +
                               " (the coflow). Default: no jet";
  const std::string center_help   = "Jet centre (m, dim values; the component normal to the face is not used). Default: the face's centre";
  const std::string radius_help   = "Jet radius (m, > 0; required with " + jet_opt + "): in 2-D the half-width of the slot along the face, in 3-D the radius of the disc on the face";
  const std::string material_help = "Jet: the gas material that flows in the jet (default: the face's, " + std::string(inflow_opt) + "_material)";
  PetscCall(PetscOptionsRealArray(jet_opt.c_str(), jet_help.c_str(), "", state, &ns, &jet_set));
  PetscCall(PetscOptionsRealArray(center_opt.c_str(), center_help.c_str(), "", center, &nc, &center_set));
  PetscCall(PetscOptionsReal(radius_opt.c_str(), radius_help.c_str(), "", radius, &radius, &radius_set));
  PetscCall(PetscOptionsString(material_opt.c_str(), material_help.c_str(), "", "", buf, sizeof(buf), &material_set));
  const char *given = jet_set ? jet_opt.c_str() : center_set ? center_opt.c_str() : radius_set ? radius_opt.c_str() : material_set ? material_opt.c_str() : nullptr;
  if (!given) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(bc.type == IceBC::Inflow, ice.comm, PETSC_ERR_USER_INPUT, "Option %s is given, but %s is %s: a jet is part of an inflow face (%s inflow)", given, face_opt, IceBCNames[(int)bc.type], face_opt);
  PetscCheck(jet_set, ice.comm, PETSC_ERR_USER_INPUT, "Option %s needs %s, the jet's state: density, velocity (%" PetscInt_FMT " components), temperature", given, jet_opt.c_str(), ice.dim);
  PetscCheck(ns == ice.dim + 2, ice.comm, PETSC_ERR_USER_INPUT, "Option %s needs %" PetscInt_FMT " values: density, velocity (%" PetscInt_FMT " components), temperature; got %" PetscInt_FMT, jet_opt.c_str(), ice.dim + 2, ice.dim, ns);
  PetscCall(CheckRange(ice.comm, (jet_opt + " (density, kg/m^3)").c_str(), state[0], 0, PETSC_MAX_REAL, PETSC_TRUE));
  PetscCall(CheckRange(ice.comm, (jet_opt + " (temperature, K)").c_str(), state[ice.dim + 1], 0, PETSC_MAX_REAL, PETSC_TRUE));
  for (PetscInt c = 0; c <= ice.dim; ++c) PetscCheck(std::isfinite(state[c]), ice.comm, PETSC_ERR_USER_INPUT, "Option %s: value %" PetscInt_FMT " is not finite", jet_opt.c_str(), c + 1);
  PetscCheck(radius_set, ice.comm, PETSC_ERR_USER_INPUT, "Option %s needs %s (m, > 0): the jet's half-width (2-D) or radius (3-D) along the face", jet_opt.c_str(), radius_opt.c_str());
  PetscCall(CheckRange(ice.comm, (radius_opt + " (m)").c_str(), radius, 0, PETSC_MAX_REAL, PETSC_TRUE));
  if (center_set) PetscCheck(nc == ice.dim, ice.comm, PETSC_ERR_USER_INPUT, "Option %s needs %" PetscInt_FMT " values (m, one per dimension), got %" PetscInt_FMT, center_opt.c_str(), ice.dim, nc);
  for (PetscInt e = 0; e < ice.dim; ++e) PetscCheck(std::isfinite(center[e]), ice.comm, PETSC_ERR_USER_INPUT, "Option %s: value %" PetscInt_FMT " is not finite", center_opt.c_str(), e + 1);
  bc.has_jet      = true;
  bc.jet_radius   = radius;
  bc.jet.material = bc.inflow.material;
  bc.jet.state[0] = state[0];
  for (PetscInt c = 0; c < ice.dim; ++c) bc.jet.state[1 + c] = state[1 + c];
  bc.jet.state[4] = state[ice.dim + 1];
  for (PetscInt e = 0; e < ice.dim; ++e) bc.jet_center[e] = center[e];
  if (material_set && ice.nmat) PetscCall(MaterialIndex(ice, material_opt.c_str(), buf, &bc.jet.material));
  // a jet that covers no face cell would be the coflow alone without a word
  PetscInt covered = 0, n[3] = {1, 1, 1};
  for (PetscInt e = 0; e < ice.dim; ++e) n[e] = e == d ? 1 : ice.cells[e];
  for (PetscInt k = 0; k < n[2] && !covered; ++k)
    for (PetscInt j = 0; j < n[1] && !covered; ++j)
      for (PetscInt i = 0; i < n[0] && !covered; ++i) covered += &IceInflowAt(ice, d, s, i, j, k) == &bc.jet;
  PetscCheck(covered, ice.comm, PETSC_ERR_USER_INPUT, "Option %s = %g m: the jet about %s covers no cell centre of the face (cells %g m wide along it); widen it or move the centre onto the face", radius_opt.c_str(), (double)radius,
             center_opt.c_str(), (double)ice.h[d == 0 ? 1 : 0]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode ReadOptions(IceSolver &ice, RiemannSetup &rs)
{
  char     *names[kIceMaxMaterials];
  PetscInt  n = kIceMaxMaterials;
  PetscBool set;
  int       choice;
  char      buf[256];
  PetscFunctionBeginUser;
  PetscOptionsBegin(ice.comm, "", "Gas (ICE)", "ICE");
  PetscCall(PetscOptionsStringArray("-ice_materials", "Names of the gas (ICE) materials; each is configured with -<name>_eos_type and its parameters. None: no gas", "", names, &n, &set));
  if (!set) n = 0;
  PetscCheck(n <= kIceMaxMaterials, ice.comm, PETSC_ERR_USER_INPUT, "Option -ice_materials lists more than %d materials", kIceMaxMaterials);
  {
    // a solid (of -materials) named here would be read as a gas and fail on its equation of state
    char     *solids[64];
    PetscInt  nsolid = 64;
    PetscBool has_solids;
    PetscCall(PetscOptionsGetStringArray(nullptr, nullptr, "-materials", solids, &nsolid, &has_solids));
    if (!has_solids) nsolid = 0;
    std::string clash;
    for (PetscInt i = 0; i < n; ++i)
      for (PetscInt j = 0; j < nsolid; ++j)
        if (!std::strcmp(names[i], solids[j])) clash = names[i];
    for (PetscInt j = 0; j < nsolid; ++j) PetscCall(PetscFree(solids[j]));
    PetscCheck(clash.empty(), ice.comm, PETSC_ERR_USER_INPUT, "Option -ice_materials lists '%s', a solid of -materials: -ice_materials names the gases only; a solid meets the gas through the coupling, which gives it a cell state of its own",
               clash.c_str());
  }
  for (PetscInt i = 0; i < n; ++i) {
    for (PetscInt j = 0; j < i; ++j) PetscCheck(std::strcmp(names[i], names[j]), ice.comm, PETSC_ERR_USER_INPUT, "Option -ice_materials lists '%s' twice", names[i]);
    IceMaterial m;
    m.name = names[i];
    ice.materials.push_back(std::move(m));
  }
  for (PetscInt i = 0; i < n; ++i) PetscCall(PetscFree(names[i]));
  ice.nmat = n;

  choice = (int)ice.equilibration_form;
  PetscCall(OptionsChoice(PetscOptionsObject, "-ice_equilibration",
                          "In cells that hold a solid: mass (every volume from its mass, sum rho_m/rho_micro_m(p) = 1) or normalized (the volumes at the old pressure, the gases' from their transported specific volume, rescaled to fill the cell, so "
                          "an overfill does not become pressure)",
                          IceEquilibrationFormNames, 2, &choice, nullptr));
  ice.equilibration_form = (IceEquilibrationForm)choice;
  choice                 = (int)ice.pressure_solver;
  PetscCall(OptionsChoice(PetscOptionsObject, "-ice_pressure_solver", "Pressure update: explicit (ice.md 1.5) or semi_implicit (KSP on the cell DMDA, options under -ice_pressure_)", IcePressureSolverNames, 2, &choice, nullptr));
  ice.pressure_solver = (IcePressureSolver)choice;
  PetscCall(PetscOptionsInt("-ice_advection_order", "Advection: 1 (donor cell) or 2 (limited linear reconstruction, van Leer)", "", ice.advection_order, &ice.advection_order, nullptr));
  PetscCheck(ice.advection_order == 1 || ice.advection_order == 2, ice.comm, PETSC_ERR_USER_INPUT, "Option -ice_advection_order = %" PetscInt_FMT " is not supported: valid choices are 1 and 2", ice.advection_order);
  PetscCall(PetscOptionsBool("-ice_compatible_fluxes", "Second order: compatible fluxes for velocity, temperature and specific volume (VanderHeyden & Kashiwa 1998)", "", ice.compatible_fluxes, &ice.compatible_fluxes, nullptr));
  PetscCall(PetscOptionsBool("-ice_conservative_energy", "Lagrangian energy from the work of the face pressures minus the kinetic energy gained (conserves total energy), instead of the reference's -p dV form", "", ice.conservative_energy,
                             &ice.conservative_energy, nullptr));
  {
    PetscInt  nv   = 2;
    PetscReal v[2] = {ice.viscosity[0], ice.viscosity[1]};
    PetscCall(PetscOptionsRealArray("-ice_artificial_viscosity", "Shock viscosity c1,c2 (-, >= 0): q = rho (1 - psi)(c2 du^2 + c1 c |du|) on compressing faces, psi Christensen's limiter (viscosity.cxx); 0,0 off", "", v, &nv, &set));
    if (set) {
      PetscCheck(nv == 2, ice.comm, PETSC_ERR_USER_INPUT, "Option -ice_artificial_viscosity needs 2 values (c1,c2), got %" PetscInt_FMT, nv);
      PetscCall(CheckRange(ice.comm, "-ice_artificial_viscosity (c1)", v[0], 0, 100, PETSC_FALSE));
      PetscCall(CheckRange(ice.comm, "-ice_artificial_viscosity (c2)", v[1], 0, 100, PETSC_FALSE));
      ice.viscosity[0] = v[0];
      ice.viscosity[1] = v[1];
    }
  }
  PetscCall(PetscOptionsBool("-ice_solid_cell_energy",
                             "With -ice_conservative_energy and -ice_drag_heating: a gas in a cell that holds a solid gets its own compression work and the pressure source's work at the cell's centre-of-mass velocity (the drag holds it there); what "
                             "its face work holds beyond those goes to the solids as heat, so that no gas there falls back to the temperature form (false: the face work's; doc/gas.md)",
                             "", ice.solid_cell_energy, &ice.solid_cell_energy, nullptr));
  PetscCall(PetscOptionsBool("-ice_mixed_cell_energy",
                             "With -ice_conservative_energy: in a cell that holds several gases, each gets the kinetic energy of its own momentum source and its own compression work; what the cell's face work holds beyond those is shared by heat "
                             "capacity (false: each gas gets the work of its own face fluxes)",
                             "", ice.mixed_cell_energy, &ice.mixed_cell_energy, nullptr));
  PetscCall(PetscOptionsBool("-ice_drag_heating", "With -ice_conservative_energy: the kinetic energy that the momentum exchange removes becomes heat of the cell's materials (false: dropped, as the reference does)", "", ice.drag_heating,
                             &ice.drag_heating, nullptr));
  PetscCall(PetscOptionsBool("-ice_advect_total_energy", "Advect total energy c_v T + |u|^2/2 instead of c_v T, so the kinetic energy the remap averages away becomes heat (the reference advects c_v T only)", "", ice.advect_total_energy,
                             &ice.advect_total_energy, nullptr));
  PetscCall(PetscOptionsReal("-ice_dual_energy_fraction",
                             "With total-energy advection: where the internal energy left is below this fraction of the total, take the separately remapped internal energy instead (dual energy; counted in energy_fallbacks), in [0, 1)", "",
                             ice.dual_energy_fraction, &ice.dual_energy_fraction, nullptr));
  PetscCall(CheckRange(ice.comm, "-ice_dual_energy_fraction", ice.dual_energy_fraction, 0, 1, PETSC_FALSE));
  PetscCall(PetscOptionsReal("-ice_cfl", "Gas Courant number: dt = cfl min_d h_d/(k c + |u_d|), in (0, 1]", "", ice.cfl, &ice.cfl, nullptr));
  PetscCall(CheckRange(ice.comm, "-ice_cfl", ice.cfl, 0, 1, PETSC_TRUE));
  PetscCall(PetscOptionsReal("-ice_sound_speed_knob", "k in the gas CFL, in [0, 1]; default 1 explicit, 0.5 semi-implicit", "", ice.sound_speed_knob, &ice.sound_speed_knob, &set));
  if (set) PetscCall(CheckRange(ice.comm, "-ice_sound_speed_knob", ice.sound_speed_knob, 0, 1, PETSC_FALSE));
  else ice.sound_speed_knob = ice.pressure_solver == IcePressureSolver::Explicit ? 1.0 : 0.5;
  PetscCall(PetscOptionsReal("-ice_dt", "Fixed gas time step (s) instead of the CFL rule; 0 = CFL rule", "", ice.dt_fixed, &ice.dt_fixed, nullptr));
  PetscCall(CheckRange(ice.comm, "-ice_dt", ice.dt_fixed, 0, PETSC_MAX_REAL, PETSC_FALSE));
  PetscCall(PetscOptionsReal("-ice_rho_tiny", "Mass of an absent material as a fraction of its density times the cell volume (ice.md 7.1)", "", ice.rho_tiny, &ice.rho_tiny, nullptr));
  PetscCall(CheckRange(ice.comm, "-ice_rho_tiny", ice.rho_tiny, 0, 1e-3, PETSC_TRUE));
  PetscCall(PetscOptionsReal("-ice_trace_fraction", "A gas below this volume fraction in a cell is a trace: it does no compression work and does not set the time step", "", ice.trace_fraction, &ice.trace_fraction, nullptr));
  PetscCall(CheckRange(ice.comm, "-ice_trace_fraction", ice.trace_fraction, 0, 1e-2, PETSC_FALSE));
  PetscCall(PetscOptionsReal("-ice_trace_mass", "A gas below this share of its cell's mass is a trace too, whatever its volume fraction (0: the volume fraction alone)", "", ice.trace_mass, &ice.trace_mass, nullptr));
  PetscCall(CheckRange(ice.comm, "-ice_trace_mass", ice.trace_mass, 0, 1e-3, PETSC_FALSE));
  PetscCall(PetscOptionsReal("-ice_cfl_min_fraction", "A gas below this volume fraction in a cell (a pocket in a solid) limits the time step by its flow speed only, not its sound speed; 0 = every gas above the trace fraction by both, in [0, 0.5]",
                             "", ice.cfl_min_fraction, &ice.cfl_min_fraction, nullptr));
  PetscCall(CheckRange(ice.comm, "-ice_cfl_min_fraction", ice.cfl_min_fraction, 0, 0.5, PETSC_FALSE));
  PetscCall(PetscOptionsReal("-ice_outer_tolerance", "Semi-implicit: outer iterations stop when max_c |residual_c|/V < this (relative volume)", "", ice.outer_tolerance, &ice.outer_tolerance, nullptr));
  PetscCall(CheckRange(ice.comm, "-ice_outer_tolerance", ice.outer_tolerance, 0, 1, PETSC_TRUE));
  PetscCall(PetscOptionsInt("-ice_outer_max_iterations", "Semi-implicit: most outer iterations per step", "", ice.outer_max_iterations, &ice.outer_max_iterations, nullptr));
  PetscCheck(ice.outer_max_iterations >= 1, ice.comm, PETSC_ERR_USER_INPUT, "Option -ice_outer_max_iterations = %" PetscInt_FMT " is out of range: it must be >= 1", ice.outer_max_iterations);

  // Boundary conditions per domain face
  const char *face_opt[3][2]   = {{"-ice_bc_xmin", "-ice_bc_xmax"}, {"-ice_bc_ymin", "-ice_bc_ymax"}, {"-ice_bc_zmin", "-ice_bc_zmax"}};
  const char *inflow_opt[3][2] = {{"-ice_inflow_xmin", "-ice_inflow_xmax"}, {"-ice_inflow_ymin", "-ice_inflow_ymax"}, {"-ice_inflow_zmin", "-ice_inflow_zmax"}};
  const char *inflow_mat[3][2] = {{"-ice_inflow_xmin_material", "-ice_inflow_xmax_material"}, {"-ice_inflow_ymin_material", "-ice_inflow_ymax_material"}, {"-ice_inflow_zmin_material", "-ice_inflow_zmax_material"}};
  const char *outflow_p[3][2]  = {{"-ice_outflow_xmin_pressure", "-ice_outflow_xmax_pressure"}, {"-ice_outflow_ymin_pressure", "-ice_outflow_ymax_pressure"}, {"-ice_outflow_zmin_pressure", "-ice_outflow_zmax_pressure"}};
  for (PetscInt d = 0; d < ice.dim; ++d)
    for (int s = 0; s < 2; ++s) {
      IceFaceBC &bc = ice.bc[d][s];
      choice        = (int)bc.type;
      PetscCall(OptionsChoice(PetscOptionsObject, face_opt[d][s], "Gas boundary condition on this face: wall (reflective), symmetry, outflow (zero gradient), inflow (prescribed state)", IceBCNames, 4, &choice, nullptr));
      bc.type            = (IceBC)choice;
      PetscReal state[5] = {0, 0, 0, 0, 0};
      PetscInt  ns       = 5;
      PetscCall(PetscOptionsRealArray(inflow_opt[d][s], "Inflow state: density (kg/m^3), velocity (m/s, dim values), temperature (K)", "", state, &ns, &set));
      if (bc.type == IceBC::Inflow) {
        PetscCheck(set && ns == ice.dim + 2, ice.comm, PETSC_ERR_USER_INPUT, "Option %s inflow needs %s with %" PetscInt_FMT " values: density, velocity (%" PetscInt_FMT " components), temperature", face_opt[d][s], inflow_opt[d][s], ice.dim + 2,
                   ice.dim);
        PetscCall(CheckRange(ice.comm, inflow_opt[d][s], state[0], 0, PETSC_MAX_REAL, PETSC_TRUE));
        PetscCall(CheckRange(ice.comm, inflow_opt[d][s], state[ice.dim + 1], 0, PETSC_MAX_REAL, PETSC_TRUE));
        bc.inflow.state[0] = state[0];
        for (PetscInt c = 0; c < ice.dim; ++c) bc.inflow.state[1 + c] = state[1 + c];
        bc.inflow.state[4] = state[ice.dim + 1];
      }
      PetscCall(PetscOptionsString(inflow_mat[d][s], "Inflow: the gas material that flows in (default: the first)", "", "", buf, sizeof(buf), &set));
      if (set && ice.nmat) PetscCall(MaterialIndex(ice, inflow_mat[d][s], buf, &bc.inflow.material));
      PetscCall(ReadInflowJet(ice, PetscOptionsObject, d, s, face_opt[d][s], inflow_opt[d][s]));
      // An open face: the pressure drives the flow through it, and a semi-implicit run keeps its level
      PetscCall(PetscOptionsReal(outflow_p[d][s],
                                 "Outflow: the far-field pressure that the face's ghost cells hold (Pa), >= 0; 0: zero gradient, as the other fields (a semi-implicit run with every face zero-gradient has no pressure level: it drifts)", "",
                                 bc.pressure, &bc.pressure, &set));
      if (set) {
        PetscCall(CheckRange(ice.comm, outflow_p[d][s], bc.pressure, 0, 1e12, PETSC_FALSE));
        PetscCheck(bc.type == IceBC::Outflow || bc.pressure == 0, ice.comm, PETSC_ERR_USER_INPUT, "Option %s needs %s outflow (it is %s)", outflow_p[d][s], face_opt[d][s], IceBCNames[(int)bc.type]);
      }
    }

  // Exchange coefficients (ice.md 1.8): the upper triangle in material order
  {
    for (PetscInt a = 0; a < kIceMaxMaterials; ++a)
      for (PetscInt b = 0; b < kIceMaxMaterials; ++b) {
        ice.exchange_K[a][b] = a == b ? 0 : 1e15;
        ice.exchange_H[a][b] = a == b ? 0 : 1e10;
      }
    PetscCall(
      ReadExchange(ice, PetscOptionsObject, "-ice_exchange_momentum", "Momentum exchange coefficients K_ij (kg/(m^3 s)), upper triangle in -ice_materials order, or one value for all pairs; <= 1e20 (default 1e15, ice.md 1.8)", 1e20, ice.exchange_K));
    PetscCall(ReadExchange(ice, PetscOptionsObject, "-ice_exchange_heat", "Heat exchange coefficients H_ij (W/(m^3 K)), upper triangle, or one value for all pairs; <= 1e15 (default 1e10)", 1e15, ice.exchange_H));
  }

  // Initial state: a Riemann problem, or every material uniform
  PetscCall(OptionsRealVector(PetscOptionsObject, "-ice_riemann_left", "Riemann problem: left (inside) state rho (kg/m^3), u (m/s, along x or radial), p (Pa)", rs.left, 3, &rs.set));
  PetscCall(OptionsRealVector(PetscOptionsObject, "-ice_riemann_right", "Riemann problem: right (outside) state rho (kg/m^3), u (m/s), p (Pa)", rs.right, 3, &set));
  rs.set = (PetscBool)(rs.set || set);
  PetscCall(PetscOptionsReal("-ice_riemann_position", "Riemann problem: diaphragm x (planar) or radius (cylinder, sphere), m", "", rs.position, &rs.position, nullptr));
  PetscCall(OptionsRealVector(PetscOptionsObject, "-ice_riemann_center", "Riemann problem: centre of the cylinder or sphere (m, 3 values)", rs.center, 3, nullptr));
  choice = (int)rs.shape;
  PetscCall(OptionsChoice(PetscOptionsObject, "-ice_riemann_shape", "Riemann problem: planar diaphragm normal to x, or a cylinder (about z) or sphere of the left state", RiemannShapeNames, 3, &choice, nullptr));
  rs.shape = (RiemannShape)choice;
  PetscCall(PetscOptionsString("-ice_riemann_left_material", "Riemann problem: the gas on the left (default: the first)", "", "", buf, sizeof(buf), &set));
  if (set && ice.nmat) PetscCall(MaterialIndex(ice, "-ice_riemann_left_material", buf, &rs.left_material));
  PetscCall(PetscOptionsString("-ice_riemann_right_material", "Riemann problem: the gas on the right (default: the left one)", "", "", buf, sizeof(buf), &set));
  rs.right_material = rs.left_material;
  if (set && ice.nmat) PetscCall(MaterialIndex(ice, "-ice_riemann_right_material", buf, &rs.right_material));
  if (rs.set) {
    PetscCall(CheckRange(ice.comm, "-ice_riemann_left (density)", rs.left[0], 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(CheckRange(ice.comm, "-ice_riemann_left (pressure)", rs.left[2], 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(CheckRange(ice.comm, "-ice_riemann_right (density)", rs.right[0], 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(CheckRange(ice.comm, "-ice_riemann_right (pressure)", rs.right[2], 0, PETSC_MAX_REAL, PETSC_TRUE));
  }
  {
    PetscReal fractions[kIceMaxMaterials];
    PetscInt  nf = kIceMaxMaterials;
    PetscCall(PetscOptionsRealArray("-ice_uniform_volume_fraction", "Without a Riemann problem: the volume fraction of each gas material in every cell (must sum to 1; default 1 for the first, 0 for the others)", "", fractions, &nf, &set));
    for (PetscInt m = 0; m < ice.nmat; ++m) ice.materials[m].volume_fraction = m == 0 ? 1 : 0;
    if (set) {
      PetscCheck(nf == ice.nmat, ice.comm, PETSC_ERR_USER_INPUT, "Option -ice_uniform_volume_fraction needs %" PetscInt_FMT " values (one per -ice_materials entry), got %" PetscInt_FMT, ice.nmat, nf);
      PetscReal sum = 0;
      for (PetscInt m = 0; m < ice.nmat; ++m) {
        PetscCall(CheckRange(ice.comm, "-ice_uniform_volume_fraction", fractions[m], 0, 1, PETSC_FALSE));
        ice.materials[m].volume_fraction = fractions[m];
        sum += fractions[m];
      }
      PetscCheck(std::fabs(sum - 1) < 1e-10, ice.comm, PETSC_ERR_USER_INPUT, "Option -ice_uniform_volume_fraction: the volume fractions sum to %.12g; they must sum to 1", (double)sum);
    }
  }
  PetscOptionsEnd();

  // Per material: the equation of state and the uniform initial state
  for (IceMaterial &m : ice.materials) {
    GasEOS     *eos;
    std::string prefix = m.name + "_";
    PetscCall(GasEOSCreate(ice.comm, m.name.c_str(), &eos));
    m.eos.reset(eos);
    PetscOptionsBegin(ice.comm, prefix.c_str(), "Gas material initial state", "ICE");
    PetscCall(PetscOptionsReal("-density", "Initial material density (kg/m^3), > 0 (uniform initial state; with a Riemann problem the density of the absent side's tiny mass)", "", m.density, &m.density, &set));
    PetscCall(PetscOptionsReal("-temperature", "Initial temperature (K), > 0", "", m.temperature, &m.temperature, nullptr));
    PetscCall(OptionsRealVector(PetscOptionsObject, "-velocity", "Initial velocity (m/s), one value per dimension", m.velocity, ice.dim, nullptr));
    PetscOptionsEnd();
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CreateDMs(IceSolver &ice, DM nodes)
{
  PetscInt              m, n, p;
  const PetscInt       *lnode[3] = {nullptr, nullptr, nullptr};
  std::vector<PetscInt> lcell[3];
  PetscFunctionBeginUser;
  PetscCall(DMDAGetInfo(nodes, nullptr, nullptr, nullptr, nullptr, &m, &n, &p, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr));
  PetscCall(DMDAGetOwnershipRanges(nodes, &lnode[0], &lnode[1], &lnode[2]));
  const PetscInt procs[3] = {m, n, p};
  for (PetscInt d = 0; d < ice.dim; ++d) {
    lcell[d].assign(lnode[d], lnode[d] + procs[d]);
    lcell[d].back() -= 1; // the last node of each direction starts no cell
    for (PetscInt r = 0; r < procs[d]; ++r)
      PetscCheck(lcell[d][r] >= 2 || procs[d] == 1, ice.comm, PETSC_ERR_USER_INPUT,
                 "Gas: rank slot %" PetscInt_FMT " owns %" PetscInt_FMT " cell(s) in direction %" PetscInt_FMT "; the gas solver needs at least 2 per rank: use fewer ranks or more cells", r, lcell[d][r], d);
  }
  ice.stride = ice.nmat * icef::kMatFields + icef::kCellFields;
  {
    PetscMPIInt size;
    PetscCallMPI(MPI_Comm_size(ice.comm, &size));
    const PetscReal cells = (PetscReal)ice.cells[0] * ice.cells[1] * ice.cells[2];
    PetscCall(MemoryCheck(ice.comm, "The gas cells (-grid_cells and -ice_materials)", cells / size * ice.stride * kMemoryCellEntryBytes, "use fewer cells or more ranks"));
  }
  const DMBoundaryType bt = DM_BOUNDARY_GHOSTED;
  if (ice.dim == 2) {
    PetscCall(DMDACreate2d(ice.comm, bt, bt, DMDA_STENCIL_BOX, ice.cells[0], ice.cells[1], m, n, ice.stride, 2, lcell[0].data(), lcell[1].data(), &ice.da));
    if (ice.pressure_solver == IcePressureSolver::SemiImplicit) PetscCall(DMDACreate2d(ice.comm, bt, bt, DMDA_STENCIL_STAR, ice.cells[0], ice.cells[1], m, n, 1, 1, lcell[0].data(), lcell[1].data(), &ice.da_p));
  } else {
    PetscCall(DMDACreate3d(ice.comm, bt, bt, bt, DMDA_STENCIL_BOX, ice.cells[0], ice.cells[1], ice.cells[2], m, n, p, ice.stride, 2, lcell[0].data(), lcell[1].data(), lcell[2].data(), &ice.da));
    if (ice.pressure_solver == IcePressureSolver::SemiImplicit) PetscCall(DMDACreate3d(ice.comm, bt, bt, bt, DMDA_STENCIL_STAR, ice.cells[0], ice.cells[1], ice.cells[2], m, n, p, 1, 1, lcell[0].data(), lcell[1].data(), lcell[2].data(), &ice.da_p));
  }
  PetscCall(DMSetUp(ice.da));
  PetscCall(DMDASetUniformCoordinates(ice.da, ice.lower[0] + 0.5 * ice.h[0], ice.lower[0] + (ice.cells[0] - 0.5) * ice.h[0], ice.lower[1] + 0.5 * ice.h[1], ice.lower[1] + (ice.cells[1] - 0.5) * ice.h[1], ice.lower[2] + 0.5 * ice.h[2],
                                      ice.lower[2] + (ice.cells[2] - 0.5) * ice.h[2]));
  PetscCall(DMCreateGlobalVector(ice.da, &ice.state));
  PetscCall(DMCreateLocalVector(ice.da, &ice.local));
  PetscCall(PetscObjectSetName((PetscObject)ice.state, "gas"));
  PetscInt xs[3], xm[3], gxs[3], gxm[3];
  PetscCall(DMDAGetCorners(ice.da, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(DMDAGetGhostCorners(ice.da, &gxs[0], &gxs[1], &gxs[2], &gxm[0], &gxm[1], &gxm[2]));
  for (int d = 0; d < 3; ++d) {
    ice.xs[d]  = xs[d];
    ice.xm[d]  = xm[d];
    ice.gxs[d] = gxs[d];
    ice.gxm[d] = gxm[d];
  }
  ice.lstride[0]      = 1;
  ice.lstride[1]      = gxm[0];
  ice.lstride[2]      = gxm[0] * gxm[1];
  const size_t nlocal = (size_t)gxm[0] * gxm[1] * gxm[2];
  for (PetscInt d = 0; d < ice.dim; ++d) {
    ice.face_vel[d].assign(nlocal * ice.nmat, 0);
    ice.face_vel_star[d].assign(nlocal * ice.nmat, 0);
    ice.face_spvol[d].assign(nlocal * ice.nmat, 0);
    ice.face_spvol_eff[d].assign(nlocal * ice.nmat, 0);
    ice.face_pressure[d].assign(nlocal, 0);
    ice.face_viscosity[d].assign(nlocal, 0);
  }
  if (ice.da_p) {
    // The pressure DMDA reads its own options under the KSP's prefix, so -ice_pressure_dm_mat_type
    // aij|hyprestruct selects the matrix type (hyprestruct: 3-D only, for pc pfmg/smg).
    PetscCall(PetscObjectSetOptionsPrefix((PetscObject)ice.da_p, "ice_pressure_"));
    PetscCall(DMSetFromOptions(ice.da_p));
    PetscCall(DMSetUp(ice.da_p));
    PetscCall(DMCreateGlobalVector(ice.da_p, &ice.dp));
    PetscCall(VecDuplicate(ice.dp, &ice.rhs));
    PetscCall(KSPCreate(ice.comm, &ice.ksp));
    PetscCall(KSPSetOptionsPrefix(ice.ksp, "ice_pressure_"));
    PetscCall(KSPSetDM(ice.ksp, ice.da_p));
    PetscCall(KSPSetDMActive(ice.ksp, PETSC_FALSE));
    PetscCall(KSPSetType(ice.ksp, KSPCG));
    PetscCall(KSPSetTolerances(ice.ksp, 1e-10, 1e-50, PETSC_DEFAULT, 1000));
    // Default preconditioner by dimension, from scripts/bench_ice.py (CG, rtol 1e-10, 1 rank; blast
    // at the default CFL, acoustic Courant number ~0.125, and a low-Mach flow at 35 x the acoustic
    // limit, the regime the semi-implicit path exists for). 2-D: hypre BoomerAMG, 2-7 iterations
    // per solve and the least time per step at low Mach on 65^2-257^2 (257^2: 126 ms/step against
    // PCMG 138, GAMG 161, Jacobi 377 with 610 iterations). 3-D: hypre PFMG on a MATHYPRESTRUCT
    // matrix, the fastest at low Mach by 1.6-2.7x (65^3: 468 ms/step against PCMG 749, Jacobi
    // 1040, GAMG/BoomerAMG ~1265; Uintah uses it for this equation; petsc.md 6). Jacobi is the
    // fastest while the acoustic Courant number is small (blast: 45 ms against 142 at 257^2, 297
    // against 414 at 65^3) but its iterations grow with the grid and the time step, so it is not
    // the default: pass -ice_pressure_pc_type jacobi for such runs. Any -ice_pressure_pc_type
    // overrides the default; the structured matrix is used only with pfmg/smg unless
    // -ice_pressure_dm_mat_type says otherwise.
    PC pc;
    PetscCall(KSPGetPC(ice.ksp, &pc));
    if (ice.dim == 3) PetscCall(PCSetType(pc, PCPFMG));
    else {
      PetscCall(PCSetType(pc, PCHYPRE));
      PetscCall(PCHYPRESetType(pc, "boomeramg"));
    }
    PetscCall(KSPSetFromOptions(ice.ksp));
    // A user who chooses or watches the pressure KSP (its type, preconditioner, view, monitor or
    // converged reason) gets that KSP for every solve, unless -ice_pressure_jacobi_below is given.
    PetscBool pc_type_set = PETSC_FALSE, jacobi_below_set = PETSC_FALSE;
    for (const char *name : {"-pc_type", "-ksp_type", "-ksp_view", "-ksp_monitor", "-ksp_converged_reason"}) {
      PetscBool set;
      PetscCall(PetscOptionsHasName(nullptr, "ice_pressure_", name, &set));
      pc_type_set = (PetscBool)(pc_type_set || set);
    }
    PetscOptionsBegin(ice.comm, "ice_pressure_", "Semi-implicit pressure preconditioner", "");
    PetscCall(PetscOptionsReal("-jacobi_below", "CG + Jacobi for a step whose pressure matrix has max_rows sum|offdiag|/diag below this (default preconditioner, and no -ice_pressure_ksp_type/_view/_monitor/_converged_reason, unless given; 0: never)",
                               "", ice.jacobi_below, &ice.jacobi_below, &jacobi_below_set));
    PetscCall(PetscOptionsInt("-pc_lag", "Rebuild the preconditioner every this many gas steps (it is reused by a step's later outer iterations)", "", ice.pc_lag, &ice.pc_lag, nullptr));
    PetscOptionsEnd();
    PetscCheck(ice.pc_lag >= 1, ice.comm, PETSC_ERR_USER_INPUT, "-ice_pressure_pc_lag must be at least 1");
    if (pc_type_set && !jacobi_below_set) ice.jacobi_below = 0; // the user's KSP for every solve
    if (ice.jacobi_below > 0) {
      // Its own prefix, -ice_pressure_jacobi_ (e.g. -ice_pressure_jacobi_ksp_monitor); the
      // relative tolerance is the main KSP's.
      PC        pcj;
      PetscReal rtol;
      PetscCall(KSPGetTolerances(ice.ksp, &rtol, nullptr, nullptr, nullptr));
      PetscCall(KSPCreate(ice.comm, &ice.ksp_jacobi));
      PetscCall(KSPSetOptionsPrefix(ice.ksp_jacobi, "ice_pressure_jacobi_"));
      PetscCall(KSPSetDM(ice.ksp_jacobi, ice.da_p));
      PetscCall(KSPSetDMActive(ice.ksp_jacobi, PETSC_FALSE));
      PetscCall(KSPSetType(ice.ksp_jacobi, KSPCG));
      PetscCall(KSPSetTolerances(ice.ksp_jacobi, rtol, 1e-50, PETSC_DEFAULT, 200)); // beyond that the step falls back to ksp
      PetscCall(KSPGetPC(ice.ksp_jacobi, &pcj));
      PetscCall(PCSetType(pcj, PCJACOBI));
      PetscCall(KSPSetFromOptions(ice.ksp_jacobi));
      PetscCall(PetscObjectTypeCompare((PetscObject)pcj, PCJACOBI, &pc_type_set));
      PetscCheck(pc_type_set, ice.comm, PETSC_ERR_USER_INPUT, "-ice_pressure_jacobi_pc_type: only jacobi");
    }
    PetscCall(PetscLogEventRegister("ICE_PAssemble", KSP_CLASSID, &ice.ev_p_assemble));
    PetscCall(PetscLogEventRegister("ICE_PSolve", KSP_CLASSID, &ice.ev_p_solve));
    PetscBool mat_type_set, structured;
    PetscCall(PetscOptionsHasName(nullptr, "ice_pressure_", "-dm_mat_type", &mat_type_set));
    PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, &structured, PCPFMG, PCSMG, ""));
    if (structured && !mat_type_set) PetscCall(DMSetMatType(ice.da_p, MATHYPRESTRUCT));
    PetscCall(DMCreateMatrix(ice.da_p, &ice.A));
    // Every nonzero of the DMDA's pattern is set at each assembly (pressure_implicit.cxx), so an AIJ
    // matrix is refilled without MatZeroEntries; all rows are owned, so no stash communication.
    PetscCall(PetscObjectTypeCompareAny((PetscObject)ice.A, &ice.matrix_aij, MATMPIAIJ, MATSEQAIJ, ""));
    if (ice.matrix_aij) {
      PetscCall(MatSetOption(ice.A, MAT_NO_OFF_PROC_ENTRIES, PETSC_TRUE));
      PetscCall(MatSetOption(ice.A, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
    } else { // hypre's structured matrix (3-D PFMG) has no MatGetDiagonal: no Jacobi path
      PetscCall(KSPDestroy(&ice.ksp_jacobi));
      ice.jacobi_below = 0;
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

bool IceMaterialsRequested(MPI_Comm)
{
  PetscBool set = PETSC_FALSE;
  PetscOptionsHasName(nullptr, nullptr, "-ice_materials", &set);
  return set;
}

// Exchange with the solids: -ice_exchange_momentum_solid / -ice_exchange_heat_solid, one value for
// every gas-solid pair (the gas-gas coefficients stay as read); solid-solid pairs are 0.
static PetscErrorCode ReadSolidExchange(IceSolver &ice)
{
  PetscReal K = 1e15, H = 1e10;
  PetscFunctionBeginUser;
  PetscOptionsBegin(ice.comm, "", "Gas-solid exchange", "ICE");
  PetscCall(PetscOptionsReal("-ice_exchange_momentum_solid", "Momentum exchange coefficient between each gas and each solid (kg/(m^3 s)), <= 1e20", "", K, &K, nullptr));
  PetscCall(CheckRange(ice.comm, "-ice_exchange_momentum_solid", K, 0, 1e20, PETSC_FALSE));
  PetscCall(PetscOptionsReal("-ice_exchange_heat_solid", "Heat exchange coefficient between each gas and each solid (W/(m^3 K)), <= 1e15", "", H, &H, nullptr));
  PetscCall(CheckRange(ice.comm, "-ice_exchange_heat_solid", H, 0, 1e15, PETSC_FALSE));
  PetscOptionsEnd();
  for (PetscInt a = 0; a < ice.nmat; ++a)
    for (PetscInt b = 0; b < ice.nmat; ++b) {
      if (a < ice.ngas && b < ice.ngas) continue;
      const bool pair      = a != b && (a < ice.ngas || b < ice.ngas);
      ice.exchange_K[a][b] = pair ? K : 0;
      ice.exchange_H[a][b] = pair ? H : 0;
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IceCreate(MPI_Comm comm, const IceGridSpec &grid, PetscBool help, IceSolver **out)
{
  PetscFunctionBeginUser;
  *out      = nullptr;
  auto ice  = std::make_unique<IceSolver>();
  ice->comm = comm;
  ice->dim  = grid.dim;
  for (int d = 0; d < 3; ++d) {
    ice->cells[d]   = d < grid.dim ? grid.cells[d] : 1;
    ice->lower[d]   = grid.lower[d];
    ice->h[d]       = grid.h[d];
    ice->gravity[d] = grid.gravity[d];
  }
  RiemannSetup rs;
  PetscCall(ReadOptions(*ice, rs));
  if (rs.set && !help) { // a diaphragm outside the domain would give one uniform state without a word
    const PetscReal upper0 = grid.lower[0] + grid.cells[0] * grid.h[0];
    if (rs.shape == RiemannShape::Planar)
      PetscCheck(rs.position > grid.lower[0] && rs.position < upper0, comm, PETSC_ERR_USER_INPUT, "Option -ice_riemann_position = %g m puts the diaphragm outside the domain: it must be in (%g, %g) m (x)", (double)rs.position, (double)grid.lower[0],
                 (double)upper0);
    else PetscCheck(rs.position > 0, comm, PETSC_ERR_USER_INPUT, "Option -ice_riemann_position = %g m is the radius of the %s: it must be > 0", (double)rs.position, rs.shape == RiemannShape::Sphere ? "sphere" : "cylinder");
  }
  ice->ngas = ice->nmat;
  if (ice->nmat == 0 || help) {
    if (help && !grid.solids.empty()) PetscCall(ReadSolidExchange(*ice)); // listed by -help
    for (const IceSolidSpec &s : grid.solids) delete s.eos;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCheck(!grid.axisymmetric, comm, PETSC_ERR_SUP, "Option -axisymmetric does not support gas materials (-ice_materials): the ICE cells are Cartesian");
  // the solids, after the gases; solid-solid pairs do not exchange (MPM contact handles them)
  PetscCheck(ice->nmat + (PetscInt)grid.solids.size() <= kIceMaxMaterials, comm, PETSC_ERR_USER_INPUT, "Gas and solid materials together: at most %d", kIceMaxMaterials);
  for (const IceSolidSpec &s : grid.solids) {
    IceMaterial m;
    m.name        = s.name;
    m.solid       = true;
    m.temperature = s.temperature;
    m.eos.reset(s.eos);
    ice->materials.push_back(std::move(m));
  }
  ice->nmat = (PetscInt)ice->materials.size();
  if (ice->nmat > ice->ngas) PetscCall(ReadSolidExchange(*ice));
  PetscCall(CreateDMs(*ice, grid.nodes));
  PetscClassId id;
  PetscCall(PetscClassIdRegister("burst ICE", &id));
  PetscCall(PetscLogEventRegister("ICE_Equilibrate", id, &ice->ev_equilibrate));
  PetscCall(PetscLogEventRegister("ICE_FaceVelocity", id, &ice->ev_face));
  PetscCall(PetscLogEventRegister("ICE_Pressure", id, &ice->ev_pressure));
  PetscCall(PetscLogEventRegister("ICE_Sources", id, &ice->ev_sources));
  PetscCall(PetscLogEventRegister("ICE_Exchange", id, &ice->ev_exchange));
  PetscCall(PetscLogEventRegister("ICE_Advect", id, &ice->ev_advect));
  PetscCall(PetscLogEventRegister("ICE_Ghosts", id, &ice->ev_bc));
  PetscCall(PetscLogEventRegister("ICE_TimeStep", id, &ice->ev_dt));
  PetscCall(PetscLogEventRegister("ICE_Budget", id, &ice->ev_budget));

  // The initial state (ice.md 8: sub-cell sampling of each region, 4 points per direction).
  const IceSolver &cice = *ice;
  for (PetscInt m = 0; m < cice.ngas; ++m) {
    const IceMaterial &mat        = cice.materials[m];
    const bool         in_riemann = rs.set && (m == rs.left_material || m == rs.right_material);
    if (!in_riemann) {
      PetscCheck(mat.density > 0, comm, PETSC_ERR_USER_INPUT, "Gas material %s needs -%s_density > 0 (kg/m^3)", mat.name.c_str(), mat.name.c_str());
      PetscCheck(mat.temperature > 0, comm, PETSC_ERR_USER_INPUT, "Gas material %s needs -%s_temperature > 0 (K)", mat.name.c_str(), mat.name.c_str());
    }
  }
  PetscScalar *a;
  PetscCall(IceGetLocalArray(*ice, &a));
  const PetscInt nsub = 4;
  for (PetscInt k = ice->xs[2]; k < ice->xs[2] + ice->xm[2]; ++k)
    for (PetscInt j = ice->xs[1]; j < ice->xs[1] + ice->xm[1]; ++j)
      for (PetscInt i = ice->xs[0]; i < ice->xs[0] + ice->xm[0]; ++i) {
        PetscScalar   *c      = a + ice->LocalIndex(i, j, k) * ice->stride;
        const PetscInt ijk[3] = {i, j, k};
        // fraction of the cell on the left (inside) of the diaphragm
        PetscReal left_fraction = 0;
        if (rs.set) {
          PetscInt inside = 0, total = 0;
          for (PetscInt sk = 0; sk < (ice->dim == 3 ? nsub : 1); ++sk)
            for (PetscInt sj = 0; sj < nsub; ++sj)
              for (PetscInt si = 0; si < nsub; ++si) {
                const PetscInt s[3] = {si, sj, sk};
                PetscReal      x[3] = {0, 0, 0}, r2 = 0;
                for (PetscInt d = 0; d < ice->dim; ++d) x[d] = ice->lower[d] + (ijk[d] + (s[d] + 0.5) / nsub) * ice->h[d];
                bool left;
                if (rs.shape == RiemannShape::Planar) left = x[0] < rs.position;
                else {
                  for (PetscInt d = 0; d < (rs.shape == RiemannShape::Sphere ? 3 : 2); ++d) r2 += (x[d] - rs.center[d]) * (x[d] - rs.center[d]);
                  left = r2 < rs.position * rs.position;
                }
                inside += left;
                ++total;
              }
          left_fraction = (PetscReal)inside / total;
        }
        PetscReal xc[3] = {0, 0, 0}, radial[3] = {1, 0, 0};
        for (PetscInt d = 0; d < ice->dim; ++d) xc[d] = ice->lower[d] + (ijk[d] + 0.5) * ice->h[d];
        if (rs.set && rs.shape != RiemannShape::Planar) {
          PetscReal r = 0;
          for (PetscInt d = 0; d < (rs.shape == RiemannShape::Sphere ? 3 : 2); ++d) r += (xc[d] - rs.center[d]) * (xc[d] - rs.center[d]);
          r = std::sqrt(r);
          for (PetscInt d = 0; d < 3; ++d) radial[d] = (r > 0 && d < (rs.shape == RiemannShape::Sphere ? 3 : 2)) ? (xc[d] - rs.center[d]) / r : 0;
        }
        PetscReal pressure = 0, dominant = -1, dominant_u[3] = {0, 0, 0};
        for (PetscInt m = 0; m < ice->nmat; ++m) {
          const IceMaterial &mat = ice->materials[m];
          PetscReal          fraction, rho_micro, T, u[3] = {0, 0, 0}, p;
          if (mat.solid) { // the coupling projects the particles before the first step
            fraction  = 0;
            rho_micro = mat.eos->Density(1e5, mat.temperature);
            T         = mat.temperature;
            p         = 1e5;
          } else if (rs.set && (m == rs.left_material || m == rs.right_material)) {
            // one material for both sides: the state of the side holding the cell centre;
            // two materials: each its own side's state, in proportion to the sub-cell samples
            const bool       same = rs.left_material == rs.right_material;
            const bool       left = same ? left_fraction >= 0.5 : m == rs.left_material;
            const PetscReal *st   = left ? rs.left : rs.right;
            fraction              = same ? 1 : (left ? left_fraction : 1 - left_fraction);
            rho_micro             = st[0];
            p                     = st[2];
            T                     = mat.eos->Temperature(rho_micro, p);
            for (PetscInt d = 0; d < 3; ++d) u[d] = st[1] * radial[d];
          } else {
            fraction  = rs.set ? 0 : mat.volume_fraction;
            rho_micro = mat.density;
            T         = mat.temperature;
            p         = mat.eos->Evaluate(rho_micro, T).pressure;
            for (PetscInt d = 0; d < ice->dim; ++d) u[d] = mat.velocity[d];
          }
          PetscCheck(T > 0 && std::isfinite(T), comm, PETSC_ERR_USER_INPUT, "Gas material %s: initial temperature %g K from its equation of state is not positive; check its density, pressure and -%s_eos_type parameters", mat.name.c_str(), (double)T,
                     mat.name.c_str());
          // the equilibration solves for p in [1e-6, 1e15] Pa: a state outside it cannot start
          PetscCheck(mat.solid || (p >= 1e-6 && p <= 1e15 && rho_micro <= 1e5 && T <= 1e6), comm, PETSC_ERR_USER_INPUT,
                     "Gas material %s: the initial state (density %g kg/m^3, temperature %g K, pressure %g Pa) is outside what the solver takes (pressure in [1e-6, 1e15] Pa, density <= 1e5 kg/m^3, temperature <= 1e6 K); check -%s_density, "
                     "-%s_temperature (or -ice_riemann_left/right) and -%s_eos_type parameters",
                     mat.name.c_str(), (double)rho_micro, (double)T, (double)p, mat.name.c_str(), mat.name.c_str(), mat.name.c_str());
          c[ice->Offset(m, icef::rho)]   = PetscMax(fraction, ice->rho_tiny) * rho_micro;
          c[ice->Offset(m, icef::temp)]  = T;
          c[ice->Offset(m, icef::spvol)] = 1 / rho_micro;
          c[ice->Offset(m, icef::theta)] = fraction;
          for (PetscInt d = 0; d < 3; ++d) c[ice->Offset(m, icef::vel + d)] = u[d];
          if (fraction > dominant) {
            dominant = fraction;
            pressure = p;
            for (PetscInt d = 0; d < 3; ++d) dominant_u[d] = u[d];
          }
        }
        // an absent material moves with the cell's dominant one
        for (PetscInt m = 0; m < ice->nmat; ++m)
          if (c[ice->Offset(m, icef::theta)] == 0)
            for (PetscInt d = 0; d < 3; ++d) c[ice->Offset(m, icef::vel + d)] = dominant_u[d];
        c[ice->CellOffset(icef::press)]    = pressure;
        c[ice->CellOffset(icef::press_eq)] = pressure;
      }
  PetscCall(IceRestoreLocalArray(*ice, &a));
  PetscCall(IceUpdateGhosts(*ice));
  PetscCall(IceComputeTotals(*ice, ice->initial));
  *out = ice.release();
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IceView(const IceSolver &ice, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "  gas (ICE): %" PetscInt_FMT " material(s), pressure %s, advection order %" PetscInt_FMT "%s, cfl %g (sound-speed knob %g)\n", ice.nmat, IcePressureSolverNames[(int)ice.pressure_solver],
                                   ice.advection_order, ice.advection_order == 2 && ice.compatible_fluxes ? " with compatible fluxes" : "", (double)ice.cfl, (double)ice.sound_speed_knob));
  const char *faces[3][2] = {{"xmin", "xmax"}, {"ymin", "ymax"}, {"zmin", "zmax"}};
  PetscCall(PetscViewerASCIIPrintf(viewer, "    boundaries:"));
  for (PetscInt d = 0; d < ice.dim; ++d)
    for (int s = 0; s < 2; ++s) PetscCall(PetscViewerASCIIPrintf(viewer, " %s %s", faces[d][s], IceBCNames[(int)ice.bc[d][s].type]));
  PetscCall(PetscViewerASCIIPrintf(viewer, "\n"));
  for (PetscInt d = 0; d < ice.dim; ++d)
    for (int s = 0; s < 2; ++s) {
      const IceFaceBC &bc = ice.bc[d][s];
      if (bc.type != IceBC::Inflow) continue;
      const IceInflowState *states[2] = {&bc.inflow, bc.has_jet ? &bc.jet : nullptr};
      for (int which = 0; which < 2 && states[which]; ++which) {
        const IceInflowState &in = *states[which];
        PetscCall(PetscViewerASCIIPrintf(viewer, "    inflow %s%s: %s, density %g kg/m^3, velocity (%g, %g, %g) m/s, temperature %g K", faces[d][s], which ? " jet" : (bc.has_jet ? " coflow" : ""),
                                         ice.nmat ? ice.materials[in.material].name.c_str() : "", (double)in.state[0], (double)in.state[1], (double)in.state[2], (double)in.state[3], (double)in.state[4]));
        if (which) PetscCall(PetscViewerASCIIPrintf(viewer, " within %g m of (%g, %g, %g) m along the face", (double)bc.jet_radius, (double)bc.jet_center[0], (double)bc.jet_center[1], (double)bc.jet_center[2]));
        PetscCall(PetscViewerASCIIPrintf(viewer, "\n"));
      }
    }
  for (const IceMaterial &m : ice.materials) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "    gas material %s: ", m.name.c_str()));
    PetscCall(m.eos->View(viewer));
  }
  if (ice.nmat > 1)
    for (PetscInt a = 0; a < ice.nmat; ++a)
      for (PetscInt b = a + 1; b < ice.nmat; ++b)
        PetscCall(PetscViewerASCIIPrintf(viewer, "    exchange %s-%s: K %g kg/(m^3 s), H %g W/(m^3 K)\n", ice.materials[a].name.c_str(), ice.materials[b].name.c_str(), (double)ice.exchange_K[a][b], (double)ice.exchange_H[a][b]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

IceSolver::~IceSolver()
{
  VecDestroy(&state);
  VecDestroy(&local);
  VecDestroy(&dp);
  VecDestroy(&rhs);
  MatDestroy(&A);
  KSPDestroy(&ksp);
  KSPDestroy(&ksp_jacobi);
  DMDestroy(&da_p);
  DMDestroy(&da);
}

void IceSolverDeleter::operator()(IceSolver *ice) const { delete ice; }

} // namespace burst
