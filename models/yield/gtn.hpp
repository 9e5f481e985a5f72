// Gurson-Tvergaard-Needleman yield condition (paper eqs. 13-14) and its full return mapping
// (Aravas, IJNME 24 (1987) 1395; models.md 4.7, pitfall 2.1).
//
//   Phi(sigma_m, q, sigma_f, f*) = (q/sigma_f)^2 + 2 q1 f* cosh(3 q2 sigma_m/(2 sigma_f)) - (1 + q3 f*^2)
//   f* = f (f <= f_c),  f_c + k (f - f_c) (f > f_c)                                     (eq. 14)
//
// Return (backward Euler, associated flow). Unknowns: dv = tr(Delta eps_p) and dq = Delta eps_q
// (equivalent deviatoric plastic strain), from the elastic trial state (sigma_m,tr = -p_tr from the
// EOS, q_tr = sqrt(3/2 s_tr:s_tr)):
//   sigma_m = sigma_m,tr - K dv,      q = q_tr - 3 mu dq,      s = (q/q_tr) s_tr
//   f       = f_n + (1 - f_n) dv      (eq. 16, growth implicit; see "Porosity" below)
//   (1 - f) sigma_f(eps_M,n + de, de/dt, T) de = sigma_m dv + q dq        (matrix plastic work -> de)
//   R1 = Phi(sigma_m, q, sigma_f, f*(f)) = 0
//   R2 = dv dPhi/dq - dq dPhi/dsigma_m = 0    (normality; scaled by sigma_f/2:
//        R2 = dv q/sigma_f - dq (3/2) q1 q2 f* sinh(x), x = 3 q2 sigma_m/(2 sigma_f))
// solved by a 2x2 Newton on (dv, dq) with the exact Jacobian. For every Newton iterate the matrix
// strain increment de is solved from the plastic-work equation by an inner scalar Newton, so
// sigma_f is always consistent; its derivatives d(de)/d(dv), d(de)/d(dq) come from the implicit
// function theorem and enter the Jacobian. The flow model is fed the matrix plastic rate de/dt
// floored at flow.min_rate, as in the radial return (MakeFlowPoint); the rate term of the
// hardening enters only above the floor.
// A non-hydrostatic point is first returned by the one-level Newton on (dv, dq, de) (SolveCoupled:
// the work equation as a third residual, one flow evaluation per iterate, warm-started from the
// previous step's plastic rate, else from the trial state); the nested iteration above (Solve) runs
// only where that fails, with the fallbacks below after it.
// Safeguards: the iterates stay in the box dv between 0 and sigma_m,tr/K (sigma_m keeps its sign:
// dv has the sign of dPhi/dsigma_m, i.e. of sigma_m), dv >= -f_n/(1 - f_n) (voids close at most to
// f = 0; under strong compression the solution has f_{n+1} small but positive, since the hydrostatic
// extent of the surface grows without bound as f* -> 0) and 0 <= dq <= q_tr/(3 mu); a Newton step is
// projected onto the box and halved until the merit Phi^2 + (R2/scale)^2 decreases.
// Convergence: |Phi| <= tol (at f = 0, Phi ~ 2 (q - sigma_f)/sigma_f, the radial return's test) and
// |R2| <= tol (|dv q/sigma_f| + |dq (3/2) q1 q2 f* sinh x|) (relative normality error).
//
// Special cases:
// - f* = 0 (f_n = 0): dPhi/dsigma_m = 0, so the Newton keeps dv = 0 exactly, sigma_m = sigma_m,tr and
//   the iteration is the scalar radial return on dq with de = dq q/sigma_f = dq at convergence: the
//   von Mises result (tested).
// - q_tr = 0 (pure hydrostatic trial state; also q_tr <= 1e-12 sigma_f, round-off deviators): dq = 0,
//   the deviator is left as it is, and the return is a scalar Newton on dv alone (Phi = 0).
// - Elastic (Phi_tr <= 0 with f*_n and sigma_f at de = 0), sigma_f <= 0, mu <= 0 or K <= 0: the trial
//   state stands (as in the radial return; the failure check reads sigma_f <= 0).
// - cosh/sinh argument: for |x| > 30 (the reference's clip), cosh is continued linearly,
//   cosh(30) + sinh(30)(|x| - 30), which keeps Phi convex, C^1 and finite. It changes the surface
//   only where 2 q1 f* cosh(30) < 1, i.e. f* < ~6e-14 for q1 = 1.5.
// - f* is capped at 0.99 f*_u, f*_u = 1/(q1 + sqrt(q1^2 - q3)) the porosity at which the yield
//   surface shrinks to a point (1/q1 for q3 = q1^2); beyond it eq. 13 has a spurious second branch.
//   At the cap the shear strength is about 1% of sigma_f (q3 = q1^2). With the 4340 set
//   (f_c 0.05, k 4) the cap is reached at f ~ 0.20.
//
// Porosity: the return uses f_{n+1} = f_n + (1 - f_n) dv (growth, eq. 16, with the explicit factor
// (1 - f_n)) inside Phi and the work equation, so the returned stress lies on the yield surface of the
// porosity the material stores, provided the material's update is the same: elastic_plastic.cxx
// adds exactly (1 - f_n) trace_plastic_strain when -MAT_porosity_growth is on. With growth off the
// material must set GTNParameters::growth = false (then f_{n+1} = f_n in the return). Nucleation
// (eq. 17) is explicit: elastic_plastic adds it after the return, and it enters the yield surface
// from the next step. The return does not write c.porosity.
// Explosive growth: normality with the implicit f reads dv (q/sigma_f - dq (3/2) q1 q2 (1 - f_n)
// sinh x) = dq (3/2) q1 q2 f_n sinh x, so when the step's deviatoric strain exceeds the e-folding
// strain of void growth, dq (3/2) q1 q2 sinh(x) > q/sigma_f (small f, high triaxiality, huge
// steps), the branch of Phi = 0 reached from the trial state has no root (the backward-Euler
// solution of an exponential growth over a step longer than its time constant). The implicit
// system may then still have a root far away (f_{n+1} of order 1e-2 from f_n = 1e-9), which the
// Newton does not reach. In that case the return is repeated with f fixed at f_n (growth explicit:
// a convex projection, always solvable); the material's update is the same formula, and the state is
// then on the surface of f_n, not f_{n+1}. The unit test counts how often that happens.
#pragma once
#include "../plasticity/chunk.hpp"
#include "flow_point.hpp"
#include "von_mises.hpp"
#include <cmath>
#include <utility>

namespace burst {

struct GTNParameters {
  PetscReal q1 = 1.5, q2 = 1.0, q3 = 2.25;
  PetscReal critical_porosity = 0.05; // f_c of eq. 14 (acceleration threshold)
  PetscReal acceleration      = 4.0;  // k of eq. 14
  bool      growth            = true; // porosity grows by (1 - f_n) tr(Delta eps_p) in the material: use f_{n+1} in the return
};

namespace gtn {

constexpr PetscReal kCoshClip    = 30;    // |x| beyond which cosh is continued linearly
constexpr PetscReal kSurfaceCap  = 0.99;  // f* <= kSurfaceCap f*_u
constexpr PetscReal kHydrostatic = 1e-12; // q_tr <= kHydrostatic sigma_f: pure hydrostatic return
constexpr PetscReal kMaxPorosity = 1 - 1e-9;

// cosh and its derivatives, continued linearly beyond |x| = kCoshClip: C(x), S = C', dS = C''.
inline void ClippedCosh(PetscReal x, PetscReal &C, PetscReal &S, PetscReal &dS)
{
  const PetscReal ax = std::fabs(x);
  if (ax <= kCoshClip) {
    // both from one exponential (glibc's cosh and sinh call one each): e^|x| for |x| >= 1, where
    // (e - 1/e)/2 has no cancellation; below, t = expm1|x| and sinh = (2t - t^2/(t + 1))/2,
    // cosh = 1 + t^2/(2(t + 1)) (glibc's e_sinh.c and e_cosh.c forms, accurate to round-off)
    PetscReal sh;
    if (ax >= 1) {
      const PetscReal e = std::exp(ax);
      C                 = 0.5 * e + 0.5 / e;
      sh                = 0.5 * e - 0.5 / e;
    } else {
      const PetscReal t = std::expm1(ax), w = t + 1;
      C  = 1 + t * t / (w + w);
      sh = 0.5 * (2 * t - t * t / w);
    }
    S  = std::copysign(sh, x);
    dS = C;
  } else {
    const PetscReal ch = std::cosh(kCoshClip), sh = std::sinh(kCoshClip);
    C  = ch + sh * (ax - kCoshClip);
    S  = x > 0 ? sh : -sh;
    dS = 0;
  }
}

// f*(f) of eq. 14 with the cap, and df*/df.
inline PetscReal EffectivePorosity(const GTNParameters &g, PetscReal f, PetscReal *dfs_df)
{
  PetscReal fs = f, d = 1;
  if (f > g.critical_porosity) {
    fs = g.critical_porosity + g.acceleration * (f - g.critical_porosity);
    d  = g.acceleration;
  }
  const PetscReal disc = g.q1 * g.q1 - g.q3;
  if (g.q1 > 0 && disc >= 0) {
    const PetscReal cap = kSurfaceCap / (g.q1 + std::sqrt(disc));
    if (fs > cap) {
      fs = cap;
      d  = 0;
    }
  }
  if (fs < 0) {
    fs = 0;
    d  = 0;
  }
  if (dfs_df) *dfs_df = d;
  return fs;
}

// The yield function (eq. 13, with the clipped cosh).
inline PetscReal YieldFunction(const GTNParameters &g, PetscReal sigma_m, PetscReal q, PetscReal sigma_f, PetscReal fs)
{
  PetscReal C, S, dS;
  ClippedCosh(1.5 * g.q2 * sigma_m / sigma_f, C, S, dS);
  return q * q / (sigma_f * sigma_f) + 2 * g.q1 * fs * C - (1 + g.q3 * fs * fs);
}

// Everything the Newton needs at one iterate (dv, dq).
struct State {
  PetscReal dv = 0, dq = 0;
  PetscReal sigma_m = 0, q = 0, f = 0, fs = 0, de = 0;
  FlowValue y;
  PetscReal H    = 0;           // d sigma_f / d de (strain plus rate term above the floor)
  PetscReal de_v = 0, de_q = 0; // d de / d dv, d de / d dq (implicit function theorem): predict de at the next iterate
  PetscReal Phi = 0, R2 = 0, R2_scale = 0;
  PetscReal J[2][2] = {{0, 0}, {0, 0}}; // d(Phi, R2)/d(dv, dq)
};

// Constants of one point's return.
struct Point {
  PetscReal        sigma_m_tr, q_tr, K, mu, f_n, growth; // growth 1: f = f_n + (1 - f_n) dv; 0: f = f_n
  const FlowValue *y0 = nullptr;                         // the flow model at de = 0 (the yield test's), reused
};

// Solves (1 - f) sigma_f(eps0 + de, de/dt) de = W for de >= 0 (inner scalar Newton, bracketed),
// starting from de. Returns false if it does not converge.
template <class Flow>
inline bool MatrixStrain(const Flow &flow, const Chunk &c, int k, PetscReal one_minus_f, PetscReal W, PetscReal tol, PetscInt max_it, const FlowValue *y0, PetscReal &de, FlowValue &y, PetscReal &H)
{
  auto rate_slope = [&](PetscReal, const FlowValue &v) { return v.d_strain + v.d_rate / c.dt; };
  auto at_zero    = [&]() {
    if (y0) y = *y0; // the same point and state: the same values
    else flow.Evaluate(MakeFlowPoint(flow, c, k, 0.0), y);
  };
  if (!(W > 0)) {
    de = 0;
    at_zero();
    H = rate_slope(0.0, y);
    return true;
  }
  if (!(de > 0) || !std::isfinite(de)) {
    at_zero();
    de = y.sigma > 0 ? W / (one_minus_f * y.sigma) : 0;
  }
  PetscReal lo = 0, hi = PETSC_MAX_REAL;
  for (PetscInt it = 0; it < 4 * max_it; ++it) {
    flow.Evaluate(MakeFlowPoint(flow, c, k, de), y);
    H                 = rate_slope(de, y);
    const PetscReal h = one_minus_f * y.sigma * de - W;
    if (std::fabs(h) <= tol * W) return true;
    if (h < 0) lo = de;
    else hi = de;
    const PetscReal slope = one_minus_f * (y.sigma + de * H);
    PetscReal       next  = slope > 0 ? de - h / slope : -1;
    if (!(next > lo && next < hi)) next = hi < PETSC_MAX_REAL ? 0.5 * (lo + hi) : 2 * de + 1e-300;
    if (next == de) return std::fabs(h) <= 1e3 * tol * W; // bracket at round-off
    de = next;
  }
  return false;
}

// Evaluates the residuals and the Jacobian at (dv, dq); de is the inner solve's warm start.
template <class Flow>
inline bool Evaluate(const Flow &flow, const Chunk &c, int k, const GTNParameters &g, const Point &P, PetscReal inner_tol, PetscInt max_it, State &s)
{
  s.sigma_m           = P.sigma_m_tr - P.K * s.dv;
  s.q                 = P.q_tr - 3 * P.mu * s.dq;
  const PetscReal fr  = P.f_n + P.growth * (1 - P.f_n) * s.dv;
  PetscReal       f_v = P.growth * (1 - P.f_n);
  s.f                 = fr;
  if (fr < 0) s.f = 0, f_v = 0;
  if (fr > kMaxPorosity) s.f = kMaxPorosity, f_v = 0;
  PetscReal dfs;
  s.fs                 = EffectivePorosity(g, s.f, &dfs);
  const PetscReal fs_v = dfs * f_v;
  const PetscReal omf  = 1 - s.f;
  const PetscReal W    = s.sigma_m * s.dv + s.q * s.dq;
  const PetscReal W_v = s.sigma_m - P.K * s.dv, W_q = s.q - 3 * P.mu * s.dq;
  if (!MatrixStrain(flow, c, k, omf, W, inner_tol, max_it, P.y0, s.de, s.y, s.H)) return false;
  const PetscReal sf = s.y.sigma;
  if (!(sf > 0)) return false;
  const PetscReal den  = omf * (sf + s.de * s.H);
  const PetscReal de_v = (W_v + f_v * sf * s.de) / den, de_q = W_q / den;
  s.de_v               = de_v;
  s.de_q               = de_q;
  const PetscReal sf_v = s.H * de_v, sf_q = s.H * de_q;
  const PetscReal x = 1.5 * g.q2 * s.sigma_m / sf;
  PetscReal       C, S, dS;
  ClippedCosh(x, C, S, dS);
  const PetscReal x_v = (-1.5 * g.q2 * P.K - x * sf_v) / sf, x_q = -x * sf_q / sf;
  const PetscReal q2sf = s.q * s.q / (sf * sf);
  s.Phi                = q2sf + 2 * g.q1 * s.fs * C - (1 + g.q3 * s.fs * s.fs);
  s.J[0][0]            = -2 * q2sf / sf * sf_v + 2 * g.q1 * (fs_v * C + s.fs * S * x_v) - 2 * g.q3 * s.fs * fs_v;
  s.J[0][1]            = -6 * P.mu * s.q / (sf * sf) - 2 * q2sf / sf * sf_q + 2 * g.q1 * s.fs * S * x_q;
  const PetscReal A = s.q / sf, A_v = -s.q * sf_v / (sf * sf), A_q = -3 * P.mu / sf - s.q * sf_q / (sf * sf);
  const PetscReal b = 1.5 * g.q1 * g.q2;
  const PetscReal B = b * s.fs * S, B_v = b * (fs_v * S + s.fs * dS * x_v), B_q = b * s.fs * dS * x_q;
  s.R2       = s.dv * A - s.dq * B;
  s.R2_scale = std::fabs(s.dv * A) + std::fabs(s.dq * B);
  s.J[1][0]  = A + s.dv * A_v - s.dq * B_v;
  s.J[1][1]  = s.dv * A_q - B - s.dq * B_q;
  return std::isfinite(s.Phi) && std::isfinite(s.R2);
}

// The Newton iteration of one point: 2x2 on (dv, dq), or, for a hydrostatic trial state, a scalar
// Newton on dv kept inside a sign-change bracket (Phi > 0 at dv = 0, Phi < 0 at the far end of the
// box, where sigma_m = 0 or f = 0). Returns true with the converged state in st.
template <class Flow>
inline bool Solve(const Flow &flow, const Chunk &c, int k, const GTNParameters &g, const Point &P, bool hydrostatic, PetscReal tol, PetscInt max_it, State &st)
{
  const PetscReal inner_tol = PetscMax(1e-2 * tol, 1e-14);
  const PetscReal dv_bound = P.sigma_m_tr / P.K, dq_bound = hydrostatic ? 0 : P.q_tr / (3 * P.mu);
  PetscReal       dv_lo = PetscMin(0.0, dv_bound), dv_hi = PetscMax(0.0, dv_bound);
  if (P.growth > 0) dv_lo = PetscMax(dv_lo, -P.f_n / (1 - P.f_n)); // void closure stops at f = 0
  const PetscReal scale = std::fabs(dv_bound) + dq_bound;          // strain scale of R2 in the merit

  auto merit = [&](const State &x) {
    const PetscReal r2 = hydrostatic ? 0 : x.R2 / scale;
    return x.Phi * x.Phi + r2 * r2;
  };
  auto converged = [&](const State &x) { return std::fabs(x.Phi) <= tol && (hydrostatic || std::fabs(x.R2) <= tol * x.R2_scale); };
  st             = State();
  if (!Evaluate(flow, c, k, g, P, inner_tol, max_it, st)) return false;
  if (hydrostatic) {
    // bracket [a, b] in dv: Phi(a) > 0 (a = 0 is the trial state), Phi(b) <= 0
    State far    = st;
    far.dv       = dv_bound > 0 ? dv_hi : dv_lo;
    PetscReal  a = 0, b = far.dv;
    const bool bracket = Evaluate(flow, c, k, g, P, inner_tol, max_it, far) && far.Phi <= 0;
    for (PetscInt it = 0; it < 4 * max_it; ++it) {
      if (converged(st)) return true;
      if (!bracket && !(st.J[0][0] != 0)) return false;
      PetscReal next = st.J[0][0] != 0 ? st.dv - st.Phi / st.J[0][0] : 0.5 * (a + b); // bisection if flat
      if (bracket) {
        if (st.Phi > 0) a = st.dv;
        else b = st.dv;
        if (!((next - a) * (next - b) < 0)) next = 0.5 * (a + b);
        if (a == b || next == st.dv) return std::fabs(st.Phi) <= 100 * tol;
      } else next = PetscMin(PetscMax(next, dv_lo), dv_hi);
      st.dv = next;
      if (!Evaluate(flow, c, k, g, P, inner_tol, max_it, st)) return false;
    }
    return converged(st);
  }
  for (PetscInt it = 0; it < max_it; ++it) {
    if (converged(st)) return true;
    const PetscReal det = st.J[0][0] * st.J[1][1] - st.J[0][1] * st.J[1][0];
    if (det == 0 || !std::isfinite(det)) return false;
    const PetscReal step_v = -(st.J[1][1] * st.Phi - st.J[0][1] * st.R2) / det;
    const PetscReal step_q = -(-st.J[1][0] * st.Phi + st.J[0][0] * st.R2) / det;
    // projected backtracking line search on the merit
    const PetscReal m0       = merit(st);
    State           trial    = st;
    PetscReal       lambda   = 1;
    bool            accepted = false;
    for (int ls = 0; ls < 40; ++ls, lambda *= 0.5) {
      trial.dv = PetscMin(PetscMax(st.dv + lambda * step_v, dv_lo), dv_hi);
      trial.dq = PetscMin(PetscMax(st.dq + lambda * step_q, 0.0), dq_bound);
      // the inner solve starts from de predicted to first order (one iteration fewer than from st.de)
      const PetscReal predicted = st.de + st.de_v * (trial.dv - st.dv) + st.de_q * (trial.dq - st.dq);
      trial.de                  = predicted > 0 && std::isfinite(predicted) ? predicted : st.de;
      if (Evaluate(flow, c, k, g, P, inner_tol, max_it, trial) && (merit(trial) < m0 || converged(trial))) {
        accepted = true;
        break;
      }
    }
    if (!accepted) break; // no decrease possible
    st = trial;
  }
  if (converged(st)) return true;
  // a state stuck at the round-off floor within 100 tol is accepted
  return std::fabs(st.Phi) <= 100 * tol && std::fabs(st.R2) <= 100 * tol * st.R2_scale;
}

// One-level Newton on (dv, dq, de), tried before Solve: the plastic-work equation that Evaluate
// solves by an inner Newton for every iterate becomes the third residual,
//   R3 = (1 - f) sigma_f(eps_M,n + de, de/dt) de - (sigma_m dv + q dq) = 0,
// so an iterate costs one flow evaluation instead of two to three. The 3x3 Newton system is reduced
// to 2x2 by eliminating d(de) with the row of R3, d(de) = -(R3 + R3_v d(dv) + R3_q d(dq)) / R3_e; at
// R3 = 0 the reduced matrix is Evaluate's Jacobian (implicit function theorem) and d(de) its
// first-order prediction of de. It stops at Solve's tests, |Phi| <= tol, |R2| <= tol R2_scale, and the
// inner solve's |R3| <= inner_tol W, so the state it returns passes the same tests as Solve's (its
// last step is a full Newton step in all three unknowns, so it lands closer to the root than the
// nested iteration did). Same box and projected backtracking line search, on the merit
// Phi^2 + (R2/scale)^2 + (R3/(sigma_f scale))^2. Returns false on a non-positive R3_e, a singular
// or non-finite step, or no decrease; the caller then runs Solve.
struct CoupledState {
  PetscReal dv = 0, dq = 0, de = 0;
  PetscReal sigma_m = 0, q = 0;
  FlowValue y;
  PetscReal H   = 0; // d sigma_f / d de (strain plus rate term above the floor)
  PetscReal Phi = 0, R2 = 0, R2_scale = 0, R3 = 0, W = 0;
  PetscReal J[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}; // d(Phi, R2, R3)/d(dv, dq, de)
};

// Residuals and Jacobian at (dv, dq, de) with one flow evaluation (the partial derivatives at fixed
// de; the sigma_f dependence enters through the de column).
template <class Flow>
inline bool EvaluateCoupled(const Flow &flow, const Chunk &c, int k, const GTNParameters &g, const Point &P, CoupledState &s)
{
  s.sigma_m          = P.sigma_m_tr - P.K * s.dv;
  s.q                = P.q_tr - 3 * P.mu * s.dq;
  const PetscReal fr = P.f_n + P.growth * (1 - P.f_n) * s.dv;
  PetscReal       f = fr, f_v = P.growth * (1 - P.f_n);
  if (fr < 0) f = 0, f_v = 0;
  if (fr > kMaxPorosity) f = kMaxPorosity, f_v = 0;
  PetscReal       dfs;
  const PetscReal fs = EffectivePorosity(g, f, &dfs), fs_v = dfs * f_v, omf = 1 - f;
  s.W = s.sigma_m * s.dv + s.q * s.dq;
  if (s.de == 0 && P.y0) s.y = *P.y0; // the same point and state: the same values
  else flow.Evaluate(MakeFlowPoint(flow, c, k, s.de), s.y);
  s.H                = s.y.d_strain + s.y.d_rate / c.dt;
  const PetscReal sf = s.y.sigma;
  if (!(sf > 0)) return false;
  const PetscReal x = 1.5 * g.q2 * s.sigma_m / sf;
  PetscReal       C, S, dS;
  ClippedCosh(x, C, S, dS);
  const PetscReal x_v = -1.5 * g.q2 * P.K / sf, x_e = -x * s.H / sf; // x_q = 0
  const PetscReal q2sf = s.q * s.q / (sf * sf);
  s.Phi                = q2sf + 2 * g.q1 * fs * C - (1 + g.q3 * fs * fs);
  s.J[0][0]            = 2 * g.q1 * (fs_v * C + fs * S * x_v) - 2 * g.q3 * fs * fs_v;
  s.J[0][1]            = -6 * P.mu * s.q / (sf * sf);
  s.J[0][2]            = -2 * q2sf / sf * s.H + 2 * g.q1 * fs * S * x_e;
  const PetscReal A = s.q / sf, A_q = -3 * P.mu / sf, A_e = -A * s.H / sf; // A_v = 0
  const PetscReal b = 1.5 * g.q1 * g.q2;
  const PetscReal B = b * fs * S, B_v = b * (fs_v * S + fs * dS * x_v), B_e = b * fs * dS * x_e; // B_q = 0
  s.R2       = s.dv * A - s.dq * B;
  s.R2_scale = std::fabs(s.dv * A) + std::fabs(s.dq * B);
  s.J[1][0]  = A - s.dq * B_v;
  s.J[1][1]  = s.dv * A_q - B;
  s.J[1][2]  = s.dv * A_e - s.dq * B_e;
  s.R3       = omf * sf * s.de - s.W;
  s.J[2][0]  = -f_v * sf * s.de - (s.sigma_m - P.K * s.dv);
  s.J[2][1]  = -(s.q - 3 * P.mu * s.dq);
  s.J[2][2]  = omf * (sf + s.de * s.H);
  return std::isfinite(s.Phi) && std::isfinite(s.R2) && std::isfinite(s.R3);
}

// Warm start of the one-level Newton from the point's plastic rate of the previous step (a steady
// plastic flow keeps its rate, as in the radial return's warm start): sigma_f at de_n = rate_n dt;
// q on the surface of f*_n at the trial mean stress (eq. 13 solved for q), dq = (q_tr - q)/(3 mu);
// dv from normality R2 = 0 there; de from the plastic-work equation with that sigma_f. Returns false
// (start from the trial state) when the point has no previous rate or the surface has no such q.
template <class Flow>
inline bool WarmStart(const Flow &flow, const Chunk &c, int k, const GTNParameters &g, const Point &P, PetscReal dv_lo, PetscReal dv_hi, PetscReal dq_bound, CoupledState &st)
{
  const PetscReal de_n = c.plastic_strain_rate[k] * c.dt;
  if (!(de_n > 0) || !std::isfinite(de_n)) return false;
  FlowValue y;
  flow.Evaluate(MakeFlowPoint(flow, c, k, de_n), y);
  if (!(y.sigma > 0)) return false;
  const PetscReal fs_n = EffectivePorosity(g, P.f_n, nullptr);
  PetscReal       C, S, dS;
  ClippedCosh(1.5 * g.q2 * P.sigma_m_tr / y.sigma, C, S, dS);
  const PetscReal q_surface2 = y.sigma * y.sigma * (1 + g.q3 * fs_n * fs_n - 2 * g.q1 * fs_n * C);
  if (!(q_surface2 > 0) || !std::isfinite(q_surface2)) return false;
  const PetscReal q_surface = std::sqrt(q_surface2);
  st.dq                     = PetscMin(PetscMax((P.q_tr - q_surface) / (3 * P.mu), 0.0), dq_bound);
  st.dv                     = PetscMin(PetscMax(st.dq * 1.5 * g.q1 * g.q2 * fs_n * S * y.sigma / q_surface, dv_lo), dv_hi);
  const PetscReal W         = (P.sigma_m_tr - P.K * st.dv) * st.dv + (P.q_tr - 3 * P.mu * st.dq) * st.dq;
  const PetscReal f         = PetscMin(PetscMax(P.f_n + P.growth * (1 - P.f_n) * st.dv, 0.0), kMaxPorosity);
  st.de                     = W > 0 ? W / ((1 - f) * y.sigma) : de_n;
  return true;
}

// The one-level Newton, from the warm start (warm = true; false if there is none) or from the
// trial state.
template <class Flow>
inline bool SolveCoupled(const Flow &flow, const Chunk &c, int k, const GTNParameters &g, const Point &P, PetscReal tol, PetscInt max_it, bool warm, CoupledState &st)
{
  const PetscReal inner_tol = PetscMax(1e-2 * tol, 1e-14);
  const PetscReal dv_bound = P.sigma_m_tr / P.K, dq_bound = P.q_tr / (3 * P.mu);
  PetscReal       dv_lo = PetscMin(0.0, dv_bound), dv_hi = PetscMax(0.0, dv_bound);
  if (P.growth > 0) dv_lo = PetscMax(dv_lo, -P.f_n / (1 - P.f_n)); // void closure stops at f = 0
  const PetscReal scale = std::fabs(dv_bound) + dq_bound;          // strain scale of R2 and R3 in the merit

  auto merit = [&](const CoupledState &x) {
    const PetscReal r2 = x.R2 / scale, r3 = x.R3 / (x.y.sigma * scale);
    return x.Phi * x.Phi + r2 * r2 + r3 * r3;
  };
  auto converged = [&](const CoupledState &x) { return std::fabs(x.Phi) <= tol && std::fabs(x.R2) <= tol * x.R2_scale && std::fabs(x.R3) <= inner_tol * x.W; };
  st.dv = st.dq = st.de = 0; // (EvaluateCoupled writes every other member before it is read)
  if (warm && !WarmStart(flow, c, k, g, P, dv_lo, dv_hi, dq_bound, st)) return false;
  if (!EvaluateCoupled(flow, c, k, g, P, st)) return false;
  // the iterate and the line search's trial alternate between st and spare (no state copies per
  // iterate); the result is copied to st at most once
  CoupledState  spare;
  CoupledState *cur = &st, *next = &spare;

  auto finish = [&](bool ok) {
    if (cur != &st) st = *cur;
    return ok;
  };
  for (PetscInt it = 0; it < max_it; ++it) {
    const CoupledState &now = *cur; // the current iterate
    if (converged(now)) return finish(true);
    const PetscReal r3_e = now.J[2][2];
    if (!(r3_e > 0)) return false;
    const PetscReal e_0 = -now.R3 / r3_e, e_v = -now.J[2][0] / r3_e, e_q = -now.J[2][1] / r3_e; // d(de) = e_0 + e_v d(dv) + e_q d(dq)
    const PetscReal a00 = now.J[0][0] + now.J[0][2] * e_v, a01 = now.J[0][1] + now.J[0][2] * e_q;
    const PetscReal a10 = now.J[1][0] + now.J[1][2] * e_v, a11 = now.J[1][1] + now.J[1][2] * e_q;
    const PetscReal r0 = now.Phi + now.J[0][2] * e_0, r1 = now.R2 + now.J[1][2] * e_0;
    const PetscReal det = a00 * a11 - a01 * a10;
    if (det == 0 || !std::isfinite(det)) return false;
    const PetscReal step_v = -(a11 * r0 - a01 * r1) / det;
    const PetscReal step_q = -(-a10 * r0 + a00 * r1) / det;
    const PetscReal step_e = e_0 + e_v * step_v + e_q * step_q;
    // projected backtracking line search on the merit; de >= 0 (a step across 0 halves de instead)
    const PetscReal m0       = merit(now);
    CoupledState   &trial    = *next;
    PetscReal       lambda   = 1;
    bool            accepted = false;
    for (int ls = 0; ls < 40; ++ls, lambda *= 0.5) {
      trial.dv           = PetscMin(PetscMax(now.dv + lambda * step_v, dv_lo), dv_hi);
      trial.dq           = PetscMin(PetscMax(now.dq + lambda * step_q, 0.0), dq_bound);
      const PetscReal de = now.de + lambda * step_e;
      trial.de           = de > 0 ? de : 0.5 * now.de;
      if (EvaluateCoupled(flow, c, k, g, P, trial) && (merit(trial) < m0 || converged(trial))) {
        accepted = true;
        break;
      }
    }
    if (!accepted) return false;
    std::swap(cur, next);
  }
  return finish(converged(*cur));
}

// Last resort when the 2x2 Newton stalls: the flow direction is frozen at the trial state
// (associated flow, dv = lambda dPhi/dsigma_m, dq = lambda dPhi/dq) and Phi(lambda) = 0 is solved
// by a bracketed secant/bisection (Illinois) on [0, lambda_max], where the box of (dv, dq) ends.
// This happens at first yield from a trial state a hair outside the surface: the Johnson-Cook
// hardening B eps^n has an infinite slope at eps_p = 0, so the Newton linearisation is useless there
// while the increments are tiny and the frozen normal is exact to their order.
template <class Flow>
inline bool SolveAlongTrialNormal(const Flow &flow, const Chunk &c, int k, const GTNParameters &g, const Point &P, PetscReal tol, PetscInt max_it, State &st)
{
  const PetscReal inner_tol = PetscMax(1e-2 * tol, 1e-14);
  State           s0;
  if (!Evaluate(flow, c, k, g, P, inner_tol, max_it, s0) || !(s0.Phi > 0)) return false;
  const PetscReal sf = s0.y.sigma, x = 1.5 * g.q2 * P.sigma_m_tr / sf;
  PetscReal       C, S, dS;
  ClippedCosh(x, C, S, dS);
  const PetscReal n_v = 3 * g.q1 * g.q2 * s0.fs * S / sf, n_q = 2 * P.q_tr / (sf * sf);
  // largest lambda inside the box: dq <= q_tr/(3 mu), dv within [0, sigma_m_tr/K] (or closure)
  PetscReal lambda_max = n_q > 0 ? P.q_tr / (3 * P.mu) / n_q : PETSC_MAX_REAL;
  if (n_v != 0) {
    PetscReal dv_end = P.sigma_m_tr / P.K;
    if (P.growth > 0 && dv_end < 0) dv_end = PetscMax(dv_end, -P.f_n / (1 - P.f_n));
    if (dv_end / n_v > 0) lambda_max = PetscMin(lambda_max, dv_end / n_v);
  }
  if (!(lambda_max > 0) || lambda_max >= PETSC_MAX_REAL) return false;
  auto at = [&](PetscReal lambda, State &x_state) {
    x_state    = State();
    x_state.dv = lambda * n_v;
    x_state.dq = lambda * n_q;
    return Evaluate(flow, c, k, g, P, inner_tol, max_it, x_state);
  };
  State hi_state;
  if (!at(lambda_max, hi_state) || !(hi_state.Phi < 0)) return false;
  PetscReal a = 0, b = lambda_max, fa = s0.Phi, fb = hi_state.Phi;
  int       side = 0;
  for (PetscInt it = 0; it < 8 * max_it; ++it) {
    PetscReal lambda = b - fb * (b - a) / (fb - fa);
    if (!(lambda > a && lambda < b)) lambda = 0.5 * (a + b);
    if (!at(lambda, st)) return false;
    if (std::fabs(st.Phi) <= tol || b - a <= 1e-15 * b) return std::fabs(st.Phi) <= 100 * tol;
    if (st.Phi > 0) {
      a = lambda, fa = st.Phi;
      if (side == 1) fb *= 0.5; // Illinois: keep the secant from stalling on one end
      side = 1;
    } else {
      b = lambda, fb = st.Phi;
      if (side == -1) fa *= 0.5;
      side = -1;
    }
  }
  return false;
}

} // namespace gtn

// Full GTN return for every point of the chunk. Same contract as VonMisesReturn, plus: reads
// c.pressure (trial p from the EOS), c.bulk_modulus and c.porosity (f_n); writes c.pressure
// (p_tr + K dv), c.trace_plastic_strain (dv, drives eq. 16 in the material) and sets
// c.delta_plastic_strain / c.plastic_strain to the matrix equivalent plastic strain. c.porosity is
// not changed (the material integrates eqs. 15-17 from trace_plastic_strain and
// delta_plastic_strain). Returns PETSC_ERR_NOT_CONVERGED if a Newton iteration fails.
template <class Flow>
PetscErrorCode GTNReturn(const Flow &flow, Chunk &c, const GTNParameters &gtn, PetscReal tol, PetscInt max_it)
{
  gtn::State        st; // the solvers' states, reused from point to point (each solver starts its own)
  gtn::CoupledState cs;
  for (int k = 0; k < c.n; ++k) {
    PetscReal *s  = c.deviator[k];
    PetscReal  ss = 0;
    for (int a = 0; a < 9; ++a) ss += s[a] * s[a];
    const PetscReal q_trial = std::sqrt(1.5 * ss), mu = c.shear_modulus[k], K = c.bulk_modulus[k], dt = c.dt;
    const PetscReal eps0 = c.plastic_strain[k], f_n = PetscMin(PetscMax(c.porosity[k], 0.0), gtn::kMaxPorosity);
    FlowValue       y;
    flow.Evaluate(MakeFlowPoint(flow, c, k, 0.0), y);
    c.plastic[k]                = 0;
    c.delta_plastic_strain[k]   = 0;
    c.trace_plastic_strain[k]   = 0;
    const PetscReal fs_n        = gtn::EffectivePorosity(gtn, f_n, nullptr);
    const PetscReal sigma_m_tr  = -c.pressure[k];
    const bool      no_strength = !(y.sigma > 0) || !(mu > 0) || !(K > 0);
    if (no_strength || gtn::YieldFunction(gtn, sigma_m_tr, q_trial, y.sigma, fs_n) <= 0) {
      // elastic (or no strength left: the failure check reads sigma_f <= 0)
      c.flow_stress[k]         = y.sigma;
      c.hardening[k]           = y.d_strain;
      c.rate_hardening[k]      = 0;
      c.thermal_softening[k]   = y.d_temperature;
      c.equivalent_stress[k]   = q_trial;
      c.plastic_strain_rate[k] = 0;
      continue;
    }
    const bool hydrostatic = q_trial <= gtn::kHydrostatic * y.sigma;
    gtn::Point P{sigma_m_tr, q_trial, K, mu, f_n, gtn.growth ? 1.0 : 0.0, &y};
    bool       ok = false;
    if (!hydrostatic) { // the one-level Newton from the warm start, else from the trial state
      ok = gtn::SolveCoupled(flow, c, k, gtn, P, tol, max_it, true, cs) || gtn::SolveCoupled(flow, c, k, gtn, P, tol, max_it, false, cs);
      if (ok) st.dv = cs.dv, st.dq = cs.dq, st.de = cs.de, st.sigma_m = cs.sigma_m, st.q = cs.q, st.y = cs.y, st.H = cs.H;
    }
    if (!ok) ok = gtn::Solve(flow, c, k, gtn, P, hydrostatic, tol, max_it, st);
    if (!ok && P.growth > 0) {
      // explosive void growth: no root of the implicit system reachable from the trial state; the
      // return is repeated with f fixed at f_n (explicit growth, same update in the material)
      P.growth = 0;
      ok       = gtn::Solve(flow, c, k, gtn, P, hydrostatic, tol, max_it, st);
    }
    if (!ok && !hydrostatic) ok = gtn::SolveAlongTrialNormal(flow, c, k, gtn, P, tol, max_it, st);
    if (!ok || !std::isfinite(st.dv) || !std::isfinite(st.dq)) {
      c.failed_point = k;
      return PETSC_ERR_NOT_CONVERGED;
    }
    // write back
    if (q_trial > 0 && !hydrostatic) {
      const PetscReal ratio = st.q / q_trial;
      for (int a = 0; a < 9; ++a) s[a] *= ratio;
    }
    const PetscReal de = st.de;
    flow.UpdateHistory(MakeFlowPoint(flow, c, k, de), de, c.history[k]);
    c.plastic[k]              = 1;
    c.pressure[k]             = -st.sigma_m; // = p_tr + K dv
    c.trace_plastic_strain[k] = st.dv;
    c.delta_plastic_strain[k] = de;
    c.plastic_strain[k]       = eps0 + de;
    c.plastic_strain_rate[k]  = de / dt;
    c.flow_stress[k]          = st.y.sigma;
    c.hardening[k]            = st.y.d_strain;
    c.rate_hardening[k]       = st.H - st.y.d_strain;
    c.thermal_softening[k]    = st.y.d_temperature;
    c.equivalent_stress[k]    = hydrostatic ? q_trial : st.q;
  }
  return PETSC_SUCCESS;
}

} // namespace burst
