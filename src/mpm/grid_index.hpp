// Flat index of a node in the ghosted local arrays of the node DMDAs (petsc.md 5.2).
#pragma once
#include "mpm.hpp"
#include "shape.hpp"
#include <cstdint>
#include <cstring>

namespace burst {

struct LocalNodeIndex {
  PetscInt gxs[3], gxm[3];
  explicit LocalNodeIndex(const Grid &g)
  {
    for (int d = 0; d < 3; ++d) {
      gxs[d] = g.gxs[d];
      gxm[d] = g.gxm[d];
    }
  }
  inline PetscInt operator()(PetscInt i, PetscInt j, PetscInt k) const { return ((k - gxs[2]) * gxm[1] + (j - gxs[1])) * gxm[0] + (i - gxs[0]); }
};

// Calls f(l, at, count, i, j, k) for each run of consecutive marked nodes in the rows of the box
// [xs, xs + xm): l is the run's first place in an array over that box, at its ghosted local index,
// (i, j, k) its first node. `marks`: one byte per ghosted local node (null: every node, one run per
// row); `also` (optional): one byte per node of the box, marking more nodes. The box is the ghosted
// one (local vectors) or the owned one (global vectors). Runs, so that a grid the particles fill is
// walked row by row (the P2G zeroes it like the memset it replaces), and eight unmarked nodes are
// passed over at a time, so that an empty grid costs little (the grid update).
template <class Fn>
inline void ForEachMarkedRun(const Grid &g, const unsigned char *marks, const PetscInt xs[3], const PetscInt xm[3], Fn &&f, const unsigned char *also = nullptr)
{
  const LocalNodeIndex index(g);
  PetscInt             l = 0;
  for (PetscInt k = xs[2]; k < xs[2] + xm[2]; ++k)
    for (PetscInt j = xs[1]; j < xs[1] + xm[1]; l += xm[0], ++j) {
      const PetscInt at = index(xs[0], j, k);
      if (!marks) {
        f(l, at, xm[0], xs[0], j, k);
        continue;
      }
      const unsigned char *m = marks + at, *a = also ? also + l : nullptr;

      auto marked = [&](PetscInt i) { return m[i] || (a && a[i]); };
      for (PetscInt i = 0; i < xm[0];) {
        if (i + 8 <= xm[0]) {
          std::uint64_t m8, a8 = 0;
          std::memcpy(&m8, m + i, 8);
          if (a) std::memcpy(&a8, a + i, 8);
          if (!(m8 | a8)) {
            i += 8;
            continue;
          }
        }
        if (!marked(i)) {
          ++i;
          continue;
        }
        PetscInt end = i + 1;
        while (end < xm[0] && marked(end)) ++end;
        f(l + i, at + i, end - i, xs[0] + i, j, k);
        i = end;
      }
    }
}

// G2P's velocity update of one particle, shared by GridToParticles and MUSL's remap: v_p <- v_new
// (the FLIP/PIC blend, or a rigid body's prescribed velocity) and the work of the external force over
// the step, f_ext . (v_n + v_{n+1})/2 dt (fext_p: the particle's force, null without loads).
inline PetscReal FlipBlend(PetscReal flip, PetscReal v_particle, PetscReal dv_grid, PetscReal v_grid) { return flip * (v_particle + dv_grid) + (1 - flip) * v_grid; }
template <int DIM>
inline void SetParticleVelocity(PetscReal vp[], const PetscReal v_new[], const PetscReal *fext_p, PetscReal dt, PetscReal &work)
{
  for (int a = 0; a < DIM; ++a) {
    if (fext_p) work += 0.5 * dt * fext_p[a] * (vp[a] + v_new[a]);
    vp[a] = v_new[a];
  }
}

// ForEachNode for the transfers: f(at, N, dN[DIM]) with at = index(i, j, k) * scale, the node's
// first entry in a ghosted local array of `scale` values per node. The flat index is a sum of one
// offset per direction, formed once per particle instead of a product per node (the same integers).
template <int DIM, ShapeType S, class Fn>
inline void ForEachLocalNode(const Stencil<DIM, S> &st, const LocalNodeIndex &index, PetscInt scale, Fn &&f)
{
  constexpr int NS            = Stencil<DIM, S>::NS;
  PetscInt      offset[3][NS] = {};
  for (int d = 0; d < DIM; ++d) {
    const PetscInt step = d == 0 ? scale : (d == 1 ? index.gxm[0] * scale : index.gxm[0] * index.gxm[1] * scale);
    for (int a = 0; a < NS; ++a) offset[d][a] = (st.idx[d][a] - index.gxs[d]) * step;
  }
  if constexpr (DIM == 2) ForEachStencilNode(st, [&](int a, int b, int, PetscReal N, const PetscReal dN[]) { f(offset[0][a] + offset[1][b], N, dN); });
  else {
    // ForEachStencilNode's loops (same products, same order), with the x-y offsets beside the x-y
    // weight products
    using St               = Stencil<DIM, S>;
    constexpr bool trimmed = St::kTrimmed;
    const int      lo[3]   = {trimmed ? st.lo[0] : 0, trimmed ? st.lo[1] : 0, trimmed ? st.lo[DIM - 1] : 0};
    const int      end[3]  = {trimmed ? st.hi[0] + 1 : NS, trimmed ? st.hi[1] + 1 : NS, trimmed ? st.hi[DIM - 1] + 1 : NS};
    PetscReal      ww[NS][NS], dww[NS][NS], wdw[NS][NS];
    PetscInt       oxy[NS][NS];
    for (int b = lo[1]; b < end[1]; ++b)
      for (int a = lo[0]; a < end[0]; ++a) {
        ww[b][a]  = st.w[0][a] * st.w[1][b];
        dww[b][a] = st.dw[0][a] * st.w[1][b];
        wdw[b][a] = st.w[0][a] * st.dw[1][b];
        oxy[b][a] = offset[0][a] + offset[1][b];
      }
    for (int c = lo[2]; c < end[2]; ++c) {
      const PetscReal wc = st.w[DIM - 1][c], dwc = st.dw[DIM - 1][c];
      const PetscInt  oz = offset[DIM - 1][c];
      for (int b = lo[1]; b < end[1]; ++b)
        for (int a = lo[0]; a < end[0]; ++a) {
          const PetscReal dN[3] = {dww[b][a] * wc, wdw[b][a] * wc, ww[b][a] * dwc};
          f(oxy[b][a] + oz, ww[b][a] * wc, dN);
        }
    }
  }
}

} // namespace burst
