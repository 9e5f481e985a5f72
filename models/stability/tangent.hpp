// Pieces shared by the stability checks (drucker.cxx, acoustic.cxx, becker.cxx).
#pragma once
#include "../plasticity/chunk.hpp"
#include <cmath>

namespace burst {

// Slope of the flow stress along the plastic path (models.md 4.11 and pitfall 8): the strain
// hardening plus, when adiabatic, the thermal softening of the plastic heating,
// H = d sigma_f/d eps_p + (d sigma_f/dT) chi sigma_f/(rho Cp). The rate term of the return's Newton
// slope (c.rate_hardening) is left out: it is a time-step artefact, not material stability.
inline PetscReal EffectiveHardening(const Chunk &c, int k)
{
  PetscReal       H    = c.hardening[k];
  const PetscReal heat = c.density[k] * c.specific_heat[k];
  if (c.adiabatic && heat > 0) H += c.thermal_softening[k] * c.taylor_quinney * c.flow_stress[k] / heat;
  return H;
}

// Principal values (descending) of the deviatoric part of the symmetric part of S (closed form via
// the Lode angle).
inline void PrincipalDeviator(const PetscReal *S, PetscReal ev[3])
{
  const PetscReal m  = (S[0] + S[4] + S[8]) / 3;
  const PetscReal d0 = S[0] - m, d1 = S[4] - m, d2 = S[8] - m;
  const PetscReal o01 = 0.5 * (S[1] + S[3]), o02 = 0.5 * (S[2] + S[6]), o12 = 0.5 * (S[5] + S[7]);
  const PetscReal J2 = 0.5 * (d0 * d0 + d1 * d1 + d2 * d2) + o01 * o01 + o02 * o02 + o12 * o12;
  if (J2 <= 0) {
    ev[0] = ev[1] = ev[2] = 0;
    return;
  }
  const PetscReal J3  = d0 * (d1 * d2 - o12 * o12) - o01 * (o01 * d2 - o12 * o02) + o02 * (o01 * o12 - d1 * o02);
  const PetscReal inv = 3 / J2;
  PetscReal       r   = 0.5 * J3 * inv * std::sqrt(inv); // J3/2 (3/J2)^(3/2)
  r                   = r > 1 ? 1 : (r < -1 ? -1 : r);
  const PetscReal t = std::acos(r) / 3, a = 2 * std::sqrt(J2 / 3);
  const PetscReal cos_t = std::cos(t), sin_t = std::sin(t); // cos(t + 2 pi/3) = -cos t/2 - sin t sqrt(3)/2
  ev[0] = a * cos_t;
  ev[2] = -a * (0.5 * cos_t + 0.8660254037844386 * sin_t);
  ev[1] = -ev[0] - ev[2];
}

} // namespace burst
