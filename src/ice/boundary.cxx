// Ghost cells and boundary faces of the gas (ice.md 1.10).
//
// Two layers of ghost cells. Inter-rank ghosts come from the DMDA; ghosts outside the domain are
// filled per face: wall and symmetry mirror the interior with the normal velocity negated (the
// gas is inviscid, so a wall is a free-slip reflector), outflow copies the boundary cell (zero
// gradient), inflow holds the prescribed state of its material (others at their tiny mass), per
// cell of the face: a jet's state where the cell is within its radius (IceInflowAt).
// Directions are filled in order x, y, z over the whole ghosted box, so corners are consistent.
// Boundary faces: wall and symmetry have zero normal velocity, inflow the prescribed one, outflow
// keeps the computed value. The pressure is zero-gradient on every face (Neumann), except an outflow
// face given a far-field pressure (-ice_outflow_<face>_pressure): its ghosts hold that pressure, so
// the pressure difference drives the flow through the face (and anchors the semi-implicit solve).
#include "ice.hpp"

namespace burst {

PetscErrorCode IceGetLocalArray(IceSolver &ice, PetscScalar **a)
{
  PetscFunctionBeginUser;
  PetscCall(VecGetArray(ice.local, a));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IceRestoreLocalArray(IceSolver &ice, PetscScalar **a)
{
  PetscFunctionBeginUser;
  PetscCall(VecRestoreArray(ice.local, a));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IceApplyBoundaryGhosts(IceSolver &ice, PetscScalar *a)
{
  const PetscInt S = ice.stride;
  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < ice.dim; ++d)
    for (int s = 0; s < 2; ++s) {
      const bool touches = s == 0 ? ice.xs[d] == 0 : ice.xs[d] + ice.xm[d] == ice.cells[d];
      if (!touches) continue;
      const IceFaceBC &bc = ice.bc[d][s];
      for (PetscInt layer = 1; layer <= 2; ++layer) {
        const PetscInt ghost = s == 0 ? -layer : ice.cells[d] - 1 + layer;
        // (a domain one cell wide mirrors its only cell into both layers)
        const PetscInt mirror = s == 0 ? PetscMin(layer - 1, ice.cells[d] - 1) : PetscMax(ice.cells[d] - layer, 0);
        const PetscInt edge   = s == 0 ? 0 : ice.cells[d] - 1;
        const PetscInt source = (bc.type == IceBC::Wall || bc.type == IceBC::Symmetry) ? mirror : edge;
        // loop over the ghosted box in the other directions
        PetscInt lo[3], hi[3];
        for (PetscInt e = 0; e < 3; ++e) {
          lo[e] = ice.gxs[e];
          hi[e] = ice.gxs[e] + ice.gxm[e];
        }
        lo[d] = 0;
        hi[d] = 1;
        for (PetscInt k = lo[2]; k < hi[2]; ++k)
          for (PetscInt j = lo[1]; j < hi[1]; ++j)
            for (PetscInt i = lo[0]; i < hi[0]; ++i) {
              PetscInt g[3] = {i, j, k}, f[3] = {i, j, k};
              g[d]                  = ghost;
              f[d]                  = source;
              PetscScalar       *cg = a + ice.LocalIndex(g[0], g[1], g[2]) * S;
              const PetscScalar *cf = a + ice.LocalIndex(f[0], f[1], f[2]) * S;
              for (PetscInt q = 0; q < S; ++q) cg[q] = cf[q];
              if (bc.type == IceBC::Wall || bc.type == IceBC::Symmetry) {
                for (PetscInt m = 0; m < ice.nmat; ++m) {
                  cg[ice.Offset(m, icef::vel + d)]   = -cg[ice.Offset(m, icef::vel + d)];
                  cg[ice.Offset(m, icef::vel_L + d)] = -cg[ice.Offset(m, icef::vel_L + d)];
                }
              } else if (bc.type == IceBC::Outflow && bc.pressure > 0) {
                cg[ice.CellOffset(icef::press)]    = bc.pressure;
                cg[ice.CellOffset(icef::press_eq)] = bc.pressure;
              } else if (bc.type == IceBC::Inflow) {
                const IceInflowState &in_state = IceInflowAt(ice, d, s, i, j, k); // the jet's or the face's
                for (PetscInt m = 0; m < ice.nmat; ++m) {
                  const bool      in   = m == in_state.material;
                  const PetscReal rho0 = in ? in_state.state[0] : 1 / cf[ice.Offset(m, icef::spvol)];
                  const PetscReal rho  = in ? in_state.state[0] : ice.rho_tiny * rho0;
                  const PetscReal T    = in ? in_state.state[4] : cf[ice.Offset(m, icef::temp)];
                  for (int fset = 0; fset < 2; ++fset) { // state and Lagrangian copies
                    cg[ice.Offset(m, fset ? icef::rho_L : icef::rho)]   = rho;
                    cg[ice.Offset(m, fset ? icef::temp_L : icef::temp)] = T;
                    for (PetscInt c = 0; c < 3; ++c) cg[ice.Offset(m, (fset ? icef::vel_L : icef::vel) + c)] = in_state.state[1 + c];
                  }
                  cg[ice.Offset(m, icef::spvol)]    = 1 / rho0;
                  cg[ice.Offset(m, icef::energy_L)] = T; // (kinetic part set by the advection)
                  cg[ice.Offset(m, icef::theta)]    = in ? 1 : ice.rho_tiny;
                }
              }
            }
      }
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

// The local vector is the working copy; ghosts come from the neighbours' owned cells directly
// (DMLocalToLocal), and the global vector is brought up to date only for output.
PetscErrorCode IceUpdateGhosts(IceSolver &ice)
{
  PetscScalar *a;
  PetscMPIInt  size;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ice.ev_bc, 0, 0, 0, 0));
  PetscCallMPI(MPI_Comm_size(ice.comm, &size));
  if (size > 1) {
    PetscCall(DMLocalToLocalBegin(ice.da, ice.local, INSERT_VALUES, ice.local));
    PetscCall(DMLocalToLocalEnd(ice.da, ice.local, INSERT_VALUES, ice.local));
  }
  PetscCall(IceGetLocalArray(ice, &a));
  PetscCall(IceApplyBoundaryGhosts(ice, a));
  PetscCall(IceRestoreLocalArray(ice, &a));
  PetscCall(PetscLogEventEnd(ice.ev_bc, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IceSyncGlobal(IceSolver &ice)
{
  PetscFunctionBeginUser;
  PetscCall(DMLocalToGlobal(ice.da, ice.local, INSERT_VALUES, ice.state));
  PetscFunctionReturn(PETSC_SUCCESS);
}

void IceBoundaryFaceVelocities(IceSolver &ice)
{
  for (PetscInt d = 0; d < ice.dim; ++d)
    for (int s = 0; s < 2; ++s) {
      const bool       touches = s == 0 ? ice.xs[d] == 0 : ice.xs[d] + ice.xm[d] == ice.cells[d];
      const IceFaceBC &bc      = ice.bc[d][s];
      if (!touches || bc.type == IceBC::Outflow) continue;
      PetscInt lo[3], hi[3];
      for (PetscInt e = 0; e < 3; ++e) {
        lo[e] = ice.gxs[e];
        hi[e] = ice.gxs[e] + ice.gxm[e];
      }
      lo[d] = s == 0 ? 0 : ice.cells[d]; // the lower face of this cell is the domain face
      hi[d] = lo[d] + 1;
      for (PetscInt k = lo[2]; k < hi[2]; ++k)
        for (PetscInt j = lo[1]; j < hi[1]; ++j)
          for (PetscInt i = lo[0]; i < hi[0]; ++i) {
            const PetscInt  idx   = ice.LocalIndex(i, j, k);
            const PetscReal value = bc.type == IceBC::Inflow ? IceInflowAt(ice, d, s, i, j, k).state[1 + d] : 0; // (the jet's or the face's)
            for (PetscInt m = 0; m < ice.nmat; ++m) {
              ice.face_vel[d][idx * ice.nmat + m]      = value;
              ice.face_vel_star[d][idx * ice.nmat + m] = value;
            }
          }
    }
}

} // namespace burst
