// Johnson-Cook flow stress (paper eq. 10; Johnson & Cook 1983):
//   sigma_f = [A + B eps_p^n] [1 + C ln(rate*)] [1 - T*^m],  rate* = eps_p_dot / rate0,
//   T* = (T - T_r) / (T_m - T_r) clamped to [0, 1], T_m from the material's melt model.
// Rate regularisation (NOTES eq. 10, models.md 2.10): the logarithm takes the smoothly floored rate
// sqrt(eps_p_dot^2 + min_rate^2) (-MAT_flow_stress_min_rate, default 1e-3 /s): smooth, equal to the
// literal law well above the floor (1e-6 relative at 1 /s), and for min_rate > rate0 exp(-1/C) the
// factor stays positive. sigma_f = 0 at and above melt.
#include "flow_stress.hpp"
#include <cmath>
#include <limits>

namespace burst {

class JohnsonCook final : public FlowStressModel<JohnsonCook> {
public:
  PetscReal A = 0, B = 0, n = 1, C = 0, m = 1, rate0 = 1, room_temperature = 298;

  // What one chain of evaluations caches (a return mapping's point): the thermal factor of its (T,
  // T_m) and the series anchors below. The von Mises return runs two points at once, each with its
  // own Lane, so their chains overlap and neither evicts the other's anchors (von_mises.hpp).
  struct Lane {
    // Last (T, T_m) and its thermal factor and derivative (a return mapping holds T and T_m fixed
    // over its iterations, so a one-entry cache hits on every iteration after the first; NaN: empty).
    PetscReal T = std::numeric_limits<PetscReal>::quiet_NaN(), Tm = std::numeric_limits<PetscReal>::quiet_NaN(), thermal = 1, d_thermal = 0;
    // Series anchors (see Power and LogRate; NaN: none)
    PetscReal eps = std::numeric_limits<PetscReal>::quiet_NaN(), eps_inverse = 0, power = 0;
    PetscReal rate = std::numeric_limits<PetscReal>::quiet_NaN(), rate_inverse = 0, rate0 = std::numeric_limits<PetscReal>::quiet_NaN(), log = 0;
  };

private:
  mutable Lane lane_; // the two-argument Evaluate's (GTN's returns, the point-by-point callers)
  // The rate factor at zero plastic rate (every yield test and elastic point: the smooth floor gives
  // the floor itself), for the (min_rate, rate0, C) it was computed with (NaN: empty).
  mutable PetscReal cached_floor_ = std::numeric_limits<PetscReal>::quiet_NaN(), cached_rate0_ = std::numeric_limits<PetscReal>::quiet_NaN(), cached_C_ = std::numeric_limits<PetscReal>::quiet_NaN(), cached_floor_rate_ = 1;

  // Series continuation of eps^n and ln(rate) from the last values computed with libm (the anchors):
  // a return's Newton iterates and line-search trials move little once near the root, where
  // eps^n = a^n (1 + x)^n, x = (eps - a)/a, and ln r = ln b + ln(1 + y), y = (r - b)/b, by their
  // Taylor series to x^8 (|x|, |y| <= kSeriesRange = 2^-7: the first term left out is below 1e-19
  // relative, so each value is the libm one to a few ulp; the anchor is always a libm value, so the
  // error does not accumulate). A far point calls pow/log and becomes the anchor. The polynomials
  // are summed by Estrin's scheme with the anchor's inverse stored: a Newton iterate waits on this
  // value, and a Horner chain of eight multiply-adds after a division took longer than glibc's log.
  // Every return starts a point with its yield test at delta_strain = 0, which drops the lane's
  // anchors: a point's values never depend on the point evaluated before it (the same on any rank
  // count, and whichever lane runs it).
  static constexpr PetscReal kSeriesRange = 0.0078125;
  mutable PetscReal          anchor_n_    = std::numeric_limits<PetscReal>::quiet_NaN();
  mutable PetscReal          binomial_[9] = {}; // n choose k, k = 0..8, for anchor_n_

  // c0 + c1 x + ... + c8 x^8 by Estrin's scheme (a dependency chain of four multiply-adds)
  static inline PetscReal Estrin8(const PetscReal *c, PetscReal x)
  {
    const PetscReal x2 = x * x, x4 = x2 * x2;
    const PetscReal p01 = c[0] + c[1] * x, p23 = c[2] + c[3] * x, p45 = c[4] + c[5] * x, p67 = c[6] + c[7] * x;
    return (p01 + p23 * x2) + ((p45 + p67 * x2) + c[8] * x4) * x4;
  }

  // eps^n (eps > 0)
  inline PetscReal Power(PetscReal eps, Lane &lane) const
  {
    const PetscReal x = (eps - lane.eps) * lane.eps_inverse;
    if (n == anchor_n_ && std::fabs(x) <= kSeriesRange) return lane.power * Estrin8(binomial_, x);
    if (n != anchor_n_) {
      binomial_[0] = 1;
      for (int k = 1; k <= 8; ++k) binomial_[k] = binomial_[k - 1] * (n - (k - 1)) / k;
      anchor_n_ = n;
    }
    lane.eps         = eps;
    lane.eps_inverse = 1 / eps;
    lane.power       = std::pow(eps, n);
    return lane.power;
  }

  // ln(r / rate0) (r > 0)
  inline PetscReal LogRate(PetscReal r, Lane &lane) const
  {
    static constexpr PetscReal log1p_over_y[9] = {1, -1.0 / 2, 1.0 / 3, -1.0 / 4, 1.0 / 5, -1.0 / 6, 1.0 / 7, -1.0 / 8, 1.0 / 9}; // ln(1 + y)/y
    const PetscReal            y               = (r - lane.rate) * lane.rate_inverse;
    if (rate0 == lane.rate0 && std::fabs(y) <= kSeriesRange) return lane.log + y * Estrin8(log1p_over_y, y);
    lane.rate         = r;
    lane.rate_inverse = 1 / r;
    lane.rate0        = rate0;
    lane.log          = std::log(r / rate0);
    return lane.log;
  }

public:
  inline void Evaluate(const FlowPoint &x, FlowValue &y) const { Evaluate(x, y, lane_); }

  inline void Evaluate(const FlowPoint &x, FlowValue &y, Lane &lane) const
  {
    if (x.delta_strain == 0) lane.eps = lane.rate = std::numeric_limits<PetscReal>::quiet_NaN(); // a new point (see Power)
    const PetscReal eps      = x.plastic_strain > 0 ? x.plastic_strain : 0;
    const PetscReal power    = eps > 0 ? Power(eps, lane) : 0;
    const PetscReal strain   = A + B * power;
    const PetscReal d_strain = eps > 0 ? B * n * power / eps : (n < 1 ? 0 : (n == 1 ? B : 0));
    PetscReal       rate, d_rate;
    if (x.plastic_strain_rate == 0) { // (the yield test of every point): the floor's rate factor, kept; slope 0
      if (!(min_rate == cached_floor_ && rate0 == cached_rate0_ && C == cached_C_)) {
        PetscReal slope;
        cached_floor_rate_ = 1 + C * std::log(SmoothRateFloor(0.0, min_rate, &slope) / rate0);
        cached_floor_      = min_rate;
        cached_rate0_      = rate0;
        cached_C_          = C;
      }
      rate   = cached_floor_rate_;
      d_rate = 0;
    } else {
      PetscReal       slope;
      const PetscReal effective = SmoothRateFloor(x.plastic_strain_rate, min_rate, &slope);
      rate                      = 1 + C * LogRate(effective, lane);
      d_rate                    = C / effective * slope;
    }
    // The thermal factor depends on T and T_m only, which a return mapping holds fixed over its
    // iterations: computed once per point and reused (the same bits as recomputing it).
    if (!(x.temperature == lane.T && x.melt_temperature == lane.Tm)) {
      const PetscReal homologous = (x.temperature - room_temperature) / (x.melt_temperature - room_temperature);
      lane.thermal = 1, lane.d_thermal = 0;
      if (homologous >= 1) lane.thermal = 0;
      else if (homologous > 0) {
        const PetscReal tm = std::pow(homologous, m);
        lane.thermal       = 1 - tm;
        lane.d_thermal     = -m * tm / homologous / (x.melt_temperature - room_temperature);
      }
      lane.T  = x.temperature;
      lane.Tm = x.melt_temperature;
    }
    const PetscReal thermal = lane.thermal, d_thermal = lane.d_thermal;
    y.sigma         = strain * rate * thermal;
    y.d_strain      = d_strain * rate * thermal;
    y.d_rate        = strain * d_rate * thermal;
    y.d_temperature = strain * rate * d_thermal;
  }

  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const MaterialConstants &material) override
  {
    PetscFunctionBeginUser;
    room_temperature = material.room_temperature;
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-A", "Johnson-Cook yield stress A (Pa)", &A));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-B", "Johnson-Cook hardening modulus B (Pa)", &B));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-n", "Johnson-Cook hardening exponent n (-)", &n));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-C", "Johnson-Cook rate coefficient C (-)", &C));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-m", "Johnson-Cook thermal softening exponent m (-)", &m));
    PetscCall(PetscOptionsReal("-reference_rate", "Johnson-Cook reference plastic strain rate (1/s)", "", rate0, &rate0, nullptr));
    PetscCall(PetscOptionsReal("-room_temperature", "Johnson-Cook room temperature T_r (K)", "", room_temperature, &room_temperature, nullptr));
    PetscCall(PetscOptionsReal("-min_rate", "Floor of the plastic strain rate in ln(rate*) (1/s)", "", min_rate, &min_rate, nullptr));
    const std::string P = PetscOptionsObject->prefix;
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "A").c_str(), A, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "B").c_str(), B, 0, PETSC_MAX_REAL, PETSC_FALSE));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "n").c_str(), n, 0, 1, PETSC_TRUE));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "C").c_str(), C, 0, 1, PETSC_FALSE));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "m").c_str(), m, 0, 10, PETSC_TRUE));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "reference_rate").c_str(), rate0, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "min_rate").c_str(), min_rate, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCheck(C == 0 || 1 + C * std::log(min_rate / rate0) > 0, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "Option -%smin_rate = %g makes the Johnson-Cook rate factor 1 + C ln(rate*) non-positive; it must exceed %g 1/s", P.c_str(), (double)min_rate,
               (double)(rate0 * std::exp(-1 / C)));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  PetscErrorCode View(PetscViewer viewer) const override
  {
    PetscFunctionBeginUser;
    PetscCall(PetscViewerASCIIPrintf(viewer, "  flow stress: johnson_cook A %g Pa, B %g Pa, n %g, C %g, m %g, reference rate %g 1/s, T_r %g K, rate floor %g 1/s\n", (double)A, (double)B, (double)n, (double)C, (double)m, (double)rate0,
                                     (double)room_temperature, (double)min_rate));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
};

PetscErrorCode JohnsonCookCreate(SubModel **model) { return CreateSubModel<JohnsonCook>(model); }

} // namespace burst
