// Flow-stress models and the return mapping that calls them.
//
// A flow model is a class Derived : FlowStressModel<Derived> with an inline pointwise
//   void Evaluate(const FlowPoint &x, FlowValue &y) const   // sigma_f and its derivatives
// and optionally history variables (NumHistory, HistoryName, InitialHistory, UpdateHistory).
// FlowStressModel<Derived> instantiates the return-mapping loops for Derived, so Evaluate is inlined
// inside the Newton iterations: no virtual call per particle (the one virtual call, Return, is per
// chunk). See johnson_cook.cxx for a complete model in one file.
#pragma once
#include "../plasticity/families.hpp"
#include "../yield/von_mises.hpp"
#include "../yield/gtn.hpp"

namespace burst {

enum class YieldType : int { VonMises = 0, GTN = 1 };

// Settings of the return mapping, from the material's options.
struct ReturnSettings {
  YieldType     yield = YieldType::VonMises;
  GTNParameters gtn;
  PetscReal     tolerance      = 1e-10; // relative tolerance of the Newton iterations on sigma_f
  PetscInt      max_iterations = 100;
};

// The flow-stress family as the stress update sees it: one virtual call per chunk.
class FlowStress : public SubModel {
public:
  // Return mapping for every point of the chunk: reads the trial deviator in c.deviator, writes the
  // returned deviator, plastic_strain(_rate), delta_plastic_strain, trace_plastic_strain,
  // flow_stress, hardening, rate_hardening, thermal_softening, equivalent_stress, plastic, history,
  // and for GTN the pressure (the material updates the porosity from trace_plastic_strain).
  // Returns non-zero on a Newton failure.
  virtual PetscErrorCode Return(Chunk &c, const ReturnSettings &settings) const = 0;
  virtual int            NumHistory() const { return 0; }
  virtual const char    *HistoryName(int) const { return ""; }
  virtual PetscReal      InitialHistory(int) const { return 0; }
  PetscReal              min_rate = 1e-3; // floor of the plastic strain rate fed to the model, 1/s
};

template <class Derived>
class FlowStressModel : public FlowStress {
public:
  PetscErrorCode Return(Chunk &c, const ReturnSettings &settings) const override
  {
    const Derived &model = static_cast<const Derived &>(*this);
    if (settings.yield == YieldType::VonMises) return VonMisesReturn(model, c, settings.tolerance, settings.max_iterations);
    return GTNReturn(model, c, settings.gtn, settings.tolerance, settings.max_iterations);
  }
  // Default: no history.
  inline void UpdateHistory(const FlowPoint &, PetscReal, PetscReal *) const {}
};

} // namespace burst
