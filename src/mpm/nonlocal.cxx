// Nonlocal average of per-particle values over a material length ell (issue 12: a length scale for
// softening and failure), for the materials whose NonlocalLength() is positive (elastic_plastic with
// -MAT_regularization nonlocal). Runs at the end of each MPM step, after the migration (every
// particle is on its owning rank, as the heat step needs); the material reads the averages at the
// start of its next stress update (models/plasticity/elastic_plastic.cxx).
//
// The integral average (Pijaudier-Cabot & Bazant 1987; Bazant & Jirasek 2002, eq. 5):
//   <s>(x_p) = sum_q w_q alpha(x_p - x_q) s_q / sum_q w_q alpha(x_p - x_q)
// with the particle weights w_q (mass; 0 for a particle that neither gives nor takes, e.g. eroded)
// and the bell function alpha(r) = prod_d a(r_d), a(r) = (1 - r^2/ell^2)^2 for |r| < ell, 0 beyond
// (a tensor product, so it is evaluated as one 1-D pass per direction). It is computed through the
// grid rather than by a particle neighbour search:
//   1. P2G with the linear hat N_I: g_I = sum_q N_I(x_q) w_q [1, s_q]         (ADD_VALUES)
//   2. on the nodes, G_I = sum_J alpha(X_I - X_J) g_J, one direction at a time; a symmetry face
//      mirrors the nodes beyond it (the modelled region is half of a symmetric body), other faces
//      truncate the weight (the normalisation below then averages over what is there)
//   3. G2P: <s>_p = sum_I N_I(x_p) G_I[1..] / sum_I N_I(x_p) G_I[0]
// The kernel is the bell widened by two hats, so it tends to alpha as h -> 0 at fixed ell; the cost
// is two particle passes and (2 ceil(ell/h) + 1) dim node operations per node and component.
//
// Parallel: a node DMDA of its own with the ownership of the grid's and a box stencil of width
// ceil(ell/h), so that the passes of step 2 see every node within ell; an owned node's sum runs over
// the same nodes in the same order on any number of ranks, so the answer differs from one rank's
// only by the order of the P2G sums of step 1 (round-off). The DMDA is rebuilt when the grid's
// ownership changes (load balance).
#include "grid_index.hpp"
#include "mpm/swarm_access.hpp"
#include <cmath>
#include <vector>

namespace burst {

namespace {

constexpr PetscInt kDof = 1 + kNonlocalComponents; // [weight, weighted values]

struct NonlocalGrid {
  DM                     da     = nullptr;
  Vec                    global = nullptr, local = nullptr;
  std::vector<PetscReal> scratch[2]; // pass buffers over the local ghosted box
  std::vector<PetscInt>  ranges[3];  // ownership of the node DMDA it was built with
  PetscInt               width      = 0;
  PetscLogEvent          event      = 0;
  bool                   first_call = true;
};

PetscErrorCode NonlocalGridDestroy(void *ctx)
{
  auto *g = static_cast<NonlocalGrid *>(ctx);
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&g->global));
  PetscCall(VecDestroy(&g->local));
  PetscCall(DMDestroy(&g->da));
  delete g;
  PetscFunctionReturn(PETSC_SUCCESS);
}

// The state, composed with the swarm (it lives and dies with it).
PetscErrorCode NonlocalGridGet(MpmSolver &mpm, NonlocalGrid **out)
{
  PetscContainer container = nullptr;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectQuery((PetscObject)mpm.swarm, "burst_nonlocal_grid", (PetscObject *)&container));
  if (!container) {
    auto *g = new NonlocalGrid();
    PetscCall(PetscLogEventRegister("MPM_Nonlocal", DM_CLASSID, &g->event));
    PetscCall(PetscContainerCreate(mpm.comm, &container));
    PetscCall(PetscContainerSetPointer(container, g));
    PetscCall(PetscContainerSetUserDestroy(container, NonlocalGridDestroy));
    PetscCall(PetscObjectCompose((PetscObject)mpm.swarm, "burst_nonlocal_grid", (PetscObject)container));
    PetscCall(PetscContainerDestroy(&container));
    PetscCall(PetscObjectQuery((PetscObject)mpm.swarm, "burst_nonlocal_grid", (PetscObject *)&container));
  }
  PetscCall(PetscContainerGetPointer(container, (void **)out));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// (Re)builds the DMDA when the width or the grid's ownership changed.
PetscErrorCode NonlocalGridSetUp(MpmSolver &mpm, NonlocalGrid &g, PetscInt width, const char material[], PetscReal ell)
{
  const Grid     &grid = mpm.grid;
  const PetscInt *l[3] = {nullptr, nullptr, nullptr};
  PetscInt        m[3] = {1, 1, 1};
  PetscFunctionBeginUser;
  PetscCall(DMDAGetInfo(grid.da_nodes, nullptr, nullptr, nullptr, nullptr, &m[0], &m[1], &m[2], nullptr, nullptr, nullptr, nullptr, nullptr, nullptr));
  PetscCall(DMDAGetOwnershipRanges(grid.da_nodes, &l[0], &l[1], &l[2]));
  bool same = g.da && g.width == width;
  for (PetscInt d = 0; d < grid.dim && same; ++d) same = g.ranges[d] == std::vector<PetscInt>(l[d], l[d] + m[d]);
  if (same) PetscFunctionReturn(PETSC_SUCCESS);
  for (PetscInt d = 0; d < grid.dim; ++d) {
    g.ranges[d].assign(l[d], l[d] + m[d]);
    for (PetscInt r = 0; r < m[d] && m[d] > 1; ++r) // one rank along d: every node is local (DMDA allows that)
      PetscCheck(l[d][r] >= width, mpm.comm, PETSC_ERR_USER_INPUT,
                 "-%s_regularization_length %g m spans %" PetscInt_FMT " cells, more than the %" PetscInt_FMT " nodes a rank owns along direction %" PetscInt_FMT ": use fewer ranks, a finer grid or a shorter length", material, (double)ell, width,
                 l[d][r], d);
  }
  PetscCall(VecDestroy(&g.global));
  PetscCall(VecDestroy(&g.local));
  PetscCall(DMDestroy(&g.da));
  const DMBoundaryType bt = DM_BOUNDARY_NONE;
  if (grid.dim == 2) PetscCall(DMDACreate2d(mpm.comm, bt, bt, DMDA_STENCIL_BOX, grid.cells[0] + 1, grid.cells[1] + 1, m[0], m[1], kDof, width, l[0], l[1], &g.da));
  else PetscCall(DMDACreate3d(mpm.comm, bt, bt, bt, DMDA_STENCIL_BOX, grid.cells[0] + 1, grid.cells[1] + 1, grid.cells[2] + 1, m[0], m[1], m[2], kDof, width, l[0], l[1], l[2], &g.da));
  PetscCall(DMSetUp(g.da));
  PetscCall(DMCreateGlobalVector(g.da, &g.global));
  PetscCall(DMCreateLocalVector(g.da, &g.local));
  PetscInt n;
  PetscCall(VecGetLocalSize(g.local, &n));
  g.scratch[0].assign(n, 0);
  g.scratch[1].assign(n, 0);
  g.width = width;
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Linear hat weights of a particle: the lower node per direction and its two weights.
struct Hat {
  PetscInt  i[3]    = {0, 0, 0};
  PetscReal w[3][2] = {{1, 0}, {1, 0}, {1, 0}};
};
inline Hat HatAt(const Grid &grid, const PetscReal *x)
{
  Hat h;
  for (PetscInt d = 0; d < grid.dim; ++d) {
    const PetscReal s = (x[d] - grid.lower[d]) / grid.h[d];
    PetscInt        i = (PetscInt)std::floor(s);
    i                 = PetscMin(PetscMax(i, 0), grid.cells[d] - 1);
    const PetscReal t = PetscMin(PetscMax(s - i, 0.0), 1.0);
    h.i[d]            = i;
    h.w[d][0]         = 1 - t;
    h.w[d][1]         = t;
  }
  return h;
}

// One pass of the bell along direction `dir` (step 2): out = sum_k a(k h) in(. + k e_dir), at the
// owned nodes in the directions up to dir and the ghosted ones beyond (the next pass reads them).
void BellPass(const Grid &grid, const PetscInt xs[3], const PetscInt xm[3], const PetscInt gs[3], const PetscInt gm[3], PetscInt dir, PetscInt width, const PetscReal *a, const PetscReal *in, PetscReal *out)
{
  PetscInt lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  for (PetscInt d = 0; d < grid.dim; ++d) {
    lo[d] = d <= dir ? xs[d] : gs[d];
    hi[d] = d <= dir ? xs[d] + xm[d] : gs[d] + gm[d];
  }
  const PetscInt M = grid.cells[dir] + 1, stride = dir == 0 ? 1 : (dir == 1 ? gm[0] : gm[0] * gm[1]);
  const bool     mirror_lo = grid.bc[dir][0] == FaceBC::Symmetry, mirror_hi = grid.bc[dir][1] == FaceBC::Symmetry;
  for (PetscInt k = lo[2]; k < hi[2]; ++k)
    for (PetscInt j = lo[1]; j < hi[1]; ++j)
      for (PetscInt i = lo[0]; i < hi[0]; ++i) {
        const PetscInt ijk[3] = {i, j, k}, base = ((k - gs[2]) * gm[1] + (j - gs[1])) * gm[0] + (i - gs[0]);
        const PetscInt c         = ijk[dir];
        PetscReal      sum[kDof] = {};
        for (PetscInt off = -width; off <= width; ++off) {
          PetscInt n       = c + off;
          bool     outside = false;
          while (!outside && (n < 0 || n > M - 1)) { // mirrored images (repeatedly, for a strip between two symmetry faces)
            if (n < 0) {
              if (mirror_lo) n = -n;
              else outside = true;
            } else {
              if (mirror_hi && M > 1) n = 2 * (M - 1) - n;
              else outside = true;
            }
          }
          if (outside) continue;
          const PetscReal *v = in + kDof * (base + (n - c) * stride);
          const PetscReal  w = a[off + width];
          for (PetscInt e = 0; e < kDof; ++e) sum[e] += w * v[e];
        }
        for (PetscInt e = 0; e < kDof; ++e) out[kDof * base + e] = sum[e];
      }
}

} // namespace

// The nonlocal averages of the kNonlocalSource values of every material with a NonlocalLength.
// Collective; a no-op (one loop over the materials) when no material asks for it.
PetscErrorCode NonlocalAverage(MpmSolver &mpm)
{
  const Grid   &grid = mpm.grid;
  NonlocalGrid *g    = nullptr;
  PetscFunctionBeginUser;
  if (!mpm.HasParticles()) PetscFunctionReturn(PETSC_SUCCESS);
  bool any = false;
  for (const auto &m : mpm.materials) any = any || m->NonlocalLength() > 0;
  if (!any) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(NonlocalGridGet(mpm, &g));
  if (g->first_call) {
    // The stress update before the first average applied its increments locally (nonlocal_active_
    // was false): from the next step on it leaves them to the average.
    g->first_call = false;
    for (auto &m : mpm.materials)
      if (m->NonlocalLength() > 0) m->nonlocal_active_ = true;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscLogEventBegin(g->event, 0, 0, 0, 0));
  for (PetscInt id = 0; id < (PetscInt)mpm.materials.size(); ++id) {
    const PetscReal ell = mpm.materials[id]->NonlocalLength();
    if (!(ell > 0)) continue;
    PetscInt width = 1;
    for (PetscInt d = 0; d < grid.dim; ++d) width = PetscMax(width, (PetscInt)std::ceil(ell / grid.h[d] - 1e-12));
    PetscCall(NonlocalGridSetUp(mpm, *g, width, mpm.materials[id]->Name(), ell));
    PetscInt xs[3] = {0, 0, 0}, xm[3] = {1, 1, 1}, gs[3] = {0, 0, 0}, gm[3] = {1, 1, 1};
    PetscCall(DMDAGetCorners(g->da, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
    PetscCall(DMDAGetGhostCorners(g->da, &gs[0], &gs[1], &gs[2], &gm[0], &gm[1], &gm[2]));
    auto             local_index = [&](const PetscInt ijk[3]) { return ((ijk[2] - gs[2]) * gm[1] + (ijk[1] - gs[1])) * gm[0] + (ijk[0] - gs[0]); };
    PetscInt         n;
    const PetscReal *x, *source;
    PetscReal       *average;
    const PetscInt  *material;

    SwarmAccess fields(mpm.swarm);
    PetscCall(DMSwarmGetLocalSize(mpm.swarm, &n));
    PetscCall(fields.Get(DMSwarmPICField_coor, &x));
    PetscCall(fields.Get(field::material, &material));
    PetscCall(fields.Get(kNonlocalSource, &source));
    PetscCall(fields.Get(kNonlocalAverage, &average));
    const PetscInt nx = grid.dim == 3 ? 2 : 1;
    // 1. P2G
    PetscReal *L;
    PetscCall(VecSet(g->local, 0));
    PetscCall(VecGetArray(g->local, &L));
    for (PetscInt p = 0; p < n; ++p) {
      const PetscReal *s = source + kDof * p;
      if (material[p] != id || !(s[0] > 0)) continue;
      const Hat h = HatAt(grid, x + grid.dim * p);
      for (PetscInt c = 0; c < nx; ++c)
        for (PetscInt b = 0; b < 2; ++b)
          for (PetscInt a = 0; a < 2; ++a) {
            const PetscInt ijk[3] = {h.i[0] + a, h.i[1] + b, grid.dim == 3 ? h.i[2] + c : 0};
            for (PetscInt d = 0; d < grid.dim; ++d) PetscCheck(ijk[d] >= gs[d] && ijk[d] < gs[d] + gm[d], PETSC_COMM_SELF, PETSC_ERR_PLIB, "Nonlocal average: a particle of rank %d lies outside its ghosted nodes", mpm.rank);
            const PetscReal w = s[0] * h.w[0][a] * h.w[1][b] * h.w[2][c];
            PetscReal      *v = L + kDof * local_index(ijk);
            v[0] += w;
            for (PetscInt e = 1; e < kDof; ++e) v[e] += w * s[e];
          }
    }
    PetscCall(VecRestoreArray(g->local, &L));
    PetscCall(VecSet(g->global, 0));
    PetscCall(DMLocalToGlobal(g->da, g->local, ADD_VALUES, g->global));
    PetscCall(DMGlobalToLocal(g->da, g->global, INSERT_VALUES, g->local));
    // 2. the bell, one direction at a time (a(r) on the node offsets of the direction)
    {
      const PetscReal *in;
      PetscCall(VecGetArrayRead(g->local, &in));
      const PetscReal       *src = in;
      PetscInt               buf = 0;
      std::vector<PetscReal> a(2 * width + 1); // once per step and material, not per particle
      for (PetscInt d = 0; d < grid.dim; ++d) {
        for (PetscInt o = -width; o <= width; ++o) {
          const PetscReal r = o * grid.h[d] / ell;
          a[o + width]      = std::fabs(r) < 1 ? (1 - r * r) * (1 - r * r) : 0;
        }
        BellPass(grid, xs, xm, gs, gm, d, width, a.data(), src, g->scratch[buf].data());
        src = g->scratch[buf].data();
        buf = 1 - buf;
      }
      PetscCall(VecRestoreArrayRead(g->local, &in));
      // the owned nodes to the global vector, then ghosts for the G2P
      PetscReal *out;
      PetscCall(VecGetArray(g->global, &out));
      PetscInt q = 0;
      for (PetscInt k = xs[2]; k < xs[2] + xm[2]; ++k)
        for (PetscInt j = xs[1]; j < xs[1] + xm[1]; ++j)
          for (PetscInt i = xs[0]; i < xs[0] + xm[0]; ++i, ++q) {
            const PetscInt ijk[3] = {i, j, k};
            for (PetscInt e = 0; e < kDof; ++e) out[kDof * q + e] = src[kDof * local_index(ijk) + e];
          }
      PetscCall(VecRestoreArray(g->global, &out));
      PetscCall(DMGlobalToLocal(g->da, g->global, INSERT_VALUES, g->local));
    }
    // 3. G2P: the ratio of the interpolated sums
    const PetscReal *G;
    PetscCall(VecGetArrayRead(g->local, &G));
    for (PetscInt p = 0; p < n; ++p) {
      if (material[p] != id) continue;
      const Hat h         = HatAt(grid, x + grid.dim * p);
      PetscReal sum[kDof] = {};
      for (PetscInt c = 0; c < nx; ++c)
        for (PetscInt b = 0; b < 2; ++b)
          for (PetscInt a = 0; a < 2; ++a) {
            const PetscInt   ijk[3] = {h.i[0] + a, h.i[1] + b, grid.dim == 3 ? h.i[2] + c : 0};
            const PetscReal  w      = h.w[0][a] * h.w[1][b] * h.w[2][c];
            const PetscReal *v      = G + kDof * local_index(ijk);
            for (PetscInt e = 0; e < kDof; ++e) sum[e] += w * v[e];
          }
      const PetscReal *s = source + kDof * p;
      for (PetscInt e = 1; e < kDof; ++e) average[kNonlocalComponents * p + e - 1] = s[0] > 0 && sum[0] > 0 ? sum[e] / sum[0] : 0; // weight 0: takes nothing
    }
    PetscCall(VecRestoreArrayRead(g->local, &G));
    PetscCall(fields.RestoreAll());
  }
  PetscCall(PetscLogEventEnd(g->event, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
