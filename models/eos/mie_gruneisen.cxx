// Mie-Gruneisen equation of state (paper eq. 7 as corrected in NOTES; models.md 4.2):
//   zeta = rho/rho0 - 1,  E = rho0 e  (e: specific internal energy from the stress work, J/kg)
//   compression (zeta >= 0): p = rho0 C0^2 zeta [1 + (1 - Gamma0/2) zeta] / [1 - (S - 1) zeta]^2 + Gamma0 E
//   tension     (zeta <  0): p = rho0 C0^2 zeta + Gamma0 E
// The energy term uses the mechanical energy e (which already contains the plastic work), not
// rho0 Cp T, so plastic heating is not counted twice (models.md 2.7). Tangent for the wave speed:
//   c^2 = dp/drho|_e + (p / rho^2) dp/de,  bulk_modulus = rho c^2.
// For small zeta, p -> rho0 C0^2 zeta: the bulk modulus of this EOS is rho0 C0^2 (NOTES: for 4340
// that is 100 GPa, not Table 1's 173.3 GPa; the run uses this EOS for both pressure and wave speed).
#include "../plasticity/families.hpp"

namespace burst {

class MieGruneisen final : public EquationOfState {
public:
  PetscReal C0 = 0, Gamma0 = 0, S = 0, rho0 = 0;

  inline void Pressure(PetscReal rho, PetscReal e, PetscReal &p, PetscReal &dp_drho) const
  {
    const PetscReal zeta = rho / rho0 - 1, K0 = rho0 * C0 * C0;
    if (zeta >= 0) {
      const PetscReal num = zeta * (1 + (1 - 0.5 * Gamma0) * zeta), den = 1 - (S - 1) * zeta;
      const PetscReal dnum = 1 + 2 * (1 - 0.5 * Gamma0) * zeta;
      p                    = K0 * num / (den * den);
      dp_drho              = K0 * (dnum / (den * den) + 2 * (S - 1) * num / (den * den * den)) / rho0;
    } else {
      p       = K0 * zeta;
      dp_drho = K0 / rho0;
    }
    p += Gamma0 * rho0 * e;
  }

  void Evaluate(Chunk &c) const override
  {
    for (int k = 0; k < c.n; ++k) {
      PetscReal p, dp_drho;
      Pressure(c.density[k], c.specific_energy[k], p, dp_drho);
      const PetscReal rho = c.density[k];
      const PetscReal c2  = dp_drho + p / (rho * rho) * Gamma0 * rho0;
      c.pressure[k]       = p;
      c.bulk_modulus[k]   = rho * (c2 > 0 ? c2 : dp_drho);
      c.gruneisen[k]      = Gamma0 * rho0 / rho;
    }
  }

  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const MaterialConstants &material) override
  {
    PetscFunctionBeginUser;
    rho0 = material.density;
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-C0", "Mie-Gruneisen bulk sound speed C0 (m/s)", &C0));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-Gamma0", "Mie-Gruneisen Gruneisen gamma Gamma0 (-)", &Gamma0));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-S_alpha", "Mie-Gruneisen linear Hugoniot slope S_alpha (-)", &S));
    const std::string P = PetscOptionsObject->prefix;
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "C0").c_str(), C0, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "Gamma0").c_str(), Gamma0, 0, 10, PETSC_FALSE));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "S_alpha").c_str(), S, 1, 10, PETSC_FALSE));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscErrorCode View(PetscViewer viewer) const override
  {
    return PetscViewerASCIIPrintf(viewer, "  equation of state: mie_gruneisen C0 %g m/s, Gamma0 %g, S_alpha %g (bulk modulus rho0 C0^2 = %g Pa)\n", (double)C0, (double)Gamma0, (double)S, (double)(rho0 * C0 * C0));
  }
};

PetscErrorCode MieGruneisenCreate(SubModel **model) { return CreateSubModel<MieGruneisen>(model); }

} // namespace burst
