// Steady Burn (ice.md 3.3; Uintah HE/Steady_Burn.cc): the Ward-Son-Brewster (WSB, Combust. Flame 114
// (1998) 556) steady deflagration of HMX, with Uintah's ignition logic.
//
// Ignition (the caller does the 3x3x3 neighbourhood search and fills BurnInput):
//   M_min/M_max < 0.7 at the cell's nodes, i.e. mass_contrast = (M_max - M_min)/M_max > 0.3,
//   at least one reactant particle in the cell (n_particles >= 1),
//   T_hot > T_ign (some neighbour with <= BoundaryParticles particles holds a material with volume
//   fraction > 0.2 hotter than T_ign), and p >= p_th (p: the pressure of the neighbour with the
//   largest product volume fraction; T_s: the solid temperature T0 of the neighbour with the
//   largest reactant volume fraction).
// Burn rate: the surface temperature T_s solves T_s = F(T_s),
//   F(T_s)  = T0 + Q_c/C_p + (Q_g/C_p) Da/(sqrt(1 + Da) + 1)^2,
//   Da      = 4 kappa_g B_g W^2 P^2/(C_p R^2 mdot^2)   (Uintah's code: W^2, dimensionally consistent),
//   mdot    = sqrt(kappa_c rho_c A_c R T_s^2 exp(-E_c/(R T_s)) / (C_p E_c (T_s - T0 - Q_c/(2 C_p)))),
// and mdot'' = mdot(T_s); Q = Q_c + Q_g.
// Root bracket (derived): Da/(sqrt(1 + Da) + 1)^2 = (s - 1)/(s + 1) with s = sqrt(1 + Da) lies in
// [0, 1), so g(T) = T - F(T) has g <= 0 at T_lo = T0 + Q_c/C_p and g > 0 at T_hi = T0 + (Q_c + Q_g)/C_p.
// On [T_lo, T_hi] mdot is increasing (its minimum, Uintah's Ts_max ~ C2 + R C2^2/E_c with
// C2 = T0 + Q_c/(2 C_p), lies below T_lo for T0 up to ~1500 K), so F decreases and the root is unique.
// It is found by Newton's method safeguarded by bisection on the bracket, from 850 K (Uintah's start),
// to |g| < 1e-6 K. g'(T) = 1 + (Q_g/C_p) Da (dln mdot^2/dT)/(s (s + 1)^2),
// dln mdot^2/dT = 2/T + E_c/(R T^2) - 1/(T - T0 - Q_c/(2 C_p)).
//
// T0 is clamped to [T0_min, T0_max] (default [200, 550] K) before the solve. Why: the WSB fit is for
// a cold (ambient) reactant; as T0 rises the condensed-phase heat alone lifts the surface to
// T0 + Q_c/C_p and the gas-flame term, which carries the pressure dependence, collapses: at 1 MPa
// T_s - T0 - Q_c/C_p is 157 K at T0 = 300 K, 12 K at 500 K, 2.7 K at 550 K and 0.6 K at 600 K, while
// mdot doubles every ~50 K (4.0, 15.7, 32.6, 68.7 kg/(m^2 s)) (derived from the formulas above).
// ice.md 3.3 warns that from T0 ~ 550 K the root sits at T0 + Q_c/C_p, outside the model's range, so
// the default ceiling is 550 K (= T_ign): a reactant hotter than that burns at the 550 K rate; the
// floor only guards against an unset (0 K) temperature. The clamped T0 is what enters the rate; the
// energy bookkeeping still uses the cell's own solid temperature (ice.md 2.4).
// Options (prefix -<material>_): -burn_steady_{A_c,E_c,B_g,Q_c,Q_g,kappa_g,kappa_c,C_p,W,R,p_th,
// T_ign,boundary_particles,T0_min,T0_max}.
#include "options.hpp"
#include <algorithm>
#include <cmath>

namespace burst {

class SteadyBurn final : public BurnModel {
public:
  // PBX 9501/HMX values of ice.md 3.3 (Uintah SteadyBurn_2dRT, DDT, TBurner_2dRT inputs)
  PetscReal R                  = 8.314;    // J/(mol K)
  PetscReal A_c                = 1.637e15; // 1/s, condensed-phase pre-exponential factor
  PetscReal E_c                = 1.76e5;   // J/mol, condensed-phase activation energy
  PetscReal B_g                = 1.6e-3;   // m^3/(kg s K^2), gas-phase pre-exponential factor
  PetscReal Q_c                = 4.0e5;    // J/kg, condensed-phase heat release
  PetscReal Q_g                = 3.018e6;  // J/kg, gas-phase heat release
  PetscReal kappa_g            = 0.07;     // W/(m K), gas conductivity
  PetscReal kappa_c            = 0.2;      // W/(m K), condensed-phase conductivity (Uintah's inputs; the guide's table says 0.02)
  PetscReal C_p                = 1400;     // J/(kg K)
  PetscReal W                  = 0.0342;   // kg/mol, product molecular weight
  PetscReal p_th               = 5e4;      // Pa
  PetscReal T_ign              = 550;      // K
  PetscInt  boundary_particles = 3;        // BP: the caller's neighbourhood search counts neighbours with <= BP particles
  PetscReal T0_min             = 200;      // K
  PetscReal T0_max             = 550;      // K

  bool Ignites(const BurnInput &in) const override { return in.mass_contrast > 0.3 && in.n_particles >= 1 && in.T_hot > T_ign && in.p >= p_th; }

  // mdot(T) and dln(mdot^2)/dT for bulk temperature T0 and reactant density rho.
  void Rate(PetscReal T, PetscReal T0, PetscReal rho, PetscReal *mdot, PetscReal *dlnm2) const
  {
    const PetscReal d = T - T0 - Q_c / (2 * C_p); // > Q_c/(2 C_p) on the bracket
    *mdot             = std::sqrt(kappa_c * rho * A_c * R * T * T * std::exp(-E_c / (R * T)) / (C_p * E_c * d));
    *dlnm2            = 2 / T + E_c / (R * T * T) - 1 / d;
  }

  // Surface temperature and burn rate at bulk temperature T0 (already clamped), pressure P, density rho.
  PetscErrorCode Solve(PetscReal T0, PetscReal P, PetscReal rho, PetscReal *Ts_out, PetscReal *mdot_out) const
  {
    PetscFunctionBeginUser;
    const PetscReal K  = 4 * kappa_g * B_g * W * W * P * P / (C_p * R * R); // Da = K/mdot^2
    PetscReal       lo = T0 + Q_c / C_p, hi = T0 + (Q_c + Q_g) / C_p;
    PetscReal       T = 850, m = 0, dlnm2 = 0, g_prev = PETSC_MAX_REAL;
    if (!(T > lo && T < hi)) T = 0.5 * (lo + hi);
    for (int it = 0; it < 200; ++it) {
      Rate(T, T0, rho, &m, &dlnm2);
      const PetscReal Da = K / (m * m), s = std::sqrt(1 + Da);
      const PetscReal g = T - (T0 + Q_c / C_p + (Q_g / C_p) * Da / ((s + 1) * (s + 1)));
      if (std::fabs(g) < 1e-6) {
        *Ts_out   = T;
        *mdot_out = m;
        PetscFunctionReturn(PETSC_SUCCESS);
      }
      if (g < 0) lo = T; // g increases through the root
      else hi = T;
      const PetscReal dg = 1 + (Q_g / C_p) * Da * dlnm2 / (s * (s + 1) * (s + 1));
      PetscReal       Tn = T - g / dg;
      // bisect when Newton leaves the bracket or does not halve the residual: at GPa pressures it
      // jumps from side to side of the root without closing in (measured at 1.39 GPa)
      if (!(Tn > lo && Tn < hi) || std::fabs(g) > 0.5 * g_prev) Tn = 0.5 * (lo + hi);
      g_prev = std::fabs(g);
      if (Tn == T || hi - lo <= 1e-13 * T) { // the root is bracketed to double precision: where
        *Ts_out   = T;                       // g is steep (high pressure) |g| < 1e-6 K may be out
        *mdot_out = m;                       // of reach of one ulp of T
        PetscFunctionReturn(PETSC_SUCCESS);
      }
      T = Tn;
    }
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED, "Steady Burn: the surface temperature did not converge (T0 %g K, P %g Pa, rho %g kg/m^3, last T_s %g K)", (double)T0, (double)P, (double)rho, (double)T);
  }

  PetscErrorCode MassFlux(const BurnInput &in, PetscReal *mdot, PetscReal *T_surf) const override
  {
    PetscFunctionBeginUser;
    PetscCheck(in.rho_s > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Steady Burn needs the reactant density, got rho_s = %g kg/m^3", (double)in.rho_s);
    const PetscReal T0 = std::min(std::max(in.T_s, T0_min), T0_max);
    PetscCall(Solve(T0, std::max(in.p, (PetscReal)0), in.rho_s, T_surf, mdot));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscReal HeatOfReaction() const override { return Q_c + Q_g; }
  PetscReal IgnitionTemperature() const override { return T_ign; }

  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const char[]) override
  {
    const PetscReal big = PETSC_MAX_REAL;
    PetscFunctionBeginUser;
    PetscCall(BurnOptionsReal(PetscOptionsObject, "-burn_steady_A_c", "Steady Burn (WSB): condensed-phase pre-exponential factor A_c (1/s), > 0", &A_c, 0, big, PETSC_TRUE));
    PetscCall(BurnOptionsReal(PetscOptionsObject, "-burn_steady_E_c", "Steady Burn (WSB): condensed-phase activation energy E_c (J/mol), > 0", &E_c, 0, big, PETSC_TRUE));
    PetscCall(BurnOptionsReal(PetscOptionsObject, "-burn_steady_B_g", "Steady Burn (WSB): gas-phase pre-exponential factor B_g (m^3/(kg s K^2)), >= 0", &B_g, 0, big, PETSC_FALSE));
    PetscCall(BurnOptionsReal(PetscOptionsObject, "-burn_steady_Q_c", "Steady Burn (WSB): condensed-phase heat release Q_c (J/kg), > 0", &Q_c, 0, big, PETSC_TRUE));
    PetscCall(BurnOptionsReal(PetscOptionsObject, "-burn_steady_Q_g", "Steady Burn (WSB): gas-phase heat release Q_g (J/kg), >= 0", &Q_g, 0, big, PETSC_FALSE));
    PetscCall(BurnOptionsReal(PetscOptionsObject, "-burn_steady_kappa_g", "Steady Burn (WSB): gas thermal conductivity kappa_g (W/(m K)), >= 0", &kappa_g, 0, big, PETSC_FALSE));
    PetscCall(BurnOptionsReal(PetscOptionsObject, "-burn_steady_kappa_c", "Steady Burn (WSB): condensed-phase thermal conductivity kappa_c (W/(m K)), > 0", &kappa_c, 0, big, PETSC_TRUE));
    PetscCall(BurnOptionsReal(PetscOptionsObject, "-burn_steady_C_p", "Steady Burn (WSB): specific heat C_p (J/(kg K)), > 0", &C_p, 0, big, PETSC_TRUE));
    PetscCall(BurnOptionsReal(PetscOptionsObject, "-burn_steady_W", "Steady Burn (WSB): molecular weight of the products W (kg/mol), > 0", &W, 0, big, PETSC_TRUE));
    PetscCall(BurnOptionsReal(PetscOptionsObject, "-burn_steady_R", "Steady Burn (WSB): universal gas constant R (J/(mol K)), > 0", &R, 0, big, PETSC_TRUE));
    PetscCall(BurnOptionsReal(PetscOptionsObject, "-burn_steady_p_th", "Steady Burn: ignition pressure threshold p_th (Pa), >= 0", &p_th, 0, big, PETSC_FALSE));
    PetscCall(BurnOptionsReal(PetscOptionsObject, "-burn_steady_T_ign", "Steady Burn: ignition temperature T_ign (K), > 0", &T_ign, 0, big, PETSC_TRUE));
    PetscCall(PetscOptionsInt("-burn_steady_boundary_particles", "Steady Burn: a neighbour cell with at most this many particles can ignite the cell (-), >= 0", "BurnModel", boundary_particles, &boundary_particles, nullptr));
    PetscCall(CheckRange(PetscOptionsObject->comm, Prefixed(PetscOptionsObject->prefix, "-burn_steady_boundary_particles").c_str(), (PetscReal)boundary_particles, 0, PETSC_MAX_REAL, PETSC_FALSE));
    PetscCall(BurnOptionsReal(PetscOptionsObject, "-burn_steady_T0_min", "Steady Burn: lower clamp of the bulk reactant temperature T0 in the rate (K), > 0", &T0_min, 0, big, PETSC_TRUE));
    PetscCall(BurnOptionsReal(PetscOptionsObject, "-burn_steady_T0_max", "Steady Burn: upper clamp of the bulk reactant temperature T0 in the rate (K), >= T0_min", &T0_max, T0_min, big, PETSC_FALSE));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscErrorCode View(PetscViewer viewer) const override
  {
    PetscFunctionBeginUser;
    PetscCall(PetscViewerASCIIPrintf(viewer, "  burn model: steady_burn (WSB) A_c %g 1/s, E_c %g J/mol, B_g %g m^3/(kg s K^2), Q_c %g J/kg, Q_g %g J/kg, kappa_g %g W/(m K), kappa_c %g W/(m K), C_p %g J/(kg K), W %g kg/mol, R %g J/(mol K)\n",
                                     (double)A_c, (double)E_c, (double)B_g, (double)Q_c, (double)Q_g, (double)kappa_g, (double)kappa_c, (double)C_p, (double)W, (double)R));
    PetscCall(PetscViewerASCIIPrintf(viewer, "    ignites if T > %g K within %" PetscInt_FMT "-particle neighbours and p >= %g Pa; T0 clamped to [%g, %g] K\n", (double)T_ign, boundary_particles, (double)p_th, (double)T0_min, (double)T0_max));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
};

PetscErrorCode SteadyBurnCreate(BurnModel **model)
{
  *model = new SteadyBurn();
  return PETSC_SUCCESS;
}

} // namespace burst
