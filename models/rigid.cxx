// A rigid body with a prescribed velocity (-<name>_velocity, m/s): an anvil or a platen. Its particles
// move in a velocity field of their own whose nodal velocity is the prescribed one; deformable
// fields meet it through contact (src/mpm/grid_update.cxx). It carries no stress, and its wave
// speed is zero (it does not limit the time step beyond its own motion).
#include "material.hpp"
#include "util.hpp"

namespace burst {

class Rigid final : public Material {
public:
  PetscReal velocity[3] = {0, 0, 0};

  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject) override
  {
    PetscInt n = 3;
    PetscFunctionBeginUser;
    PetscCall(PetscOptionsRealArray("-velocity", "Prescribed velocity of the rigid body (m/s), one value per dimension", "", velocity, &n, nullptr));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscErrorCode UpdateStress(const MaterialPointFields &f, PetscInt id, PetscReal) override { return ComputeWaveSpeed(f, id); }
  PetscErrorCode ComputeWaveSpeed(const MaterialPointFields &f, PetscInt id) override
  {
    for (PetscInt p = 0; p < f.n; ++p)
      if (f.material[p] == id) f.wave_speed[p] = 0;
    return PETSC_SUCCESS;
  }
  bool IsRigid(PetscReal v[3]) const override
  {
    for (int d = 0; d < 3; ++d) v[d] = velocity[d];
    return true;
  }
  PetscErrorCode View(PetscViewer viewer) const override
  {
    return PetscViewerASCIIPrintf(viewer, "Material %s: rigid, density %g kg/m^3, velocity (%g, %g, %g) m/s\n", Name(), (double)density_, (double)velocity[0], (double)velocity[1], (double)velocity[2]);
  }
};

PetscErrorCode RigidCreate(Material **m)
{
  *m = new Rigid();
  return PETSC_SUCCESS;
}

} // namespace burst
