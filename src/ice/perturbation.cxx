// Smooth initial perturbations of the gas (the verification problems of tests/verify_ice.py
// acoustic and low_mach): a Gaussian g = exp(-|x - x0|^2 / (2 w^2)) laid over the uniform initial
// state of IceCreate, in every material present in a cell.
//   -ice_perturbation acoustic   isentropic pressure pulse at rest: p = p0 (1 + A g), density and
//                                temperature on the isentrope through (rho0, T0) (integrated with
//                                the material's own EOS: drho/dp = 1/c^2, dT/dp = T (dP/dT)_rho /
//                                (rho^2 c_v c^2)). In linear acoustics it splits into two half
//                                pulses that travel at -c and +c.
//   -ice_perturbation entropy    temperature spot at uniform pressure: T = T0 (1 + A g), density from
//                                the EOS at p0; advected unchanged by a uniform flow.
//   -ice_perturbation checkerboard  the two-cell pressure mode p = p0 (1 + A g (-1)^(i+j+k)), each
//                                material on its isentrope as for acoustic: the mode a cell-centred
//                                pressure with node-averaged gradients could leave undamped
//                                (tests/verify_solid_pressure.py checkerboard).
// -ice_perturbation_center gives 1 to dim coordinates: with one, |x - x0| is the distance along x
// (a planar pulse); with more, the distance in those directions.
#include "ice.hpp"
#include "util.hpp"
#include <cmath>

namespace burst {

enum class IcePerturbation : int { None = 0, Acoustic = 1, Entropy = 2, Checkerboard = 3 };
static const char *const IcePerturbationNames[] = {"none", "acoustic", "entropy", "checkerboard"};

// (rho, T) on the isentrope through (rho, T) at pressure p0 moved to pressure p1 (RK4 in p).
static void Isentrope(const GasEOS &eos, PetscReal p0, PetscReal p1, PetscReal *rho, PetscReal *T)
{
  const int       nsteps = 16;
  const PetscReal dp     = (p1 - p0) / nsteps;

  auto rhs = [&](PetscReal r, PetscReal t, PetscReal *dr, PetscReal *dt) {
    const GasEOSPoint s  = eos.Evaluate(r, t);
    const PetscReal   c2 = eos.SoundSpeed2(r, t);
    *dr                  = 1 / c2;
    *dt                  = t * s.dp_dT / (r * r * eos.cv * c2);
  };
  PetscReal r = *rho, t = *T;
  for (int n = 0; n < nsteps; ++n) {
    PetscReal k1r, k1t, k2r, k2t, k3r, k3t, k4r, k4t;
    rhs(r, t, &k1r, &k1t);
    rhs(r + 0.5 * dp * k1r, t + 0.5 * dp * k1t, &k2r, &k2t);
    rhs(r + 0.5 * dp * k2r, t + 0.5 * dp * k2t, &k3r, &k3t);
    rhs(r + dp * k3r, t + dp * k3t, &k4r, &k4t);
    r += dp / 6 * (k1r + 2 * k2r + 2 * k3r + k4r);
    t += dp / 6 * (k1t + 2 * k2t + 2 * k3t + k4t);
  }
  *rho = r;
  *T   = t;
}

PetscErrorCode IceApplyPerturbation(IceSolver &ice)
{
  int       kind      = 0;
  PetscReal amplitude = 1e-3, width = -1, center[3] = {0, 0, 0};
  PetscInt  ncenter = 3;
  PetscBool set;
  PetscFunctionBeginUser;
  PetscOptionsBegin(ice.comm, "", "Gas (ICE) initial perturbation", "ICE");
  PetscCall(
    OptionsChoice(PetscOptionsObject, "-ice_perturbation",
                  "Smooth Gaussian perturbation of the uniform initial gas state: none, acoustic (isentropic pressure pulse at rest), entropy (temperature spot at uniform pressure), checkerboard (two-cell pressure mode under a Gaussian envelope)",
                  IcePerturbationNames, 4, &kind, nullptr));
  PetscCall(PetscOptionsReal("-ice_perturbation_amplitude", "Relative amplitude A of the perturbation (pressure for acoustic, temperature for entropy)", "", amplitude, &amplitude, nullptr));
  PetscCall(CheckRange(ice.comm, "-ice_perturbation_amplitude", amplitude, -0.5, 0.5, PETSC_FALSE));
  PetscCall(PetscOptionsReal("-ice_perturbation_width", "Gaussian width w (m) of the perturbation, exp(-r^2/(2 w^2)), > 0", "", width, &width, nullptr));
  PetscCall(PetscOptionsRealArray("-ice_perturbation_center", "Centre of the perturbation (m): one value (planar along x) or up to dim values", "", center, &ncenter, &set));
  PetscOptionsEnd();
  if (kind == (int)IcePerturbation::None) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(width > 0, ice.comm, PETSC_ERR_USER_INPUT, "Option -ice_perturbation %s needs -ice_perturbation_width > 0 (m)", IcePerturbationNames[kind]);
  PetscCheck(set && ncenter >= 1 && ncenter <= ice.dim, ice.comm, PETSC_ERR_USER_INPUT, "Option -ice_perturbation %s needs -ice_perturbation_center with 1 to %" PetscInt_FMT " coordinates (m)", IcePerturbationNames[kind], ice.dim);

  PetscScalar   *a;
  const PetscInt S = ice.stride;
  PetscCall(IceGetLocalArray(ice, &a));
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        PetscScalar   *c      = a + ice.LocalIndex(i, j, k) * S;
        const PetscInt ijk[3] = {i, j, k};
        PetscReal      r2     = 0;
        for (PetscInt d = 0; d < ncenter; ++d) {
          const PetscReal x = ice.lower[d] + (ijk[d] + 0.5) * ice.h[d];
          r2 += (x - center[d]) * (x - center[d]);
        }
        const PetscReal g        = std::exp(-0.5 * r2 / (width * width));
        PetscReal       pressure = 0, dominant = -1;
        for (PetscInt m = 0; m < ice.nmat; ++m) {
          const GasEOS   &eos   = *ice.materials[m].eos;
          const PetscReal theta = c[ice.Offset(m, icef::theta)];
          PetscReal       rho = 1 / c[ice.Offset(m, icef::spvol)], T = c[ice.Offset(m, icef::temp)];
          const PetscReal p0 = eos.Evaluate(rho, T).pressure;
          PetscReal       p  = p0;
          if (kind == (int)IcePerturbation::Acoustic || kind == (int)IcePerturbation::Checkerboard) {
            const PetscReal sign = kind == (int)IcePerturbation::Checkerboard && (i + j + k) % 2 ? -1 : 1;
            p                    = p0 * (1 + sign * amplitude * g);
            Isentrope(eos, p0, p, &rho, &T);
          } else {
            T   = T * (1 + amplitude * g);
            rho = eos.Density(p0, T);
            PetscCheck(rho > 0, ice.comm, PETSC_ERR_USER_INPUT, "Gas material %s: no density gives p = %g Pa at T = %g K (-ice_perturbation entropy)", ice.materials[m].name.c_str(), (double)p0, (double)T);
          }
          c[ice.Offset(m, icef::rho)]   = PetscMax(theta, ice.rho_tiny) * rho;
          c[ice.Offset(m, icef::temp)]  = T;
          c[ice.Offset(m, icef::spvol)] = 1 / rho;
          if (theta > dominant) {
            dominant = theta;
            pressure = p;
          }
        }
        c[ice.CellOffset(icef::press)]    = pressure;
        c[ice.CellOffset(icef::press_eq)] = pressure;
      }
  PetscCall(IceRestoreLocalArray(ice, &a));
  PetscCall(IceUpdateGhosts(ice));
  PetscCall(IceComputeTotals(ice, ice.initial));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
