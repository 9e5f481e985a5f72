// The hypoelastic-plastic material of the paper (Algorithm 1; models.md 1), model name
// `elastic_plastic`. Per particle and step:
//   1. D = sym L; the Green-Naghdi frame: R_{n+1} from the polar decomposition of F_{n+1}; the old
//      stress is rotated with R_n (stored per particle), D with the mean of R_n and R_{n+1}.
//   2. Equation of state (pressure at t_{n+1}, tangent bulk modulus), melt temperature, shear
//      modulus, specific heat.
//   3. Trial deviator s_tr = s_n + 2 mu dt dev(D_hat); melted points (T >= Tm) lose their deviator.
//   4. Yield test and return (von Mises radial return or GTN), inlined with the flow-stress model.
//   5. Porosity (eqs. 15-17), damage (eq. 20/21), temperature (eq. 18 and the Mie-Gruneisen
//      isentropic term), stability checks (eqs. 23-24).
//   6. Failure tags (melt, TEPLA-F, critical porosity, stability, sigma_f <= 0), with the time, and
//      the failure response of failed points (-MAT_failure_response, applied from the failing step
//      on: models.md 5.9 and pitfall 15): none, zero_stress, no_tension (keep compressive pressure),
//      no_shear (keep the pressure). The elastic energy a response releases is accumulated in the
//      failure_energy field (J) so the energy balance can report it.
//   7. sigma_{n+1} = R_{n+1} (s - p I) R_{n+1}^T; stress work; wave speed sqrt((K + 4 mu/3)/rho).
// Regularisation of failure (-MAT_regularization; issue 12, off by default, and then every line
// below runs as before):
//   nonlocal:   the failure drivers are averaged over the material length ell
//               (-MAT_regularization_length), Tvergaard & Needleman (1995): the local increments of
//               the step, the damage Delta D = Delta eps_p / eps_f (eqs. 20-21) and the porosity
//               Delta f (growth + nucleation, eqs. 16-17), go to the nonlocal average of
//               src/mpm/nonlocal.cxx (weights a(r) = (1 - r^2/ell^2)^2 per direction,
//               mass-weighted), and the averages are added at the start of the next step:
//               f <- f + <Delta f> (GTN sees the nonlocal porosity, so the void softening has a
//               length), D_bar <- D_bar + <Delta D> (from the initial damage), and TEPLA-F (eq. 22)
//               reads (f/f_c)^2 + D_bar^2: the strain term as the accumulated damage, which is
//               eps_p/eps_f on a proportional path and what the code the paper ran used
//               (ElasticPlastic.cc, models.md 2). The one-step lag is O(dt) (1e-8 s steps).
// -MAT_failure_tepla_damage (off by default): the same damage form of TEPLA-F without the average,
// (f/f_c)^2 + D^2 with the local D, instead of eps_p / eps_f at the current triaxiality (which an
// elastic step with a tensile mean stress and a small deviator, eps_f -> its floor, fails at once).
//   crack_band: a criterion starts softening instead of failing the particle (Bazant & Oh 1983;
//               Hillerborg's linear law in Abaqus's plastic-displacement form): the stress is
//               (1 - omega) times the stress of the intact update, omega = u_p / u_f, with the
//               plastic displacement u_p = h_p sum Delta eps_p since the criterion was met, h_p the
//               particle size, and u_f = 2 G_f / sigma_i (sigma_i = (1 - f) sigma_f then), so the
//               energy per unit crack area of a one-particle band is G_f (-MAT_fracture_energy)
//               whatever h_p; at omega = 1 the particle fails with the criterion's bits and the
//               failure response applies as before. The work done while softening (less the
//               change of stored elastic energy) is counted as failure energy.
// Particles are processed in chunks of kChunk; each sub-model is called once per chunk.
#include "families.hpp"
#include "polar.hpp"
#include "../flow_stress/flow_stress.hpp"
#include "../material.hpp"
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

namespace burst {

namespace {
// Field names of the model's per-particle state.
constexpr const char *kPlasticStrain     = state_field::plastic_strain;
constexpr const char *kPlasticStrainRate = state_field::plastic_strain_rate;
constexpr const char *kPorosity          = "porosity";
constexpr const char *kDamage            = "damage";
constexpr const char *kRotation          = "rotation";           // R of the polar decomposition at t_n, bs 9
constexpr const char *kFlowHistory       = "flow_history";       // flow-model history, bs kMaxHistory
constexpr const char *kFlowStress        = "flow_stress";        // Pa (output)
constexpr const char *kFailed            = state_field::failed;  // int: failure criterion bits, 0 = intact
constexpr const char *kFailureTime       = "failure_time";       // s
constexpr const char *kUnstable          = "unstable";           // int: stability bits at the last step
constexpr const char *kPlasticDilatation = "plastic_dilatation"; // accumulated tr(eps_p) (GTN), -
constexpr const char *kFailureEnergy     = "failure_energy";     // elastic energy released by the failure response, J
constexpr const char *kPlasticWork       = "plastic_work";       // accumulated plastic work sigma : d eps_p V, J
constexpr const char *kPlasticHeat       = "plastic_heat";       // the part of it turned into heat (eq. 18), J
constexpr const char *kElasticEnergy     = "elastic_energy";     // stored elastic energy (p^2/(2K) + q^2/(6 mu)) V now, J
// Regularisation state (registered only when a material uses -MAT_regularization)
constexpr const char *kNonlocalStrain = "nonlocal_damage";               // D_bar: initial damage + sum of the nonlocal averages of Delta D, -
constexpr const char *kSofteningDisp  = "softening_displacement";        // u_p = h_p sum Delta eps_p since the criterion was met, m
constexpr const char *kSofteningLimit = "softening_limit";               // u_f = 2 G_f / sigma_i, m (0: not softening)
constexpr const char *kSoftening      = "softening";                     // omega = u_p / u_f in [0, 1] (output)
constexpr const char *kSofteningBits  = state_field::softening_criteria; // int: the criterion bits that started the softening

// Views of the model's per-particle state, gotten together (the members in declaration order, so a
// structured binding names them).
struct PlasticState {
  PetscReal *eps, *rate, *f, *D, *R, *history, *sigma_f, *t_fail, *dilatation, *released, *work, *heat, *elastic;
  PetscInt  *failed, *unstable;

  PetscErrorCode Get(const MaterialState &fields)
  {
    PetscFunctionBeginUser;
    PetscCall(fields.Get(kPlasticStrain, &eps));
    PetscCall(fields.Get(kPlasticStrainRate, &rate));
    PetscCall(fields.Get(kPorosity, &f));
    PetscCall(fields.Get(kDamage, &D));
    PetscCall(fields.Get(kRotation, &R));
    PetscCall(fields.Get(kFlowHistory, &history));
    PetscCall(fields.Get(kFlowStress, &sigma_f));
    PetscCall(fields.Get(kFailureTime, &t_fail));
    PetscCall(fields.Get(kPlasticDilatation, &dilatation));
    PetscCall(fields.Get(kFailureEnergy, &released));
    PetscCall(fields.Get(kPlasticWork, &work));
    PetscCall(fields.Get(kPlasticHeat, &heat));
    PetscCall(fields.Get(kElasticEnergy, &elastic));
    PetscCall(fields.Get(kFailed, &failed));
    PetscCall(fields.Get(kUnstable, &unstable));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
};

// Reproducible uniform and normal draws keyed by (seed, particle id): the same on any rank count.
inline std::uint64_t SplitMix64(std::uint64_t x)
{
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}
inline PetscReal Uniform(std::uint64_t seed, std::uint64_t id, std::uint64_t stream) { return ((SplitMix64(SplitMix64(seed ^ SplitMix64(id)) + stream) >> 11) + 0.5) * (1.0 / 9007199254740992.0); }
inline PetscReal Normal(std::uint64_t seed, std::uint64_t id, std::uint64_t stream)
{
  const PetscReal u1 = Uniform(seed, id, 2 * stream), u2 = Uniform(seed, id, 2 * stream + 1);
  return std::sqrt(-2 * std::log(u1)) * std::cos(2 * PETSC_PI * u2);
}

// Views of the regularisation state (all null unless the fields are registered).
struct RegularizationFields {
  PetscReal       *source = nullptr, *average = nullptr, *strain = nullptr, *disp = nullptr, *limit = nullptr, *omega = nullptr;
  PetscInt        *bits        = nullptr;
  const PetscReal *half_width0 = nullptr; // bs dim, the particle half-widths at seeding (m), if the particles have them
  const PetscReal *volume0     = nullptr; // else the volume at seeding (the point driver), m^3
  PetscInt         dim         = 0;
  PetscReal        band_length = 0; // -MAT_crack_band_length cell: the cell size (m); 0: the particle's size
  // The length h of the crack band, m: the particle's size, or the cell's.
  PetscReal Size(PetscInt q) const { return band_length > 0 ? band_length : half_width0 ? 2 * half_width0[dim * q] : std::pow(volume0[q], 1.0 / dim); }

  PetscErrorCode Get(const MaterialPointFields &mp, bool band_on_cell)
  {
    PetscFunctionBeginUser;
    if (!mp.state->Has(kNonlocalSource)) PetscFunctionReturn(PETSC_SUCCESS); // no material regularises
    PetscCall(mp.state->Get(kNonlocalSource, &source));
    PetscCall(mp.state->Get(kNonlocalAverage, &average));
    PetscCall(mp.state->Get(kNonlocalStrain, &strain));
    PetscCall(mp.state->Get(kSofteningDisp, &disp));
    PetscCall(mp.state->Get(kSofteningLimit, &limit));
    PetscCall(mp.state->Get(kSoftening, &omega));
    PetscCall(mp.state->Get(kSofteningBits, &bits));
    half_width0 = mp.half_width0;
    volume0     = mp.volume0;
    dim         = mp.dim;
    band_length = band_on_cell ? mp.cell_size : 0;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
};

// Per-chunk values that the steps of UpdateStress hand on to each other.
struct ChunkScratch {
  PetscReal R_next[kChunk][9];          // R_{n+1} of the chunk's points (row-major)
  PetscReal omega_old[kChunk];          // crack band: the softening at t_n (0 otherwise)
  PetscReal omega[kChunk];              // crack band: the softening at t_{n+1}
  PetscReal failed_porosity[kChunk];    // a failed point's porosity, set aside during the return
  PetscReal porosity_old[kChunk];       // f before step 5
  PetscReal porosity_increment[kChunk]; // Delta f of the step (growth + nucleation)
  PetscReal plastic_work[kChunk];       // J/kg
  bool      newly_failed[kChunk];
};

enum FailureBits : int { FailMelt = 1, FailTepla = 2, FailPorosity = 4, FailStability = 8, FailStrength = 16 };
enum class FailureResponse : int { None = 0, ZeroStress = 1, NoTension = 2, NoShear = 3 };
enum class Regularization : int { None = 0, Nonlocal = 1, CrackBand = 2 };
const char *const kRegularizationNames[] = {"none", "nonlocal", "crack_band"};
const char *const kResponseNames[]       = {"none", "zero_stress", "no_tension", "no_shear"};
const char *const kFailureNames[]        = {"melt", "tepla", "porosity", "stability", "strength"};
} // namespace

class ElasticPlastic final : public Material {
public:
  MaterialConstants                            constants;
  std::unique_ptr<EquationOfState>             eos;
  std::unique_ptr<ShearModulusModel>           shear;
  std::unique_ptr<MeltModel>                   melt;
  std::unique_ptr<SpecificHeatModel>           specific_heat;
  std::unique_ptr<FlowStress>                  flow;
  std::unique_ptr<DamageModel>                 damage;
  std::vector<std::unique_ptr<StabilityCheck>> stability;
  ReturnSettings                               settings;
  PetscReal                                    taylor_quinney = 0.9;
  PetscBool                                    adiabatic      = PETSC_TRUE;
  // Porosity (eqs. 15-17) and initial distributions
  PetscBool porosity_growth = PETSC_FALSE, porosity_nucleation = PETSC_FALSE, nucleation_tension_only = PETSC_TRUE;
  PetscReal nucleation_fraction = 0.1, nucleation_strain = 0.3, nucleation_deviation = 0.1; // f_n, eps_n, s_n
  PetscReal porosity_mean = 0, porosity_deviation = 0, damage_mean = 0, damage_deviation = 0;
  PetscInt  seed = 1;
  // Failure
  int             failure_criteria        = FailMelt;
  FailureResponse failure_response        = FailureResponse::None;
  PetscReal       tepla_critical_porosity = 0.3; // f_c of eq. 22 and of the critical-porosity criterion
  // Regularisation (issue 12; see the head of the file)
  Regularization regularization        = Regularization::None;
  PetscReal      regularization_length = 0;           // ell, m (nonlocal)
  PetscReal      fracture_energy       = 0;           // G_f, J/m^2 (crack_band)
  PetscBool      band_on_cell          = PETSC_FALSE; // crack_band: the band's length h is the cell size, not the particle's
  PetscBool      tepla_damage          = PETSC_FALSE; // TEPLA-F with the accumulated damage D

  PetscReal NonlocalLength() const override { return regularization == Regularization::Nonlocal ? regularization_length : 0; }
  bool      BandOnCell() const { return regularization == Regularization::CrackBand && band_on_cell; } // the crack band's length is the cell's

  PetscErrorCode SetFromOptions(PetscOptionItems *PetscOptionsObject) override
  {
    const std::string P = PetscOptionsObject->prefix;
    PetscFunctionBeginUser;
    constants.name    = name_;
    constants.density = density_;
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-shear_modulus", "Reference shear modulus mu0 (Pa), > 0", &constants.shear_modulus));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "shear_modulus").c_str(), constants.shear_modulus, 0, PETSC_MAX_REAL, PETSC_TRUE));
    PetscCall(OptionsRequiredReal(PetscOptionsObject, "-bulk_modulus", "Reference bulk modulus K0 (Pa), > 0", &constants.bulk_modulus));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "bulk_modulus").c_str(), constants.bulk_modulus, 0, PETSC_MAX_REAL, PETSC_TRUE));
    bulk_modulus_ = constants.bulk_modulus;
    PetscCall(PetscOptionsReal("-room_temperature", "Room (reference) temperature (K)", "", constants.room_temperature, &constants.room_temperature, nullptr));
    PetscCall(PetscOptionsReal("-taylor_quinney", "Fraction of plastic work converted to heat, chi of eq. 18 (-), in [0, 1]", "", taylor_quinney, &taylor_quinney, nullptr));
    PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "taylor_quinney").c_str(), taylor_quinney, 0, 1, PETSC_FALSE));
    PetscCall(PetscOptionsBool("-adiabatic", "Plastic work heats the particle (eq. 18); false keeps the temperature (isothermal)", "", adiabatic, &adiabatic, nullptr));
    int               yield         = (int)settings.yield;
    const char *const yield_names[] = {"von_mises", "gtn"};
    PetscCall(OptionsChoice(PetscOptionsObject, "-yield_type", "Yield condition: von_mises (eq. 12) or gtn (Gurson-Tvergaard-Needleman, eqs. 13-14)", yield_names, 2, &yield, nullptr));
    settings.yield = (YieldType)yield;
    PetscCall(PetscOptionsReal("-yield_q1", "GTN q1 (-)", "", settings.gtn.q1, &settings.gtn.q1, nullptr));
    PetscCall(PetscOptionsReal("-yield_q2", "GTN q2 (-)", "", settings.gtn.q2, &settings.gtn.q2, nullptr));
    PetscCall(PetscOptionsReal("-yield_q3", "GTN q3 (-)", "", settings.gtn.q3, &settings.gtn.q3, nullptr));
    PetscCall(PetscOptionsReal("-yield_critical_porosity", "GTN f_c of eq. 14, where void coalescence accelerates f* (-)", "", settings.gtn.critical_porosity, &settings.gtn.critical_porosity, nullptr));
    PetscCall(PetscOptionsReal("-yield_acceleration", "GTN k of eq. 14 (-)", "", settings.gtn.acceleration, &settings.gtn.acceleration, nullptr));
    PetscCall(PetscOptionsReal("-return_tolerance", "Relative tolerance of the return-mapping Newton iterations (-)", "", settings.tolerance, &settings.tolerance, nullptr));
    PetscCall(PetscOptionsBool("-porosity_growth", "Void growth (eq. 16), (1 - f) tr(D_p); zero with von Mises yield", "", porosity_growth, &porosity_growth, nullptr));
    PetscCall(PetscOptionsBool("-porosity_nucleation", "Strain-controlled void nucleation (eq. 17)", "", porosity_nucleation, &porosity_nucleation, nullptr));
    PetscCall(
      PetscOptionsBool("-porosity_nucleation_tension_only", "Nucleate voids only under tensile mean stress (with GTN, nucleation under strong compression collapses the pressure)", "", nucleation_tension_only, &nucleation_tension_only, nullptr));
    PetscCall(PetscOptionsReal("-porosity_nucleation_fraction", "Volume fraction of void-nucleating particles f_n (-)", "", nucleation_fraction, &nucleation_fraction, nullptr));
    PetscCall(PetscOptionsReal("-porosity_nucleation_strain", "Mean nucleation strain eps_n (-) (NOTES: 0.3; Table 1 swaps it with s_n)", "", nucleation_strain, &nucleation_strain, nullptr));
    PetscCall(PetscOptionsReal("-porosity_nucleation_deviation", "Standard deviation of the nucleation strain s_n (-)", "", nucleation_deviation, &nucleation_deviation, nullptr));
    PetscCall(PetscOptionsReal("-porosity_initial_mean", "Initial porosity: mean of the Gaussian (-)", "", porosity_mean, &porosity_mean, nullptr));
    PetscCall(PetscOptionsReal("-porosity_initial_deviation", "Initial porosity: standard deviation (-), draws clipped at 0", "", porosity_deviation, &porosity_deviation, nullptr));
    PetscCall(PetscOptionsReal("-damage_initial_mean", "Initial scalar damage: mean of the Gaussian (-)", "", damage_mean, &damage_mean, nullptr));
    PetscCall(PetscOptionsReal("-damage_initial_deviation", "Initial scalar damage: standard deviation (-), draws clipped at 0", "", damage_deviation, &damage_deviation, nullptr));
    PetscCall(PetscOptionsInt("-random_seed", "Seed of the initial porosity and damage draws (same run on any rank count)", "", seed, &seed, nullptr));
    settings.gtn.growth = porosity_growth; // the GTN return grows f implicitly exactly as step 5 does
    PetscCheck(nucleation_deviation > 0, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "Option -%sporosity_nucleation_deviation must be > 0", P.c_str());
    PetscCheck(porosity_mean >= 0 && porosity_mean < 1 && porosity_deviation >= 0, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "Options -%sporosity_initial_mean in [0, 1) and -%sporosity_initial_deviation >= 0", P.c_str(), P.c_str());
    {
      char     *names[8];
      PetscInt  n = 8;
      PetscBool set;
      PetscCall(PetscOptionsStringArray("-failure_criteria", "Failure criteria, any of melt, tepla, porosity, stability, strength (sigma_f <= 0), or none", "", names, &n, &set));
      if (set) {
        failure_criteria = 0;
        for (PetscInt i = 0; i < n; ++i) {
          int bit = -1;
          for (int b = 0; b < 5; ++b)
            if (std::string(names[i]) == kFailureNames[b]) bit = b;
          PetscCheck(bit >= 0 || std::string(names[i]) == "none", PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "Unknown failure criterion '%s' for -%sfailure_criteria; valid choices: melt, tepla, porosity, stability, strength, none", names[i], P.c_str());
          if (bit >= 0) failure_criteria |= 1 << bit;
          PetscCall(PetscFree(names[i]));
        }
      }
    }
    {
      int response = (int)failure_response;
      PetscCall(OptionsChoice(PetscOptionsObject, "-failure_response", "What a failed particle carries: none, zero_stress, no_tension (compressive pressure only), no_shear (pressure only)", kResponseNames, 4, &response, nullptr));
      failure_response = (FailureResponse)response;
    }
    PetscCall(PetscOptionsReal("-failure_porosity", "Critical porosity of TEPLA-F (eq. 22) and of the porosity criterion (-)", "", tepla_critical_porosity, &tepla_critical_porosity, nullptr));
    PetscCall(PetscOptionsBool("-failure_tepla_damage", "TEPLA-F (eq. 22) as (f/f_c)^2 + D^2 with the accumulated damage D of the damage model (as ElasticPlastic.cc, which the paper ran), instead of eps_p/eps_f at the current triaxiality", "",
                               tepla_damage, &tepla_damage, nullptr));
    {
      int reg = (int)regularization;
      PetscCall(OptionsChoice(PetscOptionsObject, "-regularization",
                              "Length scale of failure (issue 12): none, nonlocal (failure drivers Delta D, Delta f averaged over -regularization_length), crack_band (linear softening after a criterion, energy -fracture_energy per unit crack area)",
                              kRegularizationNames, 3, &reg, nullptr));
      regularization = (Regularization)reg;
      PetscBool set_length, set_energy;
      PetscCall(PetscOptionsReal("-regularization_length", "Material length ell of the nonlocal average: radius of the weight (1 - r^2/ell^2)^2 per direction (m), > 0", "", regularization_length, &regularization_length, &set_length));
      PetscCall(PetscOptionsReal("-fracture_energy", "Fracture energy G_f of the crack band: energy per unit crack area dissipated by the softening (J/m^2), > 0", "", fracture_energy, &fracture_energy, &set_energy));
      {
        const char *const band_lengths[] = {"particle", "cell"};
        int               band           = band_on_cell ? 1 : 0;
        PetscCall(OptionsChoice(PetscOptionsObject, "-crack_band_length",
                                "Length h of the crack band, u_p = h sum Delta eps_p: particle (the particle's size: a band one particle wide dissipates G_f) or cell (the grid's cell size: a band one "
                                "cell wide dissipates G_f, whatever the particles per cell)",
                                band_lengths, 2, &band, nullptr));
        band_on_cell = band == 1 ? PETSC_TRUE : PETSC_FALSE;
      }
      if (regularization == Regularization::Nonlocal) {
        PetscCheck(set_length, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "-%sregularization nonlocal needs -%sregularization_length (m, > 0)", P.c_str(), P.c_str());
        PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "regularization_length").c_str(), regularization_length, 0, 1.0, PETSC_TRUE));
      }
      if (regularization == Regularization::CrackBand) {
        PetscCheck(set_energy, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "-%sregularization crack_band needs -%sfracture_energy (J/m^2, > 0)", P.c_str(), P.c_str());
        PetscCall(CheckRange(PETSC_COMM_WORLD, ("-" + P + "fracture_energy").c_str(), fracture_energy, 0, 1e9, PETSC_TRUE));
        PetscCheck(failure_criteria, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "-%sregularization crack_band softens after a failure criterion: give -%sfailure_criteria", P.c_str(), P.c_str());
      }
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  // Sub-models are created after the material's own options (they need its constants).
  PetscErrorCode SetUp(MPI_Comm comm) override
  {
    PetscFunctionList list;
    SubModel         *m;
    PetscFunctionBeginUser;
    PetscCall(EquationOfStateList(&list));
    PetscCall(SubModelCreate(comm, list, constants, "eos", "hypoelastic", "Equation of state", &m));
    eos.reset(static_cast<EquationOfState *>(m));
    PetscCall(MeltList(&list));
    PetscCall(SubModelCreate(comm, list, constants, "melt", "constant", "Melt temperature model", &m));
    melt.reset(static_cast<MeltModel *>(m));
    PetscCall(ShearModulusList(&list));
    PetscCall(SubModelCreate(comm, list, constants, "shear_modulus", "constant", "Shear modulus model", &m));
    shear.reset(static_cast<ShearModulusModel *>(m));
    PetscCall(SpecificHeatList(&list));
    PetscCall(SubModelCreate(comm, list, constants, "specific_heat", "constant", "Specific heat model", &m));
    specific_heat.reset(static_cast<SpecificHeatModel *>(m));
    MaterialConstants flow_constants = constants;
    flow_constants.shear_modulus     = shear->ReferenceShearModulus();
    PetscCall(FlowStressList(&list));
    PetscCall(SubModelCreate(comm, list, flow_constants, "flow_stress", "johnson_cook", "Flow stress model", &m));
    flow.reset(static_cast<FlowStress *>(m));
    PetscCall(DamageList(&list));
    PetscCall(SubModelCreate(comm, list, constants, "damage", "none", "Damage model", &m));
    damage.reset(static_cast<DamageModel *>(m));
    {
      char             *names[8];
      PetscInt          n = 8;
      PetscBool         set;
      const std::string prefix = name_ + "_stability_";
      PetscCall(StabilityList(&list));
      PetscOptionsBegin(comm, prefix.c_str(), "Stability checks", "Material");
      PetscCall(PetscOptionsStringArray("-types", "Stability checks, any of the registered names (drucker, acoustic, becker), or none", "", names, &n, &set));
      PetscOptionsEnd();
      if (!set) {
        names[0] = nullptr;
        PetscCall(PetscStrallocpy("none", &names[0]));
        n = 1;
      }
      for (PetscInt i = 0; i < n; ++i) {
        PetscCall(SubModelCreate(comm, list, constants, "stability", names[i], "Stability check", &m, PETSC_TRUE));
        stability.emplace_back(static_cast<StabilityCheck *>(m));
        PetscCall(PetscFree(names[i]));
      }
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  // The regularisation state first, and only when this material regularises (runs without it keep
  // their fields and bytes); then the plastic state, shared by every elastic_plastic material.
  std::vector<StateField> StateFields() const override
  {
    std::vector<StateField> fields;
    if (regularization != Regularization::None) {
      fields.push_back({kNonlocalSource, 1 + kNonlocalComponents, false});
      fields.push_back({kNonlocalAverage, kNonlocalComponents, false});
      for (const char *name : {kNonlocalStrain, kSofteningDisp, kSofteningLimit, kSoftening}) fields.push_back({name, 1, false});
      fields.push_back({kSofteningBits, 1, true});
    }
    for (const char *name : {kPlasticStrain, kPlasticStrainRate, kPorosity, kDamage, kPlasticDilatation, kFlowStress, kFailureTime, kFailureEnergy, kPlasticWork, kPlasticHeat, kElasticEnergy}) fields.push_back({name, 1, false});
    fields.push_back({kRotation, 9, false});
    fields.push_back({kFlowHistory, kMaxHistory, false});
    fields.push_back({kFailed, 1, true});
    fields.push_back({kUnstable, 1, true});
    return fields;
  }

  PetscErrorCode InitializeState(const MaterialPointFields &mp, PetscInt begin, PetscInt end) override
  {
    const PetscInt      *material = mp.material;
    const PetscInt64    *pid      = mp.id;
    PlasticState         state;
    RegularizationFields reg;
    PetscFunctionBeginUser;
    PetscCall(state.Get(*mp.state));
    PetscCall(reg.Get(mp, BandOnCell()));
    auto [eps, rate, f, D, R, history, sigma_f, t_fail, dilatation, released, work, heat, elastic, failed, unstable] = state;
    const PetscInt id                                                                                                = id_;
    for (PetscInt p = begin; p < end; ++p) {
      if (material[p] != id) continue;
      eps[p] = rate[p] = sigma_f[p] = dilatation[p] = released[p] = work[p] = heat[p] = elastic[p] = 0;
      t_fail[p]                                                                                    = -1;
      failed[p] = unstable[p] = 0;
      const PetscReal fp      = porosity_mean + porosity_deviation * (porosity_deviation > 0 ? Normal((std::uint64_t)seed, (std::uint64_t)pid[p], 0) : 0);
      const PetscReal Dp      = damage_mean + damage_deviation * (damage_deviation > 0 ? Normal((std::uint64_t)seed, (std::uint64_t)pid[p], 1) : 0);
      f[p]                    = fp > 0 ? fp : 0;
      D[p]                    = Dp > 0 ? Dp : 0;
      for (int a = 0; a < 9; ++a) R[9 * p + a] = (a % 4 == 0) ? 1 : 0;
      for (int h = 0; h < kMaxHistory; ++h) history[kMaxHistory * p + h] = h < flow->NumHistory() ? flow->InitialHistory(h) : 0;
      if (reg.source) {
        for (int a = 0; a <= kNonlocalComponents; ++a) reg.source[(1 + kNonlocalComponents) * p + a] = 0;
        for (int a = 0; a < kNonlocalComponents; ++a) reg.average[kNonlocalComponents * p + a] = 0;
        reg.disp[p] = reg.limit[p] = reg.omega[p] = 0;
        reg.strain[p]                             = D[p];
        reg.bits[p]                               = 0;
      }
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  // Algorithm 1 over this material's particles, a chunk of kChunk points at a time; each numbered
  // step (the header's list) is one kernel over the chunk.
  PetscErrorCode UpdateStress(const MaterialPointFields &mp, PetscInt id, PetscReal dt) override
  {
    PlasticState         state;
    RegularizationFields reg;
    Chunk                c;
    ChunkScratch         scratch;
    PetscFunctionBeginUser;
    if (dt <= 0) PetscFunctionReturn(ComputeWaveSpeed(mp, id)); // initial call: stress stays as seeded
    PetscCall(state.Get(*mp.state));
    PetscCheck(!BandOnCell() || mp.cell_size > 0, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "Option -%s_crack_band_length cell needs a background grid, which this driver has not; valid here: particle", name_.c_str());
    PetscCall(reg.Get(mp, BandOnCell()));
    // nonlocal: averaged drivers when the average runs (a scene); the point driver has no
    // neighbours, so there the local increments are their own average
    const bool nonlocal = regularization == Regularization::Nonlocal && nonlocal_active_;
    if (nonlocal) TakeNonlocalAverages(mp, id, state, reg);
    c.dt             = dt;
    c.density0       = density_;
    c.taylor_quinney = taylor_quinney;
    c.adiabatic      = adiabatic ? 1 : 0;
    PetscInt p       = 0;
    while (p < mp.n) {
      // gather the next chunk of this material's particles
      c.n = 0;
      for (; p < mp.n && c.n < kChunk; ++p)
        if (mp.material[p] == id) c.index[c.n++] = p;
      if (!c.n) break;
      Kinematics(mp, state, reg, c, scratch); // 1.
      eos->Evaluate(c);                       // 2. EOS, melt, shear modulus, specific heat
      melt->Evaluate(c);
      shear->Evaluate(c);
      specific_heat->Evaluate(c);
      TrialDeviator(c);                                          // 3.
      PetscCall(Return(mp, state, c, scratch));                  // 4.
      EvolveInternalVariables(state, reg, nonlocal, c, scratch); // 5.
      Failure(mp, state, reg, nonlocal, c, scratch);             // 6. (with the crack band's softening)
      StressAndEnergy(mp, state, reg, c, scratch);               // 7.
      WriteState(mp, state, c, scratch);
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  // The averages of the previous step's increments (src/mpm/nonlocal.cxx) join the drivers.
  void TakeNonlocalAverages(const MaterialPointFields &mp, PetscInt id, const PlasticState &state, const RegularizationFields &reg) const
  {
    for (PetscInt q = 0; q < mp.n; ++q) {
      if (mp.material[q] != id) continue;
      PetscReal *avg = reg.average + kNonlocalComponents * q;
      reg.strain[q] += avg[0];
      state.f[q] = PetscMin(PetscMax(state.f[q] + avg[1], 0.0), 1.0);
      avg[0] = avg[1] = 0;
    }
  }

  // 1. Kinematics in the co-rotated frame (scalar code: see RotateToFrame) and the state at t_n.
  void Kinematics(const MaterialPointFields &mp, const PlasticState &state, const RegularizationFields &reg, Chunk &c, ChunkScratch &scratch) const
  {
    const bool crack_band  = regularization == Regularization::CrackBand;
    const int  num_history = flow->NumHistory(); // the history entries the flow model uses (the others are never read)
    for (int k = 0; k < c.n; ++k) {
      const PetscInt   q = c.index[k];
      const PetscReal *L = mp.L + 9 * q, *R_old = state.R + 9 * q;
      PetscReal       *R_new = scratch.R_next[k];
      if (!PolarRotationWarm(mp.F + 9 * q, R_old, R_new)) { // warm start: R moves little per step
        Mat3Map R_fallback(R_new);
        R_fallback = PolarRotation(Mat3CMap(mp.F + 9 * q));
      }
      // D_hat = (R_old^T D R_old + R_new^T D R_new)/2, D = sym L
      const PetscReal D_lab[9] = {L[0], 0.5 * (L[1] + L[3]), 0.5 * (L[2] + L[6]), 0.5 * (L[3] + L[1]), L[4], 0.5 * (L[5] + L[7]), 0.5 * (L[6] + L[2]), 0.5 * (L[7] + L[5]), L[8]};
      PetscReal      *Dh       = c.D_hat[k];
      {
        const SymmetricTensor d_old = RotatedToFrame(R_old, D_lab), d_new = RotatedToFrame(R_new, D_lab);
        StoreSymmetric({0.5 * (d_old.xx + d_new.xx), 0.5 * (d_old.xy + d_new.xy), 0.5 * (d_old.xz + d_new.xz), 0.5 * (d_old.yy + d_new.yy), 0.5 * (d_old.yz + d_new.yz), 0.5 * (d_old.zz + d_new.zz)}, Dh);
      }
      // crack band: the stored stress is (1 - omega) times the intact stress; recover the latter
      scratch.omega_old[k] = crack_band && !state.failed[q] && reg.limit[q] > 0 ? reg.omega[q] : 0;
      PetscReal *sh        = c.deviator[k]; // s_n for now
      RotateToFrame(R_old, mp.stress + 9 * q, sh);
      if (scratch.omega_old[k] != 0) // (nine divisions by 1 spared elsewhere)
        for (int a = 0; a < 9; ++a) sh[a] /= 1 - scratch.omega_old[k];
      const PetscReal mean = (sh[0] + sh[4] + sh[8]) / 3, trD = Dh[0] + Dh[4] + Dh[8];
      sh[0] -= mean;
      sh[4] -= mean;
      sh[8] -= mean;
      const PetscReal Ddev0 = Dh[0] - trD / 3, Ddev1 = Dh[4] - trD / 3, Ddev2 = Dh[8] - trD / 3;
      const PetscReal Ddev_squared = Ddev0 * Ddev0 + Ddev1 * Ddev1 + Ddev2 * Ddev2 + 2 * (Dh[1] * Dh[1] + Dh[2] * Dh[2] + Dh[5] * Dh[5]);
      // the EOS sees the elastic density: the plastic dilatation of the voids (GTN) is not
      // elastic compression, rho_e = rho exp(tr eps_p)
      c.density[k]             = mp.mass[q] / mp.volume[q] * (state.dilatation[q] != 0 ? std::exp(state.dilatation[q]) : 1);
      c.temperature[k]         = mp.temperature[q];
      c.specific_energy[k]     = mp.internal_energy[q] / mp.mass[q];
      c.trace_D[k]             = trD;
      c.total_rate[k]          = std::sqrt(2.0 / 3.0 * Ddev_squared);
      c.mean_stress_old[k]     = mean;
      c.plastic_strain[k]      = state.eps[q];
      c.plastic_strain_rate[k] = state.rate[q];
      c.porosity[k]            = state.f[q];
      c.damage[k]              = state.D[q];
      for (int h = 0; h < num_history; ++h) c.history[k][h] = state.history[kMaxHistory * q + h];
      c.unstable[k] = 0;
    }
  }

  // 3. Trial deviator s_tr = s_n + 2 mu dt dev(D_hat); melted points carry no deviator.
  static void TrialDeviator(Chunk &c)
  {
    for (int k = 0; k < c.n; ++k) { // (plain arrays: the Eigen temporaries were not inlined)
      PetscReal *s = c.deviator[k];
      if (c.temperature[k] >= c.melt_temperature[k]) {
        for (int a = 0; a < 9; ++a) s[a] = 0;
        continue;
      }
      const PetscReal *Dh = c.D_hat[k], third = c.trace_D[k] / 3, factor = 2 * c.shear_modulus[k] * c.dt;
      for (int a = 0; a < 9; ++a) s[a] += factor * (a % 4 ? Dh[a] : Dh[a] - third); // 2 mu dt dev(D_hat)
    }
  }

  // 4. Yield test and return mapping (flow model inlined). A failed point with a response keeps at
  // most its pressure: it takes no trial deviator and its voids no longer grow, so it goes through
  // the return as a dense elastic point (a swollen fragment at porosity 1 in tension would otherwise
  // ask GTN for a return that does not exist); its porosity is restored after.
  PetscErrorCode Return(const MaterialPointFields &mp, const PlasticState &state, Chunk &c, ChunkScratch &scratch) const
  {
    PetscFunctionBeginUser;
    if (failure_response != FailureResponse::None)
      for (int k = 0; k < c.n; ++k)
        if (state.failed[c.index[k]]) {
          Mat3Map(c.deviator[k]).setZero();
          scratch.failed_porosity[k] = c.porosity[k];
          c.porosity[k]              = 0;
        }
    c.failed_point            = -1;
    const PetscErrorCode ierr = flow->Return(c, settings);
    if (ierr && c.failed_point >= 0) {
      const int k = c.failed_point;
      PetscCall(PetscPrintf(PETSC_COMM_SELF,
                            "Material %s, t = %g s, particle index %" PetscInt_FMT
                            ": return mapping failed at plastic strain %.17g, porosity %.17g, trial pressure %.17g Pa, trial q %.17g Pa (rate %g 1/s), T %.17g K, mu %.17g Pa, K %.17g Pa, density %.17g, dt %.17g s\n",
                            Name(), (double)mp.time, c.index[k], (double)c.plastic_strain[k], (double)c.porosity[k], (double)c.pressure[k], (double)std::sqrt(1.5 * Mat3Map(c.deviator[k]).squaredNorm()), (double)c.total_rate[k],
                            (double)c.temperature[k], (double)c.shear_modulus[k], (double)c.bulk_modulus[k], (double)c.density[k], (double)c.dt));
    }
    PetscCheck(!ierr, PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED, "Material %s: the return mapping did not converge (increase -%s_return_tolerance or reduce -mpm_cfl)", Name(), Name());
    if (failure_response != FailureResponse::None)
      for (int k = 0; k < c.n; ++k)
        if (state.failed[c.index[k]]) c.porosity[k] = scratch.failed_porosity[k];
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  // 5. Porosity (eqs. 15-17), temperature (eq. 18 and the isentropic term), triaxiality; then
  // damage (eqs. 20-21) and the stability checks (eqs. 23-24).
  void EvolveInternalVariables(const PlasticState &state, const RegularizationFields &reg, bool nonlocal, Chunk &c, ChunkScratch &scratch) const
  {
    const bool      crack_band           = regularization == Regularization::CrackBand;
    const PetscReal nucleation_amplitude = nucleation_fraction / (nucleation_deviation * std::sqrt(2 * PETSC_PI));
    for (int k = 0; k < c.n; ++k) scratch.porosity_old[k] = c.porosity[k];
    for (int k = 0; k < c.n; ++k) {
      const PetscReal de = c.delta_plastic_strain[k];
      PetscReal       df = 0;
      if (porosity_growth) df += (1 - c.porosity[k]) * c.trace_plastic_strain[k];
      if (porosity_nucleation && de > 0 && !(nucleation_tension_only && c.pressure[k] >= 0)) {
        const PetscReal z = (c.plastic_strain[k] - nucleation_strain) / nucleation_deviation;
        df += nucleation_amplitude * std::exp(-0.5 * z * z) * de;
      }
      // crack band: once softening, omega carries the damage and the voids stop growing (else
      // the local void softening would go on inside the band, with no length)
      if (crack_band && reg.limit[c.index[k]] > 0) df = 0;
      scratch.porosity_increment[k] = df;
      if (!nonlocal) c.porosity[k] = PetscMin(PetscMax(c.porosity[k] + df, 0.0), 1.0); // nonlocal: the average adds it
      // eq. 18 plastic heating plus the isentropic term of the Mie-Gruneisen EOS
      // the plastic work per unit volume is sigma : d eps_p = (1 - f) sigma_f d eps_M for GTN
      const PetscReal matrix  = settings.yield == YieldType::GTN ? 1 - scratch.porosity_old[k] : 1;
      scratch.plastic_work[k] = matrix * c.flow_stress[k] * de / c.density[k]; // J/kg; times mass below
      // A point that failed with zero_stress carries no stress, so it does no work: neither plastic
      // heating nor the isentropic cooling -Gamma T tr(D) dt, which would take a failed fragment
      // that swells freely from 600 K to a few kelvin; its temperature stays as it failed, with or
      // without a gas around it (the coupling takes its mass and temperature, never its volume).
      // The same holds for no_tension while it carries no pressure (p <= 0, the test of the
      // response below) and for every response's deviator; a failed point still heats when it is
      // compressed under pressure. An opened no_tension point that closes (tr D < 0, p <= 0) does no
      // work either: with Gamma = Gamma0 rho0/rho (Mie-Gruneisen; 20 at J = 12) the term would
      // multiply T by exp(Gamma0 dJ) per closing while expansions leave it, a ratchet that took a
      // failed HY-100 particle from 1e4 K to 1e8 K and its gas cells to 1e9 K (the step to 3e-10 s).
      const bool holds_pressure = failure_response == FailureResponse::NoShear || (failure_response == FailureResponse::NoTension && c.pressure[k] > 0);
      const bool inert          = failure_response != FailureResponse::None && state.failed[c.index[k]] && !holds_pressure;
      if (adiabatic && !inert) c.temperature[k] += taylor_quinney * matrix * c.flow_stress[k] * de / (c.density[k] * c.specific_heat[k]) - c.gruneisen[k] * c.temperature[k] * c.trace_D[k] * c.dt;
      c.triaxiality[k] = c.equivalent_stress[k] > 0 ? -c.pressure[k] / c.equivalent_stress[k] : (c.pressure[k] < 0 ? PETSC_INFINITY : (c.pressure[k] > 0 ? PETSC_NINFINITY : 0));
    }
    damage->Evaluate(c);
    for (auto &check : stability) check->Evaluate(c);
  }

  // 6. Failure: the criteria asked for, then (crack band) the softening they start, and the tag
  // with its time once a point fails.
  void Failure(const MaterialPointFields &mp, const PlasticState &state, const RegularizationFields &reg, bool nonlocal, const Chunk &c, ChunkScratch &scratch) const
  {
    const bool crack_band = regularization == Regularization::CrackBand;
    for (int k = 0; k < c.n; ++k) {
      const PetscInt q    = c.index[k];
      int            bits = 0;
      if (c.temperature[k] >= c.melt_temperature[k]) bits |= FailMelt;
      if (failure_criteria & FailTepla) { // (only the criteria asked for are evaluated: two divisions per point)
        const PetscReal ratio_f = c.porosity[k] / tepla_critical_porosity;
        PetscReal       ratio_e = std::isfinite(c.fracture_strain[k]) && c.fracture_strain[k] > 0 ? c.plastic_strain[k] / c.fracture_strain[k] : 0;
        if (regularization == Regularization::Nonlocal) ratio_e = nonlocal ? reg.strain[q] : c.damage[k]; // eq. 22 with the nonlocal damage D_bar (no average yet: D)
        else if (tepla_damage) ratio_e = c.damage[k];                                                     // eq. 22 with the accumulated damage D
        if (ratio_f * ratio_f + ratio_e * ratio_e >= 1) bits |= FailTepla;
      }
      if (c.porosity[k] >= tepla_critical_porosity) bits |= FailPorosity;
      if (c.unstable[k]) bits |= FailStability;
      if (c.flow_stress[k] <= 0) bits |= FailStrength;
      bits &= failure_criteria;
      PetscReal omega = 0; // crack band: softening at t_{n+1}
      if (crack_band && !state.failed[q]) {
        if (bits && reg.limit[q] == 0) { // the criterion starts the softening: u_f = 2 G_f / sigma_i
          const PetscReal sigma_i = (settings.yield == YieldType::GTN ? 1 - c.porosity[k] : 1) * c.flow_stress[k];
          reg.limit[q]            = 2 * fracture_energy / PetscMax(sigma_i, 1.0);
          reg.bits[q]             = bits;
        }
        if (reg.limit[q] > 0) {
          reg.disp[q] += reg.Size(q) * c.delta_plastic_strain[k]; // h_p Delta eps_p
          omega = PetscMin(reg.disp[q] / reg.limit[q], 1.0);
        }
        bits = omega >= 1 ? (int)reg.bits[q] : 0; // fails once the softening is complete
      }
      scratch.omega[k]        = omega;
      scratch.newly_failed[k] = false;
      if (bits && !state.failed[q]) {
        state.failed[q]         = bits;
        state.t_fail[q]         = mp.time;
        scratch.newly_failed[k] = true;
      }
    }
  }

  // 7. The failure response (what a failed point cannot carry is dropped, its stored elastic energy
  // counted as released), the crack band's softened stress, sigma_{n+1} = R_{n+1} (s - p I)
  // R_{n+1}^T, the stress work, and the energies: stored elastic, the band's dissipation.
  void StressAndEnergy(const MaterialPointFields &mp, const PlasticState &state, const RegularizationFields &reg, const Chunk &c, ChunkScratch &scratch) const
  {
    const bool crack_band = regularization == Regularization::CrackBand;
    for (int k = 0; k < c.n; ++k) {
      const PetscInt q            = c.index[k];
      const bool     newly_failed = scratch.newly_failed[k];
      PetscReal      s_hat[9]; // s - p I
      for (int a = 0; a < 9; ++a) s_hat[a] = a % 4 ? c.deviator[k][a] : c.deviator[k][a] - c.pressure[k];
      if (state.failed[q] && failure_response != FailureResponse::None) {
        // the response: drop what the failed point cannot carry; count the elastic energy that goes
        // (q^2/(6 mu) + p^2/(2 K) per unit volume for the dropped parts)
        const PetscReal q_eq = c.equivalent_stress[k], p = c.pressure[k], mu = c.shear_modulus[k], K = c.bulk_modulus[k];
        PetscReal       dropped       = mu > 0 ? q_eq * q_eq / (6 * mu) : 0;
        const bool      keep_pressure = failure_response == FailureResponse::NoShear || (failure_response == FailureResponse::NoTension && p > 0);
        if (!keep_pressure) dropped += K > 0 ? p * p / (2 * K) : 0;
        if (newly_failed && !crack_band) state.released[q] += dropped * mp.volume[q];   // afterwards nothing is stored to release (crack band: counted below)
        for (int a = 0; a < 9; ++a) s_hat[a] = a % 4 || !keep_pressure ? 0.0 : 0.0 - p; // (as zeroing, then subtracting p)
      }
      // crack band: from the criterion to the end of the softening (its last step included) the
      // work is the band's dissipation
      const bool softening = crack_band && reg.limit[q] > 0 && (!state.failed[q] || newly_failed);
      if (crack_band && !state.failed[q]) {
        for (int a = 0; a < 9; ++a) s_hat[a] *= 1 - scratch.omega[k]; // the softened stress; the particle state stays the intact one
        reg.omega[q] = scratch.omega[k];
      }
      const PetscReal elastic_old = state.elastic[q];
      {
        const PetscReal p = -Mat3CMap(s_hat).trace() / 3, mu = c.shear_modulus[k], K = c.bulk_modulus[k];
        PetscReal       dev[9];
        for (int a = 0; a < 9; ++a) dev[a] = a % 4 ? s_hat[a] : s_hat[a] + p;
        state.elastic[q] = ((K > 0 ? p * p / (2 * K) : 0) + (mu > 0 ? 0.25 * Mat3CMap(dev).squaredNorm() / mu : 0)) * mp.volume[q]; // s:s/(4 mu) = q^2/(6 mu)
      }
      PetscReal *sigma = mp.stress + 9 * q, sigma_old[9];
      for (int a = 0; a < 9; ++a) sigma_old[a] = sigma[a];
      RotateFromFrame(scratch.R_next[k], s_hat, sigma);
      for (int a = 0; a < 9; ++a) state.R[9 * q + a] = scratch.R_next[k][a];
      const PetscReal stress_work = StressWork(sigma_old, sigma, mp.L + 9 * q, mp.volume[q], c.dt);
      mp.internal_energy[q] += stress_work;
      if (softening) { // crack band: what the softening band dissipates, stress work less stored elastic energy
        state.released[q] += stress_work - (state.elastic[q] - elastic_old);
        scratch.plastic_work[k] = 0;
      }
      if (reg.source && regularization == Regularization::Nonlocal) { // the drivers for the average
        PetscReal *src = reg.source + (1 + kNonlocalComponents) * q;
        src[0]         = state.failed[q] && failure_response != FailureResponse::None ? 0 : mp.mass[q];
        src[1]         = c.damage[k] - state.D[q]; // Delta D of this step (D[q] is still D_n)
        src[2]         = scratch.porosity_increment[k];
      }
    }
  }

  // The chunk's state at t_{n+1} back to the particles, with the wave speed sqrt((K + 4 mu/3)/rho)
  // and the plastic work and heat. A failed point with a response carries no shear (sqrt(K/rho)),
  // and with no_tension or zero_stress no stress at all below its reference density: there rho is
  // taken no lower than the reference, the speed it has again once compressed. (With the intact
  // moduli over its current density, a failed steel point drawn out to 15 times its volume reported
  // 14.6 km/s and set the exploding cylinder's step, a third of the intact steel's, for the last
  // 40 % of the run.)
  void WriteState(const MaterialPointFields &mp, const PlasticState &state, const Chunk &c, const ChunkScratch &scratch) const
  {
    const int num_history = flow->NumHistory();
    for (int k = 0; k < c.n; ++k) {
      const PetscInt q  = c.index[k];
      mp.temperature[q] = c.temperature[k];
      if (state.failed[q] && failure_response != FailureResponse::None) mp.wave_speed[q] = std::sqrt(c.bulk_modulus[k] / (failure_response == FailureResponse::NoShear ? c.density[k] : PetscMax(c.density[k], density_)));
      else mp.wave_speed[q] = std::sqrt((c.bulk_modulus[k] + 4.0 / 3.0 * c.shear_modulus[k]) / c.density[k]);
      state.eps[q] = c.plastic_strain[k];
      state.work[q] += scratch.plastic_work[k] * mp.mass[q];
      if (adiabatic) state.heat[q] += taylor_quinney * scratch.plastic_work[k] * mp.mass[q];
      state.dilatation[q] += c.trace_plastic_strain[k];
      state.rate[q]     = c.plastic_strain_rate[k];
      state.f[q]        = c.porosity[k];
      state.D[q]        = c.damage[k];
      state.sigma_f[q]  = c.flow_stress[k];
      state.unstable[q] = c.unstable[k];
      for (int h = 0; h < num_history; ++h) state.history[kMaxHistory * q + h] = c.history[k][h];
    }
  }

  std::vector<OutputField> OutputFields() const override
  {
    std::vector<OutputField> out = {{kPlasticStrain, 1, false}, {kPlasticStrainRate, 1, false}, {kPorosity, 1, false},      {kDamage, 1, false},      {kFlowStress, 1, false},  {kFailed, 1, true},
                                    {kFailureTime, 1, false},   {kUnstable, 1, true},           {kFailureEnergy, 1, false}, {kPlasticWork, 1, false}, {kPlasticHeat, 1, false}, {kElasticEnergy, 1, false}};
    if (regularization == Regularization::Nonlocal) out.push_back({kNonlocalStrain, 1, false});
    if (regularization == Regularization::CrackBand) {
      out.push_back({kSoftening, 1, false});
      out.push_back({kSofteningBits, 1, true}); // (also where src/mpm/fragments.cxx sees a criterion met)
    }
    return out;
  }

  // Wave speed from the reference moduli (before the first step).
  PetscErrorCode ComputeWaveSpeed(const MaterialPointFields &f, PetscInt id) override
  {
    for (PetscInt p = 0; p < f.n; ++p)
      if (f.material[p] == id) f.wave_speed[p] = std::sqrt((constants.bulk_modulus + 4.0 / 3.0 * constants.shear_modulus) * f.volume[p] / f.mass[p]);
    return PETSC_SUCCESS;
  }

  PetscErrorCode View(PetscViewer viewer) const override
  {
    PetscFunctionBeginUser;
    PetscCall(PetscViewerASCIIPrintf(viewer, "Material %s: elastic_plastic (hypoelastic-plastic, Green-Naghdi frame)\n  density %g kg/m^3, shear modulus %g Pa, bulk modulus %g Pa, room temperature %g K\n", Name(), (double)density_,
                                     (double)constants.shear_modulus, (double)constants.bulk_modulus, (double)constants.room_temperature));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  yield: %s; Taylor-Quinney %g, %s\n", settings.yield == YieldType::VonMises ? "von_mises" : "gtn", (double)taylor_quinney, adiabatic ? "adiabatic" : "isothermal"));
    PetscCall(eos->View(viewer));
    PetscCall(melt->View(viewer));
    PetscCall(shear->View(viewer));
    PetscCall(specific_heat->View(viewer));
    PetscCall(flow->View(viewer));
    PetscCall(damage->View(viewer));
    for (auto &s : stability) PetscCall(s->View(viewer));
    if (regularization == Regularization::Nonlocal) PetscCall(PetscViewerASCIIPrintf(viewer, "  regularization: nonlocal, length %g m (Delta D and Delta f averaged; TEPLA-F with the nonlocal damage)\n", (double)regularization_length));
    if (regularization == Regularization::CrackBand)
      PetscCall(PetscViewerASCIIPrintf(viewer, "  regularization: crack_band, fracture energy %g J/m^2 (linear softening over u_f = 2 G_f / sigma_i after a criterion), band length: the %s size\n", (double)fracture_energy,
                                       band_on_cell ? "cell" : "particle"));
    if (tepla_damage) PetscCall(PetscViewerASCIIPrintf(viewer, "  TEPLA-F with the accumulated damage D\n"));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  porosity: growth %s, nucleation %s (f_n %g, eps_n %g, s_n %g); initial porosity %g +- %g, damage %g +- %g, seed %" PetscInt_FMT "\n", porosity_growth ? "on" : "off", porosity_nucleation ? "on" : "off",
                                     (double)nucleation_fraction, (double)nucleation_strain, (double)nucleation_deviation, (double)porosity_mean, (double)porosity_deviation, (double)damage_mean, (double)damage_deviation, seed));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
};

PetscErrorCode ElasticPlasticCreate(Material **m)
{
  *m = new ElasticPlastic();
  return PETSC_SUCCESS;
}

} // namespace burst
