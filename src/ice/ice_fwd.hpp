// The gas solver's name and its deleter, for the owners that need no more (src/simulation.hpp).
#pragma once

namespace burst {

struct IceSolver;
struct IceSolverDeleter {
  void operator()(IceSolver *ice) const; // src/ice/setup.cxx
};

} // namespace burst
