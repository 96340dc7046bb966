// The CI smoke test of `stagger bench` (docs/benchmarks.md): `stagger bench --quick` writes the CSVs
// with the required columns, every run keeps the energy audit at round-off, the quick
// ladders show the expected orders, and the plot script turns the CSVs into figures.
// Timings are reported by the bench, never asserted here.
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const std::string stagger_binary = STAGGER_BINARY_DIR "/bin/stagger";
const fs::path quick_out = fs::path(STAGGER_BINARY_DIR) / "tests" / "bench_quick";

using Row = std::map<std::string, std::string>;

struct Table {
  std::vector<std::string> header;
  std::vector<Row> rows;
};

// RFC 4180 fields: quoted fields may hold commas and doubled quotes.
std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

Table read_csv(const fs::path& path) {
  Table table;
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line)) return table;
  table.header = split_csv_line(line);
  while (std::getline(in, line)) {
    const auto fields = split_csv_line(line);
    Row row;
    for (std::size_t i = 0; i < table.header.size() && i < fields.size(); ++i) row[table.header[i]] = fields[i];
    table.rows.push_back(row);
  }
  return table;
}

// Runs the quick bench once per build of the binary: every test of this executable (ctest
// runs each in its own process) reuses the output, guarded by a lock and a stamp newer than
// the binary.
const fs::path& quick_bench_output() {
  static const fs::path output = [] {
    fs::create_directories(quick_out.parent_path());
    const std::string lock_path = quick_out.string() + ".lock";
    std::FILE* lock = std::fopen(lock_path.c_str(), "w");
    if (lock != nullptr) flock(fileno(lock), LOCK_EX);
    const fs::path stamp = quick_out / "stamp";
    const bool fresh = fs::exists(stamp) && fs::last_write_time(stamp) > fs::last_write_time(stagger_binary);
    if (!fresh) {
      fs::remove_all(quick_out);
      const std::string command = "'" + stagger_binary + "' bench --quick --out '" + quick_out.string() + "' > '" +
                                  quick_out.string() + ".log' 2>&1";
      if (std::system(command.c_str()) == 0) std::ofstream(stamp) << "ok\n";
    }
    if (lock != nullptr) {
      flock(fileno(lock), LOCK_UN);
      std::fclose(lock);
    }
    return quick_out;
  }();
  return output;
}

double number(const Row& row, const std::string& key) {
  const auto found = row.find(key);
  if (found == row.end() || found->second.empty()) return std::nan("");
  return std::strtod(found->second.c_str(), nullptr);
}

std::string python_with_matplotlib() {
  for (const std::string python : {"python3", "/usr/bin/python3"})
    if (std::system((python + " -c 'import matplotlib' > /dev/null 2>&1").c_str()) == 0) return python;
  return "";
}

TEST(BenchQuick, WritesOneCsvPerSuiteWithTheRequiredColumns) {
  const fs::path& out = quick_bench_output();
  ASSERT_TRUE(fs::exists(out / "stamp")) << "stagger bench --quick failed; see " << out.string() << ".log";
  const std::vector<std::string> required = {"suite",          "scene",       "option",       "threads",
                                             "zones",          "cycles",      "wall_seconds", "zone_cycles_per_second",
                                             "peak_rss_bytes", "energy_audit"};
  for (const std::string suite : {"ladders", "throughput", "stress"}) {
    const Table table = read_csv(out / (suite + ".csv"));
    ASSERT_FALSE(table.rows.empty()) << suite << ".csv has no rows";
    for (std::size_t i = 0; i < required.size(); ++i) {
      ASSERT_GT(table.header.size(), i);
      EXPECT_EQ(table.header[i], required[i]) << suite << ".csv column " << i;
    }
    for (const auto& row : table.rows) {
      EXPECT_EQ(row.at("suite"), suite);
      EXPECT_GT(number(row, "zones"), 0) << suite << " " << row.at("scene") << " " << row.at("option");
      EXPECT_GT(number(row, "cycles"), 0) << suite << " " << row.at("scene") << " " << row.at("option");
      // Peak RSS from the child's own /proc/self/status: at least the zones' state.
      EXPECT_GT(number(row, "peak_rss_bytes"), 100.0 * number(row, "zones"));
      EXPECT_GT(number(row, "zone_cycles_per_second"), 0);
    }
  }
  // The L1 density error is one of the measure columns of the ladders.
  const Table ladders = read_csv(out / "ladders.csv");
  EXPECT_NE(std::find(ladders.header.begin(), ladders.header.end(), "L1_density"), ladders.header.end());
  EXPECT_TRUE(fs::exists(out / "orders.csv"));
}

TEST(BenchQuick, LaddersAndThroughputRunsComplete) {
  const fs::path& out = quick_bench_output();
  for (const std::string suite : {"ladders", "throughput"})
    for (const auto& row : read_csv(out / (suite + ".csv")).rows)
      EXPECT_EQ(row.at("status"), "completed") << suite << " " << row.at("scene") << " " << row.at("option");
}

TEST(BenchQuick, EnergyAuditStaysAtRoundOffInEveryRun) {
  const fs::path& out = quick_bench_output();
  for (const std::string suite : {"ladders", "throughput", "stress"})
    for (const auto& row : read_csv(out / (suite + ".csv")).rows) {
      const double audit = number(row, "energy_audit");
      EXPECT_TRUE(std::isfinite(audit)) << suite << " " << row.at("scene");
      EXPECT_LT(audit, 1e-12) << suite << " " << row.at("scene") << " " << row.at("option");
    }
}

// Each quick stress case has one expected outcome (docs/benchmarks.md, "Stress"): the 20 %
// perturbed Sod mesh with bulk q and no hourglass control folds and must stop as tangled,
// naming the zone, cycle and time; Sedov at CFL 0.5 (the scene's subzonal pressures) and the
// 2000-cycle Sod runs must complete.
// A case the bench adds must be given its outcome here.
TEST(BenchQuick, StressRunsHaveTheirExpectedOutcome) {
  const fs::path& out = quick_bench_output();
  const Table stress = read_csv(out / "stress.csv");
  const std::map<std::string, std::string> expected = {
      {"sod perturb=0.2 seed=1", "tangled"},
      {"sedov cfl=0.5", "completed"},
      {"sod long 2000 cycles", "completed"},
      {"sod long 2000 cycles, hourglass 0.1", "completed"},
  };
  std::set<std::string> seen;
  for (const auto& row : stress.rows) {
    const std::string key = row.at("scene") + " " + row.at("option");
    const std::string& status = row.at("status");
    seen.insert(key);
    const auto outcome = expected.find(key);
    if (outcome == expected.end()) {
      ADD_FAILURE() << "stress case without an expected outcome: " << key << " (" << status << ")";
      continue;
    }
    if (outcome->second == "completed") {
      EXPECT_EQ(status, "completed") << key;
      // The long runs are capped by their cycle count (t_end = 1e4 is never reached).
      if (key.find("long 2000 cycles") == std::string::npos) {
        EXPECT_EQ(number(row, "time"), number(row, "t_end")) << key;
      }
    } else {
      EXPECT_EQ(status.rfind("stopped: ", 0), 0u) << key << ": " << status;
      for (const std::string& part :
           {outcome->second, std::string("zone "), std::string("cycle "), std::string("t = ")})
        EXPECT_NE(status.find(part), std::string::npos) << key << ": " << part << " missing in " << status;
    }
    if (key.find("long 2000 cycles") != std::string::npos) {
      EXPECT_EQ(number(row, "cycles"), 2000) << key;
    }
  }
  EXPECT_EQ(seen.size(), expected.size());
}

TEST(BenchQuick, QuickLadderOrdersAreInRange) {
  const Table orders = read_csv(quick_bench_output() / "orders.csv");
  int sod = 0, smooth = 0;
  for (const auto& row : orders.rows) {
    const double order = number(row, "order");
    if (row.at("scene") == "sod" && row.at("measure") == "L1_density") {
      ++sod;  // first order at the shock and contact
      EXPECT_GE(order, 0.6) << "sod refine " << row.at("refine_coarse") << " -> " << row.at("refine_fine");
      EXPECT_LE(order, 1.3) << "sod refine " << row.at("refine_coarse") << " -> " << row.at("refine_fine");
    }
    if (row.at("scene") == "smooth" && row.at("measure") == "L2_velocity") {
      ++smooth;  // second order on the smooth Taylor-Green vortex
      EXPECT_GE(order, 1.7) << "smooth refine " << row.at("refine_coarse") << " -> " << row.at("refine_fine");
    }
  }
  EXPECT_GE(sod, 1);
  EXPECT_GE(smooth, 1);
}

TEST(BenchQuick, PlotScriptWritesTheFigures) {
  const std::string python = python_with_matplotlib();
  if (python.empty()) GTEST_SKIP() << "no python3 with matplotlib";
  const fs::path figures = quick_bench_output() / "figures";
  fs::remove_all(figures);
  const std::string command = python + " '" STAGGER_SOURCE_DIR "/scripts/plot_benchmarks.py' --csv '" +
                              quick_bench_output().string() + "' --out '" + figures.string() + "' > /dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0);
  for (const std::string name : {"bench_work_precision.png", "bench_convergence.png", "bench_throughput.png",
                                 "bench_stress.md", "bench_orders.md"}) {
    ASSERT_TRUE(fs::exists(figures / name)) << name;
    EXPECT_GT(fs::file_size(figures / name), 100u) << name;
  }
}

TEST(BenchCommand, UnknownSuiteIsOneLineErrorAndExitOne) {
  const std::string command =
      "'" + stagger_binary + "' bench nosuch --out /tmp/never_written 2> '" + quick_out.string() + ".err'";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  std::ifstream in(quick_out.string() + ".err");
  std::string message((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(message.find("unknown suite 'nosuch'"), std::string::npos) << message;
  EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 1) << message;
}

TEST(BenchCommand, UnknownLadderIsOneLineErrorNamingTheLadders) {
  const std::string command = "'" + stagger_binary +
                              "' bench ladders --ladder sedov/nosuch --out /tmp/never_written 2> '" +
                              quick_out.string() + ".ladder.err'";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  std::ifstream in(quick_out.string() + ".ladder.err");
  std::string message((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(message.find("--ladder 'sedov/nosuch'"), std::string::npos) << message;
  EXPECT_NE(message.find("sedov/edge_ale"), std::string::npos) << message;  // the ALE ladders are listed
  EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 1) << message;
}

TEST(BenchCommand, ABadOverrideBecomesAFailedRowNotACrash) {
  fs::create_directories(quick_out.parent_path());
  const fs::path report = quick_out.string() + ".one";
  const std::string command = "'" + stagger_binary +
                              "' bench --one --scene '" STAGGER_SOURCE_DIR
                              "/apps/scenes/sod.toml' --set mesh.no_such_key=1 > '" +
                              report.string() + "'";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream in(report);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("status\tset-up failed: "), std::string::npos) << text;
  EXPECT_NE(text.find("no_such_key"), std::string::npos) << text;
}

}  // namespace
