// Options that nothing reads are an error (issue 11).
//
// PETSc marks an option "used" when something queries it, so after set-up PetscOptionsLeftGet lists
// what was given but never read. For the "did you mean" we need the names that *could* have been
// read: every PetscOptionsBegin/End block prints each option it queries through PetscHelpPrintf
// when -help is in the database, so during set-up burst puts -help there and points PetscHelpPrintf
// at a recorder that keeps the option name of each help line and prints nothing. The components
// therefore need no list of their own; an option read outside Begin/End still counts as used but is
// not offered as a suggestion.
//
// PETSc reads a few of its own options only at the end of the run (PetscFinalize: -log_view,
// -options_view, ...) or when an object is used (KSPSolve: -ksp_view, -ksp_converged_reason);
// those are listed below by name and not reported.
#include "options_check.hpp"
#include "util.hpp"
#include "simulation.hpp"
#include "ice/ice.hpp"
#include <algorithm>
#include <cctype>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <set>
#include <string>
#include <vector>

namespace burst {

namespace {
std::set<std::string> known; // option names (without the dash) seen in help lines
bool                  recording                                  = false;
bool                  inserted_help                              = false;
PetscErrorCode (*saved_help_printf)(MPI_Comm, const char[], ...) = nullptr;

// Keeps the option name of a help line, "  -mpm_shape_type <now linear ...>: ...".
void Record(const char *line)
{
  const char *p = line;
  while (*p == ' ' || *p == '\t') ++p;
  if (p[0] != '-' || !std::isalpha((unsigned char)p[1])) return;
  const char *q = p + 1;
  while (std::isalnum((unsigned char)*q) || *q == '_') ++q;
  known.insert(std::string(p + 1, q));
}

PetscErrorCode RecordHelpLine(MPI_Comm, const char format[], ...)
{
  char    line[1024];
  va_list args;
  va_start(args, format);
  std::vsnprintf(line, sizeof(line), format, args);
  va_end(args);
  Record(line);
  return PETSC_SUCCESS;
}

// Choice lists (PetscOptionsFList, PetscOptionsEnum) print their help line with PetscFPrintf to
// stdout in pieces, "  -name <now a : formerly a>: text (one of)", " a", " b", " (Manual)\n": those
// are recorded and swallowed up to the newline; everything else is printed as usual.
PetscErrorCode (*saved_vfprintf)(FILE *, const char[], va_list) = nullptr;
bool in_help_line                                               = false;

PetscErrorCode RecordOrPrint(FILE *fd, const char format[], va_list args)
{
  char    text[1024];
  va_list copy;
  va_copy(copy, args);
  std::vsnprintf(text, sizeof(text), format, copy);
  va_end(copy);
  const size_t n = std::strlen(text);
  if (!in_help_line && std::strstr(text, " <now ") && text[0] == ' ') {
    Record(text);
    in_help_line = true;
  }
  if (in_help_line) {
    if (n && text[n - 1] == '\n') in_help_line = false;
    return PETSC_SUCCESS;
  }
  return saved_vfprintf(fd, format, args);
}

// PETSc's options read after set-up: in PetscFinalize (pinit.c, 3.18), and the *ViewFromOptions
// of objects in use (read at every KSPSolve, MatAssemblyEnd, VecAssemblyEnd, DMSetUp/DMView).
const char *const finalize_options[] =
  {"options_view", "options_left", "objects_dump", "mpidump",         "malloc_dump", "malloc_view", "malloc_view_threshold",    "memory_view",         "citations", "log_view", "log_view_memory", "log_view_gpu_time",
   "log_all",      "log",          "log_mpe",      "get_total_flops", "x_virtual",   "saw_options", "mpi_linear_solver_server", "options_allow_unused"};
// Object prefixes burst gives PETSc objects, and the viewer options read when those objects are used.
// clang-format off (a table laid out by hand)
const char *const object_prefixes[] = {"", "ice_pressure_", "swarm_"};
const char *const object_views[]    = {"ksp_view",
                                       "ksp_converged_reason",
                                       "ksp_view_pre",
                                       "ksp_view_mat",
                                       "ksp_view_pmat",
                                       "ksp_view_rhs",
                                       "ksp_view_solution",
                                       "ksp_view_eigenvalues",
                                       "ksp_view_singularvalues",
                                       "ksp_view_final_residual",
                                       "ksp_converged_rate",
                                       "ksp_view_mat_explicit",
                                       "ksp_view_preconditioned_operator_explicit",
                                       "ksp_view_diagonal_scale",
                                       "ksp_compute_eigenvalues",
                                       "ksp_compute_singularvalues",
                                       "pc_view",
                                       "mat_view",
                                       "vec_view",
                                       "dm_view",
                                       "da_view",
                                       "is_view"};
// clang-format on

bool ReadLater(const std::string &name)
{
  for (const char *f : finalize_options)
    if (name == f) return true;
  for (const char *prefix : object_prefixes) {
    const size_t n = std::strlen(prefix);
    if (name.compare(0, n, prefix) != 0) continue;
    for (const char *v : object_views)
      if (name.compare(n, std::string::npos, v) == 0) return true;
  }
  return false;
}

// Optimal-string-alignment distance: Levenshtein plus transposition of neighbours (typos).
size_t EditDistance(const std::string &a, const std::string &b)
{
  const size_t                     n = a.size(), m = b.size();
  std::vector<std::vector<size_t>> d(n + 1, std::vector<size_t>(m + 1));
  for (size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (size_t i = 1; i <= n; ++i)
    for (size_t j = 1; j <= m; ++j) {
      const size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j]           = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[n][m];
}

// Up to three nearest known names within a distance that grows with the length.
std::string Suggestions(const std::string &name, const std::set<std::string> &candidates)
{
  const size_t                                limit = std::max<size_t>(2, name.size() / 4);
  std::vector<std::pair<size_t, std::string>> near;
  for (const std::string &c : candidates) {
    if (c == name) continue;
    const size_t d = EditDistance(name, c);
    if (d <= limit) near.push_back({d, c});
  }
  std::sort(near.begin(), near.end());
  while (!near.empty() && near.back().first > near.front().first) near.pop_back(); // the nearest only
  std::string out;
  for (size_t i = 0; i < near.size() && i < 3; ++i) out += std::string(i ? (i + 1 == std::min<size_t>(near.size(), 3) ? " or -" : ", -") : "-") + near[i].second;
  return out;
}
} // namespace

namespace {
// Option values as given: name -> value (PetscOptionsGetAll's "-name value -name ..." text).
std::vector<std::pair<std::string, std::string>> GivenOptions()
{
  std::vector<std::pair<std::string, std::string>> out;
  char                                            *all = nullptr;
  if (PetscOptionsGetAll(nullptr, &all)) return out;
  const std::string s(all);
  PetscFree(all);
  size_t pos = 0;
  while (pos < s.size()) {
    const size_t start = s.find_first_not_of(' ', pos);
    if (start == std::string::npos) break;
    const size_t      end   = std::min(s.find(' ', start), s.size());
    const std::string token = s.substr(start, end - start);
    if (token.size() > 1 && token[0] == '-' && std::isalpha((unsigned char)token[1])) out.push_back({token, ""});
    else if (!out.empty()) out.back().second += (out.back().second.empty() ? "" : " ") + token;
    pos = end;
  }
  return out;
}

// PETSc's own parse errors ("Input string abc has no numeric value") do not say which option held the
// string: this handler finds the options whose value contains it and adds their names to the message.
PetscErrorCode NameTheOption(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  char bad[256];
  if (p == PETSC_ERROR_INITIAL && mess && std::sscanf(mess, "Input string %255s has no", bad) == 1) {
    std::string names;
    for (const auto &o : GivenOptions()) {
      std::string v = "," + o.second + ",";
      for (char &c : v)
        if (c == ' ') c = ',';
      if (v.find("," + std::string(bad) + ",") != std::string::npos) names += (names.empty() ? "" : ", ") + o.first;
    }
    if (!names.empty()) {
      char text[1024];
      std::snprintf(text, sizeof(text), "Option %s: the value '%s' is not a valid number (%s)", names.c_str(), bad, mess);
      return PetscTraceBackErrorHandler(comm, line, fun, file, n, p, text, ctx);
    }
  }
  return PetscTraceBackErrorHandler(comm, line, fun, file, n, p, mess, ctx);
}
} // namespace

PetscErrorCode OptionsCheckBegin(MPI_Comm comm)
{
  PetscBool help;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasHelp(nullptr, &help));
  if (!help) PetscCall(PetscPushErrorHandler(NameTheOption, nullptr)); // popped by OptionsCheckEnd
  // No burst option takes NaN or infinity; PETSc would parse them as numbers and set-up would carry them on.
  for (const auto &o : GivenOptions()) {
    std::string v = o.second;
    for (char &c : v) c = (char)std::tolower((unsigned char)c);
    for (char &c : v)
      if (c == ',') c = ' ';
    std::string part;
    for (size_t i = 0; i <= v.size(); ++i) {
      if (i == v.size() || v[i] == ' ') {
        const std::string t = part.size() && (part[0] == '-' || part[0] == '+') ? part.substr(1) : part;
        PetscCheck(t != "nan" && t != "inf" && t != "infinity", comm, PETSC_ERR_USER_INPUT, "Option %s = %s: burst takes no NaN or infinite values", o.first.c_str(), o.second.c_str());
        part.clear();
      } else part += v[i];
    }
  }
  if (help) PetscFunctionReturn(PETSC_SUCCESS);
  known.clear();
  saved_help_printf = PetscHelpPrintf;
  PetscHelpPrintf   = RecordHelpLine;
  saved_vfprintf    = PetscVFPrintf;
  PetscVFPrintf     = RecordOrPrint;
  PetscCall(PetscOptionsSetValue(nullptr, "-help", nullptr));
  inserted_help = true;
  recording     = true;
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::vector<OptionsFeature> RunFeatures(const Simulation &sim, bool point_mode)
{
  const bool gas = sim.ice != nullptr, coupled = sim.coupling != nullptr;
  const bool heat = sim.mpm.heat != nullptr, ksp = gas && sim.ice->ksp;
  return {
    {"point_", "", "", "-mode point", point_mode},
    {"", "", "_thermal_conductivity", "-mpm_heat_conduction", heat},
    {"", "", "_heat_capacity", "-mpm_heat_conduction, or solids in gas (-materials with -ice_materials)", heat || coupled},
    {"ice_pressure_", "", "", "-ice_pressure_solver semi_implicit with gas (-ice_materials)", ksp},
    {"", "_solid", "", "solids in gas (-materials with -ice_materials)", coupled},
    {"coupling_", "", "", "solids in gas (-materials with -ice_materials)", coupled},
    {"", "_burn_", "", "solids in gas (-materials with -ice_materials)", coupled},
    {"ice_", "", "", "gas (-ice_materials)", gas},
    // read by the set-up in every run, but inert without their feature: said, so a user knows
    {"taylor_", "", "", "-taylor", sim.taylor != nullptr, true},
    {"analytic", "", "", "solids (-materials)", !sim.mpm.materials.empty(), true},
    {"mpm_", "", "", "solids (-materials)", !sim.mpm.materials.empty(), true},
  };
}

// Whether option `name` (without the dash) belongs to feature f.
static bool Matches(const OptionsFeature &f, const std::string &name)
{
  return name.compare(0, f.prefix.size(), f.prefix) == 0 && name.find(f.contains) != std::string::npos && name.size() >= f.suffix.size() && name.compare(name.size() - f.suffix.size(), f.suffix.size(), f.suffix) == 0;
}

// The names (without the dash) of every option given: command line, option files, PETSC_OPTIONS.
static PetscErrorCode GivenOptionNames(std::vector<std::string> &names)
{
  char *all;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetAll(nullptr, &all));
  const std::string s(all);
  PetscCall(PetscFree(all));
  for (size_t pos = 0; pos < s.size();) { // "-name value -name ..."
    const size_t start = s.find_first_not_of(' ', pos);
    if (start == std::string::npos) break;
    const size_t end = std::min(s.find(' ', start), s.size());
    if (s[start] == '-' && end > start + 1 && std::isalpha((unsigned char)s[start + 1])) names.push_back(s.substr(start + 1, end - start - 1));
    pos = end;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode OptionsCheckEnd(MPI_Comm comm, const std::vector<OptionsFeature> &features)
{
  PetscBool allow = PETSC_FALSE;
  PetscInt  n;
  char    **names, **values;
  PetscFunctionBeginUser;
  if (!recording) PetscFunctionReturn(PETSC_SUCCESS);
  recording = false;
  PetscCall(PetscPopErrorHandler()); // options are parsed during set-up; -on_error_* apply again from here
  PetscHelpPrintf = saved_help_printf;
  PetscVFPrintf   = saved_vfprintf;
  if (inserted_help) PetscCall(PetscOptionsClearValue(nullptr, "-help"));
  inserted_help = false;
  PetscOptionsBegin(comm, "", "Unused options", "Options");
  PetscCall(PetscOptionsBool("-options_allow_unused", "Warn about options that nothing reads instead of stopping", "", allow, &allow, nullptr));
  PetscOptionsEnd();

  PetscCall(PetscOptionsLeftGet(nullptr, &n, &names, &values));
  std::vector<std::string> unused;
  for (PetscInt i = 0; i < n; ++i) {
    const std::string name = names[i];
    if (ReadLater(name)) continue;
    const OptionsFeature *off = nullptr;
    for (const OptionsFeature &f : features) {
      if (f.read_when_off) continue; // read in every run: what nothing read is a typo
      const bool match = Matches(f, name);
      if (match && !f.on) off = &f;
      if (match) break;
    }
    if (off) PetscCall(PetscPrintf(comm, "Note: option -%s is read only with %s, which is off in this run; ignored\n", name.c_str(), off->needs.c_str()));
    else unused.push_back(name);
  }
  // Options that were read but do nothing in this run (read_when_off features that are off)
  std::vector<std::string> given;
  PetscCall(GivenOptionNames(given));
  std::set<std::string> noted;
  for (const std::string &name : given)
    for (const OptionsFeature &f : features) {
      if (!f.read_when_off || f.on || noted.count(name) || std::find(unused.begin(), unused.end(), name) != unused.end() || !Matches(f, name)) continue;
      noted.insert(name);
      PetscCall(PetscPrintf(comm, "Note: option -%s does nothing without %s, which is off in this run; ignored\n", name.c_str(), f.needs.c_str()));
    }
  // Candidates: every name a component queried, and every option given that something read.
  std::set<std::string> candidates = known;
  for (const char *f : finalize_options) candidates.insert(f);
  for (const std::string &name : given)
    if (std::find(unused.begin(), unused.end(), name) == unused.end()) candidates.insert(name);
  // A parameter of a sub-model that this run does not select (material files carry the parameters
  // of alternatives: -steel_eos_C0 with -steel_eos_type hypoelastic) is noted, naming the selector,
  // unless a known name is within 2 edits (then it is taken for a typo).
  std::vector<std::string> errors;
  for (const std::string &u : unused) {
    size_t nearest = std::string::npos;
    for (const std::string &c : candidates) nearest = std::min(nearest, EditDistance(u, c));
    std::string selector;
    for (const std::string &c : known) {
      // selectors: -<prefix>_type(s) of a sub-model, -<material>_model of a material (a scene that
      // switches its charge to another model leaves the first model's parameters unread)
      const auto ends = [&](const char *suffix) {
        const size_t k = std::strlen(suffix);
        return c.size() > k && c.compare(c.size() - k, k, suffix) == 0;
      };
      const size_t cut = ends("_type") ? c.size() - 4 : ends("_types") ? c.size() - 5 : ends("_model") ? c.size() - 5 : 0;
      if (cut && u.size() > cut && u.compare(0, cut, c, 0, cut) == 0 && c.size() > selector.size()) selector = c;
    }
    if (!selector.empty() && nearest > 2) {
      char      value[256] = "";
      PetscBool set        = PETSC_FALSE;
      PetscCall(PetscOptionsGetString(nullptr, nullptr, ("-" + selector).c_str(), value, sizeof(value), &set));
      PetscCall(PetscPrintf(comm, "Note: option -%s is not read by the model this run selects (-%s%s%s); ignored\n", u.c_str(), selector.c_str(), set ? " " : "", set ? value : " default"));
      continue;
    }
    errors.push_back(u);
    const std::string near = Suggestions(u, candidates);
    if (near.empty()) PetscCall(PetscPrintf(comm, "Unknown option -%s; nothing reads it and no known option is close\n", u.c_str()));
    else PetscCall(PetscPrintf(comm, "Unknown option -%s; did you mean %s?\n", u.c_str(), near.c_str()));
  }
  PetscCall(PetscOptionsLeftRestore(nullptr, &n, &names, &values));
  // rank 0 decides for all: the names the components queried are recorded from the help text, which
  // only rank 0 prints, so another rank would take a selected model's alternatives for typos
  PetscMPIInt count = (PetscMPIInt)errors.size();
  PetscCallMPI(MPI_Bcast(&count, 1, MPI_INT, 0, comm));
  if (!count) PetscFunctionReturn(PETSC_SUCCESS);
  if (allow) {
    PetscCall(PetscPrintf(comm, "WARNING: %d option(s) above are not read by this run (-options_allow_unused); continuing\n", (int)count));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  SETERRQ(comm, PETSC_ERR_USER_INPUT, "%d option(s) given but never read (listed above): correct or remove them, or pass -options_allow_unused to run anyway", (int)count);
}

} // namespace burst
