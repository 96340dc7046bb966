// Every call of try_step (lib/src/hydro/step.cpp) is a row of the step's table in
// docs/algorithm.md §1, so the table reads as the step: a new phase (a contact pass, a
// mixed-zone closure) cannot enter the step without its row.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The body of `bool Simulation::Impl::try_step(double dt) { ... }`, comments removed.
std::string try_step_body() {
  const std::string src = read_text(fs::path(STAGGER_SOURCE_DIR) / "lib/src/hydro/step.cpp");
  const std::size_t head = src.find("bool Simulation::Impl::try_step(");
  if (head == std::string::npos) return {};
  std::size_t i = src.find('{', head);
  const std::size_t begin = i;
  int depth = 0;
  for (; i < src.size(); ++i) {
    if (src[i] == '{') ++depth;
    if (src[i] == '}' && --depth == 0) break;
  }
  return std::regex_replace(src.substr(begin, i - begin), std::regex("//[^\n]*"), "");
}

// The names called in the body: identifiers followed by '(' (the collective's through -> included;
// an array's `.data()` is not a call of the step).
std::set<std::string> called_names(const std::string& body) {
  static const std::set<std::string> not_phases = {"if",     "for",          "while",       "return",
                                                   "switch", "data_or_null", "failure_kind"};  // accessors, not phases
  std::set<std::string> names;
  const std::regex call(R"((?:^|[^.A-Za-z0-9_])([A-Za-z_][A-Za-z0-9_]*)\s*\()");
  for (auto it = std::sregex_iterator(body.begin(), body.end(), call); it != std::sregex_iterator(); ++it)
    if (!not_phases.count((*it)[1].str())) names.insert((*it)[1].str());
  return names;
}

// The step table's "call in `try_step`" column: every `name` quoted in it.
std::set<std::string> table_calls() {
  const std::string doc = read_text(fs::path(STAGGER_SOURCE_DIR) / "docs/algorithm.md");
  const std::size_t head = doc.find("| steps | call in `try_step` (kernels) | what |");
  std::set<std::string> names;
  if (head == std::string::npos) return names;
  std::istringstream rows(doc.substr(head));
  std::string row;
  std::getline(rows, row);  // the header
  const std::regex quoted("`([A-Za-z_][A-Za-z0-9_]*)`");
  while (std::getline(rows, row) && row.rfind("|", 0) == 0) {
    const std::size_t a = row.find('|', 1), b = row.find('|', a + 1);
    if (a == std::string::npos || b == std::string::npos) continue;
    const std::string column = row.substr(a, b - a);
    for (auto it = std::sregex_iterator(column.begin(), column.end(), quoted); it != std::sregex_iterator(); ++it)
      names.insert((*it)[1].str());
  }
  return names;
}

// The rows of the table, each the set of names quoted in its call column.
std::vector<std::set<std::string>> table_rows() {
  const std::string doc = read_text(fs::path(STAGGER_SOURCE_DIR) / "docs/algorithm.md");
  const std::size_t head = doc.find("| steps | call in `try_step` (kernels) | what |");
  std::vector<std::set<std::string>> found;
  if (head == std::string::npos) return found;
  std::istringstream rows(doc.substr(head));
  std::string row;
  std::getline(rows, row);
  const std::regex quoted("`([A-Za-z_][A-Za-z0-9_]*)`");
  while (std::getline(rows, row) && row.rfind("|", 0) == 0) {
    const std::size_t a = row.find('|', 1), b = row.find('|', a + 1);
    if (a == std::string::npos || b == std::string::npos) continue;
    const std::string column = row.substr(a, b - a);
    std::set<std::string> names;
    for (auto it = std::sregex_iterator(column.begin(), column.end(), quoted); it != std::sregex_iterator(); ++it)
      names.insert((*it)[1].str());
    found.push_back(names);
  }
  return found;
}

// Every function NAME_loop defined or declared in lib/src/hydro/kernels/.
std::set<std::string> kernel_loops() {
  std::set<std::string> loops;
  const std::regex loop(R"(\b([a-z_][a-z0-9_]*_loop)\s*\()");
  for (const auto& entry : fs::directory_iterator(fs::path(STAGGER_SOURCE_DIR) / "lib/src/hydro/kernels")) {
    const std::string text = read_text(entry.path());
    for (auto it = std::sregex_iterator(text.begin(), text.end(), loop); it != std::sregex_iterator(); ++it)
      loops.insert((*it)[1].str());
  }
  return loops;
}

TEST(StepTable, TheRuleSeesTheStepAndTheTable) {
  const std::set<std::string> calls = called_names(try_step_body());
  EXPECT_GE(calls.size(), 10u);
  EXPECT_TRUE(calls.count("zone_forces"));
  EXPECT_TRUE(calls.count("end_of_step"));
  EXPECT_GE(table_calls().size(), 10u);
}

TEST(StepTable, EveryCallOfTryStepIsARowOfTheAlgorithmTable) {
  const std::set<std::string> rows = table_calls();
  for (const std::string& name : called_names(try_step_body()))
    EXPECT_TRUE(rows.count(name)) << "try_step calls `" << name
                                  << "`, which no row of the step table in docs/algorithm.md names";
}

TEST(StepTable, EveryLoopKernelIsNamedAfterItsRow) {
  // The fused loops of the step (P1, Z1, edge, rz weighting, P2, Z2, commit) and nothing else.
  const std::set<std::string> loops = kernel_loops();
  EXPECT_GE(loops.size(), 7u);
  for (const std::string& loop : loops) {
    const std::string call = loop.substr(0, loop.size() - 5);
    bool named = false;
    for (const std::set<std::string>& row : table_rows())
      if (row.count(call) && row.count(loop)) named = true;
    EXPECT_TRUE(named) << "the kernel `" << loop << "` is not listed in the row of the call `" << call
                       << "` in the step table of docs/algorithm.md";
  }
}

}  // namespace
