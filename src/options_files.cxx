// The -options_file chain, checked before PETSc reads it (options_files.hpp).
//
// Tokens follow PETSc's option-file reader closely enough to find every include: a line is split at
// white space after dropping what follows '#'; "-options_file NAME" includes NAME (relative to the
// working directory, as PETSc opens it). A file in the chain of its own includes (compared by
// realpath) is a cycle; siblings that include the same file are fine.
#include "options_files.hpp"
#include <cctype>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

namespace burst {

namespace {

struct Include {
  std::string file; // as written
  std::string real; // realpath (or the name if it has none)
  int         line; // line of the -options_file that named it in its parent (0: command line)
};

std::string RealPath(const std::string &name)
{
  char buf[PATH_MAX];
  return realpath(name.c_str(), buf) ? std::string(buf) : name;
}

std::string Chain(const std::vector<Include> &chain, const std::string &last)
{
  std::string s;
  for (size_t i = 0; i < chain.size(); ++i) {
    s += chain[i].file;
    if (i + 1 < chain.size() || !last.empty()) s += " -> ";
  }
  return s + last;
}

bool IsOptionName(const std::string &t) { return t.size() > 1 && t[0] == '-' && (std::isalpha((unsigned char)t[1]) || t[1] == '_'); }

std::string CheckFile(std::vector<Include> &chain);

// Follows "-options_file NAME" in a token list; `where` names the source for messages.
std::string FollowTokens(std::vector<Include> &chain, const std::vector<std::pair<std::string, int>> &tokens, const std::string &where)
{
  for (size_t i = 0; i < tokens.size(); ++i) {
    if (tokens[i].first != "-options_file") continue;
    const int line = tokens[i].second;
    if (i + 1 >= tokens.size() || IsOptionName(tokens[i + 1].first)) {
      std::ostringstream m;
      m << where << (line ? ", line " + std::to_string(line) : std::string()) << ": -options_file names no file ";
      m << (i + 1 >= tokens.size() ? "(it is the last option" + std::string(line ? " of the file)" : ")") : "(" + tokens[i + 1].first + " follows it)");
      if (!chain.empty()) m << "; chain of option files: " << Chain(chain, "");
      return m.str();
    }
    const std::string name = tokens[i + 1].first, real = RealPath(name);
    for (const Include &inc : chain)
      if (inc.real == real)
        return (chain.size() == 1 ? "Option file " + chain.back().file + " includes itself" : std::string("Option files include each other in a loop")) + ": chain of option files " + Chain(chain, name) + " (-options_file on line " +
               std::to_string(line) + " of " + chain.back().file + "); remove the -options_file that closes the loop";
    if ((int)chain.size() + 1 > kMaxOptionFileDepth) return "Option files nested deeper than " + std::to_string(kMaxOptionFileDepth) + " levels: chain of option files " + Chain(chain, name);
    chain.push_back({name, real, line});
    const std::string error = CheckFile(chain);
    chain.pop_back();
    if (!error.empty()) return error;
    ++i;
  }
  return "";
}

std::string CheckFile(std::vector<Include> &chain)
{
  const std::string &file = chain.back().file;

  std::ifstream in(file, std::ios::binary);
  if (!in) return ""; // PETSc says it cannot open it
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string                        text = buffer.str();
  std::vector<std::pair<std::string, int>> tokens;
  int                                      line  = 1;
  size_t                                   start = 0;
  while (start <= text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string  l   = text.substr(start, end - start);
    const size_t nul = l.find('\0');
    if (nul != std::string::npos) {
      std::string msg = "Option file " + file + ", line " + std::to_string(line) + ", column " + std::to_string(nul + 1) + ": a NUL byte (PETSc would drop the rest of the line); remove it";
      if (chain.size() > 1) msg += "; chain of option files: " + Chain(chain, "");
      return msg;
    }
    const size_t hash = l.find('#');
    if (hash != std::string::npos) l.resize(hash);
    std::istringstream words(l);
    for (std::string w; words >> w;) tokens.push_back({w, line});
    if (end == text.size()) break;
    start = end + 1;
    ++line;
  }
  return FollowTokens(chain, tokens, "Option file " + file);
}

std::vector<std::pair<std::string, int>> Words(const std::string &s)
{
  std::vector<std::pair<std::string, int>> out;

  std::istringstream words(s);
  for (std::string w; words >> w;) out.push_back({w, 0});
  return out;
}
} // namespace

std::string CheckOptionFiles(int argc, char **argv)
{
  std::vector<Include>                     chain;
  bool                                     skip_rc = false;
  std::vector<std::pair<std::string, int>> args;
  for (int i = 1; i < argc; ++i) {
    args.push_back({argv[i], 0});
    if (!std::strcmp(argv[i], "-skip_petscrc")) skip_rc = true;
  }
  // the petscrc files PETSc reads by default: the home folder's, then the working directory's
  if (!skip_rc) {
    std::vector<std::string> rc;
    if (const char *home = std::getenv("HOME")) rc.push_back(std::string(home) + "/.petscrc");
    rc.push_back(".petscrc");
    rc.push_back("petscrc");
    for (const std::string &f : rc) {
      chain.assign(1, {f, RealPath(f), 0});
      const std::string error = CheckFile(chain);
      if (!error.empty()) return error;
    }
  }
  chain.clear();
  if (const char *env = std::getenv("PETSC_OPTIONS")) {
    const std::string error = FollowTokens(chain, Words(env), "Environment variable PETSC_OPTIONS");
    if (!error.empty()) return error;
  }
  return FollowTokens(chain, args, "Command line");
}

} // namespace burst
