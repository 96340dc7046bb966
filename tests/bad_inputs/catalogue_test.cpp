// The bad-input catalogue (docs/robustness.md §1): every case of cases.txt is run through the real
// `stagger check` and `stagger run` binaries. Each must fail cleanly: exit status 1 (not a
// signal, not a hang), exactly one `stagger: error:` line on stderr that holds the expected
// text, and the same line from both commands. Repair cases exit 0 with a note; run-only
// cases (mid-run tangling) must also leave summary.json with the error and a final dump.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/files.hpp"
#include "support/stagger_binary.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path kCases = fs::path(STAGGER_SOURCE_DIR) / "tests" / "bad_inputs";
const fs::path kBinary = stagger::testing::stagger_binary();
const fs::path kWork = fs::path(STAGGER_BINARY_DIR) / "tests" / "bad_inputs_work";
constexpr double kTimeoutSeconds = 60;

std::string trim(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t");
  if (begin == std::string::npos) return "";
  return text.substr(begin, text.find_last_not_of(" \t") - begin + 1);
}

std::vector<std::string> split(const std::string& text, const std::string& separator) {
  std::vector<std::string> parts;
  std::size_t begin = 0;
  for (std::size_t at; (at = text.find(separator, begin)) != std::string::npos; begin = at + separator.size())
    parts.push_back(trim(text.substr(begin, at - begin)));
  parts.push_back(trim(text.substr(begin)));
  return parts;
}

void replace_all(std::string& text, const std::string& from, const std::string& to) {
  for (std::size_t at = 0; (at = text.find(from, at)) != std::string::npos; at += to.size())
    text.replace(at, from.size(), to);
}

struct Case {
  std::string name, mode;
  std::vector<std::string> arguments;
  std::vector<std::string> expected;
};

// gtest prints the parameter in test listings (ctest): the case name, not its bytes.
void PrintTo(const Case& c, std::ostream* out) {
  *out << c.name;
}

std::vector<Case> read_cases() {
  std::ifstream in(kCases / "cases.txt");
  std::vector<Case> cases;
  for (std::string line; std::getline(in, line);) {
    if (trim(line).empty() || trim(line)[0] == '#') continue;
    const auto fields = split(line, "|");
    if (fields.size() != 4) {
      ADD_FAILURE() << "cases.txt: malformed line: " << line;
      continue;
    }
    Case c{fields[0], fields[1], {}, split(fields[3], " && ")};
    std::istringstream words(fields[2]);
    for (std::string word; words >> word;) c.arguments.push_back(word);
    cases.push_back(c);
  }
  return cases;
}

struct Outcome {
  int exit_code = -1;  ///< -1 if not a normal exit
  int signal = 0;      ///< the signal that ended it, or 0
  bool timed_out = false;
  double seconds = 0;
  std::string out, err;
};

using stagger::testing::read_text;

/// Runs the stagger binary in `directory` with a time limit; stdout and stderr to files.
Outcome run_stagger(const std::vector<std::string>& args, const fs::path& directory, const fs::path& log_stem) {
  const std::string out_path = log_stem.string() + ".out", err_path = log_stem.string() + ".err";
  std::vector<std::string> argv_storage{kBinary.string()};
  argv_storage.insert(argv_storage.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& arg : argv_storage) argv.push_back(arg.data());
  argv.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    // Child: only async-signal-safe calls until exec.
    if (chdir(directory.c_str()) != 0) _exit(126);
    if (!freopen(out_path.c_str(), "w", stdout) || !freopen(err_path.c_str(), "w", stderr)) _exit(126);
    execv(argv[0], argv.data());
    _exit(127);
  }
  Outcome outcome;
  int status = 0;
  for (;;) {
    const pid_t done = waitpid(pid, &status, WNOHANG);
    outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (done == pid) break;
    if (outcome.seconds > kTimeoutSeconds) {
      outcome.timed_out = true;
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (WIFEXITED(status)) outcome.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) outcome.signal = WTERMSIG(status);
  outcome.out = read_text(out_path);
  outcome.err = read_text(err_path);
  return outcome;
}

std::vector<std::string> lines_starting(const std::string& text, const std::string& prefix) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(prefix, 0) == 0) lines.push_back(line);
  return lines;
}

std::string describe(const std::string& command, const Outcome& o) {
  return command + ": exit " + std::to_string(o.exit_code) + ", signal " + std::to_string(o.signal) +
         (o.timed_out ? " (TIMED OUT)" : "") + ", stderr:\n" + o.err;
}

class BadInput : public testing::TestWithParam<Case> {};

TEST_P(BadInput, FailsCleanlyWithTheExpectedMessage) {
  const Case& c = GetParam();
  const fs::path scene = kCases / (c.name + ".toml");
  ASSERT_TRUE(fs::is_regular_file(scene)) << scene;
  const fs::path work = kWork / c.name;
  fs::remove_all(work);
  fs::create_directories(work);
  const fs::path a_file = work / "a_file";
  std::ofstream(a_file) << "not a directory\n";

  std::vector<std::string> arguments = c.arguments;
  bool has_out = false;
  for (auto& arg : arguments) {
    replace_all(arg, "{file}", a_file.string());
    has_out = has_out || arg == "--out";
  }
  std::vector<std::string> expected = c.expected;
  for (auto& text : expected) replace_all(text, "{file}", a_file.string());

  std::vector<std::string> messages;
  for (const std::string command : {"check", "run"}) {
    SCOPED_TRACE(c.name + ": stagger " + command);
    std::vector<std::string> args{command, c.name + ".toml"};
    args.insert(args.end(), arguments.begin(), arguments.end());
    if (!has_out) args.insert(args.end(), {"--out", (work / ("out_" + command)).string()});
    const Outcome o = run_stagger(args, kCases, work / command);
    ASSERT_FALSE(o.timed_out) << describe(command, o);
    ASSERT_EQ(o.signal, 0) << "crashed: " << describe(command, o);
    ASSERT_GE(o.exit_code, 0) << describe(command, o);
    const auto errors = lines_starting(o.err, "stagger: error: ");
    const bool must_fail = c.mode == "both" || (c.mode == "run" && command == "run");
    if (!must_fail) {
      EXPECT_EQ(o.exit_code, 0) << describe(command, o);
      EXPECT_TRUE(errors.empty()) << describe(command, o);
      if (c.mode == "repair") {
        const auto notes =
            lines_starting(command == "check" ? o.out : o.err, command == "check" ? "  note: " : "stagger: note: ");
        bool found = false;
        for (const auto& note : notes)
          for (const auto& text : expected) found = found || note.find(text) != std::string::npos;
        EXPECT_TRUE(found) << "no note with '" << expected.front() << "'; " << describe(command, o) << o.out;
      }
      continue;
    }
    EXPECT_EQ(o.exit_code, 1) << describe(command, o);
    ASSERT_EQ(errors.size(), 1u) << "expected exactly one error line; " << describe(command, o);
    for (const auto& text : expected)
      EXPECT_NE(errors.front().find(text), std::string::npos) << "missing '" << text << "' in\n" << errors.front();
    messages.push_back(errors.front());
    if (c.mode == "run") {
      // The run stopped mid-way: summary.json holds the error, and a final dump exists.
      const fs::path out = work / "out_run";
      const std::string summary = read_text(out / "summary.json");
      EXPECT_NE(summary.find("\"status\": \"cycle"), std::string::npos) << summary;
      EXPECT_NE(summary.find("a zone tangled"), std::string::npos) << summary;
      bool pvd = false;
      for (const auto& entry : fs::directory_iterator(out)) pvd = pvd || entry.path().extension() == ".pvd";
      EXPECT_TRUE(pvd) << "no final dump in " << out;
    }
  }
  if (c.mode == "both") {
    ASSERT_EQ(messages.size(), 2u);
    EXPECT_EQ(messages[0], messages[1]) << "check and run disagree";
  }
}

std::string case_name(const testing::TestParamInfo<Case>& info) {
  return info.param.name;
}

INSTANTIATE_TEST_SUITE_P(Catalogue, BadInput, testing::ValuesIn(read_cases()), case_name);

TEST(BadInputCatalogue, HasAtLeastThirtyDistinctCases) {
  const auto cases = read_cases();
  EXPECT_GE(cases.size(), 30u);
  std::vector<std::string> names;
  for (const auto& c : cases) names.push_back(c.name);
  std::sort(names.begin(), names.end());
  EXPECT_EQ(std::adjacent_find(names.begin(), names.end()), names.end()) << "a case is listed twice";
  // Every scene in the folder is in the catalogue (no orphan, untested case).
  for (const auto& entry : fs::directory_iterator(kCases))
    if (entry.path().extension() == ".toml") {
      EXPECT_TRUE(std::binary_search(names.begin(), names.end(), entry.path().stem().string()))
          << entry.path().filename() << " is not listed in cases.txt";
    }
}

}  // namespace
