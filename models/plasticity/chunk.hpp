// The per-point state that the sub-models of the hypoelastic-plastic update share (the "sockets" of
// the paper's Algorithm 1, Uintah's PlasticityState), held for a chunk of particles as structure of
// arrays. The stress update (elastic_plastic.cxx) walks a material's particles in chunks of
// kChunk; each sub-model family is called once per chunk (one virtual call per chunk, flat loops
// inside), and the flow-stress model is inlined into the return mapping (flow_stress.hpp).
//
// Conventions (models.md 0): SI units, stress tension-positive, pressure p = -tr(sigma)/3
// compression-positive, strain rates are equivalent (von Mises) rates.
#pragma once
#include "../petsc_compat.hpp"

namespace burst {

constexpr int kChunk      = 64; // particles per chunk
constexpr int kMaxHistory = 4;  // history variables a flow model may keep per particle

struct Chunk {
  int       n = 0;                // particles in this chunk
  PetscInt  index[kChunk];        // their indices in the particle arrays
  PetscReal dt             = 0;   // s
  PetscReal density0       = 0;   // reference density, kg/m^3
  PetscReal taylor_quinney = 0.9; // chi of eq. 18
  int       adiabatic      = 1;   // plastic work heats the point (stability tangents add thermal softening)

  // Kinematics and thermodynamic state (inputs to the sub-models)
  PetscReal density[kChunk];         // current density rho = m / V, kg/m^3
  PetscReal temperature[kChunk];     // K, at t_n (updated by plastic heating)
  PetscReal specific_energy[kChunk]; // internal energy per unit mass from the stress work, J/kg
  PetscReal trace_D[kChunk];         // tr D, 1/s
  PetscReal total_rate[kChunk];      // sqrt(2/3 D':D'), 1/s
  PetscReal mean_stress_old[kChunk]; // tr(sigma_n)/3, Pa

  // Filled by the equation of state, shear modulus, melt and specific heat models
  PetscReal pressure[kChunk];         // p at t_{n+1}, Pa (compression positive)
  PetscReal bulk_modulus[kChunk];     // tangent K = rho dp/drho, Pa (wave speed and GTN return)
  PetscReal shear_modulus[kChunk];    // mu, Pa
  PetscReal melt_temperature[kChunk]; // Tm, K
  PetscReal specific_heat[kChunk];    // Cp, J/(kg K)
  PetscReal gruneisen[kChunk];        // Gamma rho0 / rho (isentropic heating term), -

  // Plastic state (in: t_n, out: t_{n+1})
  PetscReal plastic_strain[kChunk];       // equivalent plastic strain
  PetscReal plastic_strain_rate[kChunk];  // 1/s
  PetscReal porosity[kChunk];             // void volume fraction f
  PetscReal damage[kChunk];               // scalar damage D
  PetscReal history[kChunk][kMaxHistory]; // flow-model history (e.g. MTS sigma_hat_e)

  // Results of the return mapping, read by damage, stability and failure
  PetscReal flow_stress[kChunk];       // sigma_f at t_{n+1}, Pa
  PetscReal hardening[kChunk];         // strain hardening d sigma_f / d eps_p, Pa (what the stability tangents use)
  PetscReal rate_hardening[kChunk];    // d sigma_f / d eps_p_dot / dt, Pa: the rate part of the return's Newton
                                       // slope; left out of the stability tangents (it grows as dt shrinks)
  PetscReal thermal_softening[kChunk]; // d sigma_f / dT, Pa/K
  PetscReal delta_plastic_strain[kChunk];
  PetscReal trace_plastic_strain[kChunk]; // tr(Delta eps_p) (GTN), -
  PetscReal equivalent_stress[kChunk];    // q = sqrt(3/2 s:s) at t_{n+1}, Pa
  PetscReal triaxiality[kChunk];          // sigma_m / sigma_eq
  PetscReal fracture_strain[kChunk];      // eps_f of the damage model (for TEPLA-F), +inf if none
  PetscReal deviator[kChunk][9];          // s at t_{n+1} in the co-rotated frame
  PetscReal D_hat[kChunk][9];             // D in the co-rotated frame, 1/s
  int       plastic[kChunk];              // 1 if the step yielded
  int       unstable[kChunk];             // bit 1: Drucker, bit 2: loss of hyperbolicity
  int       failed_point = -1;            // set by a return mapping that did not converge (for the message)
};

} // namespace burst
