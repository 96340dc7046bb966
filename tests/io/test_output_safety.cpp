// Output safety: one run per output directory (flock), the previous run's dumps of the same
// scene removed, the dump-count limit, and write errors (full disk, file-size limit, a device
// as target) reported instead of "completed" with truncated files (docs/output.md).
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io_test_support.hpp"
#include "stagger/error.hpp"
#include "stagger/output.hpp"
#include "stagger/run.hpp"
#include "stagger/simulation.hpp"

namespace stagger {
namespace {

namespace fs = std::filesystem;

RunControl quick_control(const fs::path& directory, const std::string& name = "sod_io") {
  RunControl control;
  control.output_directory = directory.string();
  control.name = name;
  control.checkpoints = false;
  return control;
}

TEST(OutputSafety, EstimatedDumpsCountFirstLastAndEveryInterval) {
  RunControl control;
  control.dump_interval = 0;
  EXPECT_EQ(estimated_dumps(control, 1.0), 2);
  control.dump_interval = 0.1;
  EXPECT_EQ(estimated_dumps(control, 1.0), 12);  // floor(1 / 0.1) + 2: an upper bound (t = 1 is one slot)
  control.dump_interval = 0.3;
  EXPECT_EQ(estimated_dumps(control, 1.0), 5);
  control.dump_interval = 1e-300;
  EXPECT_EQ(estimated_dumps(control, 1e300), LONG_MAX);  // saturates, no overflow
  control.dumps = false;
  EXPECT_EQ(estimated_dumps(control, 1.0), 0);
}

TEST(OutputSafety, TooManyDumpsAreRefusedBeforeAnythingIsWritten) {
  io_test::ScratchDirectory scratch("too_many_dumps");
  const fs::path out = scratch.path() / "out";
  Simulation simulation(io_test::sod_problem(10, 0.2));
  RunControl control = quick_control(out);
  control.dump_interval = 1e-9;
  try {
    run(simulation, control);
    FAIL() << "expected an error";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("output.max_dumps = 10000"), std::string::npos) << message;
    EXPECT_NE(message.find("200000002 dumps"), std::string::npos) << message;
  }
  EXPECT_FALSE(fs::exists(out));
  control.max_dumps = 100'000'000;  // the option raises the limit (to its maximum)
  control.dump_interval = 0.05;
  EXPECT_TRUE(run(simulation, control).completed);
}

TEST(OutputSafety, ASecondRunIntoALockedDirectoryFailsNamingItAndThePid) {
  io_test::ScratchDirectory scratch("locked");
  // Another run holds the lock: a separate open file description, as another process has.
  const fs::path lock = scratch.path() / ".stagger.lock";
  const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  ASSERT_EQ(::write(fd, "4242\n", 5), 5);
  Simulation simulation(io_test::sod_problem(10, 0.05));
  try {
    run(simulation, quick_control(scratch.path()));
    FAIL() << "expected an error";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("'" + scratch.path().string() + "' is in use by another stagger run (pid 4242)"),
              std::string::npos)
        << message;
  }
  EXPECT_FALSE(fs::exists(scratch.path() / "sod_io.pvd")) << "the second run wrote into the locked directory";
  ::close(fd);  // the first run ends: the directory is free again
  Simulation again(io_test::sod_problem(10, 0.05));
  EXPECT_TRUE(run(again, quick_control(scratch.path())).completed);
  // The lock is released when the run ends: a third run needs no cleanup.
  Simulation third(io_test::sod_problem(10, 0.05));
  EXPECT_TRUE(run(third, quick_control(scratch.path())).completed);
}

TEST(OutputSafety, ANewRunRemovesThePreviousRunsDumpsOfTheSameSceneOnly) {
  io_test::ScratchDirectory scratch("stale");
  const fs::path out = scratch.path();
  for (int i = 0; i < 40; ++i) {
    char name[64];
    std::snprintf(name, sizeof name, "sod_io_%06d.vtu", i);
    std::ofstream(out / name) << "stale";
  }
  std::ofstream(out / "sod_io.pvd") << "stale";
  for (const char* keep : {"other_000001.vtu", "sod_io_notes.vtu", "sod_io_12.vtu", "notes.txt", ".notes.tmp.999999"})
    std::ofstream(out / keep) << "keep";
  Simulation simulation(io_test::sod_problem(10, 0.05));
  ASSERT_TRUE(run(simulation, quick_control(out)).completed);
  const auto entries = io_test::read_pvd((out / "sod_io.pvd").string());
  ASSERT_EQ(entries.size(), 2u);  // first and last
  int series = 0;
  for (const auto& entry : fs::directory_iterator(out)) {
    const std::string name = entry.path().filename().string();
    if (name.starts_with("sod_io_0")) {
      ++series;
      EXPECT_NE(io_test::read_text(entry.path().string()), "stale") << name;
    }
  }
  EXPECT_EQ(series, 2);
  for (const char* keep : {"other_000001.vtu", "sod_io_notes.vtu", "sod_io_12.vtu", "notes.txt", ".notes.tmp.999999"})
    EXPECT_EQ(io_test::read_text((out / keep).string()), "keep") << keep;
}

TEST(OutputSafety, UnsafeOutputNamesAreRefusedByTheDriver) {
  io_test::ScratchDirectory scratch("names");
  for (const std::string name : {"../escape", "a/b", "..", "a\nb", ".hidden", ""}) {
    Simulation simulation(io_test::sod_problem(4, 0.01));
    EXPECT_THROW(run(simulation, quick_control(scratch.path(), name)), Error) << name;
  }
  EXPECT_FALSE(fs::exists(scratch.path().parent_path() / "escape.pvd"));
}

TEST(OutputSafety, ADeviceIsNeverReplacedByAnOutputFile) {
  struct stat before {};
  ASSERT_EQ(::stat("/dev/null", &before), 0);
  try {
    write_file_atomically("/dev/null", "text");
    FAIL() << "expected an error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("is not a regular file"), std::string::npos) << error.what();
  }
  struct stat after {};
  ASSERT_EQ(::stat("/dev/null", &after), 0);
  EXPECT_TRUE(S_ISCHR(after.st_mode));
}

// In a child process (the limit and the ignored signal must not leak into the test runner):
// under a 4 KiB file-size limit, writes fail like on a full disk.
int write_under_file_size_limit(const std::string& path, const std::function<void()>& write) {
  const pid_t child = ::fork();
  if (child == 0) {
    ::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{4096, 4096};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    try {
      write();
    } catch (const Error& error) {
      const std::string message = error.what();
      const bool named = message.find("cannot write '" + path + "'") != std::string::npos;
      const bool says_full = message.find("full") != std::string::npos;
      ::_exit(named && says_full ? 0 : 2);
    }
    ::_exit(1);  // no error: the truncation went unnoticed
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 100 + WTERMSIG(status);
}

TEST(OutputSafety, AFullDiskIsAnErrorAndLeavesNoFile) {
  io_test::ScratchDirectory scratch("full");
  const std::string text_path = scratch.file("big.txt");
  EXPECT_EQ(write_under_file_size_limit(text_path, [&] { write_file_atomically(text_path, std::string(100000, 'x')); }),
            0);
  const std::string msh_like = scratch.file("big.msh");
  EXPECT_EQ(write_under_file_size_limit(msh_like,
                                        [&] {
                                          // A writer that ignores its own errors, like gmsh's.
                                          write_file_atomically(
                                              msh_like,
                                              [](const std::string& temporary) {
                                                FILE* file = std::fopen(temporary.c_str(), "w");
                                                for (int i = 0; i < 10000; ++i) std::fputs("0123456789\n", file);
                                                std::fputs("$EndElements\n", file);
                                                std::fclose(file);
                                              },
                                              "$EndElements\n");
                                        }),
            0);
  const std::string vtu_path = scratch.file("big.vtu");
  Simulation simulation(io_test::sod_problem(2000, 0.01));
  EXPECT_EQ(write_under_file_size_limit(vtu_path, [&] { write_vtu(vtu_path, simulation); }), 0);
  // Nothing is left behind: no target, no temporary.
  EXPECT_TRUE(fs::is_empty(scratch.path())) << fs::directory_iterator(scratch.path())->path();
  // Without the limit the same writes succeed.
  write_file_atomically(text_path, std::string(100000, 'x'));
  EXPECT_EQ(fs::file_size(text_path), 100000u);
}

}  // namespace
}  // namespace stagger
