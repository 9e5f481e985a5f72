// The coupling's name and its deleter, for the driver that owns it (src/simulation.hpp) without
// seeing its insides (src/coupling/coupling_impl.hpp).
#pragma once

namespace burst {

struct Coupling;
struct CouplingDeleter {
  void operator()(Coupling *coupling) const; // src/coupling/coupling.cxx
};

} // namespace burst
