// Mechanical Threshold Stress flow model (paper eq. 11; Follansbee & Kocks 1988, Goto et al. 2000;
// models.md 4.6 and 2.11-2.12):
//   sigma_f = sigma_a + (mu/mu0) [S_i sigma_hat_i + S_e sigma_hat_e]
//   S_x = [1 - (k T/(g0x mu b^3) ln(edot0x/edot))^{1/q_x}]^{1/p_x}, both brackets clamped at 0 (NOTES)
//   sigma_hat_es = sigma_es0 (edot/edot_es0)^{k T/(mu b^3 g0es)}
//   d sigma_hat_e/d eps_p = theta = theta0 [1 - F(X)] + theta_IV F(X), X = sigma_hat_e/sigma_hat_es,
//   F(X) = tanh(alpha X)/tanh(alpha) (NORMALISED, as Uintah and models.md 7.2; the paper prints
//   tanh(alpha X)), theta0 = a0 + a1 ln edot + a2 sqrt(edot) - a3 T with a3 >= 0 (Table 1), clamped at 0.
// mu is the current shear modulus (FlowPoint::shear_modulus, from the material's shear model) and mu0
// the shear model's ReferenceShearModulus (MaterialConstants::shear_modulus passed here). edot is the
// plastic rate floored at -min_rate (models.md 2.2). sigma_f = 0 at and above melt.
// sigma_hat_e is a per-particle history variable (history[0], Pa), integrated with the plastic strain
// increment de of the step by the explicit trapezoidal (Heun) rule at the step's rate and T
//   s* = h + theta(h) de,  sigma_hat_e = h + [theta(h) + theta(s*)] de / 2,
// so the Newton iteration of the return sees the hardening, and UpdateHistory stores the same value
// after convergence. No cap at sigma_hat_es: sigma_hat_e is the structure (eq. 11's last line,
// sigma_hat_e^{n+1} = sigma_hat_e^n + theta Delta eps) and changes only with plastic strain. Above
// saturation (X > 1, when the rate drops or the point heats) theta keeps its formula: F <= 1/tanh(alpha),
// so theta -> theta_IV - (theta0 - theta_IV)(1/tanh(alpha) - 1), stage-IV hardening for HY-100
// (theta_IV 200 MPa), slow dynamic recovery towards X = 1 for theta_IV = 0 (copper). At a constant
// rate and T, X approaches 1 from below and the curves are those of a cap (models.md 7.2 to 1e-3 MPa).
// (Issue 12: a cap at the current sigma_hat_es(edot_p) dropped a hardened HY-100 point's sigma_hat_e
// from ~450 to ~255 MPa in one plastic step of no strain at 3 /s as the wall unloaded, with zero
// hardening and the cap's thermal slope; the adiabatic Drucker check then failed 44 % of the
// particles of cylinder2d_hy100, tests/unit/test_submodels.cxx MTS.HistoryChangesOnlyWithPlasticStrain.)
// Derivatives are analytic (incl. the chain through theta(s*) and sigma_hat_es); d_temperature is the
// partial at fixed mu (the flow model does not know dmu/dT of the shear model).
#include "flow_stress.hpp"
#include <cmath>

namespace burst {

class MTSFlow final : public FlowStressModel<MTSFlow> {
public:
  PetscReal sigma_a = 0, k_over_b3 = 0, mu0 = 0;
  PetscReal sigma_i = 0, g0i = 1, edot0i = 1e13, p_i = 0.5, q_i = 1.5;
  PetscReal g0e = 0, edot0e = 0, p_e = 0, q_e = 0;
  PetscReal a0 = 0, a1 = 0, a2 = 0, a3 = 0, theta_IV = 0, alpha = 0, tanh_alpha = 1;
  PetscReal edot_es0 = 0, g0es = 0, sigma_es0 = 0;

  struct Scale {
    PetscReal S = 1, d_rate = 0, d_T = 0;
  };
  struct Theta {
    PetscReal theta, d_se, d_theta0, d_ses;
  };
  // Rate- and temperature-dependent terms of one evaluation.
  struct State {
    Scale     Si, Se;
    PetscReal ses, ses_r, ses_T, th0, th0_r, th0_T;
    PetscReal rate_slope; // d(smoothly floored rate)/d(plastic rate), flow_point.hpp
  };
  struct Evolved {
    PetscReal se, d_de, d_rate, d_T;
  };

  // S = [1 - z^{1/q}]^{1/p}, z = (k/b^3)(T/mu)/g0 ln(rate0/rate) clamped at 0, inner bracket too.
  inline Scale Factor(PetscReal T, PetscReal mu, PetscReal rate, PetscReal g0, PetscReal rate0, PetscReal p, PetscReal q) const
  {
    Scale           s;
    const PetscReal L = std::log(rate0 / rate), z_T = k_over_b3 / (mu * g0) * L, z = z_T * T;
    if (z <= 0) return s;
    const PetscReal zq = std::pow(z, 1 / q), inner = 1 - zq;
    if (inner <= 0) return Scale{0, 0, 0};
    s.S                = std::pow(inner, 1 / p);
    const PetscReal dz = -(s.S / (p * inner)) * (zq / (q * z)); // dS/dz
    s.d_rate           = dz * (-k_over_b3 * T / (mu * g0 * rate));
    s.d_T              = dz * z_T;
    return s;
  }

  inline State Terms(const FlowPoint &x) const
  {
    State           st;
    const PetscReal T = x.temperature, mu = x.shear_modulus, r = SmoothRateFloor(x.plastic_strain_rate, min_rate, &st.rate_slope);
    if (sigma_i > 0) st.Si = Factor(T, mu, r, g0i, edot0i, p_i, q_i);
    else st.Si = Scale{0, 0, 0};
    st.Se               = Factor(T, mu, r, g0e, edot0e, p_e, q_e);
    const PetscReal e_T = k_over_b3 / (mu * g0es), L = std::log(r / edot_es0); // exponent = e_T T
    st.ses             = sigma_es0 * std::exp(e_T * T * L);
    st.ses_r           = st.ses * e_T * T / r;
    st.ses_T           = st.ses * e_T * L;
    const PetscReal sq = std::sqrt(r);
    st.th0             = a0 + a1 * std::log(r) + a2 * sq - a3 * T;
    st.th0_r           = a1 / r + 0.5 * a2 / sq;
    st.th0_T           = -a3;
    if (st.th0 < 0) st.th0 = st.th0_r = st.th0_T = 0;
    return st;
  }

  // theta(X) for every X >= 0: above saturation (X > 1, after a drop of the rate or heating) the same
  // formula, F rising to 1/tanh(alpha): theta < theta_IV, negative (dynamic recovery) if theta_IV is
  // small against theta0 (copper, theta_IV = 0), positive for HY-100 (stage IV).
  inline Theta Hardening(PetscReal se, const State &st) const
  {
    const PetscReal X  = se / st.ses;
    const PetscReal th = std::tanh(alpha * X), F = th / tanh_alpha, dF = alpha * (1 - th * th) / tanh_alpha;
    return Theta{st.th0 * (1 - F) + theta_IV * F, (theta_IV - st.th0) * dF / st.ses, 1 - F, -(theta_IV - st.th0) * dF * X / st.ses};
  }

  // sigma_hat_e after the increment de from h (Heun, no cap) and its derivatives.
  inline Evolved Evolve(PetscReal h, PetscReal de, const State &st) const
  {
    const Theta     t1   = Hardening(h, st);
    const PetscReal t1_r = t1.d_theta0 * st.th0_r + t1.d_ses * st.ses_r, t1_T = t1.d_theta0 * st.th0_T + t1.d_ses * st.ses_T;
    const PetscReal s1 = h + t1.theta * de, s1_de = t1.theta, s1_r = t1_r * de, s1_T = t1_T * de;
    const Theta     t2   = Hardening(s1, st);
    const PetscReal t2_r = t2.d_theta0 * st.th0_r + t2.d_ses * st.ses_r + t2.d_se * s1_r;
    const PetscReal t2_T = t2.d_theta0 * st.th0_T + t2.d_ses * st.ses_T + t2.d_se * s1_T;
    const PetscReal se   = h + 0.5 * (t1.theta + t2.theta) * de;
    return Evolved{se, 0.5 * (t1.theta + t2.theta) + 0.5 * de * t2.d_se * s1_de, 0.5 * de * (t1_r + t2_r), 0.5 * de * (t1_T + t2_T)};
  }

  inline void Evaluate(const FlowPoint &x, FlowValue &y) const
  {
    if (x.temperature >= x.melt_temperature || x.shear_modulus <= 0) {
      y = FlowValue();
      return;
    }
    const State     st    = Terms(x);
    const Evolved   e     = Evolve(x.history[0], x.delta_strain, st);
    const PetscReal ratio = x.shear_modulus / mu0;
    y.sigma               = sigma_a + ratio * (st.Si.S * sigma_i + st.Se.S * e.se);
    y.d_strain            = ratio * st.Se.S * e.d_de;
    y.d_rate              = st.rate_slope * ratio * (st.Si.d_rate * sigma_i + st.Se.d_rate * e.se + st.Se.S * e.d_rate);
    y.d_temperature       = ratio * (st.Si.d_T * sigma_i + st.Se.d_T * e.se + st.Se.S * e.d_T);
  }

  inline void UpdateHistory(const FlowPoint &x, PetscReal de, PetscReal *history) const
  {
    if (x.temperature >= x.melt_temperature || x.shear_modulus <= 0) return;
    history[0] = Evolve(history[0], de, Terms(x)).se;
  }
  int         NumHistory() const override { return 1; }
  const char *HistoryName(int) const override { return "mts_sigma_hat_e"; }
  PetscReal   InitialHistory(int) const override { return 0; }

  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const MaterialConstants &material) override
  {
    const std::string P = PetscOptionsObject->prefix;

    auto Range = [&](const char *name, PetscReal v, PetscReal lo, PetscReal hi, PetscBool open) { return CheckRange(PETSC_COMM_WORLD, ("-" + P + name).c_str(), v, lo, hi, open); };
    PetscFunctionBeginUser;
    mu0 = material.shear_modulus;
    PetscCheck(mu0 > 0, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "MTS flow model -%s: the reference shear modulus mu0 of the shear model must be > 0 (got %g Pa)", P.c_str(), (double)mu0);
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-sigma_a", "MTS athermal stress sigma_a (Pa), >= 0", &sigma_a));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-k_over_b3", "MTS Boltzmann constant over Burgers vector cubed k/b^3 (Pa/K), > 0", &k_over_b3));
    PetscCall(PetscOptionsReal("-sigma_i", "MTS intrinsic threshold stress sigma_hat_i (Pa), >= 0; 0 drops the intrinsic term", "", sigma_i, &sigma_i, nullptr));
    if (sigma_i > 0) {
      PetscCall(OptionsRequiredReal(PetscOptionsObject, "-g0i", "MTS intrinsic normalised activation energy g0i (-), > 0", &g0i));
      PetscCall(OptionsRequiredReal(PetscOptionsObject, "-edot0i", "MTS intrinsic reference strain rate edot0i (1/s), > 0", &edot0i));
      PetscCall(OptionsRequiredReal(PetscOptionsObject, "-p_i", "MTS intrinsic exponent p_i (-), in (0, 1]", &p_i));
      PetscCall(OptionsRequiredReal(PetscOptionsObject, "-q_i", "MTS intrinsic exponent q_i (-), in [1, 2]", &q_i));
    }
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-g0e", "MTS evolution normalised activation energy g0e (-), > 0", &g0e));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-edot0e", "MTS evolution reference strain rate edot0e (1/s), > 0", &edot0e));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-p_e", "MTS evolution exponent p_e (-), in (0, 1]", &p_e));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-q_e", "MTS evolution exponent q_e (-), in [1, 2]", &q_e));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-a0", "MTS hardening theta0 = a0 + a1 ln(edot) + a2 sqrt(edot) - a3 T: a0 (Pa), >= 0", &a0));
    PetscCall(PetscOptionsReal("-a1", "MTS hardening a1 (Pa)", "", a1, &a1, nullptr));
    PetscCall(PetscOptionsReal("-a2", "MTS hardening a2 (Pa s^1/2)", "", a2, &a2, nullptr));
    PetscCall(PetscOptionsReal("-a3", "MTS hardening a3 (Pa/K), >= 0: theta0 falls with T (Table 1 sign; negate a signed +a3 T fit)", "", a3, &a3, nullptr));
    PetscCall(PetscOptionsReal("-theta_IV", "MTS stage-IV hardening rate theta_IV (Pa), >= 0", "", theta_IV, &theta_IV, nullptr));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-alpha", "MTS saturation shape alpha in F(X) = tanh(alpha X)/tanh(alpha) (-), > 0", &alpha));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-edot_es0", "MTS saturation reference strain rate edot_es0 (1/s), > 0", &edot_es0));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-g0es", "MTS saturation normalised activation energy g0es (-), > 0", &g0es));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-sigma_es0", "MTS saturation threshold stress at 0 K sigma_hat_es0 (Pa), > 0", &sigma_es0));
    PetscCall(PetscOptionsReal("-min_rate", "Floor of the plastic strain rate fed to the MTS model (1/s), > 0", "", min_rate, &min_rate, nullptr));
    PetscCall(Range("sigma_a", sigma_a, 0, PETSC_MAX_REAL, PETSC_FALSE));
    PetscCall(Range("k_over_b3", k_over_b3, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(Range("sigma_i", sigma_i, 0, PETSC_MAX_REAL, PETSC_FALSE));
    if (sigma_i > 0) {
      PetscCall(Range("g0i", g0i, 0, PETSC_MAX_REAL, PETSC_TRUE));
      PetscCall(Range("edot0i", edot0i, 0, PETSC_MAX_REAL, PETSC_TRUE));
      PetscCall(Range("p_i", p_i, 0, 1, PETSC_TRUE));
      PetscCall(Range("q_i", q_i, 1, 2, PETSC_FALSE));
    }
    PetscCall(Range("g0e", g0e, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(Range("edot0e", edot0e, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(Range("p_e", p_e, 0, 1, PETSC_TRUE));
    PetscCall(Range("q_e", q_e, 1, 2, PETSC_FALSE));
    PetscCall(Range("a0", a0, 0, PETSC_MAX_REAL, PETSC_FALSE));
    PetscCall(Range("a3", a3, 0, PETSC_MAX_REAL, PETSC_FALSE));
    PetscCall(Range("theta_IV", theta_IV, 0, PETSC_MAX_REAL, PETSC_FALSE));
    PetscCall(Range("alpha", alpha, 0, 100, PETSC_TRUE));
    PetscCall(Range("edot_es0", edot_es0, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(Range("g0es", g0es, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(Range("sigma_es0", sigma_es0, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(Range("min_rate", min_rate, 0, PETSC_MAX_REAL, PETSC_TRUE));
    tanh_alpha = std::tanh(alpha);
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  PetscErrorCode View(PetscViewer viewer) const override
  {
    PetscFunctionBeginUser;
    PetscCall(PetscViewerASCIIPrintf(viewer, "  flow stress: mts sigma_a %g Pa, k/b^3 %g Pa/K, mu0 %g Pa, rate floor %g 1/s\n", (double)sigma_a, (double)k_over_b3, (double)mu0, (double)min_rate));
    PetscCall(PetscViewerASCIIPrintf(viewer, "    intrinsic: sigma_i %g Pa, g0i %g, edot0i %g 1/s, p_i %g, q_i %g\n", (double)sigma_i, (double)g0i, (double)edot0i, (double)p_i, (double)q_i));
    PetscCall(PetscViewerASCIIPrintf(viewer, "    evolution: g0e %g, edot0e %g 1/s, p_e %g, q_e %g; theta0 = %g + %g ln(edot) + %g sqrt(edot) - %g T Pa, theta_IV %g Pa, alpha %g (F = tanh(alpha X)/tanh(alpha))\n", (double)g0e, (double)edot0e,
                                     (double)p_e, (double)q_e, (double)a0, (double)a1, (double)a2, (double)a3, (double)theta_IV, (double)alpha));
    PetscCall(PetscViewerASCIIPrintf(viewer, "    saturation: sigma_es0 %g Pa, edot_es0 %g 1/s, g0es %g\n", (double)sigma_es0, (double)edot_es0, (double)g0es));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
};

PetscErrorCode MTSFlowCreate(SubModel **model) { return CreateSubModel<MTSFlow>(model); }

} // namespace burst
