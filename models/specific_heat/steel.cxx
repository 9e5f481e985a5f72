// Two-branch specific heat of 4340 steel (models.md 4.5; Uintah PM/SteelCp.cc, 4340 defaults), J/(kg K):
//   T < T_c: Cp = 190.14 - 273.75 t + 418.30 t^{-0.2},  t = 1 - T/T_c
//   T > T_c: Cp = 465.21 + 267.52 t + 58.16 t^{-0.35},  t = T/T_c - 1
// with the Curie temperature T_c = 1040 K (-MAT_specific_heat_T_c; Uintah's default input has 10400 K,
// models.md 2.12). Both branches are singular at T_c (the Curie peak). Here the law is SMOOTHED:
// within |T - T_c| < w (-MAT_specific_heat_curie_width, default 10 K) Cp is the straight line between
// the branch values at T_c - w and T_c + w (1246.5 and 763.3 J/(kg K) for w = 10 K), so Cp is
// continuous, finite (at most max(Cp(T_c - w), Cp(T_c + w))) and unchanged outside the band.
#include "../plasticity/families.hpp"
#include <cmath>

namespace burst {

class SteelSpecificHeat final : public SpecificHeatModel {
public:
  PetscReal Tc = 1040, width = 10, cp_below = 0, cp_above = 0; // cp_below/above: branch values at T_c -+ w

  static PetscReal Low(PetscReal t) { return 190.14 - 273.75 * t + 418.30 * std::pow(t, -0.2); }
  static PetscReal High(PetscReal t) { return 465.21 + 267.52 * t + 58.16 * std::pow(t, -0.35); }
  void             Evaluate(Chunk &c) const override
  {
    for (int k = 0; k < c.n; ++k) {
      const PetscReal T = c.temperature[k];
      if (T <= Tc - width) c.specific_heat[k] = Low(1 - T / Tc);
      else if (T >= Tc + width) c.specific_heat[k] = High(T / Tc - 1);
      else c.specific_heat[k] = cp_below + (cp_above - cp_below) * (T - (Tc - width)) / (2 * width);
    }
  }
  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject, const MaterialConstants &) override
  {
    const std::string P = PetscOptionsObject->prefix;
    PetscFunctionBeginUser;
    PetscCall(PetscOptionsReal("-T_c", "Curie (alpha-gamma) temperature of the two-branch steel Cp T_c (K), > 0", "", Tc, &Tc, nullptr));
    PetscCall(PetscOptionsReal("-curie_width", "Half-width w of the band |T - T_c| < w where Cp is linear between the branch values at T_c -+ w (K), in (0, T_c]", "", width, &width, nullptr));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "T_c").c_str(), Tc, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "curie_width").c_str(), width, 0, Tc, PETSC_TRUE));
    cp_below = Low(width / Tc);
    cp_above = High(width / Tc);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscErrorCode View(PetscViewer viewer) const override { return PetscViewerASCIIPrintf(viewer, "  specific heat: steel (two-branch 4340 law) T_c %g K, linear within +-%g K of T_c\n", (double)Tc, (double)width); }
};

PetscErrorCode SteelSpecificHeatCreate(SubModel **model) { return CreateSubModel<SteelSpecificHeat>(model); }

} // namespace burst
