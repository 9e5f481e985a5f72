// Semi-implicit pressure (ice.md 1.5; Kashiwa's ICE, Uintah's impICE): the pressure change is
// implicit in the face velocities that it drives, so acoustic waves do not limit the time step.
//
// Unknowns: increments dP with P^k = p_eq + sum of the increments. Per outer iteration k:
//   residual  r_c = -V sum kappa_c (P^k - p_eq) - dt sum_m sum_f theta_hat u^k_m,f A_f n_f
//   matrix    A_cc = V sum kappa_c + sum_f a_f,  A_c,nb(f) = -a_f,
//             a_f = (A_f/dx_f) dt^2 sum_m theta_hat_m,f vtilde_m,f        (5-point / 7-point, SPD)
//   solve     A dP = r with KSP (prefix -ice_pressure_; CG with BoomerAMG in 2-D, PFMG in 3-D by
//             default: setup.cxx says why)
//   correct   u*_m,f -= dt vbar_m,f (dP_R - dP_L)/dx, then redo the face exchange
// until max_c |r_c|/V < -ice_outer_tolerance. Domain faces are Neumann (their velocity is set by
// the boundary condition), so V sum kappa keeps A nonsingular; an outflow face with a far-field
// pressure is Dirichlet (its ghost holds that pressure: a_f on the diagonal, no neighbour). theta_hat in the matrix is the
// donor cell's volume fraction; in the residual it comes from the advection operator, as in the
// explicit path, so the converged pressure is the explicit one's implicit counterpart.
#include "ice.hpp"
#include <cmath>

namespace burst {

// Assembles the pressure matrix on da_p from the current face velocities (for the donor theta)
// and the effective face specific volumes. *dominance: max over this rank's rows of
// sum |offdiag| / diag (< 1; about 2 dim C^2 / (1 + 2 dim C^2) for an acoustic Courant number C).
static PetscErrorCode AssembleMatrix(IceSolver &ice, const PetscScalar *a, PetscReal *dominance)
{
  const PetscInt  S = ice.stride, n = ice.nmat, dim = ice.dim;
  const PetscReal V   = ice.CellVolume();
  PetscReal       dom = 0;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ice.ev_p_assemble, 0, 0, 0, 0));
  // An AIJ matrix keeps the DMDA's pattern and every entry of it is inserted below, so no zeroing.
  if (!ice.matrix_aij) PetscCall(MatZeroEntries(ice.A));
  for (PetscInt k = ice.xs[2]; k < ice.xs[2] + ice.xm[2]; ++k)
    for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
      for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i) {
        const PetscInt idx = ice.LocalIndex(i, j, k);
        MatStencil     row = {k, j, i, 0}, cols[7];
        PetscScalar    vals[7];
        PetscInt       nc   = 1;
        PetscReal      diag = V * a[idx * S + ice.CellOffset(icef::sum_kappa)], offsum = 0;
        cols[0]               = row;
        const PetscInt ijk[3] = {i, j, k};
        for (PetscInt d = 0; d < dim; ++d)
          for (int side = -1; side <= 1; side += 2) {
            const PetscInt nb      = ijk[d] + side;
            const bool     outside = nb < 0 || nb >= ice.cells[d];
            if (outside && !(ice.bc[d][side > 0].type == IceBC::Outflow && ice.bc[d][side > 0].pressure > 0)) continue; // Neumann domain face
            const PetscInt face = side < 0 ? idx : idx + ice.lstride[d];                                                // lower face of the upper cell
            const PetscInt L = face - ice.lstride[d], R = face;
            PetscReal      sum = 0;
            for (PetscInt m = 0; m < n; ++m) {
              const PetscReal u     = ice.face_vel[d][face * n + m];
              const PetscReal theta = u > 0 ? a[L * S + ice.Offset(m, icef::theta)] : u < 0 ? a[R * S + ice.Offset(m, icef::theta)] : 0.5 * (a[L * S + ice.Offset(m, icef::theta)] + a[R * S + ice.Offset(m, icef::theta)]);
              sum += theta * ice.face_spvol_eff[d][face * n + m];
            }
            const PetscReal coef = (V / ice.h[d]) / ice.h[d] * ice.dt * ice.dt * sum;
            diag += coef;
            if (outside) continue; // a held far-field pressure: Dirichlet, on the diagonal only
            offsum += std::fabs(coef);
            MatStencil col = row;
            if (d == 0) col.i = nb;
            else if (d == 1) col.j = nb;
            else col.k = nb;
            cols[nc]   = col;
            vals[nc++] = -coef;
          }
        vals[0] = diag;
        dom     = diag > 0 ? PetscMax(dom, offsum / diag) : 1;
        PetscCall(MatSetValuesStencil(ice.A, 1, &row, nc, cols, vals, INSERT_VALUES));
      }
  PetscCall(MatAssemblyBegin(ice.A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(ice.A, MAT_FINAL_ASSEMBLY));
  *dominance = dom;
  PetscCall(PetscLogEventEnd(ice.ev_p_assemble, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

// One linear solve A dP = rhs with the given KSP (event ICE_PSolve).
static PetscErrorCode SolvePressure(IceSolver &ice, KSP ksp, KSPConvergedReason *reason, PetscInt *its)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ice.ev_p_solve, 0, 0, 0, 0));
  PetscCall(KSPSetOperators(ksp, ice.A, ice.A));
  PetscCall(KSPSolve(ksp, ice.rhs, ice.dp));
  PetscCall(KSPGetConvergedReason(ksp, reason));
  PetscCall(KSPGetIterationNumber(ksp, its));
  PetscCall(PetscLogEventEnd(ice.ev_p_solve, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IceSolvePressureSemiImplicit(IceSolver &ice)
{
  PetscScalar            *a;
  const PetscInt          S = ice.stride, n = ice.nmat, dim = ice.dim, nlocal = ice.gxm[0] * ice.gxm[1] * ice.gxm[2];
  const PetscReal         V     = ice.CellVolume();
  std::vector<PetscReal> &old_p = ice.work_pressure;
  old_p.resize(nlocal);
  PetscFunctionBeginUser;
  // P^0 = p_eq
  PetscCall(IceGetLocalArray(ice, &a));
  for (PetscInt idx = 0; idx < nlocal; ++idx) a[idx * S + ice.CellOffset(icef::press)] = a[idx * S + ice.CellOffset(icef::press_eq)];
  PetscCall(IceRestoreLocalArray(ice, &a));
  PetscReal residual = PETSC_MAX_REAL, smallest = PETSC_MAX_REAL;
  PetscInt  k;
  bool      use_jacobi = false;
  for (k = 0; k <= ice.outer_max_iterations; ++k) {
    PetscCall(IceGetLocalArray(ice, &a));
    // residual of the volume balance
    PetscCall(IceVolumeOutflow(ice, a, ice.work_outflow));
    PetscScalar *r;
    PetscReal    local_max = 0;
    PetscCall(VecGetArray(ice.rhs, &r));
    PetscInt row = 0;
    for (PetscInt kk = ice.xs[2]; kk < ice.xs[2] + ice.xm[2]; ++kk)
      for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
        for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i, ++row) {
          const PetscInt     idx     = ice.LocalIndex(i, j, kk);
          const PetscScalar *c       = a + idx * S;
          PetscReal          created = 0; // volume made by mass conversion, relative to V
          if (ice.has_mass_source)
            for (PetscInt m = 0; m < ice.nmat; ++m) created += ice.mass_source[idx * ice.nmat + m] * c[ice.Offset(m, icef::spvol)];
          r[row]    = -V * c[ice.CellOffset(icef::sum_kappa)] * (c[ice.CellOffset(icef::press)] - c[ice.CellOffset(icef::press_eq)]) + V * (created - ice.work_outflow[idx]);
          local_max = PetscMax(local_max, std::fabs(r[row]) / V);
        }
    PetscCall(VecRestoreArray(ice.rhs, &r));
    PetscCallMPI(MPI_Allreduce(&local_max, &residual, 1, MPIU_REAL, MPI_MAX, ice.comm));
    PetscCall(PetscInfo(ice.ksp, "Gas step %" PetscInt_FMT ", outer iteration %" PetscInt_FMT ": max |residual|/V = %g\n", ice.step, k, (double)residual));
    if (residual < ice.outer_tolerance) {
      PetscCall(IceRestoreLocalArray(ice, &a));
      break;
    }
    PetscCheck(k < ice.outer_max_iterations, ice.comm, PETSC_ERR_NOT_CONVERGED,
               "Gas step %" PetscInt_FMT ": the semi-implicit pressure did not converge in %" PetscInt_FMT " outer iterations (max |residual|/V = %g, tolerance %g); raise -ice_outer_max_iterations or -ice_outer_tolerance, or reduce -ice_cfl",
               ice.step, ice.outer_max_iterations, (double)residual, (double)ice.outer_tolerance);
    PetscCheck(residual < 100 * smallest || smallest == 0, ice.comm, PETSC_ERR_NOT_CONVERGED,
               "Gas step %" PetscInt_FMT ": the semi-implicit pressure diverges (outer iteration %" PetscInt_FMT ": max |residual|/V = %g, smallest so far %g); reduce -ice_cfl", ice.step, k, (double)residual, (double)smallest);
    smallest = PetscMin(smallest, residual);
    // solve A dP = r
    PetscReal dom;
    PetscCall(AssembleMatrix(ice, a, &dom));
    PetscCall(IceRestoreLocalArray(ice, &a));
    if (k == 0) {
      // the step's preconditioner: Jacobi while the matrix is strongly diagonally dominant (small
      // acoustic Courant number: a few iterations and no set-up), else the KSP's own, built now if
      // pc_lag steps have passed and reused by the later outer iterations
      PetscCallMPI(MPI_Allreduce(&dom, &ice.dominance, 1, MPIU_REAL, MPI_MAX, ice.comm));
      ice.dominance_max = PetscMax(ice.dominance_max, ice.dominance);
      use_jacobi        = ice.ksp_jacobi && ice.dominance < ice.jacobi_below;
      if (!use_jacobi) {
        const PetscBool rebuild = (PetscBool)(ice.pc_built_step < 0 || ice.step - ice.pc_built_step >= ice.pc_lag || ice.step < ice.pc_built_step);
        PetscCall(KSPSetReusePreconditioner(ice.ksp, (PetscBool)!rebuild));
        if (rebuild) {
          ice.pc_built_step = ice.step;
          ice.pc_setups += 1;
        }
      }
      PetscCall(PetscInfo(ice.ksp, "Gas step %" PetscInt_FMT ": pressure matrix dominance max sum|offdiag|/diag = %g, %s\n", ice.step, (double)ice.dominance, use_jacobi ? "Jacobi" : "the -ice_pressure_ preconditioner"));
    } else if (!use_jacobi) PetscCall(KSPSetReusePreconditioner(ice.ksp, PETSC_TRUE));
    KSP                ksp = use_jacobi ? ice.ksp_jacobi : ice.ksp;
    KSPConvergedReason reason;
    PetscInt           its;
    PetscCall(SolvePressure(ice, ksp, &reason, &its));
    if (use_jacobi && reason <= 0) {
      // Jacobi did not make it (it should not at this dominance): the step goes to the KSP's own
      // preconditioner, rebuilt now
      PetscCall(PetscInfo(ice.ksp, "Gas step %" PetscInt_FMT ": CG + Jacobi %s after %" PetscInt_FMT " iterations; the -ice_pressure_ preconditioner takes the step\n", ice.step, KSPConvergedReasons[reason], its));
      ice.ksp_iterations += its;
      ice.ksp_iterations_total += its;
      use_jacobi = false;
      ksp        = ice.ksp;
      PetscCall(KSPSetReusePreconditioner(ksp, PETSC_FALSE));
      ice.pc_built_step = ice.step;
      ice.pc_setups += 1;
      PetscCall(SolvePressure(ice, ksp, &reason, &its));
    }
    if (use_jacobi) ice.jacobi_solves += 1;
    PetscCheck(reason > 0, ice.comm, PETSC_ERR_NOT_CONVERGED, "Gas step %" PetscInt_FMT ": the pressure solve (-ice_pressure_ksp_type, -ice_pressure_pc_type) did not converge: %s after %" PetscInt_FMT " iterations", ice.step,
               KSPConvergedReasons[reason], its);
    ice.ksp_iterations += its;
    ice.ksp_iterations_total += its;
    ice.pressure_solves += 1;
    // P += dP on owned cells, then ghosts; dP of every local cell from the change of P
    const PetscScalar *dp;
    PetscCall(IceGetLocalArray(ice, &a));
    for (PetscInt idx = 0; idx < nlocal; ++idx) old_p[idx] = a[idx * S + ice.CellOffset(icef::press)];
    PetscCall(VecGetArrayRead(ice.dp, &dp));
    row = 0;
    for (PetscInt kk = ice.xs[2]; kk < ice.xs[2] + ice.xm[2]; ++kk)
      for (PetscInt j = ice.xs[1]; j < ice.xs[1] + ice.xm[1]; ++j)
        for (PetscInt i = ice.xs[0]; i < ice.xs[0] + ice.xm[0]; ++i, ++row) a[ice.LocalIndex(i, j, kk) * S + ice.CellOffset(icef::press)] += dp[row];
    PetscCall(VecRestoreArrayRead(ice.dp, &dp));
    PetscCall(IceRestoreLocalArray(ice, &a));
    PetscCall(IceUpdateGhosts(ice));
    PetscCall(IceGetLocalArray(ice, &a));
    // correct the pre-exchange face velocities, redo the exchange
    for (PetscInt d = 0; d < dim; ++d) {
      PetscInt lo[3], hi[3];
      for (PetscInt e = 0; e < 3; ++e) {
        lo[e] = ice.gxs[e];
        hi[e] = ice.gxs[e] + ice.gxm[e];
      }
      lo[d] += 1;
      for (PetscInt kk = lo[2]; kk < hi[2]; ++kk)
        for (PetscInt j = lo[1]; j < hi[1]; ++j)
          for (PetscInt i = lo[0]; i < hi[0]; ++i) {
            const PetscInt  R = ice.LocalIndex(i, j, kk), L = R - ice.lstride[d];
            const PetscReal ddp = (a[R * S + ice.CellOffset(icef::press)] - old_p[R]) - (a[L * S + ice.CellOffset(icef::press)] - old_p[L]);
            for (PetscInt m = 0; m < n; ++m) ice.face_vel_star[d][R * n + m] -= ice.dt * ice.face_spvol[d][R * n + m] * ddp / ice.h[d];
            IceFaceExchange(ice, a, d, R);
          }
    }
    IceBoundaryFaceVelocities(ice);
    PetscCall(IceRestoreLocalArray(ice, &a));
  }
  ice.outer_iterations = k;
  // clamp (ice.md 7.3) and the dilatational change
  PetscCall(IceGetLocalArray(ice, &a));
  for (PetscInt idx = 0; idx < nlocal; ++idx) {
    PetscScalar *c                  = a + idx * S;
    c[ice.CellOffset(icef::press)]  = PetscMax(c[ice.CellOffset(icef::press)], 1e-12);
    c[ice.CellOffset(icef::dp_dil)] = c[ice.CellOffset(icef::press)] - c[ice.CellOffset(icef::press_eq)];
  }
  PetscCall(IceRestoreLocalArray(ice, &a));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
