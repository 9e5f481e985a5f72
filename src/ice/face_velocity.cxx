// Face velocities with momentum exchange (ice.md 1.4, step 7).
//
// For the face between cells L and R in direction d, every material m:
//   u*_f = (rho_L u_L + rho_R u_R)/(rho_L + rho_R) - dt vbar (p_R - p_L)/dx_d + dt g_d,
// with vbar the harmonic mean of the materials' specific volumes; then the implicit exchange
// E du = rhs with beta_mn = dt theta_n,f K_mn vbar_m, which also gives the effective specific
// volume (E vtilde = vbar) that the semi-implicit pressure matrix needs. Faces are stored as the
// lower face of each local cell, for every local cell that has a lower neighbour, so each rank
// has every face of its own cells and of the first ghost layer without communication.
#include "ice.hpp"
#include "exchange_matrix.hpp"

namespace burst {

template <int N>
static void FaceExchange(IceSolver &ice, const PetscScalar *a, PetscInt d, PetscInt idx)
{
  const PetscInt     S = ice.stride;
  PetscReal         *u = &ice.face_vel[d][idx * N], *ustar = &ice.face_vel_star[d][idx * N];
  PetscReal         *vbar = &ice.face_spvol[d][idx * N], *veff = &ice.face_spvol_eff[d][idx * N];
  const PetscScalar *cL = a + (idx - ice.lstride[d]) * S, *cR = a + idx * S;
  PetscReal          beta[kIceMaxMaterials][kIceMaxMaterials];
  for (PetscInt m = 0; m < N; ++m)
    for (PetscInt k = 0; k < N; ++k) beta[m][k] = k == m ? 0 : ice.dt * 0.5 * (cL[ice.Offset(k, icef::theta)] + cR[ice.Offset(k, icef::theta)]) * ice.exchange_K[m][k] * vbar[m];
  ExchangeMatrix<N> E;
  E.Factor(beta);
  for (PetscInt m = 0; m < N; ++m) u[m] = ustar[m];
  E.Apply(beta, u);
  if (ice.pressure_solver == IcePressureSolver::SemiImplicit) E.Solve(vbar, veff); // the matrix's effective v
}

void IceFaceExchange(IceSolver &ice, const PetscScalar *a, PetscInt d, PetscInt idx)
{
  if (ice.nmat == 1) {
    ice.face_vel[d][idx]       = ice.face_vel_star[d][idx];
    ice.face_spvol_eff[d][idx] = ice.face_spvol[d][idx];
    return;
  }
  DispatchMaterials(ice.nmat, [&](auto N) { FaceExchange<N()>(ice, a, d, idx); });
}

PetscErrorCode IceFaceVelocities(IceSolver &ice)
{
  PetscScalar   *a;
  const PetscInt S = ice.stride, n = ice.nmat;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ice.ev_face, 0, 0, 0, 0));
  PetscCall(IceGetLocalArray(ice, &a));
  for (PetscInt d = 0; d < ice.dim; ++d) {
    PetscInt lo[3], hi[3];
    for (PetscInt e = 0; e < 3; ++e) {
      lo[e] = ice.gxs[e];
      hi[e] = ice.gxs[e] + ice.gxm[e];
    }
    lo[d] += 1;
    const PetscReal dt_dx = ice.dt / ice.h[d];
    for (PetscInt k = lo[2]; k < hi[2]; ++k)
      for (PetscInt j = lo[1]; j < hi[1]; ++j)
        for (PetscInt i = lo[0]; i < hi[0]; ++i) {
          const PetscInt     idx = ice.LocalIndex(i, j, k);
          const PetscScalar *cL = a + (idx - ice.lstride[d]) * S, *cR = a + idx * S;
          const PetscReal    dp = cR[ice.CellOffset(icef::press_eq)] - cL[ice.CellOffset(icef::press_eq)];
          for (PetscInt m = 0; m < n; ++m) {
            const PetscReal rL = cL[ice.Offset(m, icef::rho)], rR = cR[ice.Offset(m, icef::rho)];
            const PetscReal vL = cL[ice.Offset(m, icef::spvol)], vR = cR[ice.Offset(m, icef::spvol)];
            const PetscReal vbar              = 2 * vL * vR / (vL + vR);
            ice.face_spvol[d][idx * n + m]    = vbar;
            ice.face_vel_star[d][idx * n + m] = (rL * cL[ice.Offset(m, icef::vel + d)] + rR * cR[ice.Offset(m, icef::vel + d)]) / (rL + rR) - dt_dx * vbar * dp + ice.dt * ice.gravity[d];
          }
          IceFaceExchange(ice, a, d, idx);
        }
  }
  IceBoundaryFaceVelocities(ice);
  PetscCall(IceRestoreLocalArray(ice, &a));
  PetscCall(PetscLogEventEnd(ice.ev_face, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
