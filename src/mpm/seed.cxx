// Seeding: geometry objects from options and the particles they fill.
//
// Each geometry fills the cells owned by this rank with particles_per_cell^dim particles per cell at
// the centres of equal sub-cells. A particle takes the volume of its sub-cell and mass = density x
// volume. Geometries are filled in the order listed; a point already claimed is not seeded twice.
// -<name>_seeding polar fills a disk, cylinder or annulus with rings about its centre instead: the
// surfaces are smooth rather than staircases of the grid, and the arrangement is the same at every
// angle, so the lattice does not mark angles where a wall necks first.
#include "mpm/geometry.hpp"
#include "mpm/material_state.hpp"
#include "util.hpp"
#include "memory.hpp"
#include <cmath>

namespace burst {

const char *const GeometryTypeNames[]    = {"box", "disk", "cylinder", "annulus", "sphere"};
const char *const PressureSurfaceNames[] = {"none", "inner", "outer"};
const char *const SeedingNames[]         = {"lattice", "polar"};

PetscReal LoadCurve::Evaluate(PetscReal t) const
{
  if (time.empty()) return 0;
  if (t <= time.front()) return value.front();
  if (t >= time.back()) return value.back();
  size_t k = 1;
  while (time[k] < t) ++k;
  const PetscReal s = (t - time[k - 1]) / (time[k] - time[k - 1]);
  return value[k - 1] + s * (value[k] - value[k - 1]);
}

void Geometry::RadialDirection(const PetscReal x[], PetscReal r_hat[], PetscReal *r) const
{
  const PetscInt nd = (type == GeometryType::Sphere) ? dim : 2;
  PetscReal      r2 = 0;
  for (PetscInt d = 0; d < 3; ++d) r_hat[d] = 0;
  for (PetscInt d = 0; d < nd; ++d) {
    r_hat[d] = x[d] - center[d];
    r2 += r_hat[d] * r_hat[d];
  }
  *r = std::sqrt(r2);
  if (*r > 0)
    for (PetscInt d = 0; d < nd; ++d) r_hat[d] /= *r;
}

bool Geometry::Contains(const PetscReal x[]) const
{
  PetscReal r_hat[3], r;
  switch (type) {
  case GeometryType::Box:
    for (PetscInt d = 0; d < dim; ++d)
      if (x[d] < lower[d] || x[d] > upper[d]) return false;
    return true;
  case GeometryType::Sphere: RadialDirection(x, r_hat, &r); return r <= radius;
  default: break;
  }
  // disk / cylinder / annulus: in-plane radius, sector, and z-extent in 3-D
  RadialDirection(x, r_hat, &r);
  if (r > radius) return false;
  if (type == GeometryType::Annulus && r < inner_radius) return false;
  if (dim == 3 && (x[2] < lower[2] || x[2] > upper[2])) return false;
  if (angle_range[1] - angle_range[0] < 360) {
    PetscReal angle = std::atan2(x[1] - center[1], x[0] - center[0]) * 180.0 / PETSC_PI;
    // into [start, start + 360) in one step (a loop of +-360 would take ~start/360 turns: a hang for a
    // start of 1e17 degrees, which the range check start < end <= start + 360 lets through)
    angle = angle_range[0] + std::fmod(std::fmod(angle - angle_range[0], 360.0) + 360.0, 360.0);
    if (angle > angle_range[1]) return false;
  }
  return true;
}

PetscErrorCode ReadLoadCurves(MpmSolver &mpm)
{
  char     *names[32];
  PetscInt  n = 32;
  PetscBool set;
  PetscFunctionBeginUser;
  PetscOptionsBegin(mpm.comm, "", "Load curves", "Loads");
  PetscCall(PetscOptionsStringArray("-load_curves", "Names of piecewise-linear load curves; each is given by -<name>_time t0,t1,... (s) and -<name>_value v0,v1,... (Pa)", "", names, &n, &set));
  PetscOptionsEnd();
  if (!set) n = 0;
  for (PetscInt c = 0; c < n; ++c) {
    LoadCurve curve;
    PetscReal t[256], v[256];
    PetscInt  nt = 256, nv = 256;
    PetscBool st = PETSC_FALSE, sv = PETSC_FALSE;
    curve.name = names[c];
    PetscOptionsBegin(mpm.comm, (curve.name + "_").c_str(), "Load curve", "Loads");
    PetscCall(PetscOptionsRealArray("-time", "Times of the load curve points (s), increasing", "", t, &nt, &st));
    PetscCall(PetscOptionsRealArray("-value", "Values at those times (Pa)", "", v, &nv, &sv));
    PetscOptionsEnd();
    PetscCheck(st && sv && nt == nv && nt >= 1, mpm.comm, PETSC_ERR_USER_INPUT, "Load curve '%s': give -%s_time and -%s_value with the same number (>= 1) of entries", names[c], names[c], names[c]);
    for (PetscInt k = 0; k < nt; ++k) {
      PetscCheck(k == 0 || t[k] > t[k - 1], mpm.comm, PETSC_ERR_USER_INPUT, "Load curve '%s': -%s_time must be strictly increasing", names[c], names[c]);
      curve.time.push_back(t[k]);
      curve.value.push_back(v[k]);
    }
    mpm.load_curves.push_back(curve);
    PetscCall(PetscFree(names[c]));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ReadGeometries(MpmSolver &mpm)
{
  char          *names[64];
  PetscInt       n = 64;
  PetscBool      set;
  const PetscInt dim = mpm.grid.dim;
  PetscFunctionBeginUser;
  PetscOptionsBegin(mpm.comm, "", "Geometry objects", "Seeding");
  PetscCall(PetscOptionsStringArray("-geometries", "Names of the geometry objects that seed particles; each is configured with -<name>_type etc.", "", names, &n, &set));
  PetscOptionsEnd();
  if (mpm.help && (!(set && n > 0) || mpm.materials.empty())) PetscFunctionReturn(PETSC_SUCCESS);
  if (mpm.materials.empty()) { // no solids: a gas-only scene seeds nothing
    PetscCheck(!(set && n > 0), mpm.comm, PETSC_ERR_USER_INPUT, "Option -geometries seeds particles, but -materials lists no solid material for them");
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCheck(set && n > 0, mpm.comm, PETSC_ERR_USER_INPUT, "No particles: give -geometries name1,name2,... and configure each with -<name>_type (box, disk, cylinder, annulus, sphere)");
  for (PetscInt gi = 0; gi < n; ++gi) {
    auto      g    = std::make_unique<Geometry>();
    int       type = 0, surface = 0;
    char      material[256] = "", curve[256] = "";
    PetscBool has_type = PETSC_FALSE, has_material = PETSC_FALSE, has_curve = PETSC_FALSE;
    g->name               = names[gi];
    g->dim                = dim;
    const std::string pre = g->name + "_";
    const char       *P   = pre.c_str();
    PetscOptionsBegin(mpm.comm, P, "Geometry object", "Seeding");
    PetscCall(OptionsChoice(PetscOptionsObject, "-type", "Shape of the object", GeometryTypeNames, 5, &type, &has_type));
    g->type = (GeometryType)type;
    PetscCall(PetscOptionsString("-material", "Name of the material filling the object (one of -materials)", "", material, material, sizeof(material), &has_material));
    PetscCall(OptionsRealVector(PetscOptionsObject, "-lower", "Box: lower corner (m); cylinder/annulus in 3-D: z of the lower end in the last entry", g->lower, dim, nullptr));
    PetscCall(OptionsRealVector(PetscOptionsObject, "-upper", "Box: upper corner (m); cylinder/annulus in 3-D: z of the upper end in the last entry", g->upper, dim, nullptr));
    PetscCall(OptionsRealVector(PetscOptionsObject, "-center", "Centre of disk, cylinder axis, annulus or sphere (m)", g->center, dim, nullptr));
    PetscCall(PetscOptionsReal("-radius", "Outer radius (m)", "", g->radius, &g->radius, nullptr));
    PetscCall(PetscOptionsReal("-inner_radius", "Annulus inner radius (m)", "", g->inner_radius, &g->inner_radius, nullptr));
    PetscCall(OptionsRealVector(PetscOptionsObject, "-angle_range", "Sector of a disk/annulus/cylinder: start,end angle in degrees (0,90 for a quarter)", g->angle_range, 2, nullptr));
    PetscCall(PetscOptionsInt("-particles_per_cell", "Particles per cell in each direction, >= 1", "", g->particles_per_cell, &g->particles_per_cell, nullptr));
    int seeding = 0;
    PetscCall(OptionsChoice(PetscOptionsObject, "-seeding", "Particle arrangement; polar: rings about -center spaced cell/particles_per_cell (disk, cylinder, annulus)", SeedingNames, 2, &seeding, nullptr));
    g->seeding = (Seeding)seeding;
    PetscCall(OptionsRealVector(PetscOptionsObject, "-velocity", "Initial velocity (m/s), each component in [-1e5, 1e5]", g->velocity, dim, nullptr));
    PetscCall(PetscOptionsReal("-angular_velocity", "Initial rigid spin about -center (rad/s; about the z axis in 3-D) added to -velocity, default 0", "", g->angular_velocity, &g->angular_velocity, nullptr));
    PetscCall(PetscOptionsReal("-radial_velocity", "Initial radial velocity added to -velocity (m/s), in [-1e5, 1e5]", "", g->radial_velocity, &g->radial_velocity, nullptr));
    PetscCall(PetscOptionsReal("-temperature", "Initial temperature (K), in (0, 1e6]", "", g->temperature, &g->temperature, nullptr));
    PetscCall(OptionsChoice(PetscOptionsObject, "-pressure_surface", "Surface of a disk/annulus/cylinder/sphere loaded by the pressure of -<name>_pressure_curve", PressureSurfaceNames, 3, &surface, nullptr));
    g->pressure_surface = (PressureSurface)surface;
    PetscCall(PetscOptionsString("-pressure_curve", "Name of the load curve (of -load_curves) giving the pressure on that surface", "", curve, curve, sizeof(curve), &has_curve));
    PetscOptionsEnd();

    PetscCheck(has_type, mpm.comm, PETSC_ERR_USER_INPUT, "Geometry '%s': give -%stype (box, disk, cylinder, annulus, sphere)", P, P);
    PetscCheck(has_material, mpm.comm, PETSC_ERR_USER_INPUT, "Geometry '%s': give -%smaterial (one of the names in -materials)", names[gi], P);
    g->material = -1;
    for (size_t m = 0; m < mpm.materials.size(); ++m)
      if (mpm.materials[m]->name_ == material) g->material = (PetscInt)m;
    PetscCheck(g->material >= 0, mpm.comm, PETSC_ERR_USER_INPUT, "Geometry '%s': -%smaterial %s is not one of -materials", names[gi], P, material);
    PetscCheck(g->particles_per_cell >= 1 && g->particles_per_cell <= 16, mpm.comm, PETSC_ERR_USER_INPUT, "Option -%sparticles_per_cell = %" PetscInt_FMT " is out of range: it must be in [1, 16]", P, g->particles_per_cell);
    PetscCall(CheckRange(mpm.comm, Prefixed(P, "temperature").c_str(), g->temperature, 0, 1e6, PETSC_TRUE));
    // bounded by physics (detonation products move at ~1e4 m/s): a typo of exponent stops here, not as a NaN in step 0
    for (PetscInt d = 0; d < dim; ++d) PetscCall(CheckRange(mpm.comm, Prefixed(P, "velocity").c_str(), g->velocity[d], -1e5, 1e5, PETSC_FALSE));
    PetscCall(CheckRange(mpm.comm, Prefixed(P, "radial_velocity").c_str(), g->radial_velocity, -1e5, 1e5, PETSC_FALSE));
    if (g->type != GeometryType::Box) PetscCall(CheckRange(mpm.comm, Prefixed(P, "radius").c_str(), g->radius, 0, PETSC_MAX_REAL, PETSC_TRUE));
    if (g->type == GeometryType::Annulus) {
      PetscCheck(g->inner_radius >= 0 && g->inner_radius < g->radius, mpm.comm, PETSC_ERR_USER_INPUT, "Option -%sinner_radius = %g is out of range: it must be in [0, radius = %g)", P, (double)g->inner_radius, (double)g->radius);
    }
    if (g->type == GeometryType::Box || ((g->type == GeometryType::Cylinder || g->type == GeometryType::Annulus) && dim == 3)) {
      const PetscInt d0 = g->type == GeometryType::Box ? 0 : 2;
      for (PetscInt d = d0; d < dim; ++d) PetscCheck(g->upper[d] > g->lower[d], mpm.comm, PETSC_ERR_USER_INPUT, "Geometry '%s': -%supper must exceed -%slower in direction %" PetscInt_FMT, names[gi], P, P, d);
    }
    PetscCheck(g->seeding == Seeding::Lattice || g->type == GeometryType::Disk || g->type == GeometryType::Cylinder || g->type == GeometryType::Annulus, mpm.comm, PETSC_ERR_USER_INPUT,
               "Option -%sseeding polar needs -%stype disk, cylinder or annulus (the object is a %s); valid here: lattice", P, P, GeometryTypeNames[(int)g->type]);
    PetscCheck(g->seeding == Seeding::Lattice || !mpm.axisymmetric, mpm.comm, PETSC_ERR_USER_INPUT, "Option -%sseeding polar is for the x-y plane, not an axisymmetric run (-axisymmetric); valid here: lattice", P);
    PetscCheck(g->type != GeometryType::Disk || dim == 2, mpm.comm, PETSC_ERR_USER_INPUT, "Geometry '%s': -%stype disk is 2-D; in 3-D use cylinder or sphere", names[gi], P);
    PetscCheck(g->angle_range[1] > g->angle_range[0] && g->angle_range[1] - g->angle_range[0] <= 360, mpm.comm, PETSC_ERR_USER_INPUT, "Option -%sangle_range: need start < end <= start + 360 (degrees)", P);
    if (g->pressure_surface != PressureSurface::None) {
      PetscCheck(g->type != GeometryType::Box, mpm.comm, PETSC_ERR_USER_INPUT, "Geometry '%s': -%spressure_surface needs a disk, cylinder, annulus or sphere", names[gi], P);
      PetscCheck(has_curve, mpm.comm, PETSC_ERR_USER_INPUT, "Geometry '%s': -%spressure_surface needs -%spressure_curve NAME", names[gi], P, P);
      for (size_t c = 0; c < mpm.load_curves.size(); ++c)
        if (mpm.load_curves[c].name == curve) g->load_curve = (PetscInt)c;
      PetscCheck(g->load_curve >= 0, mpm.comm, PETSC_ERR_USER_INPUT, "Geometry '%s': -%spressure_curve %s is not one of -load_curves", names[gi], P, curve);
    }
    mpm.geometries.push_back(std::move(g));
    PetscCall(PetscFree(names[gi]));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

struct SeedPoint {
  PetscReal  x[3];
  PetscInt   geometry;
  PetscInt64 id; // from (global cell, geometry, sub-cell): the same on any number of ranks
  // polar seeding: the particle's volume, half-widths and radial depth (0: the lattice's sub-cell)
  PetscReal volume = 0, half_width[3] = {0, 0, 0}, depth = 0, surface_scale = 1;
};

PetscErrorCode SeedParticles(MpmSolver &mpm)
{
  const Grid            &g   = mpm.grid;
  const PetscInt         dim = g.dim;
  PetscInt               xs[3], xm[3];
  std::vector<SeedPoint> points;
  PetscFunctionBeginUser;
  PetscCall(DMDAGetCorners(g.da_nodes, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscInt ce[3]; // owned cells: lower node owned and cell index < cells
  for (int d = 0; d < 3; ++d) ce[d] = d < dim ? PetscMin(xs[d] + xm[d], g.cells[d]) : 1;
  if (dim == 2) { xs[2] = 0; }
  // Particle ids: ((cell * geometries + geometry) * max_sub + sub), independent of the decomposition,
  // so that id-keyed random draws and traced particles are the same on any number of ranks.
  PetscInt max_ppc = 1;
  for (const auto &geo : mpm.geometries) max_ppc = PetscMax(max_ppc, geo->particles_per_cell);
  const PetscInt64 max_sub = dim == 2 ? (PetscInt64)max_ppc * max_ppc : (PetscInt64)max_ppc * max_ppc * max_ppc;
  const PetscInt64 ngeom   = (PetscInt64)mpm.geometries.size();
  {
    // refuse a particle count beyond memory before the points are gathered: first an upper bound
    // (every sub-cell of every geometry), then, only if that does not fit, an estimate from the cell
    // centres (a cell whose centre a geometry contains counts all its sub-cells: one test per cell)
    const PetscReal per_particle = kMemoryParticleFactor * mpm.swarm_bytes;
    PetscReal       bound        = 0;
    for (const auto &geo : mpm.geometries) bound += (PetscReal)(ce[0] - xs[0]) * (ce[1] - xs[1]) * (ce[2] - xs[2]) * std::pow((PetscReal)geo->particles_per_cell, (PetscReal)dim);
    PetscReal available, most;
    PetscCall(MemoryAvailablePerRank(mpm.comm, &available));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &bound, 1, MPIU_REAL, MPI_MAX, mpm.comm));
    if (bound * per_particle > available) {
      PetscReal count = 0;
      for (PetscInt k = xs[2]; k < ce[2]; ++k)
        for (PetscInt j = xs[1]; j < ce[1]; ++j)
          for (PetscInt i = xs[0]; i < ce[0]; ++i) {
            const PetscInt cell[3] = {i, j, k};
            PetscReal      x[3]    = {0, 0, 0};
            for (PetscInt d = 0; d < dim; ++d) x[d] = g.lower[d] + (cell[d] + 0.5) * g.h[d];
            for (const auto &geo : mpm.geometries)
              if (geo->Contains(x)) count += std::pow((PetscReal)geo->particles_per_cell, (PetscReal)dim);
          }
      PetscCallMPI(MPI_Allreduce(&count, &most, 1, MPIU_REAL, MPI_MAX, mpm.comm));
      char what[128];
      PetscCall(PetscSNPrintf(what, sizeof(what), "Seeding %.3g particles on the fullest rank (%.0f bytes each)", (double)most, (double)per_particle));
      PetscCall(MemoryCheck(mpm.comm, what, count * per_particle, "fewer particles per cell (-<geometry>_particles_per_cell), fewer cells, or more ranks"));
    }
  }
  for (PetscInt k = xs[2]; k < ce[2]; ++k)
    for (PetscInt j = xs[1]; j < ce[1]; ++j)
      for (PetscInt i = xs[0]; i < ce[0]; ++i) {
        const PetscInt cell[3] = {i, j, k};
        for (PetscInt gi = 0; gi < (PetscInt)mpm.geometries.size(); ++gi) {
          const Geometry &geo = *mpm.geometries[gi];
          if (geo.seeding == Seeding::Polar) continue;
          const PetscInt ppc  = geo.particles_per_cell;
          const PetscInt nsub = dim == 2 ? ppc * ppc : ppc * ppc * ppc;
          for (PetscInt s = 0; s < nsub; ++s) {
            const PetscInt sub[3] = {s % ppc, (s / ppc) % ppc, s / (ppc * ppc)};
            SeedPoint      pt;
            pt.x[2] = 0;
            for (PetscInt d = 0; d < dim; ++d) pt.x[d] = g.lower[d] + (cell[d] + (sub[d] + 0.5) / ppc) * g.h[d];
            if (!geo.Contains(pt.x)) continue;
            bool claimed = false;
            for (PetscInt gj = 0; gj < gi && !claimed; ++gj) claimed = mpm.geometries[gj]->Contains(pt.x);
            if (claimed) continue;
            pt.geometry              = gi;
            const PetscInt64 cell_id = i + (PetscInt64)g.cells[0] * (j + (PetscInt64)g.cells[1] * k);
            pt.id                    = (cell_id * ngeom + gi) * max_sub + s;
            points.push_back(pt);
          }
        }
      }

  // Polar seeding: rings of radial spacing dr ~ h/ppc about the centre, each with points at arc spacing
  // ~ h/ppc (and, in 3-D, layers along z at h_z/ppc); a point r, theta stands for the element
  // r dr dtheta (dz), so the volumes add up to the object's exactly. The rank owning the grid cell
  // that holds a point seeds it (the cell as particle migration finds it); ids count the points of the
  // object in order after the lattice's ids. A rank visits only the layers and rings that cross its
  // part of the grid, and counts the others' points for the ids.
  mpm.next_pid = (PetscInt64)g.cells[0] * g.cells[1] * (dim == 3 ? g.cells[2] : 1) * ngeom * max_sub; // first id after the lattice's
  PetscReal box_lo[3], box_hi[3];                                                                     // this rank's part of the grid
  for (PetscInt d = 0; d < dim; ++d) {
    box_lo[d] = g.lower[d] + xs[d] * g.h[d];
    box_hi[d] = g.lower[d] + ce[d] * g.h[d];
  }
  for (PetscInt gi = 0; gi < (PetscInt)mpm.geometries.size(); ++gi) {
    const Geometry &geo = *mpm.geometries[gi];
    if (geo.seeding != Seeding::Polar) continue;
    const PetscReal spacing = PetscMin(g.h[0], g.h[1]) / geo.particles_per_cell;
    const PetscReal r0      = geo.type == GeometryType::Annulus ? geo.inner_radius : 0;
    const PetscReal sector  = (geo.angle_range[1] - geo.angle_range[0]) * PETSC_PI / 180;
    const PetscReal rings = (geo.radius - r0) / spacing, layers = dim == 3 ? (geo.upper[2] - geo.lower[2]) / (g.h[2] / geo.particles_per_cell) : 1;
    // an object far larger than the grid (a radius in mm typed as m) would be counted point by point
    PetscCheck(rings * layers < 1e9 && geo.radius * sector / spacing * layers < 1e12, mpm.comm, PETSC_ERR_USER_INPUT, "Geometry '%s': -%s_seeding polar would place %.3g rings of %.3g points at most: check -%s_radius against the grid",
               geo.name.c_str(), geo.name.c_str(), (double)(rings * layers), (double)(geo.radius * sector / spacing), geo.name.c_str());
    const PetscInt  nr = PetscMax(1, (PetscInt)std::lround(rings));
    const PetscReal dr = (geo.radius - r0) / nr;
    PetscInt        nz = 1;
    PetscReal       dz = 1, z0 = 0;
    if (dim == 3) {
      nz = PetscMax(1, (PetscInt)std::lround(layers));
      dz = (geo.upper[2] - geo.lower[2]) / nz;
      z0 = geo.lower[2];
    }
    // the distance from the centre to the nearest and farthest points of this rank's part (in-plane)
    PetscReal near2 = 0, far2 = 0;
    for (PetscInt d = 0; d < 2; ++d) {
      const PetscReal lo = box_lo[d] - geo.center[d], hi = box_hi[d] - geo.center[d];
      const PetscReal nd = lo > 0 ? lo : (hi < 0 ? -hi : 0);
      near2 += nd * nd;
      far2 += PetscMax(lo * lo, hi * hi);
    }
    const PetscReal near = std::sqrt(near2), far = std::sqrt(far2);
    PetscInt64      index = 0;
    for (PetscInt iz = 0; iz < nz; ++iz) {
      const PetscReal z          = z0 + (iz + 0.5) * dz;
      const bool      layer_here = dim < 3 || (z >= box_lo[2] - dz && z <= box_hi[2] + dz);
      for (PetscInt ir = 0; ir < nr; ++ir) {
        const PetscReal r      = r0 + (ir + 0.5) * dr;
        const PetscInt  ntheta = PetscMax(1, (PetscInt)std::lround(r * sector / spacing));
        const PetscReal dtheta = sector / ntheta;
        if (!layer_here || r < near - dr || r > far + dr) { // no point of this ring is in this rank's part
          index += ntheta;
          continue;
        }
        for (PetscInt it = 0; it < ntheta; ++it, ++index) {
          const PetscReal theta = geo.angle_range[0] * PETSC_PI / 180 + (it + 0.5) * dtheta;
          SeedPoint       pt;
          pt.x[0]   = geo.center[0] + r * std::cos(theta);
          pt.x[1]   = geo.center[1] + r * std::sin(theta);
          pt.x[2]   = dim == 3 ? z : 0;
          bool mine = true;
          for (PetscInt d = 0; d < dim && mine; ++d) {
            if (!(pt.x[d] >= g.lower[d] && pt.x[d] <= g.upper[d])) mine = false; // outside the grid: not seeded
            else {
              const PetscInt c = PetscMin((PetscInt)std::floor((pt.x[d] - g.lower[d]) / g.h[d]), g.cells[d] - 1);
              mine             = c >= xs[d] && c < ce[d];
            }
          }
          if (!mine) continue;
          bool claimed = false;
          for (PetscInt gj = 0; gj < gi && !claimed; ++gj) claimed = mpm.geometries[gj]->Contains(pt.x);
          if (claimed) continue;
          pt.geometry = gi;
          pt.id       = mpm.next_pid + index;
          pt.volume   = r * dr * dtheta * dz;
          pt.depth    = dr;
          // the particle domain of the GIMP shapes: a square of the element's in-plane area (dz deep
          // in 3-D), no wider than a cell (the shapes' three-node stencil)
          const PetscReal side = std::sqrt(r * dr * dtheta);
          for (PetscInt d = 0; d < 2; ++d) pt.half_width[d] = PetscMin(0.5 * side, 0.5 * g.h[d]);
          if (dim == 3) pt.half_width[2] = PetscMin(0.5 * dz, 0.5 * g.h[2]);
          // a pressure surface loads the inner (outer) ring with the arc of the surface itself
          if (geo.pressure_surface == PressureSurface::Inner && ir == 0) pt.surface_scale = r0 / r;
          if (geo.pressure_surface == PressureSurface::Outer && ir == nr - 1) pt.surface_scale = geo.radius / r;
          points.push_back(pt);
        }
      }
    }
    mpm.next_pid += index;
  }

  const PetscInt n     = (PetscInt)points.size();
  PetscInt64     local = n;
  PetscCallMPI(MPI_Allreduce(&local, &mpm.total_particles, 1, MPIU_INT64, MPI_SUM, mpm.comm));
  PetscCheck(mpm.total_particles > 0, mpm.comm, PETSC_ERR_USER_INPUT, "The geometries seeded no particle inside the grid: check -<name>_center/-radius/-lower/-upper against -grid_lower/-grid_upper");
  PetscCall(DMSwarmSetLocalSizes(mpm.swarm, n, 16));

  PetscReal  *x, *v, *mass, *vol, *vol0, *X0, *hw, *F, *sigma, *L, *T, *c, *e, *fext, *area;
  PetscInt   *mat, *curve, *cell;
  PetscInt64 *pid;
  SwarmAccess fields(mpm.swarm);
  PetscCall(fields.Get(DMSwarmPICField_coor, &x));
  PetscCall(fields.Get(DMSwarmPICField_cellid, &cell));
  PetscCall(fields.Get(DMSwarmField_pid, &pid));
  PetscCall(fields.Get(field::velocity, &v));
  PetscCall(fields.Get(field::mass, &mass));
  PetscCall(fields.Get(field::volume, &vol));
  PetscCall(fields.Get(field::volume0, &vol0));
  PetscCall(fields.Get(field::position0, &X0));
  PetscCall(fields.Get(field::half_width0, &hw));
  PetscCall(fields.Get(field::F, &F));
  PetscCall(fields.Get(field::stress, &sigma));
  PetscCall(fields.Get(field::L, &L));
  PetscCall(fields.Get(field::temperature, &T));
  PetscCall(fields.Get(field::wave_speed, &c));
  PetscCall(fields.Get(field::internal_energy, &e));
  PetscCall(fields.Get(field::external_force, &fext));
  PetscCall(fields.Get(field::traction_area0, &area));
  PetscCall(fields.Get(field::load_curve, &curve));
  PetscCall(fields.Get(field::material, &mat));
  PetscReal *q;
  PetscInt  *fragment;
  PetscCall(fields.Get(field::bulk_viscosity, &q));
  PetscCall(fields.Get(field::fragment, &fragment));
  PetscReal *ambient = nullptr, *affine = nullptr;
  if (mpm.ambient_pressure) PetscCall(fields.Get(field::ambient_pressure, &ambient));
  if (mpm.transfer == Transfer::APIC) PetscCall(fields.Get(field::affine, &affine));
  for (PetscInt p = 0; p < n; ++p) {
    const Geometry &geo = *mpm.geometries[points[p].geometry];
    const PetscInt  ppc = geo.particles_per_cell;
    // axisymmetric: per radian, the sub-cell's area times its radius
    const PetscReal sub_volume = points[p].volume > 0 ? points[p].volume : g.CellVolume() / (dim == 2 ? ppc * ppc : ppc * ppc * ppc) * (mpm.axisymmetric ? points[p].x[0] : 1.0);
    PetscReal       r_hat[3], r;
    geo.RadialDirection(points[p].x, r_hat, &r);
    pid[p]      = points[p].id;
    cell[p]     = -1;
    mat[p]      = geo.material;
    mass[p]     = mpm.materials[geo.material]->Density() * sub_volume;
    vol[p]      = sub_volume;
    vol0[p]     = sub_volume;
    T[p]        = geo.temperature;
    c[p]        = 0;
    e[p]        = 0;
    curve[p]    = -1;
    q[p]        = 0;
    fragment[p] = -1;
    if (ambient) ambient[p] = 0;
    if (affine) { // the affine part of the initial field: the spin W of -<name>_angular_velocity
      for (int a = 0; a < 9; ++a) affine[9 * p + a] = 0;
      affine[9 * p + 1] = -geo.angular_velocity;
      affine[9 * p + 3] = geo.angular_velocity;
    }
    for (PetscInt d = 0; d < dim; ++d) {
      x[p * dim + d]  = points[p].x[d];
      X0[p * dim + d] = points[p].x[d];
      hw[p * dim + d] = points[p].volume > 0 ? points[p].half_width[d] : 0.5 * g.h[d] / ppc;
      v[p * dim + d]  = geo.velocity[d] + geo.radial_velocity * r_hat[d];
      if (geo.angular_velocity != 0 && d < 2) v[p * dim + d] += geo.angular_velocity * (d == 0 ? -(points[p].x[1] - geo.center[1]) : points[p].x[0] - geo.center[0]);
      fext[p * dim + d] = 0;
      area[p * dim + d] = 0;
    }
    for (int a = 0; a < 9; ++a) {
      F[9 * p + a]     = (a % 4 == 0) ? 1.0 : 0.0;
      sigma[9 * p + a] = 0;
      L[9 * p + a]     = 0;
    }
    // Pressure-loaded surface: particles in a band one sub-cell deep carry area = volume / depth, so
    // the band's areas add up to the surface area (the lattice: to within the band's curvature, about
    // depth / (2 radius); polar: exactly, with the ring's arc scaled to the surface's radius).
    if (geo.pressure_surface != PressureSurface::None) {
      PetscReal depth = g.h[0] / ppc;
      for (PetscInt d = 1; d < dim; ++d) depth = PetscMin(depth, g.h[d] / ppc);
      if (points[p].depth > 0) depth = points[p].depth; // polar: exactly the first (last) ring
      const bool      inner = geo.pressure_surface == PressureSurface::Inner;
      const PetscReal dist  = inner ? r - (geo.type == GeometryType::Annulus ? geo.inner_radius : 0) : geo.radius - r;
      if (dist >= 0 && dist < depth && !(inner && geo.type != GeometryType::Annulus)) {
        curve[p] = geo.load_curve;
        for (PetscInt d = 0; d < dim; ++d) area[p * dim + d] = (inner ? -1.0 : 1.0) * r_hat[d] * sub_volume / depth * points[p].surface_scale;
      }
    }
  }
  PetscCall(fields.RestoreAll());
  {
    MaterialPointFields f;
    MaterialState       state;

    SwarmAccess views(mpm.swarm);
    PetscCall(GetMaterialPointFields(views, mpm.swarm, state, f));
    f.cell_size = mpm.grid.h[0];
    for (auto &m : mpm.materials) PetscCall(m->InitializeState(f, 0, n));
    PetscCall(views.RestoreAll());
  }
  PetscCall(PetscInfo(mpm.swarm, "Seeded %" PetscInt_FMT " particles on this rank, %" PetscInt64_FMT " in all\n", n, mpm.total_particles));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
