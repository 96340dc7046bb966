// The layers of lib/src (docs/architecture.md, "Layers and doors"), checked on the sources:
// the Lagrangian phase (hydro/) knows nothing of the phases composed around it, the kernels
// see only kernels, EOS and mesh geometry, and the state sits below every phase.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

struct Include {
  std::string file;  // relative to lib/src
  int line = 0;
  std::string target;  // the quoted path
};

// Every `#include "..."` of the sources under lib/src/<folder>.
std::vector<Include> includes_under(const std::string& folder) {
  const fs::path root = fs::path(STAGGER_SOURCE_DIR) / "lib" / "src";
  std::vector<Include> found;
  const std::regex include_line(R"(^\s*#\s*include\s*"([^"]+)\")");
  for (const auto& entry : fs::recursive_directory_iterator(root / folder)) {
    const std::string ext = entry.path().extension().string();
    if (!entry.is_regular_file() || (ext != ".cpp" && ext != ".hpp")) continue;
    std::ifstream in(entry.path());
    std::string text;
    for (int line = 1; std::getline(in, text); ++line) {
      std::smatch m;
      if (std::regex_search(text, m, include_line))
        found.push_back({fs::relative(entry.path(), root).string(), line, m[1].str()});
    }
  }
  return found;
}

bool starts_with_any(const std::string& path, const std::vector<std::string>& prefixes) {
  for (const std::string& p : prefixes)
    if (path.rfind(p, 0) == 0) return true;
  return false;
}

TEST(IncludeRules, TheRulesSeeTheSources) {
  EXPECT_GT(includes_under("hydro").size(), 20u);
  EXPECT_GT(includes_under("hydro/kernels").size(), 20u);
  EXPECT_GT(includes_under("state").size(), 2u);
}

TEST(IncludeRules, TheLagrangianPhaseIncludesNoOtherPhaseNorTheDriver) {
  // ALE, the distributed phases and the driver are composed by Simulation (lib/src/simulation/)
  // through the public doors; the Lagrangian step does not know they exist.
  for (const Include& inc : includes_under("hydro"))
    EXPECT_FALSE(starts_with_any(inc.target, {"ale/", "parallel/", "driver/", "simulation/", "scene/"}))
        << "lib/src/" << inc.file << ":" << inc.line << " includes \"" << inc.target << "\"";
}

TEST(IncludeRules, KernelsIncludeOnlyKernelsEosAndMeshGeometry) {
  // A kernel is a loop over explicit inputs: the options and constants it is parameterised by
  // (stagger/problem.hpp, stagger/mesh.hpp's Index), the shoelace of mesh/polygon.hpp and the
  // exact sums of hydro/exact_sum.hpp are all it may see besides other kernels, the EOS and the
  // strength model's pointwise yield and return.
  for (const Include& inc : includes_under("hydro/kernels"))
    EXPECT_TRUE(starts_with_any(
        inc.target, {"hydro/kernels/", "eos/eos_kernels.hpp", "strength/linear_hardening.hpp", "mesh/polygon.hpp",
                     "stagger/mesh.hpp", "stagger/problem.hpp", "hydro/exact_sum.hpp"}))
        << "lib/src/" << inc.file << ":" << inc.line << " includes \"" << inc.target << "\"";
}

TEST(IncludeRules, TheStateSitsBelowEveryPhase) {
  for (const Include& inc : includes_under("state"))
    EXPECT_FALSE(starts_with_any(inc.target, {"hydro/", "ale/", "parallel/", "driver/", "simulation/", "scene/"}))
        << "lib/src/" << inc.file << ":" << inc.line << " includes \"" << inc.target << "\"";
}

}  // namespace
