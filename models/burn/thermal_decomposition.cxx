// Thermal decomposition (self-heating) of a reactant element with SUNDIALS CVODE (6.x API: every
// object belongs to a SUNContext). See thermal_decomposition.hpp for the model and its sources.
#include "thermal_decomposition.hpp"
#include "../util.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <cmath>
#include <string>

namespace burst {

struct ThermalDecomposition::Impl {
  SUNContext      ctx  = nullptr;
  N_Vector        y    = nullptr;
  N_Vector        atol = nullptr;
  SUNMatrix       J    = nullptr;
  SUNLinearSolver LS   = nullptr;
  void           *mem  = nullptr;
  // CVODE's user data: the model (for the rates) and the runaway criteria of the current IgnitionDelay
  const ThermalDecomposition *model    = nullptr;
  PetscReal                   T_target = 0; // K
  PetscReal                   rate     = 0; // K/s, 0: off
  ~Impl()
  {
    if (mem) CVodeFree(&mem);
    if (LS) SUNLinSolFree(LS);
    if (J) SUNMatDestroy(J);
    if (atol) N_VDestroy(atol);
    if (y) N_VDestroy(y);
    if (ctx) SUNContext_Free(&ctx);
  }
};

namespace {

int Rhs(realtype, N_Vector y, N_Vector ydot, void *user)
{
  const ThermalDecomposition &m      = *static_cast<ThermalDecomposition::Impl *>(user)->model;
  const realtype              lambda = NV_Ith_S(y, 0), T = NV_Ith_S(y, 1);
  if (!(T > 0)) return 1; // recoverable: CVODE retries with a smaller step
  PetscReal dl, dT;
  m.Rates(lambda, T, &dl, &dT);
  NV_Ith_S(ydot, 0) = dl;
  NV_Ith_S(ydot, 1) = dT;
  return 0;
}

// J = d(dlambda/dt, dT/dt)/d(lambda, T) with r = Z (1 - lambda) e^{-T_a/T}:
//   dr/dlambda = -Z e^{-T_a/T}, dr/dT = r T_a/T^2; dT/dt = (Q r + h (T_env - T))/c.
int Jac(realtype, N_Vector y, N_Vector, SUNMatrix J, void *user, N_Vector, N_Vector, N_Vector)
{
  const ThermalDecompositionParameters &p      = static_cast<ThermalDecomposition::Impl *>(user)->model->par;
  const realtype                        lambda = NV_Ith_S(y, 0), T = NV_Ith_S(y, 1);
  if (!(T > 0)) return 1;
  const realtype k = p.Z * std::exp(-p.T_a / T), r = k * (1 - lambda);
  const realtype dr_dl = -k, dr_dT = r * p.T_a / (T * T);
  SM_ELEMENT_D(J, 0, 0) = dr_dl;
  SM_ELEMENT_D(J, 0, 1) = dr_dT;
  SM_ELEMENT_D(J, 1, 0) = p.Q * dr_dl / p.c;
  SM_ELEMENT_D(J, 1, 1) = (p.Q * dr_dT - p.h) / p.c;
  return 0;
}

// Root functions of IgnitionDelay (upward crossings): T - T_target and, if enabled, dT/dt - rate.
int IgnitionRoots(realtype, N_Vector y, realtype *g, void *user)
{
  const ThermalDecomposition::Impl &I      = *static_cast<ThermalDecomposition::Impl *>(user);
  const realtype                    lambda = NV_Ith_S(y, 0), T = NV_Ith_S(y, 1);
  g[0] = T - I.T_target;
  if (I.rate > 0) {
    PetscReal dl, dT;
    I.model->Rates(lambda, T, &dl, &dT);
    g[1] = dT - I.rate;
  }
  return 0;
}

} // namespace

ThermalDecomposition::ThermalDecomposition() : impl_(new Impl) { impl_->model = this; }
ThermalDecomposition::~ThermalDecomposition() = default;

void ThermalDecomposition::Rates(PetscReal lambda, PetscReal T, PetscReal *dlambda, PetscReal *dT) const
{
  const PetscReal r = par.Z * (1 - lambda) * std::exp(-par.T_a / T);
  *dlambda          = r;
  *dT               = (par.Q * r + par.h * (par.T_env - T)) / par.c;
}

PetscReal ThermalDecomposition::AdiabaticInductionTime(PetscReal T0) const { return par.c * T0 * T0 / (par.Q * par.Z * par.T_a) * std::exp(par.T_a / T0); }

#define CVCall(expr) \
  do { \
    const int flag_ = (expr); \
    PetscCheck(flag_ >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "SUNDIALS call %s failed with flag %d", #expr, flag_); \
  } while (0)

PetscErrorCode ThermalDecomposition::Start(PetscReal lambda, PetscReal T, int nroots)
{
  Impl &I = *impl_;
  PetscFunctionBeginUser;
  if (!I.mem) {
    CVCall(SUNContext_Create(nullptr, &I.ctx));
    I.y    = N_VNew_Serial(2, I.ctx);
    I.atol = N_VNew_Serial(2, I.ctx);
    PetscCheck(I.y && I.atol, PETSC_COMM_SELF, PETSC_ERR_MEM, "N_VNew_Serial failed");
    I.J  = SUNDenseMatrix(2, 2, I.ctx);
    I.LS = I.J ? SUNLinSol_Dense(I.y, I.J, I.ctx) : nullptr;
    PetscCheck(I.J && I.LS, PETSC_COMM_SELF, PETSC_ERR_MEM, "SUNDenseMatrix/SUNLinSol_Dense failed");
    NV_Ith_S(I.y, 0) = lambda;
    NV_Ith_S(I.y, 1) = T;
    I.mem            = CVodeCreate(CV_BDF, I.ctx);
    PetscCheck(I.mem, PETSC_COMM_SELF, PETSC_ERR_MEM, "CVodeCreate failed");
    CVCall(CVodeInit(I.mem, Rhs, 0.0, I.y));
    CVCall(CVodeSetUserData(I.mem, &I));
    CVCall(CVodeSetLinearSolver(I.mem, I.LS, I.J));
    CVCall(CVodeSetJacFn(I.mem, Jac));
    CVCall(CVodeSetMaxNumSteps(I.mem, 1000000));
    CVCall(CVodeSetNoInactiveRootWarn(I.mem));
  } else {
    NV_Ith_S(I.y, 0) = lambda;
    NV_Ith_S(I.y, 1) = T;
    CVCall(CVodeReInit(I.mem, 0.0, I.y));
  }
  // absolute tolerances: lambda 1e-15 (it starts at 0), T 1e-9 K; rtol dominates for T
  NV_Ith_S(I.atol, 0) = 1e-15;
  NV_Ith_S(I.atol, 1) = 1e-9;
  CVCall(CVodeSVtolerances(I.mem, par.rtol, I.atol));
  CVCall(CVodeRootInit(I.mem, nroots, nroots ? IgnitionRoots : nullptr));
  if (nroots) {
    int dir[2] = {1, 1}; // only upward crossings
    CVCall(CVodeSetRootDirection(I.mem, dir));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ThermalDecomposition::Advance(PetscReal dt, PetscReal *lambda, PetscReal *T)
{
  Impl    &I = *impl_;
  realtype t = 0;
  PetscFunctionBeginUser;
  PetscCheck(dt >= 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Advance needs dt >= 0, got %g", (double)dt);
  last_steps_ = 0;
  if (dt == 0) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(Start(*lambda, *T, 0));
  CVCall(CVodeSetStopTime(I.mem, dt));
  CVCall(CVode(I.mem, dt, I.y, &t, CV_NORMAL));
  CVCall(CVodeGetNumSteps(I.mem, &last_steps_));
  *lambda = NV_Ith_S(I.y, 0);
  *T      = NV_Ith_S(I.y, 1);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ThermalDecomposition::IgnitionDelay(PetscReal T0, PetscReal lambda0, PetscReal t_max, PetscReal *t_ign, PetscBool *ignited, PetscReal *T_end)
{
  Impl    &I = *impl_;
  realtype t = 0;
  PetscFunctionBeginUser;
  PetscCheck(T0 > 0 && t_max > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "IgnitionDelay needs T0 > 0 and t_max > 0, got %g K, %g s", (double)T0, (double)t_max);
  I.T_target = T0 + par.runaway_rise;
  I.rate     = par.runaway_rate;
  PetscCall(Start(lambda0, T0, par.runaway_rate > 0 ? 2 : 1));
  CVCall(CVodeSetStopTime(I.mem, t_max));
  const int flag = CVode(I.mem, t_max, I.y, &t, CV_NORMAL);
  CVCall(flag);
  CVCall(CVodeGetNumSteps(I.mem, &last_steps_));
  *ignited = flag == CV_ROOT_RETURN ? PETSC_TRUE : PETSC_FALSE;
  *t_ign   = *ignited ? t : t_max;
  if (T_end) *T_end = NV_Ith_S(I.y, 1);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ThermalDecomposition::SetFromOptions(MPI_Comm comm, const char material[])
{
  const std::string prefix = std::string(material) + "_";
  const PetscReal   big    = PETSC_MAX_REAL;
  struct Item {
    const char *opt, *help;
    PetscReal  *v;
    PetscReal   lo;
    PetscBool   open;
  } items[] = {
    {"-decomposition_Z", "Thermal decomposition: pre-exponential factor Z (1/s), > 0", &par.Z, 0, PETSC_TRUE},
    {"-decomposition_T_a", "Thermal decomposition: activation temperature T_a = E/R (K), > 0", &par.T_a, 0, PETSC_TRUE},
    {"-decomposition_Q", "Thermal decomposition: heat of reaction Q (J/kg), >= 0", &par.Q, 0, PETSC_FALSE},
    {"-decomposition_c", "Thermal decomposition: specific heat c (J/(kg K)), > 0", &par.c, 0, PETSC_TRUE},
    {"-decomposition_h", "Thermal decomposition: heat exchange with the environment per unit mass h (W/(kg K)), >= 0 (0: adiabatic)", &par.h, 0, PETSC_FALSE},
    {"-decomposition_T_env", "Thermal decomposition: environment temperature T_env (K), > 0", &par.T_env, 0, PETSC_TRUE},
    {"-decomposition_runaway_rise", "Thermal decomposition: runaway when T reaches T0 + this (K), > 0", &par.runaway_rise, 0, PETSC_TRUE},
    {"-decomposition_runaway_rate", "Thermal decomposition: runaway when dT/dt exceeds this (K/s), >= 0 (0: off)", &par.runaway_rate, 0, PETSC_FALSE},
    {"-decomposition_rtol", "Thermal decomposition: CVODE relative tolerance (-), in (0, 1e-3]", &par.rtol, 0, PETSC_FALSE},
  };
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, prefix.c_str(), "Reactant thermal decomposition (self-heating)", "Burn");
  for (Item &it : items) {
    PetscCall(PetscOptionsReal(it.opt, it.help, "ThermalDecomposition", *it.v, it.v, nullptr));
    const PetscReal hi = it.v == &par.rtol ? 1e-3 : big;
    PetscCall(CheckRange(comm, Prefixed(prefix.c_str(), it.opt).c_str(), *it.v, it.lo, hi, it.v == &par.rtol ? PETSC_TRUE : it.open));
  }
  PetscOptionsEnd();
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ThermalDecomposition::View(PetscViewer viewer) const
{
  return PetscViewerASCIIPrintf(viewer, "  thermal decomposition: Z %g 1/s, T_a %g K, Q %g J/kg, c %g J/(kg K), h %g W/(kg K), T_env %g K; runaway at T0 + %g K or dT/dt > %g K/s; CVODE BDF rtol %g\n", (double)par.Z, (double)par.T_a, (double)par.Q,
                                (double)par.c, (double)par.h, (double)par.T_env, (double)par.runaway_rise, (double)par.runaway_rate, (double)par.rtol);
}

} // namespace burst
