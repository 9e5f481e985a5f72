// Geometry objects that seed particles: box, disk (2-D) / cylinder (3-D, axis z), annulus (2-D ring,
// 3-D tube along z; full or a sector), sphere.
#pragma once
#include "mpm/mpm.hpp"

namespace burst {

enum class GeometryType : int { Box = 0, Disk = 1, Cylinder = 2, Annulus = 3, Sphere = 4 };
enum class PressureSurface : int { None = 0, Inner = 1, Outer = 2 };
enum class Seeding : int { Lattice = 0, Polar = 1 };
extern const char *const GeometryTypeNames[];
extern const char *const PressureSurfaceNames[];
extern const char *const SeedingNames[];

struct Geometry {
  std::string     name;
  GeometryType    type     = GeometryType::Box;
  PetscInt        dim      = 2;
  PetscReal       lower[3] = {0, 0, 0}, upper[3] = {0, 0, 0}; // box; z-extent of 3-D cylinders/annuli
  PetscReal       center[3] = {0, 0, 0};
  PetscReal       radius = 0, inner_radius = 0;  // m
  PetscReal       angle_range[2]     = {0, 360}; // degrees, sector of disks/annuli
  PetscInt        material           = 0;
  PetscInt        particles_per_cell = 2;                // per direction
  Seeding         seeding            = Seeding::Lattice; // polar: rings about the centre (disk, cylinder, annulus)
  PetscReal       velocity[3]        = {0, 0, 0};        // m/s
  PetscReal       angular_velocity   = 0;                // rad/s, rigid spin about the centre (z axis)
  PetscReal       radial_velocity    = 0;                // m/s, added along the radial direction
  PetscReal       temperature        = 300;              // K
  PressureSurface pressure_surface   = PressureSurface::None;
  PetscInt        load_curve         = -1;

  bool Contains(const PetscReal x[]) const;
  // Unit radial direction of x from the centre (in-plane for disks, cylinders, annuli).
  void RadialDirection(const PetscReal x[], PetscReal r_hat[], PetscReal *r) const;
};

} // namespace burst
