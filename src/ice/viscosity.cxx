// Artificial viscosity at shocks: a face (edge) viscosity limited by the smoothness of the velocity
// (Christensen 1990, UCRL-JC-105269; Caramana, Shashkov & Whalen, J. Comput. Phys. 144 (1998) 70).
//
// ICE's Lagrangian phase has no dissipation of its own, and the remap's upwinding vanishes at the
// foot of a shock that runs into gas at rest, so a shock carries a two-cell pressure spike of 15-18 %
// of its jump (Sod at any resolution; verify_ice.py overshoot). For the face between cells L and R in
// direction d, with w the cells' gas mass-averaged velocity component d and dw = w_R - w_L < 0
// (compression),
//   q_f = rho_f (1 - psi) min(c2 |dw| + c1 c_f, 0.2 h_d/dt) |dw|,
// rho_f the mean of the cells' gas bulk densities, c_f the larger of their gases' mass-averaged sound
// speeds, and psi in [0, 1] Christensen's limiter of the velocity jumps
// on either side: psi = max(0, min(1, (r_L + r_R)/2, 2 r_L, 2 r_R)), r_L = (w_L - w_LL)/dw,
// r_R = (w_RR - w_R)/dw. On smooth flow psi -> 1 and q vanishes faster than the truncation error, so
// the scheme keeps its order; at a shock psi = 0. q_f adds to the face pressure that the gases feel in
// the sources (sources.cxx), in both the momentum and the face work, so momentum and total energy
// stay conserved and the kinetic energy it removes becomes heat. The solids (MPM) are left out: their
// shocks are the particles' business (-mpm_artificial_viscosity), and a steel-filled cell's sound
// speed and density would make q of a few m/s GPa.
#include "ice.hpp"
#include <cmath>

namespace burst {

PetscReal IceFaceViscosity(const IceSolver &ice, const PetscScalar *a, PetscInt d, PetscInt R)
{
  const PetscInt S = ice.stride, st = ice.lstride[d], n = ice.ngas;
  // the gases' mass-averaged velocity component d, bulk density and mass-averaged c^2 (= v/kappa)
  // in the cell at local index idx
  auto velocity = [&](PetscInt idx, PetscReal *density, PetscReal *sound2) {
    const PetscScalar *c  = a + idx * S;
    PetscReal          mu = 0, m = 0, mc2 = 0;
    for (PetscInt k = 0; k < n; ++k) {
      const PetscReal rho = c[ice.Offset(k, icef::rho)];
      mu += rho * c[ice.Offset(k, icef::vel + d)];
      m += rho;
      if (sound2) mc2 += rho * c[ice.Offset(k, icef::spvol)] / c[ice.Offset(k, icef::kappa)];
    }
    if (density) *density = m;
    if (sound2) *sound2 = mc2 / m;
    return mu / m;
  };
  PetscReal       rho_L, rho_R, c2_L, c2_R;
  const PetscReal wL = velocity(R - st, &rho_L, &c2_L), wR = velocity(R, &rho_R, &c2_R);
  const PetscReal dw = wR - wL;
  if (!(dw < 0)) return 0;
  const PetscReal rL = (wL - velocity(R - 2 * st, nullptr, nullptr)) / dw, rR = (velocity(R + st, nullptr, nullptr) - wR) / dw;
  const PetscReal psi = PetscMax(0.0, PetscMin(PetscMin(1.0, 0.5 * (rL + rR)), PetscMin(2 * rL, 2 * rR)));
  if (psi >= 1) return 0;
  const PetscReal c2 = PetscMax(c2_L, c2_R);
  // explicit in time: the viscosity's speed is capped at 0.2 h/dt (its diffusion limit nu dt/h^2 <=
  // 1/(2 dim)), which binds only where dt exceeds the acoustic limit (the semi-implicit pressure)
  const PetscReal speed = PetscMin(ice.viscosity[1] * -dw + ice.viscosity[0] * std::sqrt(c2), 0.2 * ice.h[d] / ice.dt);
  return 0.5 * (rho_L + rho_R) * (1 - psi) * speed * -dw;
}

} // namespace burst
