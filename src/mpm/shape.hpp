// Interpolators (shape functions) of the MPM grid, evaluated one particle at a time.
//
// Every interpolator is a tensor product of 1-D weights. For one particle and one direction it
// returns NS consecutive node indices with their weights and derivatives; the P2G/G2P loops form
// the products. Kernels are pure functions with no PETSc calls so the unit tests call them directly.
//
//   linear      NS = 2, hat functions (Sulsky et al. 1994).
//   ugimp       NS = 3, uniform GIMP: particle domain of half-width lp = h/(2 ppc), never deformed
//               (Bardenhagen & Kober 2004).
//   cpgimp      NS = 3, contiguous-particle GIMP: lp_d = lp0_d F_dd, clamped to (0, h/2]
//               (Wallstedt & Guilkey 2008).
//   bspline2    NS = 3, uniform quadratic B-spline centred on the nodes (Steffen et al. 2008).
//
// Walls: a support node outside [0, M-1] (only node -1 or M can occur for a particle inside the
// domain) is replaced by linear extrapolation from the two nodes inside, f_{-1} = 2 f_0 - f_1:
// its weight moves as w_0 += 2 w_{-1}, w_1 -= w_{-1} (same for the gradients). Constants and linear
// fields stay exact up to the wall, no mass leaves the domain, and for the B-spline and GIMP the
// weights stay non-negative (w_1 >= w_{-1} whenever node -1 is in the support). A particle on a wall
// node maps fully onto it.
#pragma once
#include "petsc_compat.hpp"
#include <cmath>
#include <petscsys.h>
#include <type_traits>
#include <vector>

namespace burst {

enum class ShapeType : int { Linear = 0, UGimp = 1, CpGimp = 2, BSpline2 = 3 };

// Number of nodes per direction in the support of each interpolator.
template <ShapeType S>
constexpr int ShapeNodes()
{
  return S == ShapeType::Linear ? 2 : 3;
}

// Ghost width of the node DMDA needed by an interpolator with the lower-node cell ownership.
inline PetscInt ShapeGhostWidth(ShapeType s) { return s == ShapeType::Linear ? 1 : 2; }

// Per-direction grid description used by the kernels.
struct Axis {
  PetscReal origin; // coordinate of node 0, m
  PetscReal h;      // node spacing, m
  PetscInt  nodes;  // number of nodes M
};

// Two doubles operated on lane by lane (GCC/Clang vector extension): the transfers carry rows 0 and 1
// of the velocity gradient and of the force as one pair, the same operations in the same order as
// the scalar code, so the same bits, with fewer live registers.
typedef PetscReal Pair __attribute__((vector_size(2 * sizeof(PetscReal))));

inline PetscInt ClampNode(PetscInt i, PetscInt nodes) { return i < 0 ? 0 : (i >= nodes ? nodes - 1 : i); }

// Linear hat: nodes floor(xi), floor(xi)+1.
inline void LinearWeights1D(const Axis &a, PetscReal x, PetscInt idx[], PetscReal w[], PetscReal dw[])
{
  const PetscReal xi = (x - a.origin) / a.h;
  // a particle exactly on the upper wall belongs to the last cell (both nodes distinct)
  PetscInt        i0 = PetscMin((PetscInt)std::floor(xi), a.nodes - 2);
  const PetscReal r  = xi - (PetscReal)i0;
  idx[0]             = ClampNode(i0, a.nodes);
  idx[1]             = ClampNode(i0 + 1, a.nodes);
  w[0]               = 1.0 - r;
  w[1]               = r;
  dw[0]              = -1.0 / a.h;
  dw[1]              = 1.0 / a.h;
}

// GIMP weight of a node at signed distance d = x_p - x_I for a particle of half-width lp <= h/2:
// the hat function averaged over the particle domain [x_p - lp, x_p + lp], piece by piece (the
// reference for GimpWeights1D's closed form; unit tests).
inline void GimpWeight(PetscReal d, PetscReal h, PetscReal lp, PetscReal &w, PetscReal &dw)
{
  const PetscReal ad = std::fabs(d), s = d < 0 ? -1.0 : 1.0;
  if (ad < lp) {
    w  = 1.0 - (d * d + lp * lp) / (2.0 * h * lp);
    dw = -d / (h * lp);
  } else if (ad < h - lp) {
    w  = 1.0 - ad / h;
    dw = -s / h;
  } else if (ad < h + lp) {
    const PetscReal t = h + lp - ad;
    w                 = t * t / (4.0 * h * lp);
    dw                = -s * t / (2.0 * h * lp);
  } else {
    w  = 0.0;
    dw = 0.0;
  }
}

// Moves the weight of a node outside the grid onto the two nearest inside nodes (see the header).
inline void ExtrapolateWallNodes(const Axis &a, PetscInt nearest, PetscInt idx[], PetscReal w[], PetscReal dw[])
{
  if (nearest - 1 < 0 && a.nodes > 1) {
    w[1] += 2 * w[0];
    w[2] -= w[0];
    dw[1] += 2 * dw[0];
    dw[2] -= dw[0];
    w[0] = dw[0] = 0;
  }
  if (nearest + 1 > a.nodes - 1 && a.nodes > 1) {
    w[1] += 2 * w[2];
    w[0] -= w[2];
    dw[1] += 2 * dw[2];
    dw[0] -= dw[2];
    w[2] = dw[2] = 0;
  }
  for (int k = 0; k < 3; ++k) idx[k] = ClampNode(nearest - 1 + k, a.nodes);
}

// floor(x) as an integer: truncation, corrected below zero (no libm call without SSE4.1).
inline PetscInt FloorToInt(PetscReal x)
{
  const PetscInt t = (PetscInt)x;
  return t - (x < (PetscReal)t ? 1 : 0);
}

// GIMP: nodes nearest-1 .. nearest+1. lp is the particle half-width in this direction.
// GimpWeight's three branches in closed form, with clamps instead of branches (a particle's position
// against lp is random, so the branches mispredict). The particle domain [ad - lp, ad + lp] of a node
// at distance ad:
//   outer nodes (ad >= h/2 >= lp): the hat's slope 1 - s/h, cut at s = h; the overlap of the domain
//     with [0, h] has length t = clamp(h + lp - ad, 0, 2 lp), so
//     N = t (h + lp - ad - t/2) / (2 h lp), dN/d(ad) = -t / (2 h lp);
//   middle node (ad <= h/2): the hat 1 - |s|/h; the part of the domain below s = 0 has length
//     m = max(lp - ad, 0), so N = 1 - ad/h - m^2 / (2 h lp), dN/d(ad) = -(lp - m) / (h lp).
// Each reduces to GimpWeight's piece in its range (t = 2 lp: linear; 0 < t < 2 lp: the tail; t = 0:
// exactly zero, so the trimmed stencils drop the same nodes).
inline void GimpWeights1D(const Axis &a, PetscReal x, PetscReal lp, PetscInt idx[], PetscReal w[], PetscReal dw[])
{
  const PetscReal h = a.h, inv_h = 1 / h, inv_2hlp = 0.5 * inv_h / lp;
  const PetscInt  nearest = FloorToInt((x - a.origin) * inv_h + 0.5);
  const PetscReal d0 = x - (a.origin + (nearest - 1) * h), d1 = x - (a.origin + nearest * h), d2 = x - (a.origin + (nearest + 1) * h);
  const PetscReal u0 = h + lp - d0, u2 = h + lp + d2; // d0 > 0 > d2
  const PetscReal t0 = PetscMin(PetscMax(u0, 0.0), 2 * lp), t2 = PetscMin(PetscMax(u2, 0.0), 2 * lp);
  w[0]               = t0 * (u0 - 0.5 * t0) * inv_2hlp;
  dw[0]              = -t0 * inv_2hlp;
  w[2]               = t2 * (u2 - 0.5 * t2) * inv_2hlp;
  dw[2]              = t2 * inv_2hlp;
  const PetscReal ad = std::fabs(d1), m = PetscMax(lp - ad, 0.0);
  w[1]  = 1 - ad * inv_h - m * m * inv_2hlp;
  dw[1] = -2 * std::copysign(lp - m, d1) * inv_2hlp;
  ExtrapolateWallNodes(a, nearest, idx, w, dw);
}

// Quadratic B-spline centred on nodes: N(r) = 3/4 - r^2 (|r| < 1/2), (3/2 - |r|)^2/2 (|r| < 3/2).
inline void BSpline2Weights1D(const Axis &a, PetscReal x, PetscInt idx[], PetscReal w[], PetscReal dw[])
{
  const PetscReal xi      = (x - a.origin) / a.h;
  const PetscInt  nearest = (PetscInt)std::floor(xi + 0.5);
  const PetscReal r       = xi - (PetscReal)nearest; // in [-1/2, 1/2)
  // node nearest-1 at distance r+1, nearest at r, nearest+1 at r-1 (in cells)
  w[0]  = 0.5 * (0.5 - r) * (0.5 - r);
  w[1]  = 0.75 - r * r;
  w[2]  = 0.5 * (0.5 + r) * (0.5 + r);
  dw[0] = -(0.5 - r) / a.h;
  dw[1] = -2.0 * r / a.h;
  dw[2] = (0.5 + r) / a.h;
  ExtrapolateWallNodes(a, nearest, idx, w, dw);
}

// Weights of one particle in all directions. GIMP stencils also record, per direction, the range
// [lo, hi] of their nodes with a nonzero weight or gradient: a GIMP particle of half-width lp reaches
// the far node on the other side of its nearest node only when it lies within lp of that node
// (|x_p - x_I| < h + lp), so about half the time a direction has 2 live nodes of 3 (a 3-D stencil
// about 16 of 27). ForEachNode visits only those; the others would add exact zeros.
template <int DIM, ShapeType S>
struct Stencil {
  static constexpr int  NS       = ShapeNodes<S>();
  static constexpr bool kTrimmed = S == ShapeType::UGimp || S == ShapeType::CpGimp;
  PetscInt              idx[DIM][NS];
  PetscReal             w[DIM][NS], dw[DIM][NS];
  unsigned char         lo[DIM], hi[DIM]; // GIMP: live nodes lo..hi of each direction (else 0..NS-1)

  // x: particle position; lp0: initial particle half-widths; F: deformation gradient (row-major 3x3,
  // used by cpGIMP only).
  inline void Evaluate(const Axis axes[], const PetscReal x[], const PetscReal lp0[], const PetscReal *F)
  {
    for (int d = 0; d < DIM; ++d) {
      if constexpr (S == ShapeType::Linear) LinearWeights1D(axes[d], x[d], idx[d], w[d], dw[d]);
      else if constexpr (S == ShapeType::UGimp) GimpWeights1D(axes[d], x[d], lp0[d], idx[d], w[d], dw[d]);
      else if constexpr (S == ShapeType::CpGimp) {
        PetscReal lp = lp0[d] * std::fabs(F[d * 3 + d]);
        lp           = lp > 0.5 * axes[d].h ? 0.5 * axes[d].h : (lp < 1e-3 * axes[d].h ? 1e-3 * axes[d].h : lp);
        GimpWeights1D(axes[d], x[d], lp, idx[d], w[d], dw[d]);
      } else BSpline2Weights1D(axes[d], x[d], idx[d], w[d], dw[d]);
      // the end nodes whose weight and gradient are exactly zero (GIMP beyond h + lp, or a wall node
      // whose weight moved inside); the middle node always carries weight
      if constexpr (kTrimmed) {
        lo[d] = w[d][0] == 0 && dw[d][0] == 0 ? 1 : 0;
        hi[d] = w[d][NS - 1] == 0 && dw[d][NS - 1] == 0 ? NS - 2 : NS - 1;
      }
    }
  }
};

// The particles' stencils of the current step, evaluated once by the first transfer that needs
// them and reused by the later ones (MUSL: P2G, G2P, P2G, G2P on the same positions and F; USL: P2G,
// G2P), and by the XPIC passes. Kept per rank beside the swarm, not in it: a scratch array that grows
// with the local particle count and is never shrunk. Valid only within one step (`step` is
// Simulation::step) for the same local count, dimension and interpolator, and until something moves
// the particles, changes F (cpGIMP widths) or reorders them: G2P's position and F updates, removal,
// migration and sorting call Invalidate().
struct StencilCache {
  std::vector<PetscReal> storage; // raw storage, 8-byte aligned
  PetscInt               n = 0, step = -1, dim = 0;
  ShapeType              shape = ShapeType::Linear;
  bool                   valid = false;

  void Invalidate() { valid = false; }

  // The stencils of `n` particles at step `step`; *fill is true when the caller must evaluate them
  // (every one of them, in its particle loop) and false when they hold this step's values.
  template <int DIM, ShapeType S>
  Stencil<DIM, S> *Prepare(PetscInt n_, PetscInt step_, bool *fill)
  {
    using T = Stencil<DIM, S>;
    static_assert(std::is_trivially_copyable<T>::value && alignof(T) <= alignof(PetscReal), "stencils live in a PetscReal buffer");
    if (valid && n == n_ && step == step_ && dim == DIM && shape == S) {
      *fill = false;
      return reinterpret_cast<T *>(storage.data());
    }
    const size_t need = (sizeof(T) * (size_t)n_ + sizeof(PetscReal) - 1) / sizeof(PetscReal);
    if (storage.size() < need) storage.resize(need + need / 8); // some room for arrivals of later steps
    n     = n_;
    step  = step_;
    dim   = DIM;
    shape = S;
    valid = true;
    *fill = true;
    return reinterpret_cast<T *>(storage.data());
  }
};

// Visit every node of the tensor-product support (GIMP: the live nodes, see Stencil), in the same
// order, by its position in the stencil: f(a, b, c, N, dN[DIM]) for node (idx[0][a], idx[1][b],
// idx[2][c]) (c = 0 in 2-D).
template <int DIM, ShapeType S, class Fn>
inline void ForEachStencilNode(const Stencil<DIM, S> &st, Fn &&f)
{
  using St               = Stencil<DIM, S>;
  constexpr int  NS      = St::NS;
  constexpr bool trimmed = St::kTrimmed;
  const int      lo[3]   = {trimmed ? st.lo[0] : 0, trimmed ? st.lo[1] : 0, trimmed && DIM == 3 ? st.lo[DIM - 1] : 0};
  const int      end[3]  = {trimmed ? st.hi[0] + 1 : NS, trimmed ? st.hi[1] + 1 : NS, trimmed && DIM == 3 ? st.hi[DIM - 1] + 1 : NS};
  if constexpr (DIM == 2) {
    for (int b = lo[1]; b < end[1]; ++b)
      for (int a = lo[0]; a < end[0]; ++a) {
        const PetscReal N     = st.w[0][a] * st.w[1][b];
        const PetscReal dN[2] = {st.dw[0][a] * st.w[1][b], st.w[0][a] * st.dw[1][b]};
        f(a, b, 0, N, dN);
      }
  } else {
    // the x-y products of the weights, shared by the NS planes in z (same products, same bits)
    PetscReal ww[NS][NS], dww[NS][NS], wdw[NS][NS];
    for (int b = lo[1]; b < end[1]; ++b)
      for (int a = lo[0]; a < end[0]; ++a) {
        ww[b][a]  = st.w[0][a] * st.w[1][b];
        dww[b][a] = st.dw[0][a] * st.w[1][b];
        wdw[b][a] = st.w[0][a] * st.dw[1][b];
      }
    for (int c = lo[2]; c < end[2]; ++c)
      for (int b = lo[1]; b < end[1]; ++b)
        for (int a = lo[0]; a < end[0]; ++a) {
          const PetscReal N     = ww[b][a] * st.w[2][c];
          const PetscReal dN[3] = {dww[b][a] * st.w[2][c], wdw[b][a] * st.w[2][c], ww[b][a] * st.dw[2][c]};
          f(a, b, c, N, dN);
        }
  }
}

// The same visit by node indices: f(i, j, k, N, dN[DIM]) (k = 0 in 2-D).
template <int DIM, ShapeType S, class Fn>
inline void ForEachNode(const Stencil<DIM, S> &st, Fn &&f)
{
  ForEachStencilNode(st, [&](int a, int b, int c, PetscReal N, const PetscReal dN[]) { f(st.idx[0][a], st.idx[1][b], DIM == 3 ? st.idx[DIM - 1][c] : 0, N, dN); });
}

// Calls f.template operator()<DIM, S>() for the runtime (dim, shape) pair: the one switch that turns
// options into template instances, hoisted out of every particle loop.
template <class Fn>
inline PetscErrorCode DispatchShape(PetscInt dim, ShapeType s, Fn &&f)
{
  PetscFunctionBeginUser;
  switch (s) {
  case ShapeType::Linear:
    if (dim == 2) PetscCall(f.template operator()<2, ShapeType::Linear>());
    else PetscCall(f.template operator()<3, ShapeType::Linear>());
    break;
  case ShapeType::UGimp:
    if (dim == 2) PetscCall(f.template operator()<2, ShapeType::UGimp>());
    else PetscCall(f.template operator()<3, ShapeType::UGimp>());
    break;
  case ShapeType::CpGimp:
    if (dim == 2) PetscCall(f.template operator()<2, ShapeType::CpGimp>());
    else PetscCall(f.template operator()<3, ShapeType::CpGimp>());
    break;
  case ShapeType::BSpline2:
    if (dim == 2) PetscCall(f.template operator()<2, ShapeType::BSpline2>());
    else PetscCall(f.template operator()<3, ShapeType::BSpline2>());
    break;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
