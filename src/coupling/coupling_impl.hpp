// The coupling's state, shared by the files of src/coupling/ (not part of its interface).
#pragma once
#include "coupling.hpp"
#include "../../models/burn/burn.hpp"
#include <memory>

namespace burst {

// Who among the gases around a node pays its pressure work (pressure_work.cxx)
enum class WorkShare : int { Energy = 0, HeatCapacity = 1 };
inline constexpr const char *kWorkShareNames[] = {"energy", "heat_capacity", "WorkShare", "", nullptr};

struct Coupling {
  MpmSolver             *mpm    = nullptr; // the two solvers it couples (not owned)
  IceSolver             *ice    = nullptr;
  PetscInt               nsolid = 0, first = 0; // solids are ICE materials first .. first + nsolid - 1
  std::vector<PetscInt>  solid_of;              // MPM material id -> solid index
  PetscReal              p_ref = 101325;
  std::vector<PetscReal> rho0;                  // per solid: density as seeded (its coupling EOS at p_ref)
  DM                     da_mass     = nullptr; // nodes: per solid [mass, mass T, momentum (dim)], then with burning per solid its mass x energy beyond c_v T (burn.cxx)
  Vec                    mass_global = nullptr, mass_local = nullptr;
  DM                     da_inc     = nullptr; // nodes: [p, then per deformable velocity field: dv (dim), dT]
  Vec                    inc_global = nullptr, inc_local = nullptr;
  PetscInt               mass_stride = 0;
  bool                   burn_energy = false; // a solid burns: the nodes carry each solid's stored and kinetic energy (after the nsolid (2 + dim) values)
  PetscInt               nfield      = 1;     // deformable velocity fields (2 with -mpm_contact_material)
  std::vector<PetscInt>  field_of;            // per solid: its velocity field

  PetscInt IncDof(PetscInt dim) const { return 1 + nfield * (dim + 1); }
  // da_mass: per solid [mass, mass T, momentum (dim)], then with burning the burn energies' block
  PetscInt MassDof(PetscInt dim) const { return nsolid * (2 + dim + (burn_energy ? 1 : 0)); }
  PetscInt BurnEnergyOffset(PetscInt dim, PetscInt s) const { return nsolid * (2 + dim) + s; }
  // Burning (burn.cxx), per solid: the model (null: inert), the product gas (ICE material index),
  // the mass of a particle as seeded (burnt-out threshold); per local cell and solid, the fraction
  // of the solid's cell mass burnt this step.
  std::vector<std::unique_ptr<BurnModel>> burn;
  std::vector<PetscInt>                   product;
  std::vector<PetscReal>                  seed_mass;
  std::vector<PetscReal>                  burnt_fraction;
  PetscReal                               burnout                        = 1e-3; // a particle below this fraction of its seeded mass is removed
  PetscReal                               burnout_volume_ratio           = 0.5;  // a burning particle crushed below this det F burns out
  PetscReal                               burnt_mass                     = 0;    // kg converted to gas so far (this rank)
  PetscInt64                              burnt_particles                = 0;    // removed when burnt out (global)
  PetscReal                               counters[kNumCouplingCounters] = {};   // the budget counters (coupling.hpp)
  std::vector<char>                       burnt_out;                             // per local particle, reused every step
  DM                                      da_phi     = nullptr;                  // nodes: burnt fraction per solid
  Vec                                     phi_global = nullptr, phi_local = nullptr;
  DM                                      da_source     = nullptr; // cells: the burn sources, ghosts added to their owners
  Vec                                     source_global = nullptr, source_local = nullptr;
  // The work of the gas pressure on the solids (pressure_work.cxx): charged to the gases or not,
  // and the nodes that gather the particles' share of it.
  PetscBool              charge_pressure_work = PETSC_TRUE;
  DM                     da_impulse           = nullptr; // nodes: per velocity field, the impulse of the particles' (p - p_ref) I (dim)
  Vec                    impulse_global = nullptr, impulse_local = nullptr;
  DM                     da_dv    = nullptr; // cells: ice.solid_pressure_dv (dv_owned wraps it) and its ghost cells (dv_local)
  Vec                    dv_owned = nullptr, dv_local = nullptr;
  DM                     da_work     = nullptr; // nodes: the work of the gas on the solids there
  DM                     da_spread   = nullptr; // nodes: the open gas fraction and gas energy scale of the cells around (SpreadWorkToTheGas)
  Vec                    work_global = nullptr, work_local = nullptr;
  WorkShare              work_share           = WorkShare::Energy;
  PetscInt               work_spread_sweeps   = 4;    // sweeps that move a node's work toward the gas that can pay it
  PetscReal              work_open_fraction   = 1;    // a node passes on 1 - (its cells' mean open gas fraction) / this of its work
  PetscReal              work_closed_fraction = 0.05; // below this mean open gas fraction a node's work, left after the sweeps, is held
  std::vector<PetscReal> cell_bill;                   // per owned cell, reused every step: the work its gases pay
  std::vector<PetscReal> cell_open;                   // per local cell, reused every step: its open gas fraction and gas energy scale
  // -log_view events, one per phase of the coupled step (ice.md 1.2)
  // Convective heat transfer at the solids' surfaces (surface_heat.cxx)
  PetscReal     surface_h      = 0;       // W/(m^2 K); 0: off
  PetscReal     surface_heat   = 0;       // J the solids took from the gas so far (this rank)
  DM            da_surface     = nullptr; // cells, dof 1: the heat the gases of each cell give
  Vec           surface_global = nullptr, surface_local = nullptr;
  PetscBool     measure_surface_heat = PETSC_FALSE; // the heat each particle receives is added to its surface_heat field (src/phases.cxx)
  PetscLogEvent ev_project = 0, ev_burn = 0, ev_burn_particles = 0, ev_pressure = 0, ev_solid_velocity = 0, ev_increments = 0, ev_heat = 0, ev_work = 0, ev_surface = 0;
  ~Coupling()
  {
    VecDestroy(&surface_global);
    VecDestroy(&surface_local);
    DMDestroy(&da_surface);
    VecDestroy(&mass_global);
    VecDestroy(&mass_local);
    VecDestroy(&inc_global);
    VecDestroy(&inc_local);
    DMDestroy(&da_mass);
    DMDestroy(&da_inc);
    VecDestroy(&phi_global);
    VecDestroy(&phi_local);
    DMDestroy(&da_phi);
    VecDestroy(&source_global);
    VecDestroy(&source_local);
    DMDestroy(&da_source);
    VecDestroy(&work_global);
    VecDestroy(&work_local);
    DMDestroy(&da_work);
    DMDestroy(&da_spread);
    VecDestroy(&dv_owned);
    VecDestroy(&dv_local);
    DMDestroy(&da_dv);
    VecDestroy(&impulse_global);
    VecDestroy(&impulse_local);
    DMDestroy(&da_impulse);
  }
};

// The impulse of the (p - p_ref) I the particles carry, per node and velocity field, for the work the
// gases pay (pressure_work.cxx; after the pressure reaches the particles, before P2G(f) uses it).
PetscErrorCode CouplingAmbientImpulse(Coupling &c);

// Weight of node (i, j, k) for a cell it bounds: 1/2 per direction, 1 on a domain face.
inline PetscReal NodeWeight(const IceSolver &ice, const PetscInt node[3])
{
  PetscReal w = 1;
  for (PetscInt d = 0; d < ice.dim; ++d) w *= (node[d] == 0 || node[d] == ice.cells[d]) ? 1.0 : 0.5;
  return w;
}

// Calls f(node index triple, weight) for the 2^dim corner nodes of cell (i, j, k).
template <class Fn>
inline void ForEachCorner(const IceSolver &ice, PetscInt i, PetscInt j, PetscInt k, Fn &&f)
{
  for (PetscInt c = 0; c < (ice.dim == 3 ? 8 : 4); ++c) {
    const PetscInt node[3] = {i + (c & 1), j + ((c >> 1) & 1), ice.dim == 3 ? k + ((c >> 2) & 1) : 0};
    f(node, NodeWeight(ice, node));
  }
}

// Calls f(local cell index, inside) for the 2^dim cells around node (i, j, k); `inside` says whether
// the cell is in the domain (the others are boundary ghosts).
template <class Fn>
inline void ForEachCellAroundNode(const IceSolver &ice, PetscInt i, PetscInt j, PetscInt k, Fn &&f)
{
  for (PetscInt cc = 0; cc < (ice.dim == 3 ? 8 : 4); ++cc) {
    const PetscInt cell[3] = {i - 1 + (cc & 1), j - 1 + ((cc >> 1) & 1), ice.dim == 3 ? k - 1 + ((cc >> 2) & 1) : 0};
    bool           inside  = true;
    for (PetscInt d = 0; d < ice.dim; ++d) inside = inside && cell[d] >= 0 && cell[d] < ice.cells[d];
    f(ice.LocalIndex(cell[0], cell[1], cell[2]), inside);
  }
}

} // namespace burst
