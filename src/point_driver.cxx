// The material-point driver (`burst -mode point`): one material point driven through a prescribed
// deformation history, writing stress and state per step as CSV. It calls the same material code as
// the MPM loop (models/), on a swarm of two points: point 0 keeps the state at t_n, point 1 takes
// the trial step (for uniaxial stress the lateral strain rate is iterated until the lateral stress
// vanishes), and the accepted step is copied back.
//
// Paths (-point_path, rate r = -point_rate):
//   uniaxial_strain     L = diag(r, 0, 0)
//   uniaxial_stress     L = diag(r, a, a), a such that sigma_yy = sigma_zz = 0
//   simple_shear        L_xy = r (engineering shear rate)
//   rotation            L = W with W_xy = -r, W_yx = r (rigid spin at r rad/s)
//   hydrostatic         L = r I
//   velocity_gradient   L = r Lhat, Lhat from -point_velocity_gradient (9 values, row-major)
//   rotating_uniaxial_strain  F(t) = R(theta(t)) diag(1 + r t, 1, 1), theta from 0 to
//                       -point_rotation_angle (rad) about z over the run (verification.md 1.4); F is
//                       set exactly and L = (F_{n+1} - F_n) F_{n+1/2}^{-1} / dt. The CSV stress is
//                       rotated back by R(theta)^T so it compares with the unrotated path.
// The path runs to -point_final_strain (strain r t, shear r t, angle r t in rad). With
// -point_reverse_strain s it turns back at strain s (L becomes -L; not for the rotating path), e.g.
// to open a failed point and close it again; the strain column then goes back down.
// CSV columns: step, time, strain, stress, pressure, von Mises, temperature, F and the metal models'
// state, density and wave speed; then every other scalar field the material lists in OutputFields, by its name (e.g. crack_radius).
#include "simulation.hpp"
#include "options_check.hpp"
#include "mpm/material_state.hpp"
#include "util.hpp"
#include "mpm/expm.hpp"
#include <cstdio>
#include <memory>
#include <vector>

namespace burst {

namespace {
const char *const PathNames[] = {"uniaxial_strain", "uniaxial_stress", "simple_shear", "rotation", "hydrostatic", "velocity_gradient", "rotating_uniaxial_strain"};
enum Path { UniaxialStrain, UniaxialStress, SimpleShear, Rotation, Hydrostatic, VelocityGradient, RotatingUniaxialStrain };

struct PointOptions {
  int         path           = UniaxialStrain;
  PetscReal   rate           = 1e3; // 1/s
  PetscReal   temperature    = 298; // K
  PetscReal   final_strain   = 0.2;
  PetscInt    steps          = 1000;
  PetscBool   adiabatic      = PETSC_TRUE;
  PetscReal   L_hat[9]       = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  PetscReal   rotation_angle = 2 * PETSC_PI; // rad, rotating_uniaxial_strain
  PetscReal   reverse_strain = 0;            // the path turns back at this strain (0: never)
  std::string output         = "point.csv";
  std::string material;
};

PetscErrorCode ReadPointOptions(MPI_Comm comm, PointOptions &o)
{
  char      buf[PETSC_MAX_PATH_LEN];
  PetscBool set;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "", "Material-point driver (-mode point)", "Point");
  PetscCall(OptionsChoice(PetscOptionsObject, "-point_path", "Deformation path", PathNames, 7, &o.path, nullptr));
  PetscCall(PetscOptionsReal("-point_rotation_angle", "Total rotation about z of the rotating_uniaxial_strain path (rad)", "", o.rotation_angle, &o.rotation_angle, nullptr));
  PetscCall(PetscOptionsReal("-point_rate", "Strain rate (1/s; rad/s for rotation), > 0", "", o.rate, &o.rate, nullptr));
  PetscCall(CheckRange(comm, "-point_rate", o.rate, 0, PETSC_MAX_REAL, PETSC_TRUE));
  PetscCall(PetscOptionsReal("-point_temperature", "Initial temperature (K), > 0", "", o.temperature, &o.temperature, nullptr));
  PetscCall(CheckRange(comm, "-point_temperature", o.temperature, 0, PETSC_MAX_REAL, PETSC_TRUE));
  PetscCall(PetscOptionsReal("-point_final_strain", "Final strain (shear strain, angle in rad) of the path, > 0", "", o.final_strain, &o.final_strain, nullptr));
  PetscCall(CheckRange(comm, "-point_final_strain", o.final_strain, 0, PETSC_MAX_REAL, PETSC_TRUE));
  PetscCall(PetscOptionsReal("-point_reverse_strain", "Strain at which the path turns back (L becomes -L) (-), >= 0 (0: never; not for rotating_uniaxial_strain)", "", o.reverse_strain, &o.reverse_strain, nullptr));
  PetscCall(CheckRange(comm, "-point_reverse_strain", o.reverse_strain, 0, PETSC_MAX_REAL, PETSC_FALSE));
  PetscCheck(o.reverse_strain == 0 || o.path != RotatingUniaxialStrain, comm, PETSC_ERR_USER_INPUT, "Option -point_reverse_strain is not available with -point_path rotating_uniaxial_strain");
  PetscCall(PetscOptionsInt("-point_steps", "Number of steps, >= 1", "", o.steps, &o.steps, nullptr));
  PetscCheck(o.steps >= 1, comm, PETSC_ERR_USER_INPUT, "Option -point_steps = %" PetscInt_FMT " is out of range: it must be >= 1", o.steps);
  PetscCall(PetscOptionsBool("-point_adiabatic", "Keep the plastic heating (adiabatic); false resets the temperature every step (isothermal)", "", o.adiabatic, &o.adiabatic, nullptr));
  PetscCall(OptionsRealVector(PetscOptionsObject, "-point_velocity_gradient", "Direction of L for -point_path velocity_gradient (9 values, row-major; scaled by -point_rate)", o.L_hat, 9, &set));
  PetscCall(PetscStrncpy(buf, o.output.c_str(), sizeof(buf)));
  PetscCall(PetscOptionsString("-point_output", "CSV file written by the driver", "", buf, buf, sizeof(buf), nullptr));
  o.output = buf;
  buf[0]   = 0;
  PetscCall(PetscOptionsString("-point_material", "Material to drive (default: the first of -materials)", "", buf, buf, sizeof(buf), &set));
  if (set) o.material = buf;
  PetscOptionsEnd();
  PetscFunctionReturn(PETSC_SUCCESS);
}

// Velocity gradient of the path; a = lateral strain rate of uniaxial stress.
Mat3 PathVelocityGradient(const PointOptions &o, PetscReal a)
{
  Mat3 L = Mat3::Zero();
  switch (o.path) {
  case UniaxialStrain: L(0, 0) = o.rate; break;
  case UniaxialStress:
    L(0, 0) = o.rate;
    L(1, 1) = L(2, 2) = a;
    break;
  case SimpleShear: L(0, 1) = o.rate; break;
  case Rotation:
    L(0, 1) = -o.rate;
    L(1, 0) = o.rate;
    break;
  case Hydrostatic: L = o.rate * Mat3::Identity(); break;
  case VelocityGradient: L = o.rate * Mat3CMap(o.L_hat); break;
  case RotatingUniaxialStrain: break; // set from F(t), see RotatingF
  }
  return L;
}

// F(t) of the rotating uniaxial-strain path.
Mat3 RotatingF(const PointOptions &o, PetscReal t, PetscReal total_time)
{
  const PetscReal theta = o.rotation_angle * t / total_time;
  Mat3            R     = Mat3::Identity();
  R(0, 0) = R(1, 1) = std::cos(theta);
  R(0, 1)           = -std::sin(theta);
  R(1, 0)           = std::sin(theta);
  Mat3 U            = Mat3::Identity();
  U(0, 0)           = 1 + o.rate * t;
  return R * U;
}
} // namespace

PetscErrorCode RunPointDriver(Simulation &sim)
{
  PointOptions o;
  DM           sw;
  PetscFunctionBeginUser;
  PetscCall(ReadPointOptions(sim.comm, o));
  sim.mpm.grid.dim = 3;
  PetscCall(CreateMaterials(sim.mpm));
  if (sim.help) PetscFunctionReturn(PETSC_SUCCESS);
  PetscInt id = 0;
  if (!o.material.empty()) {
    id = -1;
    for (size_t m = 0; m < sim.mpm.materials.size(); ++m)
      if (sim.mpm.materials[m]->name_ == o.material) id = (PetscInt)m;
    PetscCheck(id >= 0, sim.comm, PETSC_ERR_USER_INPUT, "Option -point_material %s is not one of -materials", o.material.c_str());
  }
  Material &material = *sim.mpm.materials[id];

  // A two-point swarm with the fields the material layer reads.
  PetscCall(DMCreate(PETSC_COMM_SELF, &sw));
  PetscCall(DMSetType(sw, DMSWARM));
  PetscCall(DMSetDimension(sw, 3));
  PetscCall(DMSwarmSetType(sw, DMSWARM_BASIC));
  const char *real9[] = {field::F, field::stress, field::L};
  for (const char *name : real9) PetscCall(DMSwarmRegisterPetscDatatypeField(sw, name, 9, PETSC_REAL));
  const char *real1[] = {field::mass, field::volume, field::volume0, field::temperature, field::wave_speed, field::internal_energy};
  for (const char *name : real1) PetscCall(DMSwarmRegisterPetscDatatypeField(sw, name, 1, PETSC_REAL));
  PetscCall(DMSwarmRegisterPetscDatatypeField(sw, field::material, 1, PETSC_INT));
  PetscInt bytes = 0;
  PetscCall(RegisterMaterialState(sw, sim.mpm.materials, &bytes));
  PetscCall(DMSwarmFinalizeFieldRegister(sw));
  PetscCall(DMSwarmSetLocalSizes(sw, 2, 0));
  {
    SwarmAccess f(sw);
    PetscReal  *F, *sigma, *L, *m, *V, *V0, *T, *c, *e;
    PetscInt   *mat;
    PetscInt64 *pid;
    PetscCall(f.Get(field::F, &F));
    PetscCall(f.Get(field::stress, &sigma));
    PetscCall(f.Get(field::L, &L));
    PetscCall(f.Get(field::mass, &m));
    PetscCall(f.Get(field::volume, &V));
    PetscCall(f.Get(field::volume0, &V0));
    PetscCall(f.Get(field::temperature, &T));
    PetscCall(f.Get(field::wave_speed, &c));
    PetscCall(f.Get(field::internal_energy, &e));
    PetscCall(f.Get(field::material, &mat));
    PetscCall(f.Get(DMSwarmField_pid, &pid));
    for (int p = 0; p < 2; ++p) {
      for (int a = 0; a < 9; ++a) F[9 * p + a] = (a % 4 == 0) ? 1 : 0, sigma[9 * p + a] = 0, L[9 * p + a] = 0;
      V[p] = V0[p] = 1e-9; // 1 mm^3
      m[p]         = material.Density() * V[p];
      T[p]         = o.temperature;
      c[p] = e[p] = 0;
      mat[p]      = id;
      pid[p]      = 0; // the same random draws for both copies
    }
    PetscCall(f.RestoreAll());
  }
  {
    SwarmAccess         f(sw);
    MaterialState       state;
    MaterialPointFields mp;
    PetscCall(GetMaterialPointFields(f, sw, state, mp));
    PetscCall(material.InitializeState(mp, 0, 2));
    PetscCall(f.RestoreAll());
  }
  PetscCall(OptionsCheckEnd(sim.comm, RunFeatures(sim, true))); // every option read by now: none may be misspelled

  const PetscReal total_time = o.final_strain / o.rate, dt = total_time / o.steps;
  FILE           *out = nullptr;
  if (!sim.rank) {
    out = std::fopen(o.output.c_str(), "w");
    PetscCheck(out, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Could not open -point_output %s", o.output.c_str());
    std::fprintf(out,
                 "step,time,strain,stress_xx,stress_yy,stress_zz,stress_xy,stress_yz,stress_xz,pressure,von_mises,plastic_strain,plastic_strain_rate,temperature,porosity,damage,flow_stress,unstable,failed,F_xx,F_xy,F_yx,F_yy,density,wave_speed");
  }
  // model fields written when the material has them (it declares them in OutputFields)
  const char *optional[] = {state_field::plastic_strain, state_field::plastic_strain_rate, "porosity", "damage", "flow_stress", "unstable", state_field::failed};
  bool        present[7] = {false, false, false, false, false, false, false};
  for (int k = 0; k < 7; ++k)
    for (const OutputField &of : material.OutputFields()) present[k] = present[k] || std::string(of.name) == optional[k];
  // the material's other scalar fields (e.g. a crack radius) follow as extra columns, by their names
  std::vector<const char *> extra;
  for (const OutputField &of : material.OutputFields()) {
    bool listed = false;
    for (const char *name : optional) listed = listed || std::string(of.name) == name;
    if (!listed && of.bs == 1 && !of.is_int) extra.push_back(of.name);
  }
  if (out) {
    for (const char *name : extra) std::fprintf(out, ",%s", name);
    std::fprintf(out, "\n");
  }
  PetscReal lateral_rate = 0;
  // the path's strain at the end of a step (back down after -point_reverse_strain)
  auto path_strain = [&](PetscInt step) {
    const PetscReal s = o.rate * step * dt;
    return o.reverse_strain > 0 && s > o.reverse_strain ? 2 * o.reverse_strain - s : s;
  };
  for (PetscInt step = 0; step <= o.steps; ++step) {
    if (step > 0) {
      const PetscReal direction = path_strain(step) < path_strain(step - 1) ? -1 : 1; // the step turning back takes its mean direction
      // trial step on point 1 from the state of point 0; iterate a for uniaxial stress (secant)
      PetscReal a0 = lateral_rate, a1 = lateral_rate - 0.3 * o.rate, r0 = 0, r1 = 0;
      for (int it = 0; it < 50; ++it) {
        const PetscReal a = it == 0 ? a0 : a1;
        PetscCall(DMSwarmCopyPoint(sw, 0, 1)); // copies point 0 into point 1
        SwarmAccess f(sw);
        PetscInt   *mat;
        PetscReal  *F, *Lp, *V, *V0, *T, *sigma;
        PetscCall(f.Get(field::material, &mat));
        PetscCall(f.Get(field::F, &F));
        PetscCall(f.Get(field::L, &Lp));
        PetscCall(f.Get(field::volume, &V));
        PetscCall(f.Get(field::volume0, &V0));
        PetscCall(f.Get(field::temperature, &T));
        PetscCall(f.Get(field::stress, &sigma));
        Mat3 L = direction * PathVelocityGradient(o, direction * a);
        if (o.path == RotatingUniaxialStrain) {
          const Mat3 F0 = RotatingF(o, (step - 1) * dt, total_time), F1 = RotatingF(o, step * dt, total_time);
          L              = (F1 - F0) * (0.5 * (F0 + F1)).inverse() / dt;
          Mat3Map(F + 9) = F1;
        } else Mat3Map(F + 9) = (sim.mpm.f_update == FUpdate::Exponential ? Expm(L * dt) : Mat3(Mat3::Identity() + L * dt)) * Mat3Map(F + 9);
        Mat3Map(Lp + 9) = L;
        V[1]            = V0[1] * Mat3Map(F + 9).determinant();
        mat[0]          = -1; // only the trial point takes the step
        PetscCall(f.RestoreAll());
        {
          SwarmAccess         views(sw);
          MaterialState       state;
          MaterialPointFields mp;
          PetscCall(GetMaterialPointFields(views, sw, state, mp));
          mp.time = step * dt;
          PetscCall(material.UpdateStress(mp, id, dt));
          PetscCall(views.RestoreAll());
        }
        PetscCall(f.Get(field::material, &mat));
        PetscCall(f.Get(field::stress, &sigma));
        PetscCall(f.Get(field::temperature, &T));
        mat[0] = id;
        if (!o.adiabatic) T[1] = o.temperature;
        const PetscReal lateral = 0.5 * (sigma[9 + 4] + sigma[9 + 8]), scale = PetscMax(PetscAbsReal(sigma[9]), 1.0);
        PetscCall(f.RestoreAll());
        if (o.path != UniaxialStress) break;
        if (it == 0) r0 = lateral;
        else {
          r1 = lateral;
          if (PetscAbsReal(r1) <= 1e-10 * scale) {
            lateral_rate = a1;
            break;
          }
          const PetscReal next = a1 - r1 * (a1 - a0) / (r1 - r0);
          a0                   = a1;
          r0                   = r1;
          a1                   = next;
          PetscCheck(it < 49, PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED, "Point driver: uniaxial stress did not converge at step %" PetscInt_FMT, step);
        }
        if (it == 0 && PetscAbsReal(r0) <= 1e-10 * scale) {
          lateral_rate = a0;
          break;
        }
      }
      PetscCall(DMSwarmCopyPoint(sw, 1, 0)); // accept
    }
    // output of point 0
    SwarmAccess      f(sw);
    const PetscReal *sigma, *T, *F;
    PetscReal        values[7] = {0, 0, 0, 0, 0, 0, 0}; // optional[] in order
    PetscCall(f.Get(field::stress, &sigma));
    PetscCall(f.Get(field::temperature, &T));
    PetscCall(f.Get(field::F, &F));
    for (int k = 0; k < 7; ++k) {
      if (!present[k]) continue;
      if (k < 5) {
        const PetscReal *v;
        PetscCall(f.Get(optional[k], &v));
        values[k] = v[0];
      } else {
        const PetscInt *v;
        PetscCall(f.Get(optional[k], &v));
        values[k] = v[0];
      }
    }
    Mat3 s0 = Mat3CMap(sigma);
    if (o.path == RotatingUniaxialStrain) { // report in the unrotated frame
      const PetscReal theta = o.rotation_angle * step / o.steps;
      Mat3            Q     = Mat3::Identity();
      Q(0, 0) = Q(1, 1) = std::cos(theta);
      Q(0, 1)           = -std::sin(theta);
      Q(1, 0)           = std::sin(theta);
      s0                = Q.transpose() * s0 * Q;
    }
    const PetscReal p   = -s0.trace() / 3;
    Mat3            dev = s0;
    dev.diagonal().array() += p;
    const PetscReal q = std::sqrt(1.5 * dev.squaredNorm());
    if (out)
      std::fprintf(out, "%d,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%d,%d,%.10e,%.10e,%.10e,%.10e", (int)step, (double)(step * dt), (double)path_strain(step), (double)s0(0, 0), (double)s0(1, 1),
                   (double)s0(2, 2), (double)s0(0, 1), (double)s0(1, 2), (double)s0(0, 2), (double)p, (double)q, (double)values[0], (double)values[1], (double)T[0], (double)values[2], (double)values[3], (double)values[4], (int)values[5],
                   (int)values[6], (double)F[0], (double)F[1], (double)F[3], (double)F[4]);
    {
      const PetscReal *mass, *volume, *wave_speed;
      PetscCall(f.Get(field::mass, &mass));
      PetscCall(f.Get(field::volume, &volume));
      PetscCall(f.Get(field::wave_speed, &wave_speed));
      if (out) std::fprintf(out, ",%.10e,%.10e", (double)(mass[0] / volume[0]), (double)wave_speed[0]);
    }
    for (const char *name : extra) {
      const PetscReal *v;
      PetscCall(f.Get(name, &v));
      if (out) std::fprintf(out, ",%.10e", (double)v[0]);
    }
    if (out) std::fprintf(out, "\n");
    if (step == o.steps)
      PetscCall(PetscPrintf(sim.comm, "Point driver: %s %s to strain %g at %g 1/s: stress xx %.6e Pa, von Mises %.6e Pa, plastic strain %.6g, temperature %.6g K; wrote %s\n", material.Name(), PathNames[o.path], (double)o.final_strain, (double)o.rate,
                            (double)s0(0, 0), (double)q, (double)values[0], (double)T[0], o.output.c_str()));
    PetscCall(f.RestoreAll());
  }
  if (out) std::fclose(out);
  PetscCall(DMDestroy(&sw));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace burst
