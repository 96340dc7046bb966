// The run driver: dump schedule, history, summary, failures, checkpoints and restart.
#include <cstring>

#include "io_test_support.hpp"
#include "stagger/error.hpp"
#include "stagger/run.hpp"
#include "stagger/simulation.hpp"

namespace stagger {
namespace {

using io_test::read_text;
using io_test::ScratchDirectory;

RunControl quiet_control(const ScratchDirectory& scratch, const std::string& sub = "out") {
  RunControl control;
  control.output_directory = (scratch.path() / sub).string();
  control.name = "sod";
  control.progress = false;
  return control;
}

TEST(RunDriver, DumpsLandOnTheirTimesAndTheLastOnTEnd) {
  ScratchDirectory scratch("run_dumps");
  Simulation simulation(io_test::sod_problem(20, 0.05));
  RunControl control = quiet_control(scratch);
  control.dump_interval = 0.02;
  control.history_every = 5;
  const RunResult result = run(simulation, control);
  ASSERT_TRUE(result.completed) << result.message;
  EXPECT_EQ(simulation.time(), 0.05);

  const auto entries = io_test::read_pvd(control.output_directory + "/sod.pvd");
  ASSERT_EQ(entries.size(), 4u);
  const double expected[] = {0.0, 0.02, 0.04, 0.05};
  for (std::size_t i = 0; i < entries.size(); ++i) {
    EXPECT_EQ(entries[i].first, expected[i]) << "dump " << i;
    EXPECT_TRUE(std::filesystem::exists(control.output_directory + "/" + entries[i].second)) << entries[i].second;
    if (i > 0) {
      EXPECT_GT(entries[i].first, entries[i - 1].first);
    }
  }

  // History: cycle 0, every 5th cycle, and the last cycle.
  const auto lines = io_test::split_lines(read_text(control.output_directory + "/history.csv"));
  ASSERT_GE(lines.size(), 3u);
  EXPECT_EQ(lines[0].rfind("time,cycle,dt,", 0), 0u);
  const long cycles = simulation.cycle();
  const std::size_t expected_rows = 1 + cycles / 5 + (cycles % 5 != 0 ? 1 : 0);
  EXPECT_EQ(lines.size() - 1, expected_rows);
  EXPECT_EQ(std::stol(lines.back().substr(lines.back().find(',') + 1)), cycles);

  const io_test::Json summary = io_test::parse_json_file(control.output_directory + "/summary.json");
  EXPECT_EQ(summary["status"].text, "completed");
  EXPECT_EQ(summary["cycles"].number, cycles);
  EXPECT_EQ(summary["t_end"].number, 0.05);
  EXPECT_EQ(summary["time"].number, 0.05);
  EXPECT_GT(summary["zone_cycles_per_second"].number, 0);
  EXPECT_GE(summary["wall_seconds"].number, summary["loop_seconds"].number);
  EXPECT_EQ(result.summary.status, "completed");

  EXPECT_TRUE(io_test::temporary_files(control.output_directory).empty());
}

TEST(RunDriver, WithoutDumpIntervalOnlyFirstAndLastAreDumped) {
  ScratchDirectory scratch("run_first_last");
  Simulation simulation(io_test::sod_problem(10, 0.03));
  RunControl control = quiet_control(scratch);
  control.checkpoints = false;
  ASSERT_TRUE(run(simulation, control).completed);
  const auto entries = io_test::read_pvd(control.output_directory + "/sod.pvd");
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[0].first, 0.0);
  EXPECT_EQ(entries[1].first, 0.03);
  EXPECT_FALSE(std::filesystem::exists(control.output_directory + "/sod.checkpoint"));
}

TEST(RunDriver, ReferenceFillsErrorsAndDiagnostics) {
  ScratchDirectory scratch("run_reference");
  Simulation simulation(io_test::sod_problem(10, 0.02));
  RunControl control = quiet_control(scratch);
  control.dumps = false;
  control.reference = [](const Simulation& s, NamedValues& errors, NamedValues& diagnostics) {
    errors.emplace_back("L1_density", 0.5);
    diagnostics.emplace_back("final_time", s.time());
  };
  const RunResult result = run(simulation, control);
  ASSERT_TRUE(result.completed);
  EXPECT_FALSE(std::filesystem::exists(control.output_directory + "/sod.pvd"));
  const io_test::Json summary = io_test::parse_json_file(control.output_directory + "/summary.json");
  EXPECT_EQ(summary["errors"]["L1_density"].number, 0.5);
  EXPECT_EQ(summary["diagnostics"]["final_time"].number, 0.02);
}

TEST(RunDriver, OutputDirectoryUnderARegularFileIsAnErrorNamingIt) {
  ScratchDirectory scratch("run_bad_dir");
  write_file_atomically(scratch.file("plain"), "not a directory\n");
  Simulation simulation(io_test::sod_problem(4, 0.01));
  RunControl control = quiet_control(scratch, "plain/out");
  try {
    run(simulation, control);
    FAIL() << "expected stagger::Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(control.output_directory), std::string::npos) << error.what();
  }
  EXPECT_EQ(simulation.cycle(), 0) << "nothing runs before the output directory is usable";
}

TEST(RunDriver, ExistingButUnwritableOutputDirectoryIsAnErrorNamingIt) {
  // /proc/self exists and is a directory, but no one (not even root) can create files in it.
  ScratchDirectory scratch("run_unwritable");
  Simulation simulation(io_test::sod_problem(4, 0.01));
  RunControl control = quiet_control(scratch);
  control.output_directory = "/proc/self";
  try {
    run(simulation, control);
    FAIL() << "expected stagger::Error";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("'/proc/self'"), std::string::npos) << message;
    EXPECT_NE(message.find("not writable"), std::string::npos) << message;
  }
}

TEST(RunDriver, AFailedStepEndsWithAFinalDumpAndTheMessageAsStatus) {
  ScratchDirectory scratch("run_failure");
  Simulation simulation(io_test::sod_problem(10, 0.2));
  simulation.set_observer([](const Simulation& s) {
    if (s.cycle() == 7) throw Error("zone 3 tangled at cycle 7");
  });
  RunControl control = quiet_control(scratch);
  control.dump_interval = 0.1;
  const RunResult result = run(simulation, control);
  EXPECT_FALSE(result.completed);
  EXPECT_NE(result.message.find("zone 3 tangled"), std::string::npos) << result.message;
  const io_test::Json summary = io_test::parse_json_file(control.output_directory + "/summary.json");
  EXPECT_EQ(summary["status"].text, result.message);
  const auto entries = io_test::read_pvd(control.output_directory + "/sod.pvd");
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries.back().first, simulation.time());
  EXPECT_LT(simulation.time(), 0.1);
  const auto lines = io_test::split_lines(read_text(control.output_directory + "/history.csv"));
  EXPECT_EQ(std::stol(lines.back().substr(lines.back().find(',') + 1)), simulation.cycle());
}

TEST(RunDriver, WallClockCheckpointsAreWritten) {
  ScratchDirectory scratch("run_wall_checkpoint");
  Simulation simulation(io_test::sod_problem(10, 0.01));
  RunControl control = quiet_control(scratch);
  control.checkpoint_every_cycles = 0;
  control.checkpoint_every_seconds = 1e-9;
  ASSERT_TRUE(run(simulation, control).completed);
  const std::string checkpoint = control.output_directory + "/sod.checkpoint";
  ASSERT_TRUE(std::filesystem::exists(checkpoint));
  EXPECT_EQ(read_text(checkpoint).rfind("stagger checkpoint\n", 0), 0u);
}

std::vector<double> final_state(const Simulation& s) {
  std::vector<double> state;
  for (const auto field : {s.x(), s.y(), s.velocity_x(), s.velocity_y(), s.density(), s.pressure(),
                           s.specific_internal_energy(), s.artificial_viscosity()}) {
    state.insert(state.end(), field.begin(), field.end());
  }
  state.push_back(s.time());
  state.push_back(s.dt());
  state.push_back(s.energy().total);
  return state;
}

TEST(RunDriver, RestartFromACheckpointReachesBitwiseTheSameFinalState) {
  ScratchDirectory scratch("run_restart");
  const std::string saved = scratch.file("cycle20.checkpoint");
  RunControl control = quiet_control(scratch, "full");
  control.dump_interval = 0.025;
  control.checkpoint_every_cycles = 10;
  control.checkpoint_every_seconds = 0;
  control.history_every = 3;

  // Uninterrupted run; on cycle 21 the checkpoint of cycle 20 is set aside.
  Simulation full(io_test::sod_problem(40, 0.12));
  full.set_observer([&](const Simulation& s) {
    if (s.cycle() == 21) std::filesystem::copy_file(control.output_directory + "/sod.checkpoint", saved);
  });
  ASSERT_TRUE(run(full, control).completed);
  ASSERT_GT(full.cycle(), 30) << "the test needs the checkpoint to be mid-run";
  ASSERT_TRUE(std::filesystem::exists(saved));

  RunControl resumed_control = quiet_control(scratch, "resumed");
  resumed_control.dump_interval = control.dump_interval;
  resumed_control.checkpoint_every_cycles = 10;
  resumed_control.checkpoint_every_seconds = 0;
  resumed_control.history_every = 3;
  Simulation resumed(io_test::sod_problem(40, 0.12));
  const RunResult result = resume(resumed, resumed_control, saved);
  ASSERT_TRUE(result.completed) << result.message;

  EXPECT_EQ(resumed.cycle(), full.cycle());
  const auto a = final_state(full);
  const auto b = final_state(resumed);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0) << "final states differ";
  // The driver's own state continues too: same history rows and the same .pvd.
  EXPECT_EQ(read_text(control.output_directory + "/history.csv"),
            read_text(resumed_control.output_directory + "/history.csv"));
  // Restarted into another directory, the .pvd lists the dumps that are there: the full run's
  // series from the first dump after the checkpoint on, the same times and files.
  const auto full_entries = io_test::read_pvd(control.output_directory + "/sod.pvd");
  const auto entries = io_test::read_pvd(resumed_control.output_directory + "/sod.pvd");
  ASSERT_FALSE(entries.empty());
  ASSERT_LT(entries.size(), full_entries.size());
  EXPECT_TRUE(std::equal(entries.begin(), entries.end(), full_entries.end() - static_cast<long>(entries.size())));
  for (const auto& [time, file] : entries)
    EXPECT_TRUE(std::filesystem::exists(resumed_control.output_directory + "/" + file)) << file;
  // The restarted run's own checkpoint restarts again (a later end time, a third directory).
  RunControl again_control = quiet_control(scratch, "again");
  again_control.dump_interval = control.dump_interval;
  Simulation again(io_test::sod_problem(40, 0.15));
  const RunResult again_result = resume(again, again_control, resumed_control.output_directory + "/sod.checkpoint");
  EXPECT_TRUE(again_result.completed) << again_result.message;
  EXPECT_EQ(entries.back().first, 0.12);
  EXPECT_TRUE(std::filesystem::exists(resumed_control.output_directory + "/" + entries.back().second));
}

TEST(RunDriver, CorruptOrForeignCheckpointsAreRejected) {
  ScratchDirectory scratch("run_bad_checkpoint");
  RunControl control = quiet_control(scratch);
  control.checkpoint_every_cycles = 5;
  {
    Simulation simulation(io_test::sod_problem(10, 0.01));
    ASSERT_TRUE(run(simulation, control).completed);
  }
  const std::string checkpoint = control.output_directory + "/sod.checkpoint";
  const std::string good = read_text(checkpoint);

  write_file_atomically(scratch.file("junk.checkpoint"), "hello");
  Simulation a(io_test::sod_problem(10, 0.01));
  EXPECT_THROW(resume(a, control, scratch.file("junk.checkpoint")), Error);

  write_file_atomically(scratch.file("short.checkpoint"), good.substr(0, good.size() / 2));
  Simulation b(io_test::sod_problem(10, 0.01));
  try {
    resume(b, control, scratch.file("short.checkpoint"));
    FAIL() << "expected stagger::Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("short.checkpoint"), std::string::npos) << error.what();
  }

  Problem other = io_test::sod_problem(10, 0.01);
  other.name = "another_scene";
  Simulation c(std::move(other));
  EXPECT_THROW(resume(c, control, checkpoint), Error);

  Simulation d(io_test::sod_problem(10, 0.01));
  EXPECT_THROW(resume(d, control, scratch.file("does_not_exist.checkpoint")), Error);
}

}  // namespace
}  // namespace stagger
