// An output directory someone else can write into (docs/output.md, "The output directory"):
// links planted at the lock file or at temporaries' names are never followed, files the
// program did not write are never removed, another scene's results are refused (or replaced
// on request), and the lock file goes with the run.
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "io_test_support.hpp"
#include "stagger/error.hpp"
#include "stagger/run.hpp"
#include "stagger/simulation.hpp"

namespace stagger {
namespace {

namespace fs = std::filesystem;

RunControl control_for(const fs::path& directory, const std::string& name) {
  RunControl control;
  control.output_directory = directory.string();
  control.name = name;
  control.checkpoint_every_cycles = 5;
  control.checkpoint_every_seconds = 0;
  return control;
}

// Runs the small Sod problem under `name` into `directory`; returns the driver's error ("" if none).
std::string run_into(const fs::path& directory, const std::string& name, bool replace = false) {
  Problem problem = io_test::sod_problem(10, 0.05);
  problem.name = name;
  Simulation simulation(std::move(problem));
  RunControl control = control_for(directory, name);
  control.replace = replace;
  try {
    const RunResult result = run(simulation, control);
    return result.completed ? "" : "run stopped: " + result.message;
  } catch (const Error& error) {
    return error.what();
  }
}

// A file an attacker would like a run to overwrite ("precious\n") and an empty output directory.
std::pair<fs::path, fs::path> victim_and_directory(const io_test::ScratchDirectory& scratch) {
  const fs::path victim = scratch.path() / "victim.txt";
  std::ofstream(victim) << "precious\n";
  const fs::path out = scratch.path() / "out";
  fs::create_directories(out);
  return {victim, out};
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(HostileOutputs, ALinkPlantedAtTheLockFileIsRefusedAndItsTargetUntouched) {
  io_test::ScratchDirectory scratch("hostile_lock");
  const auto [victim, out] = victim_and_directory(scratch);
  fs::create_symlink(victim, out / ".stagger.lock");
  const std::string message = run_into(out, "sod");
  EXPECT_TRUE(contains(message, "'.stagger.lock' is a symbolic link")) << message;
  EXPECT_EQ(io_test::read_text(victim.string()), "precious\n");
  EXPECT_FALSE(fs::exists(out / "sod.pvd"));
}

TEST(HostileOutputs, LinksAtEveryPredictableTemporaryNameAreNeitherFollowedNorRemoved) {
  io_test::ScratchDirectory scratch("hostile_temporaries");
  const auto [victim, out] = victim_and_directory(scratch);
  // The names a writer of this process used to choose (`.<file>.tmp.<pid>`), for every file
  // of the run, and the write probe's.
  const std::string pid = std::to_string(::getpid());
  std::vector<fs::path> planted;
  for (const std::string file :
       {"history.csv", "summary.json", "sod.pvd", "sod.checkpoint", "sod_000000.vtu", "sod_000001.vtu"})
    planted.push_back(out / ("." + file + ".tmp." + pid));
  planted.push_back(out / (".stagger-write-probe." + pid));
  for (const auto& link : planted) fs::create_symlink(victim, link);
  EXPECT_EQ(run_into(out, "sod"), "");
  EXPECT_EQ(io_test::read_text(victim.string()), "precious\n");
  for (const auto& link : planted) EXPECT_TRUE(fs::is_symlink(fs::symlink_status(link))) << link;
  EXPECT_TRUE(io_test::temporary_files(out).size() == planted.size()) << "a temporary was left behind";
}

TEST(HostileOutputs, OnlyTheDeadWritersOwnPrivateDirectoriesAreCleanedUp) {
  io_test::ScratchDirectory scratch("hostile_stale");
  const fs::path out = scratch.path() / "out";
  fs::create_directories(out);
  // A killed writer's private directory (pid 999999 is above Linux's default pid_max) ...
  const fs::path stale = out / ".stagger-tmp.999999.Ab3dEf";
  fs::create_directories(stale);
  std::ofstream(stale / "history.csv") << "half";
  // ... files and links that only look like temporaries, which are not ours to remove.
  const fs::path elsewhere = scratch.path() / "elsewhere";
  fs::create_directories(elsewhere);
  std::ofstream(elsewhere / "keep.txt") << "keep";
  fs::create_directory_symlink(elsewhere, out / ".stagger-tmp.999998.Zz9yXx");
  std::ofstream(out / ".notes.tmp.999999") << "keep";
  std::ofstream(out / ".stagger-tmp.999997") << "keep";  // no random part: not a private directory
  EXPECT_EQ(run_into(out, "sod"), "");
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_EQ(io_test::read_text((elsewhere / "keep.txt").string()), "keep");
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(out / ".stagger-tmp.999998.Zz9yXx")));
  EXPECT_EQ(io_test::read_text((out / ".notes.tmp.999999").string()), "keep");
  EXPECT_EQ(io_test::read_text((out / ".stagger-tmp.999997").string()), "keep");
}

TEST(HostileOutputs, AnotherScenesResultsAreRefusedUnlessReplaced) {
  io_test::ScratchDirectory scratch("hostile_foreign");
  const fs::path out = scratch.path() / "out";
  ASSERT_EQ(run_into(out, "alpha"), "");
  std::ofstream(out / "notes.txt") << "mine";
  const std::string history = io_test::read_text((out / "history.csv").string());
  const std::string message = run_into(out, "beta");
  EXPECT_TRUE(contains(message, "holds the results of scene 'alpha', not 'beta'")) << message;
  EXPECT_TRUE(contains(message, "--replace")) << message;
  EXPECT_EQ(io_test::read_text((out / "history.csv").string()), history) << "alpha's history was touched";
  EXPECT_TRUE(fs::exists(out / "alpha.pvd"));
  EXPECT_TRUE(fs::exists(out / "alpha.checkpoint"));
  EXPECT_FALSE(fs::exists(out / "beta.pvd"));
  // A summary.json alone names its scene too (a run with dumps and checkpoints off).
  io_test::ScratchDirectory second("hostile_foreign_summary");
  fs::create_directories(second.path());
  std::ofstream(second.path() / "summary.json") << "{\n  \"scene\": \"gamma\",\n  \"cycles\": 3\n}\n";
  EXPECT_TRUE(contains(run_into(second.path(), "beta"), "scene 'gamma'"));

  // With replace: alpha's results go, beta's come, and what is not a run's output stays.
  EXPECT_EQ(run_into(out, "beta", true), "");
  for (const auto& entry : fs::directory_iterator(out))
    EXPECT_FALSE(entry.path().filename().string().starts_with("alpha")) << entry.path();
  EXPECT_TRUE(fs::exists(out / "beta.pvd"));
  EXPECT_EQ(io_test::read_text((out / "notes.txt").string()), "mine");
  // The same scene again needs no replace; its old checkpoints do not outlive a fresh run.
  std::ofstream(out / "beta.checkpoint.1.r0003") << "an earlier distributed run's piece";
  EXPECT_EQ(run_into(out, "beta"), "");
  EXPECT_FALSE(fs::exists(out / "beta.checkpoint.1.r0003"));
}

TEST(HostileOutputs, TheLockFileGoesWithTheRun) {
  io_test::ScratchDirectory scratch("hostile_lock_end");
  const fs::path out = scratch.path() / "out";
  ASSERT_EQ(run_into(out, "sod"), "");
  EXPECT_FALSE(fs::exists(fs::symlink_status(out / ".stagger.lock")));
  const std::string message = run_into(out / "sod.pvd", "sod");  // a file where a directory should be
  EXPECT_FALSE(message.empty());
}

}  // namespace
}  // namespace stagger
