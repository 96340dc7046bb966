// Atomic text files, the .pvd collection, history.csv and summary.json.
#include <sys/stat.h>

#include <cmath>
#include <limits>

#include "io_test_support.hpp"
#include "stagger/error.hpp"
#include "stagger/output.hpp"
#include "stagger/simulation.hpp"

namespace stagger {
namespace {

using io_test::read_text;
using io_test::ScratchDirectory;

TEST(AtomicFile, ReplacesContentWholeAndLeavesNoTemporaryFiles) {
  ScratchDirectory scratch("atomic");
  const std::string path = scratch.file("notes.txt");
  write_file_atomically(path, "first version, rather long\n");
  write_file_atomically(path, "second\n");
  EXPECT_EQ(read_text(path), "second\n");
  std::string binary("a\0b\n", 4);
  write_file_atomically(path, binary);
  EXPECT_EQ(read_text(path), binary);
  EXPECT_TRUE(io_test::temporary_files(scratch.path()).empty());
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(scratch.path())) ++files;
  EXPECT_EQ(files, 1);
}

TEST(AtomicFile, MissingDirectoryIsAnErrorNamingThePath) {
  ScratchDirectory scratch("atomic_missing");
  const std::string path = scratch.file("absent/notes.txt");
  try {
    write_file_atomically(path, "x");
    FAIL() << "expected stagger::Error";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
  }
}

TEST(AtomicFile, DirectoryThatIsARegularFileIsAnError) {
  ScratchDirectory scratch("atomic_file_dir");
  write_file_atomically(scratch.file("plain"), "x");
  const std::string path = scratch.file("plain/notes.txt");
  EXPECT_THROW(write_file_atomically(path, "x"), Error);
}

TEST(AtomicFile, UnwritableDirectoryIsAnError) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores directory permissions";
  ScratchDirectory scratch("atomic_readonly");
  const auto directory = scratch.path() / "readonly";
  std::filesystem::create_directories(directory);
  std::filesystem::permissions(directory, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  const std::string path = (directory / "notes.txt").string();
  try {
    write_file_atomically(path, "x");
    ADD_FAILURE() << "expected stagger::Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
  }
  std::filesystem::permissions(directory, std::filesystem::perms::owner_all);
}

TEST(PvdWriter, CollectionListsEveryDatasetWithItsTime) {
  ScratchDirectory scratch("pvd");
  const std::string path = scratch.file("run.pvd");
  PvdWriter pvd(path);
  pvd.add(0.0, "run_000000.vtu");
  EXPECT_EQ(io_test::read_pvd(path).size(), 1u);
  pvd.add(0.1, "run_000001.vtu");
  pvd.add(0.30000000000000004, "odd \"name\" & <more>.vtu");
  const std::string text = read_text(path);
  EXPECT_NE(text.find("<VTKFile type=\"Collection\""), std::string::npos);
  EXPECT_NE(text.find("</VTKFile>"), std::string::npos);
  EXPECT_NE(text.find("&quot;name&quot; &amp; &lt;more&gt;"), std::string::npos) << "attributes are escaped";
  const auto entries = io_test::read_pvd(path);
  ASSERT_EQ(entries.size(), 3u);
  EXPECT_EQ(entries[0].first, 0.0);
  EXPECT_EQ(entries[1].second, "run_000001.vtu");
  // 17 significant digits: the time survives the text round trip exactly.
  EXPECT_EQ(entries[2].first, 0.30000000000000004);
  EXPECT_EQ(pvd.entries().size(), 3u);
}

TEST(HistoryWriter, HeaderAndOneFullPrecisionRowPerRecord) {
  ScratchDirectory scratch("history");
  const std::string path = scratch.file("history.csv");
  Simulation simulation(io_test::sod_problem(10, 0.2));
  HistoryWriter history(path);
  history.record(simulation);
  for (int i = 0; i < 3; ++i) {
    simulation.step();
    history.record(simulation);
  }
  history.flush();
  const auto lines = io_test::split_lines(read_text(path));
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[0],
            "time,cycle,dt,kinetic,internal,boundary_work,source_work,total,relative_energy_error,momentum_x,"
            "momentum_y,ale_fixup");
  for (std::size_t row = 1; row < lines.size(); ++row) {
    std::vector<std::string> cells;
    std::stringstream line(lines[row]);
    for (std::string cell; std::getline(line, cell, ',');) cells.push_back(cell);
    ASSERT_EQ(cells.size(), 12u) << lines[row];
    EXPECT_EQ(std::stol(cells[1]), static_cast<long>(row - 1));
  }
  // The last row holds the simulation's values exactly (17 significant digits).
  std::vector<double> last;
  std::stringstream line(lines.back());
  for (std::string cell; std::getline(line, cell, ',');) last.push_back(std::stod(cell));
  EXPECT_EQ(last[0], simulation.time());
  EXPECT_EQ(last[2], simulation.dt());
  EXPECT_EQ(last[3], simulation.energy().kinetic);
  EXPECT_EQ(last[7], simulation.energy().total);
  EXPECT_GT(last[3], 0.0);
}

TEST(Summary, JsonIsWellFormedAndCarriesTheContractKeys) {
  ScratchDirectory scratch("summary");
  const std::string path = scratch.file("summary.json");
  Simulation simulation(io_test::sod_problem(10, 0.2));
  for (int i = 0; i < 4; ++i) simulation.step();
  RunSummary summary;
  summary.scene = "sod \"quoted\"\\ \n";
  summary.wall_seconds = 2.5;
  summary.loop_seconds = 0.5;
  summary.threads = 2;
  summary.status = "completed";
  summary.errors = {{"L1_density", 1.25e-3}, {"Linf_pressure", std::numeric_limits<double>::infinity()}};
  summary.diagnostics = {{"shock_position", 0.75}};
  write_summary(path, simulation, summary);

  const io_test::Json json = io_test::parse_json_file(path);
  for (const char* key :
       {"scene", "zones", "points", "cycles", "t_end", "time", "wall_seconds", "loop_seconds", "zone_cycles_per_second",
        "threads", "status", "energy", "momentum", "errors", "diagnostics"}) {
    EXPECT_TRUE(json.has(key)) << key;
  }
  EXPECT_EQ(json["scene"].text, summary.scene);
  EXPECT_EQ(json["zones"].number, 10);
  EXPECT_EQ(json["points"].number, 22);
  EXPECT_EQ(json["cycles"].number, 4);
  EXPECT_EQ(json["t_end"].number, 0.2);
  EXPECT_EQ(json["time"].number, simulation.time());
  EXPECT_DOUBLE_EQ(json["zone_cycles_per_second"].number, 10 * 4 / 0.5);
  for (const char* key :
       {"initial", "final", "kinetic", "internal", "boundary_work", "source_work", "ale_fixup", "relative_error"}) {
    EXPECT_TRUE(json["energy"].has(key)) << key;
  }
  EXPECT_EQ(json["energy"]["final"].number, simulation.energy().total);
  ASSERT_EQ(json["momentum"].items.size(), 2u);
  EXPECT_EQ(json["errors"]["L1_density"].number, 1.25e-3);
  EXPECT_EQ(json["errors"]["Linf_pressure"].kind, io_test::Json::Kind::null) << "non-finite numbers are null";
  EXPECT_EQ(json["diagnostics"]["shock_position"].number, 0.75);
}

}  // namespace
}  // namespace stagger
