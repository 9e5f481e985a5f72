#include "elastic_parameters.hpp"
#include "../util.hpp"

namespace burst {

PetscErrorCode IsotropicElasticity::SetFromOptions(PetscOptionItems *PetscOptionsObject, const Material &m)
{
  PetscBool set = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsReal("-youngs_modulus", "Young's modulus (Pa), required, in (0, 1e13]", "Material", youngs_modulus, &youngs_modulus, &set));
  PetscCheck(set, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "Material '%s' (%s): -%s_youngs_modulus is required (Pa, > 0)", m.Name(), m.Model(), m.Name());
  PetscCall(CheckRange(PETSC_COMM_WORLD, Prefixed(PetscOptionsObject->prefix, "youngs_modulus").c_str(), youngs_modulus, 0, 1e13, PETSC_TRUE)); // diamond: 1.2e12 Pa
  PetscCall(PetscOptionsReal("-poisson_ratio", "Poisson's ratio (-), in (-1, 0.5)", "Material", poisson_ratio, &poisson_ratio, nullptr));
  PetscCheck(poisson_ratio > -1 && poisson_ratio < 0.5, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "Option -%s_poisson_ratio = %g is out of range: it must be in (-1, 0.5)", m.Name(), (double)poisson_ratio);
  shear_modulus = youngs_modulus / (2 * (1 + poisson_ratio));
  bulk_modulus  = youngs_modulus / (3 * (1 - 2 * poisson_ratio));
  lame_lambda   = bulk_modulus - 2.0 * shear_modulus / 3.0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IsotropicElasticity::View(PetscViewer viewer) const
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "  Young's modulus  %g Pa\n  Poisson's ratio  %g\n  shear modulus    %g Pa\n  bulk modulus     %g Pa\n", (double)youngs_modulus, (double)poisson_ratio, (double)shear_modulus, (double)bulk_modulus));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
