// Flat index of a node in the ghosted local arrays of the node DMDAs (petsc.md 5.2).
#pragma once
#include "../simulation.hpp"

namespace burst {

struct LocalNodeIndex {
  PetscInt gxs[3], gxm[3];
  explicit LocalNodeIndex(const Grid &g)
  {
    for (int d = 0; d < 3; ++d) {
      gxs[d] = g.gxs[d];
      gxm[d] = g.gxm[d];
    }
  }
  inline PetscInt operator()(PetscInt i, PetscInt j, PetscInt k) const { return ((k - gxs[2]) * gxm[1] + (j - gxs[1])) * gxm[0] + (i - gxs[0]); }
};

} // namespace burst
