// The `stagger` executable: exit codes, one-line errors, mesh and run outputs.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/files.hpp"
#include "support/scene_toml.hpp"
#include "support/scratch_directory.hpp"
#include "support/stagger_binary.hpp"

namespace fs = std::filesystem;

namespace {

using Result = stagger::testing::CommandResult;
using stagger::testing::read_text;
using stagger::testing::stagger_binary;
namespace toml = stagger::testing::toml;

class Cli : public ::testing::Test {
 protected:
  // Runs `stagger ARGS` with stdout and stderr captured in files.
  Result stagger(const std::string& args) const { return stagger::testing::run_stagger(args, directory_); }
  std::string write(const std::string& name, const std::string& text) const { return scratch_.write(name, text); }
  static void expect_one_line_error(const Result& result) {
    EXPECT_EQ(result.status, 1);
    EXPECT_EQ(result.err.rfind("stagger: error: ", 0), 0u) << result.err;
    ASSERT_FALSE(result.err.empty());
    EXPECT_EQ(result.err.find('\n'), result.err.size() - 1) << "exactly one line: " << result.err;
  }

  const stagger::testing::ScratchDirectory scratch_{"cli_test_" + stagger::testing::current_test_name()};
  const fs::path directory_ = scratch_.path();
};

// Sod's tube on 10 x 1 zones, dumped every 0.05.
const std::string tiny_scene = "[scene]\nname = \"tiny\"\n" + toml::time("0.1") +
                               toml::rectangle("[0.0, 1.0]", "[0.0, 0.1]", 10, 1) + toml::ideal_gas() +
                               toml::gas_region(R"("x < 0.5 ? 1.0 : 0.125")", R"("x < 0.5 ? 1.0 : 0.1")") +
                               toml::walls() + "[output]\ndump_interval = 0.05\n";

TEST_F(Cli, HelpDescribesCommandsAndTheOutputContract) {
  const Result result = stagger("--help");
  EXPECT_EQ(result.status, 0);
  for (const char* part : {"run", "check", "mesh", "summary.json", "history.csv", ".pvd", "zone_cycles_per_second",
                           "relative_energy_error", "density", "velocity", "--set"})
    EXPECT_NE(result.out.find(part), std::string::npos) << part;
}

TEST_F(Cli, EverySubcommandHasHelp) {
  for (const char* command : {"run", "check", "mesh"}) {
    const Result result = stagger(std::string(command) + " --help");
    EXPECT_EQ(result.status, 0) << command;
    EXPECT_NE(result.out.find(std::string("usage: stagger ") + command), std::string::npos) << result.out;
  }
}

TEST_F(Cli, NoCommandOrUnknownCommandIsAOneLineError) {
  expect_one_line_error(stagger(""));
  const Result result = stagger("frobnicate");
  expect_one_line_error(result);
  EXPECT_NE(result.err.find("unknown command 'frobnicate'"), std::string::npos);
}

TEST_F(Cli, UnknownOptionIsAOneLineError) {
  const Result result = stagger("run scene.toml --fast");
  expect_one_line_error(result);
  EXPECT_NE(result.err.find("unknown option '--fast'"), std::string::npos);
}

TEST_F(Cli, CheckPrintsTheResolvedSetUp) {
  const Result result = stagger("check " + write("tiny.toml", tiny_scene));
  EXPECT_EQ(result.status, 0) << result.err;
  EXPECT_NE(result.out.find("10 zones"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("ideal gas"), std::string::npos);
  EXPECT_TRUE(result.err.empty()) << result.err;
}

TEST_F(Cli, CheckAndRunGiveTheSameOneLineErrorWithTheLine) {
  std::string text = tiny_scene;
  text.replace(text.find("nx = 10"), 7, "nx = -3");
  const std::string path = write("bad.toml", text);
  const Result check = stagger("check " + path), run = stagger("run " + path + " --out " + (directory_ / "o").string());
  expect_one_line_error(check);
  expect_one_line_error(run);
  EXPECT_EQ(check.err, run.err);
  EXPECT_NE(check.err.find("bad.toml:9: key 'mesh.nx'"), std::string::npos) << check.err;
}

TEST_F(Cli, SetOverridesReachTheScene) {
  const std::string path = write("tiny.toml", tiny_scene);
  const Result refined = stagger("check " + path + " --set mesh.refine=2");
  EXPECT_EQ(refined.status, 0) << refined.err;
  EXPECT_NE(refined.out.find("40 zones"), std::string::npos) << refined.out;
  const Result bad = stagger("check " + path + " --set numerics.cfl=7");
  expect_one_line_error(bad);
  EXPECT_NE(bad.err.find("--set numerics.cfl=7: key 'numerics.cfl'"), std::string::npos) << bad.err;
  expect_one_line_error(stagger("check " + path + " --set nonsense"));
}

TEST_F(Cli, MissingSceneIsAOneLineError) {
  const Result result = stagger("check " + (directory_ / "absent.toml").string());
  expect_one_line_error(result);
  EXPECT_NE(result.err.find("absent.toml"), std::string::npos);
}

TEST_F(Cli, MeshesEveryGeometryAndWritesVtuAndMsh) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(STAGGER_SOURCE_DIR) / "geometries")) {
    if (entry.path().extension() != ".geo") continue;
    ++count;
    const std::string stem = entry.path().stem().string();
    const fs::path vtu = directory_ / (stem + ".vtu"), msh = directory_ / (stem + ".msh");
    const Result to_vtu = stagger("mesh " + entry.path().string() + " -o " + vtu.string());
    EXPECT_EQ(to_vtu.status, 0) << stem << ": " << to_vtu.err;
    EXPECT_NE(to_vtu.out.find(" zones ("), std::string::npos) << to_vtu.out;
    EXPECT_NE(to_vtu.out.find("quality:"), std::string::npos);
    EXPECT_GT(fs::exists(vtu) ? fs::file_size(vtu) : 0, 100u) << stem;
    const Result to_msh = stagger("mesh " + entry.path().string() + " --output=" + msh.string());
    EXPECT_EQ(to_msh.status, 0) << stem << ": " << to_msh.err;
    // The written .msh reads back with the same zone count.
    const Result again = stagger("mesh " + msh.string());
    EXPECT_EQ(again.status, 0) << stem << ": " << again.err;
    const auto zones = [](const std::string& out) { return out.substr(0, out.find(" zones")); };
    EXPECT_EQ(zones(again.out).substr(zones(again.out).rfind(' ')),
              zones(to_vtu.out).substr(zones(to_vtu.out).rfind(' ')))
        << stem;
  }
  EXPECT_GE(count, 4);
}

TEST_F(Cli, MeshParametersOverrideTheGeo) {
  const std::string geo = std::string(STAGGER_SOURCE_DIR) + "/geometries/quarter_shell.geo";
  const Result base = stagger("mesh " + geo);
  const Result finer = stagger("mesh " + geo + " --set n_theta=40 --set n_r=32");
  ASSERT_EQ(base.status, 0) << base.err;
  ASSERT_EQ(finer.status, 0) << finer.err;
  EXPECT_NE(base.out.find("320 zones"), std::string::npos) << base.out;
  EXPECT_NE(finer.out.find("1280 zones"), std::string::npos) << finer.out;
  expect_one_line_error(stagger("mesh " + geo + " --set n_theta=many"));
  expect_one_line_error(stagger("mesh " + geo + " -o out.txt"));
}

TEST_F(Cli, LeftoverTrianglesCanBeRejected) {
  const std::string geo = std::string(STAGGER_SOURCE_DIR) + "/geometries/triangles_left.geo";
  EXPECT_EQ(stagger("mesh " + geo).status, 0);
  EXPECT_EQ(stagger("mesh " + geo + " --triangles subdivide").status, 0);
  expect_one_line_error(stagger("mesh " + geo + " --triangles reject"));
  expect_one_line_error(stagger("mesh " + geo + " --triangles sometimes"));
}

TEST_F(Cli, MissingGeometryIsAOneLineError) {
  expect_one_line_error(stagger("mesh " + (directory_ / "none.geo").string()));
}

TEST_F(Cli, RunWritesTheOutputContract) {
  const fs::path out = directory_ / "run";
  const Result result = stagger("run " + write("tiny.toml", tiny_scene) + " --out " + out.string() + " --threads 1");
  ASSERT_EQ(result.status, 0) << result.err << result.out;
  EXPECT_NE(result.out.find("completed"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("zone-cycles/s"), std::string::npos);
  EXPECT_NE(result.out.find("relative error"), std::string::npos);
  ASSERT_TRUE(fs::exists(out / "summary.json"));
  ASSERT_TRUE(fs::exists(out / "history.csv"));
  ASSERT_TRUE(fs::exists(out / "tiny.pvd"));
  const std::string summary = read_text(out / "summary.json");
  for (const char* key : {"\"scene\"", "\"zones\"", "\"points\"", "\"cycles\"", "\"t_end\"", "\"wall_seconds\"",
                          "\"zone_cycles_per_second\"", "\"energy\"", "\"relative_error\""})
    EXPECT_NE(summary.find(key), std::string::npos) << key << " in " << summary;
  const std::string history = read_text(out / "history.csv");
  EXPECT_NE(history.find("time"), std::string::npos);
  EXPECT_GT(std::count(history.begin(), history.end(), '\n'), 2);
  const std::string pvd = read_text(out / "tiny.pvd");
  int vtu_files = 0;
  for (const auto& entry : fs::directory_iterator(out))
    if (entry.path().extension() == ".vtu") {
      ++vtu_files;
      EXPECT_NE(pvd.find(entry.path().filename().string()), std::string::npos) << entry.path();
    }
  EXPECT_GE(vtu_files, 3);  // t = 0, 0.05, 0.1
}

TEST_F(Cli, MeshOutputIsAtomicAndAFullDiskIsAnError) {
  const std::string geo = std::string(STAGGER_SOURCE_DIR) + "/geometries/shock_tube.geo";
  for (const char* name : {"m.msh", "m.vtu"}) {
    const fs::path target = directory_ / name;
    // A 4 KiB file-size limit: the write fails as on a full disk (stagger ignores SIGXFSZ).
    std::ofstream(target) << "previous";
    const std::string limited =
        "sh -c 'ulimit -f 4; exec " + stagger_binary() + " mesh " + geo + " --set nx=400 -o " + target.string() + "'";
    const int raw = std::system(
        (limited + " >" + (directory_ / "o.txt").string() + " 2>" + (directory_ / "e.txt").string()).c_str());
    const std::string err = read_text(directory_ / "e.txt");
    EXPECT_EQ(WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, 1) << err;
    EXPECT_NE(err.find("stagger: error: cannot write '" + target.string() + "'"), std::string::npos) << err;
    EXPECT_EQ(read_text(target), "previous") << "the old file must stay whole";
    int hidden = 0;
    for (const auto& entry : fs::directory_iterator(directory_)) hidden += entry.path().filename().string()[0] == '.';
    EXPECT_EQ(hidden, 0) << "a temporary file was left behind";
    // Without the limit the same command replaces the file.
    const Result written = stagger("mesh " + geo + " --set nx=400 -o " + target.string());
    EXPECT_EQ(written.status, 0) << written.err;
    EXPECT_GT(fs::file_size(target), 4096u);
  }
}

// The shipped scenes give no warning: none turns a check off (docs/algorithm.md §9).
TEST_F(Cli, ShippedScenesGiveNoWarnings) {
  const fs::path scenes = fs::path(STAGGER_SOURCE_DIR) / "apps" / "scenes";
  int count = 0;
  for (const auto& entry : fs::directory_iterator(scenes)) {
    if (entry.path().extension() != ".toml") continue;
    ++count;
    const Result result = stagger("check " + entry.path().string() + " --out " + (directory_ / "o").string());
    EXPECT_EQ(result.status, 0) << entry.path() << result.err;
    EXPECT_EQ(result.err.find("warning"), std::string::npos) << entry.path() << ": " << result.err;
  }
  EXPECT_GE(count, 10);
}

// Each warning: printed by check (stderr, after the description) and at the start of run,
// one line naming the file, line and key; the scene still runs.
TEST_F(Cli, SetUpsThatMakeNoSenseGetAWarning) {
  struct Case {
    std::string name, edit_from, edit_to, expected;
  };
  const std::vector<Case> cases = {
      {"few_cycles", "end = 0.1", "end = 0.001", "few_cycles.toml:4: key 'time.end': 0.001 is about 1 time step(s)"},
      {"fast", "pressure = \"x < 0.5 ? 1.0 : 0.1\"", "pressure = \"x < 0.5 ? 1.0 : 0.1\"\nvelocity = [30.0, 0.0]",
       "fast.toml:20: key 'region[0].velocity': the initial speed is above 10 times the sound speed in 10 zone(s)"},
  };
  for (const auto& c : cases) {
    std::string text = tiny_scene;
    text.replace(text.find(c.edit_from), c.edit_from.size(), c.edit_to);
    const std::string path = write(c.name + ".toml", text);
    const Result check = stagger("check " + path);
    EXPECT_EQ(check.status, 0) << check.err;
    EXPECT_NE(check.err.find("stagger: warning: " + std::string(directory_ / c.expected)), std::string::npos)
        << check.err;
    EXPECT_NE(check.out.find("scene is valid (with warnings"), std::string::npos) << check.out;
    const Result run = stagger("run " + path + " --out " + (directory_ / ("run_" + c.name)).string());
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.err.find("stagger: warning: " + std::string(directory_ / c.expected)), std::string::npos) << run.err;
  }
}

TEST_F(Cli, StrengthUnitSlipsGetAWarning) {
  const std::string solid = toml::time("1e-5") + toml::rectangle("[0.0, 0.01]", "[0.0, 0.001]", 10, 1) +
                            toml::copper() + "[material.strength]\nshear_modulus = SHEAR\nyield_stress = YIELD\n" +
                            toml::region("copper", "8930.0", "0.0") + toml::walls();
  auto scene = [&](const std::string& shear, const std::string& yield) {
    std::string text = solid;
    text.replace(text.find("SHEAR"), 5, shear);
    text.replace(text.find("YIELD"), 5, yield);
    return write("solid.toml", text);
  };
  const Result good = stagger("check " + scene("45e9", "90e6"));
  EXPECT_EQ(good.status, 0) << good.err;
  EXPECT_TRUE(good.err.empty()) << good.err;
  // A yield stress in Pa where the modulus is in Mbar (and the other way round).
  const Result yield = stagger("check " + scene("0.45", "90e6"));
  EXPECT_EQ(yield.status, 0) << yield.err;
  EXPECT_NE(yield.err.find("solid.toml:18: key 'material[0].strength.yield_stress': 90000000 is 200000000 times the "
                           "shear modulus 0.45"),
            std::string::npos)
      << yield.err;
  EXPECT_NE(yield.err.find("solid.toml:17: key 'material[0].strength.shear_modulus': 0.45 is"), std::string::npos)
      << yield.err;
  const Result shear = stagger("check " + scene("45e15", "90e6"));
  EXPECT_NE(shear.err.find("key 'material[0].strength.shear_modulus': 4.5e+16 is"), std::string::npos) << shear.err;
  EXPECT_NE(shear.err.find("times the bulk modulus rho c^2 = "), std::string::npos) << shear.err;
}

TEST_F(Cli, UntaggedBoundaryEdgesGetAWarningWithTheirPlace) {
  write("square.geo", R"(Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve {1, 2, 3, 4} = 3; Transfinite Surface {1}; Recombine Surface {1};
Physical Surface("domain") = {1};
Physical Curve("bottom") = {1}; Physical Curve("sides") = {2, 4};
)");
  std::string text = tiny_scene;
  text.replace(text.find("generator = \"rectangle\""), 23, "file = \"square.geo\"");
  for (const char* key : {"x = [0.0, 1.0]\n", "y = [0.0, 0.1]\n", "nx = 10\n", "ny = 1\n"})
    text.erase(text.find(key), std::string(key).size());
  const std::string tags = "tags = [\"left\", \"right\", \"bottom\", \"top\"]";
  text.replace(text.find(tags), tags.size(), "tags = [\"bottom\", \"sides\"]");
  const Result check = stagger("check " + write("square.toml", text));
  EXPECT_EQ(check.status, 0) << check.err;
  for (const char* text : {"square.toml:5: key 'mesh': 2 boundary edge(s) have no tag and will be traction-free",
                           "(0.25, 1)", "(0.75, 1)", "all within x in [0.25, 0.75], y in [1, 1]"})
    EXPECT_NE(check.err.find(text), std::string::npos) << text << " in " << check.err;
}

TEST_F(Cli, ASecondRunIntoTheSameDirectoryFailsWhileTheFirstRuns) {
  std::string text = tiny_scene;
  text.replace(text.find("end = 0.1"), 9, "end = 1000.0");  // ~10^5 cycles: runs until killed
  text.replace(text.find("dump_interval = 0.05"), 20, "dump_interval = 0.0");
  const std::string path = write("long.toml", text);
  const fs::path out = directory_ / "shared";
  const std::string first =
      stagger_binary() + " run " + path + " --out " + out.string() + " --quiet --threads 1 >/dev/null 2>&1 & echo $!";
  FILE* pipe = ::popen(first.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  long pid = 0;
  ASSERT_EQ(std::fscanf(pipe, "%ld", &pid), 1);
  ::pclose(pipe);
  // Wait until the first run holds the lock (its pid is in the lock file).
  for (int i = 0; i < 500 && read_text(out / ".stagger.lock").find(std::to_string(pid)) == std::string::npos; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const Result second = stagger("run " + path + " --out " + out.string());
  ::kill(static_cast<pid_t>(pid), SIGKILL);
  expect_one_line_error(second);
  EXPECT_NE(second.err.find("output directory '" + out.string() + "' is in use by another stagger run (pid " +
                            std::to_string(pid) + ")"),
            std::string::npos)
      << second.err;
  // Once the first run is gone (killed: the kernel drops its lock), the directory is free.
  for (int i = 0; i < 500 && ::kill(static_cast<pid_t>(pid), 0) == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  text = tiny_scene;
  const Result third = stagger("run " + write("long.toml", text) + " --out " + out.string());
  EXPECT_EQ(third.status, 0) << third.err;
}

// Starts `stagger ARGS...` (stdout and stderr into files of `directory`), returns its pid.
pid_t start_stagger(const std::vector<std::string>& args, const fs::path& directory) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int out = ::open((directory / "stdout.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = ::open((directory / "stderr.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(out, 1);
    ::dup2(err, 2);
    std::vector<char*> argv;
    const std::string binary = stagger_binary();
    argv.push_back(const_cast<char*>(binary.c_str()));
    for (const auto& arg : args) argv.push_back(const_cast<char*>(arg.c_str()));
    argv.push_back(nullptr);
    ::execv(binary.c_str(), argv.data());
    ::_exit(127);
  }
  return pid;
}

// A signal ends a run cleanly: the cycle finishes, a checkpoint and a final dump are
// written, the status says "interrupted", the exit status is 128 + the signal, and the
// checkpoint continues the run.
TEST_F(Cli, SigtermAndSigintEndARunWithACheckpointAndAFinalDump) {
  std::string text = tiny_scene;
  text.replace(text.find("end = 0.1"), 9, "end = 1000.0");  // runs until stopped
  text.replace(text.find("dump_interval = 0.05"), 20, "dump_interval = 0.0");
  text.replace(text.find("nx = 10\n"), 8, "nx = 400\n");
  const std::string path = write("long.toml", text);
  for (const int number : {SIGTERM, SIGINT}) {
    const fs::path out = directory_ / (number == SIGTERM ? "term" : "int");
    const pid_t pid = start_stagger({"run", path, "--out", out.string(), "--quiet", "--threads", "1"}, directory_);
    ASSERT_GT(pid, 0);
    // Wait until the run is in its time loop (its first dump is written), then signal it.
    for (int i = 0; i < 1000 && !fs::exists(out / "history.csv"); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    ASSERT_EQ(::kill(pid, number), 0);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status)) << "killed by the signal instead of ending the run";
    EXPECT_EQ(WEXITSTATUS(status), 128 + number);
    const std::string err = read_text(directory_ / "stderr.txt");
    EXPECT_NE(err.find(number == SIGTERM ? "interrupted by SIGTERM at cycle" : "interrupted by SIGINT at cycle"),
              std::string::npos)
        << err;
    EXPECT_NE(err.find("--restart " + (out / "tiny.checkpoint").string()), std::string::npos) << err;
    EXPECT_NE(read_text(out / "summary.json").find("\"status\": \"interrupted\""), std::string::npos);
    ASSERT_TRUE(fs::exists(out / "tiny.checkpoint"));
    EXPECT_TRUE(fs::exists(out / "tiny_000001.vtu")) << "no final dump";
    // The checkpoint continues the run, here to a nearer end.
    const std::size_t at = err.find(", t = ");
    ASSERT_NE(at, std::string::npos);
    const double t_stop = std::stod(err.substr(at + 6));
    const Result resumed =
        stagger("run " + path + " --out " + out.string() + " --restart " + (out / "tiny.checkpoint").string() +
                " --set time.end=" + std::to_string(t_stop * 1.01) + " --quiet");
    EXPECT_EQ(resumed.status, 0) << resumed.err;
    EXPECT_NE(read_text(out / "summary.json").find("\"status\": \"completed\""), std::string::npos);
  }
}

TEST_F(Cli, RunRejectsBadThreadCounts) {
  expect_one_line_error(stagger("run " + write("tiny.toml", tiny_scene) + " --threads zero"));
}

}  // namespace
