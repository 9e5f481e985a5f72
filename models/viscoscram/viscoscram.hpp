// ViscoSCRAM (Bennett, Haberman, Johnson, Asay & Henson, JMPS 46 (1998) 2303; Bennett et al.,
// CMAME 151 (1998) 19; heating as Hackett & Bennett, IJNME 49 (2000) 1191): the point kernel.
//
// Pure physics at one material point, on plain arrays: no swarm, no grid, no PETSc calls, no
// allocation (the Material adapter, viscoscram_material.cxx, owns the per-particle state and the
// co-rotated frame). Per point the state is five symmetric deviatoric element stresses S_i (in the
// co-rotated frame) and the radius c of one mean penny-shaped crack. Given the mean stress at t_n,
// the rate of deformation D (co-rotated, constant over the step), dt, density and temperature,
// Update advances the state over the step and returns the deviatoric stress, the mean stress and
// the dissipated energies. The equations (mpmice-lessons.md "ViscoSCRAM"; symbols as there):
//   sigma_m' = K tr D                                                        (hypoelastic mean stress)
//   x = (c/a)^3,  xdot = 3 c^2 cdot / a^3,  S = sum S_i,  D' = dev D
//   Sdot   = (2 G D' - sum_j S_j/tau_j - xdot S) / (1 + x)                  (summed, G = sum G_i)
//   Sdot_i = 2 G_i D' - S_i/tau_i - (G_i/G) (xdot S + x Sdot)                (Bennett 1998, eq. 21)
// i.e. each element sees D' less the crack strain rate d/dt (x S)/(2 G), so the cracks soften the
// stress rate by 1/(1 + x). Crack growth (Bennett 1998 eqs. 24-31, Griffith/Dienes; the speed law
// of the reference code):
//   f = 1 if sigma_m > 0 (tension) else 0,  sigma_e = sqrt(S:S + 3 f sigma_m^2)
//   K_I = sqrt(3/2) sqrt(pi c) sigma_e                                     (eqs. 26-27)
//   mu' = (1 - f) sqrt(45 / (2 (3 - 2 mu^2))) mu                            (eq. 31, crack-face friction)
//   a_f = -mu' sigma_m sqrt(c),  K_0m = K_0 sqrt(1 + pi a_f (1 + a_f/K_0) / K_0)   (eq. 30)
//   K' = K_0m sqrt(1 + 2/m),  K_1 = K' (1 + m/2)^(1/m)                     (eqs. 28-29)
//   cdot = v_r (K_I/K_1)^m if K_I < K', else v_r (1 - (K_0m/K_I)^2)        (eq. 24)
//   v_r = min(v_max, phi A (sqrt(3/2) |D'|)^n), phi = tension factor if f = 1 else 1
// Dissipation per unit volume: viscous sum_i S_i:S_i/(2 G_i tau_i); crack either the whole work
// of the crack strain, S : d/dt(x S)/(2 G) = (xdot S:S + x S:Sdot)/(2 G) (crack_work: Hackett &
// Bennett 2000 and the reference code), or only the energy growth releases, xdot S:S/(4 G)
// (release: the crack-opening energy x S:S/(4 G) stays stored). Either way the stress work on the
// deviator equals the change of the stored energy plus the dissipation:
//   S : D' = d/dt [sum_i S_i:S_i/(4 G_i) + (release: x S:S/(4 G))] + viscous + crack.
// Temperature: dT = (viscous + crack) / (rho c_v) - Gamma T tr(D) dt.
//
// Integration: classical RK4 on (S_i, c, dissipated energies) together, with D constant and
// sigma_m linear over the step; the step is cut into n equal sub-steps only when it asks for it:
// n = ceil(max(dt lambda / r, |Delta cdot| / (r_v max cdot))), r = max_relaxation_per_substep,
// r_v = crack_rate_change_per_substep, lambda the largest of the relaxation rates 1/tau_i,
// d cdot/dc and the softening rate xdot/(1 + x), cdot and lambda at the start and at an elastic
// prediction of the end of the step, at most max_substeps. A step whose predicted K_I
// crosses K' (where eq. 24 switches branch, steep below it) gets a sub-step boundary at the
// crossing, 2m sub-steps on its sub-critical side (cdot ~ K_I^m there) and, when K_I rises through
// K', graded sub-steps after the crossing, from r_v times the time K_I takes to change by K', growing by half each, up to dt/n.
#pragma once
#include <petscsys.h>

namespace burst {
namespace viscoscram {

constexpr int kMaxElements = 5; // Maxwell elements
constexpr int kSym         = 6; // symmetric tensor components: xx, yy, zz, xy, yz, xz
constexpr int kStateSize   = kMaxElements * kSym;

enum class CrackHeating { CrackWork, Release };

struct Parameters {
  int          elements                       = 5;            // Maxwell elements in use (1..5)
  PetscReal    shear_moduli[kMaxElements]     = {};           // G_i, Pa
  PetscReal    relaxation_rates[kMaxElements] = {};           // 1/tau_i, 1/s (0: no relaxation)
  PetscReal    bulk_modulus                   = 0;            // K, Pa
  PetscReal    crack_scale                    = 1e-3;         // a, m
  PetscReal    fracture_toughness             = 500;          // K_0, Pa m^(1/2)
  PetscReal    crack_exponent                 = 10;           // m
  PetscReal    max_crack_speed                = 300;          // v_max, m/s
  PetscReal    friction                       = 0.35;         // mu (crack faces)
  PetscReal    tension_growth_factor          = 12;           // phi
  PetscReal    crack_speed_coefficient        = 0.0549251088; // A in v_r = A (sqrt(3/2)|D'|)^n, m/s at 1/s
  PetscReal    crack_speed_exponent           = 0.90564746;   // n
  PetscReal    specific_heat                  = 996;          // c_v, J/(kg K)
  PetscReal    gruneisen                      = 0;            // Gamma
  CrackHeating crack_heating                  = CrackHeating::CrackWork;
  PetscReal    max_relaxation_per_substep     = 0.5;  // sub-step h <= this / (fastest rate: 1/tau_min, d cdot/dc, softening)
  PetscReal    crack_rate_change_per_substep  = 0.25; // crack speed change per sub-step <= this * cdot; first sub-step after K_I rises through K', in units of the time K_I takes to change by K'
  int          max_substeps                   = 1000;
  // derived by Derive()
  PetscReal shear_modulus       = 0; // G = sum G_i
  PetscReal max_relaxation_rate = 0;
  PetscReal friction_factor = 0, threshold_factor = 0, growth_factor = 0, crack_scale_cubed = 0; // mu', K'/K_0m, K_1/K', a^3
  PetscReal shear_fraction[kMaxElements] = {}, viscous_weight[kMaxElements] = {};                // G_i/G, 1/(2 G_i tau_i)
  int       integer_exponent = 0;                                                                // m when it is a whole number in [1, 64] (the power by multiplication), else 0

  void Derive();
};

// What one update returns (energies per unit current volume).
struct Result {
  PetscReal deviator[kSym];      // S = sum S_i at t_{n+1} (co-rotated frame)
  PetscReal mean_stress;         // sigma_m at t_{n+1}, Pa (tension positive)
  PetscReal viscous_dissipation; // J/m^3 over the step
  PetscReal crack_dissipation;   // J/m^3 over the step
  PetscReal temperature_change;  // K
  int       substeps;
};

// Advances the element stresses S (kMaxElements x kSym, row per element, co-rotated frame) and the
// crack radius over dt. D: the rate of deformation (kSym, co-rotated frame), 1/s.
void Update(const Parameters &p, PetscReal *S, PetscReal *crack_radius, PetscReal mean_stress_old, const PetscReal D[kSym], PetscReal dt, PetscReal density, PetscReal temperature, Result *out);

// The crack growth rate cdot (m/s) of eq. 24 at deviator S (kSym), mean stress, crack radius c and
// deviatoric rate norm |D'| (Frobenius, 1/s).
PetscReal CrackRate(const Parameters &p, const PetscReal S[kSym], PetscReal mean_stress, PetscReal c, PetscReal deviatoric_rate_norm);

// S:T for symmetric tensors stored as kSym components.
inline PetscReal Contract(const PetscReal a[kSym], const PetscReal b[kSym]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2 * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5]); }

// The stored elastic energy per unit volume: sum_i S_i:S_i/(4 G_i), plus x S:S/(4 G) with release.
PetscReal StoredEnergy(const Parameters &p, const PetscReal *S, PetscReal crack_radius);

} // namespace viscoscram
} // namespace burst
