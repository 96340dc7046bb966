// A run killed with SIGKILL at an arbitrary moment leaves only complete files, and its
// checkpoint resumes. The victim is this test executable itself, started again with an
// environment variable that makes the test body run a long simulation instead.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <vtkCellData.h>
#include <vtkNew.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <chrono>
#include <cstdlib>
#include <thread>

#include "io_test_support.hpp"
#include "stagger/run.hpp"
#include "stagger/simulation.hpp"

extern char** environ;

namespace stagger {
namespace {

constexpr const char* child_variable = "STAGGER_IO_KILL_CHILD_DIR";
constexpr int zones = 200;

RunControl victim_control(const std::string& directory) {
  RunControl control;
  control.output_directory = directory;
  control.name = "victim";
  control.dump_interval = 0.01;
  control.history_every = 1;
  control.checkpoint_every_cycles = 7;
  control.checkpoint_every_seconds = 0;
  control.max_dumps = 2'000'000;  // a deliberately endless run: 10^6 dump slots
  return control;
}

bool vtu_is_complete(const std::string& path) {
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  return reader->GetErrorCode() == 0 && grid != nullptr && grid->GetNumberOfCells() == zones &&
         grid->GetCellData()->GetArray("density") != nullptr;
}

TEST(KillDashNine, LeavesOnlyCompleteFilesAndAResumableCheckpoint) {
  if (const char* directory = std::getenv(child_variable)) {
    // The victim: a closed shock tube that would run for a very long time.
    Simulation simulation(io_test::sod_problem(zones, 1e4));
    run(simulation, victim_control(directory));
    return;
  }

  io_test::ScratchDirectory scratch("kill9");
  const std::string directory = scratch.file("out");
  std::string variable = std::string(child_variable) + "=" + directory;
  // One thread: the victim's speed must not depend on how busy the machine is.
  std::string threads = "OMP_NUM_THREADS=1";
  std::vector<char*> environment = {variable.data(), threads.data()};
  for (char** entry = environ; *entry != nullptr; ++entry) environment.push_back(*entry);
  environment.push_back(nullptr);
  std::string filter = "--gtest_filter=KillDashNine.LeavesOnlyCompleteFilesAndAResumableCheckpoint";
  std::string self = "/proc/self/exe";
  char* arguments[] = {self.data(), filter.data(), nullptr};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);  // keep the log clean
  pid_t child = 0;
  const int spawned = posix_spawn(&child, "/proc/self/exe", &actions, nullptr, arguments, environment.data());
  posix_spawn_file_actions_destroy(&actions);
  ASSERT_EQ(spawned, 0);

  // Let it write a few dumps and checkpoints, then kill it mid-flight.
  const auto start = std::chrono::steady_clock::now();
  const std::string pvd = directory + "/victim.pvd";
  const std::string checkpoint = directory + "/victim.checkpoint";
  while (std::chrono::steady_clock::now() - start < std::chrono::seconds(20)) {
    if (std::filesystem::exists(checkpoint) && std::filesystem::exists(pvd) && io_test::read_pvd(pvd).size() >= 4) {
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(137));
  ASSERT_EQ(::kill(child, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the victim finished before it was killed";

  // Every file under its final name is complete.
  const auto entries = io_test::read_pvd(pvd);
  ASSERT_GE(entries.size(), 4u);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (i > 0) {
      EXPECT_GT(entries[i].first, entries[i - 1].first);
    }
    EXPECT_TRUE(vtu_is_complete(directory + "/" + entries[i].second)) << entries[i].second;
  }
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    const std::string name = entry.path().filename().string();
    if (name.ends_with(".vtu") && name.front() != '.') {
      EXPECT_TRUE(vtu_is_complete(entry.path().string())) << name;
    }
  }
  const auto lines = io_test::split_lines(io_test::read_text(directory + "/history.csv"));
  ASSERT_GE(lines.size(), 2u);
  for (const std::string& line : lines) {
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 11) << line;
  }

  // The checkpoint resumes (to a nearer end time) and finishes cleanly; stale temporary
  // files of the dead process are cleared.
  Problem problem = io_test::sod_problem(zones, entries.back().first + 0.05);
  Simulation simulation(std::move(problem));
  const RunResult result = resume(simulation, victim_control(directory), checkpoint);
  ASSERT_TRUE(result.completed) << result.message;
  EXPECT_GT(simulation.cycle(), 0);
  const auto resumed = io_test::read_pvd(pvd);
  ASSERT_FALSE(resumed.empty());
  EXPECT_EQ(resumed.back().first, simulation.problem().t_end);
  EXPECT_TRUE(vtu_is_complete(directory + "/" + resumed.back().second));
  EXPECT_TRUE(std::filesystem::exists(directory + "/summary.json"));
  const auto leftovers = io_test::temporary_files(directory);
  EXPECT_TRUE(leftovers.empty()) << leftovers.front();
}

}  // namespace
}  // namespace stagger
