// Analytic solutions used for verification: they set the initial state, supply the body force of a
// manufactured solution, and give the exact displacement that the monitor compares against.
//   bar_mode      first axial mode of a bar fixed at x = 0 and free at x = L (verification.md 1.1):
//                 u_x = (v0/w) sin(w t) sin(b X), b = pi/(2L), w = b sqrt(E/rho), no body force.
//   axis_aligned  Wallstedt & Guilkey (2008) axis-aligned manufactured solution for the
//                 neo-Hookean solid on the unit square/cube (verification.md 1.3).
//   heat_sine     1-D heat conduction in a bar at rest on [0, L] with both ends held at T0
//                 (-mpm_heat_bc_xmin/xmax T0): T = T0 + dT sin(pi X/L) exp(-alpha pi^2 t/L^2).
//   heat_cosine   the same with insulated ends: T = T0 + dT cos(pi X/L) exp(-alpha pi^2 t/L^2).
// All read E, nu and rho from the material named by -analytic_material (default: the first); the
// heat solutions also alpha = k/(rho c) from -<mat>_thermal_conductivity and -<mat>_heat_capacity.
#pragma once
#include "simulation.hpp"

namespace burst {

class AnalyticSolution {
public:
  virtual ~AnalyticSolution()      = default;
  virtual const char *Name() const = 0;
  // Displacement u(X, t) and velocity of the material point with reference position X.
  virtual void Displacement(const PetscReal X[], PetscReal t, PetscReal u[]) const = 0;
  virtual void Velocity(const PetscReal X[], PetscReal t, PetscReal v[]) const     = 0;
  // Deformation gradient (row-major 3x3) at X, t.
  virtual void DeformationGradient(const PetscReal X[], PetscReal t, PetscReal F[]) const = 0;
  // Body force per unit mass (m/s^2) at X, t.
  virtual bool HasBodyForce() const { return false; }
  virtual void BodyForce(const PetscReal X[], PetscReal t, PetscReal b[]) const
  {
    (void)X;
    (void)t;
    for (int d = 0; d < 3; ++d) b[d] = 0;
  }
  // Temperature (K) at X, t, for the solutions that set and check one.
  virtual bool      HasTemperature() const { return false; }
  virtual PetscReal Temperature(const PetscReal X[], PetscReal t) const
  {
    (void)X;
    (void)t;
    return 0;
  }
  PetscInt dim = 2;
};

// Computes the mass-weighted RMS and the max displacement error of the particles (global).
PetscErrorCode AnalyticDisplacementError(Simulation &sim, PetscReal *rms, PetscReal *max);
// The same for the temperature (K), of the solutions with HasTemperature().
PetscErrorCode AnalyticTemperatureError(Simulation &sim, PetscReal *rms, PetscReal *max);

} // namespace burst
