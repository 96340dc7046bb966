// `stagger bench scaling` (docs/parallel.md, "Measurements"): strong scaling of Sedov on
// 1 rank x 1 thread, 2 ranks x 1 thread and 1 rank x 2 threads, the halo figures of the
// distributed runs (messages, bytes and seconds per cycle and rank, from ranks.csv), and the
// bitwise check of an 8-rank oversubscribed run against the serial one. Every run is a
// `stagger run` child process (under mpirun for the distributed ones). Beside them, the
// machine's own 1 -> 2 core scaling: the memory bandwidth and compute probes (bench_probe.hpp).
#include "bench_scaling.hpp"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "bench_probe.hpp"
#include "stagger/output.hpp"

namespace stagger::cli::bench {

namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A number of summary.json ("key": value).
double json_number(const std::string& json, const std::string& key) {
  const std::string tag = "\"" + key + "\": ";
  const std::size_t at = json.find(tag);
  if (at == std::string::npos) return 0;
  return std::strtod(json.c_str() + at + tag.size(), nullptr);
}

double load_average() {
  double load = 0;
  if (FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf", &load) != 1) load = 0;
    std::fclose(f);
  }
  return load;
}

std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

struct Measurement {
  std::string name;
  int ranks = 1, threads = 1;
  std::string status = "not run";
  double zones = 0, cycles = 0, loop_seconds = 0, load = 0;
  // per cycle, the largest over the ranks (docs/parallel.md): messages and bytes sent, halo seconds
  double messages = 0, bytes = 0, halo_seconds = 0, ghost_fraction = 0;
  // Peak resident set (docs/parallel.md, "Memory"): the sum over the ranks (ranks.csv), or
  // the run's own when serial.
  double peak_bytes = 0;
  // The probes' rates (bytes/s of the triad, flop/s of the compute loop); 0 for the Sedov runs.
  double bandwidth = 0, flops = 0;
  bool probe = false;  // a probe's row: zones and cycles are its elements (iterations) and passes
};

// std::system, and the peak resident set of the largest process the command ran (wait4).
int system_with_peak(const std::string& command, double& peak_bytes) {
  const pid_t child = fork();
  if (child == 0) {
    execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  if (child < 0 || wait4(child, &status, 0, &usage) != child) return -1;
  peak_bytes = 1024.0 * static_cast<double>(usage.ru_maxrss);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Runs `stagger run` (under mpirun when ranks > 1) into `out`; fills the measurement.
void run(const std::string& stagger, const fs::path& scene, const std::string& sets, int ranks, int threads,
         const fs::path& out, Measurement& m) {
  fs::remove_all(out);
  fs::create_directories(out);
  std::string command = "OMP_NUM_THREADS=" + std::to_string(threads) + " ";
  if (ranks > 1) command += "mpirun --oversubscribe -x OMP_NUM_THREADS -np " + std::to_string(ranks) + " ";
  command += quoted(stagger) + " run " + quoted(scene.string()) + " --quiet --out " + quoted(out.string()) + " " +
             sets + " > " + quoted((out / "run.log").string()) + " 2>&1";
  m.ranks = ranks;
  m.threads = threads;
  m.load = load_average();
  const int code = system_with_peak(command, m.peak_bytes);
  const std::string summary = read_text(out / "summary.json");
  m.status = code == 0 && summary.find("\"status\": \"completed\"") != std::string::npos ? "completed" : "failed";
  if (m.status == "failed") {
    // Say why here, not only in the log: e.g. mpirun's refusal to run as root.
    std::istringstream log(read_text(out / "run.log"));
    std::string line, first;
    while (first.empty() && std::getline(log, line))
      if (line.find_first_not_of("- \t") != std::string::npos) first = line;
    std::cerr << "stagger bench: scaling: a run failed: " << (first.empty() ? "no output" : first) << " (see "
              << (out / "run.log").string() << ")\n";
  }
  m.zones = json_number(summary, "zones");
  m.cycles = json_number(summary, "cycles");
  m.loop_seconds = json_number(summary, "loop_seconds");
  // ranks.csv: rank, owned_zones, ghost_zones, owned_points, ghost_points, neighbours,
  // exchanges, messages, bytes, halo_seconds, loop_seconds, cycles
  std::istringstream rows(read_text(out / "ranks.csv"));
  std::string line;
  std::getline(rows, line);
  double rank_peaks = 0;
  while (std::getline(rows, line)) {
    std::vector<double> v;
    std::istringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ',')) v.push_back(std::strtod(field.c_str(), nullptr));
    if (v.size() < 12 || !(v[11] > 0)) continue;
    m.messages = std::max(m.messages, v[7] / v[11]);
    m.bytes = std::max(m.bytes, v[8] / v[11]);
    m.halo_seconds = std::max(m.halo_seconds, v[9] / v[11]);
    m.ghost_fraction = std::max(m.ghost_fraction, v[2] / std::max(1.0, v[1]));
    if (v.size() > 12) rank_peaks += v[12];
  }
  if (ranks > 1) m.peak_bytes = rank_peaks;
}

std::string median_of(std::vector<double> values, double& median) {
  std::sort(values.begin(), values.end());
  median = values.empty() ? 0 : values[values.size() / 2];
  std::ostringstream text;
  text.precision(4);
  for (std::size_t i = 0; i < values.size(); ++i) text << (i ? " " : "") << values[i];
  return text.str();
}

}  // namespace

int scaling_suite(const fs::path& scenes, const fs::path& out_dir, bool quick, int repeat) {
  const std::string stagger = fs::read_symlink("/proc/self/exe").string();
  const fs::path sedov = scenes / "sedov.toml";
  // Sedov n x n for a fixed number of cycles' worth of time (docs/parallel.md): 1M zones (the
  // size of the 2-rank targets), 24 cycles, so that the first cycle's fresh force evaluation
  // is a small part of the loop; --quick: 40 000 zones, 42 cycles.
  const int n = quick ? 200 : 1000;
  const std::string sets =
      "--set mesh.nx=" + std::to_string(n) + " --set mesh.ny=" + std::to_string(n) +
      " --set time.end=" + (quick ? std::string("2e-3") : std::string("1.8e-4")) +
      " --set output.dumps=false --set output.checkpoints=false --set output.history_every=1000000";
  if (repeat < 1) repeat = quick ? 1 : 3;
  std::vector<Measurement> all;
  std::ostringstream report;
  // The machine's own scaling first (bench_probe.hpp): the triad over 3 arrays of 128 MiB
  // (together 12x the 32 MiB last-level cache of the machine in docs/parallel.md; --quick:
  // 32 MiB each), and the compute loop; each by 1 process, 2 processes at once and 2 threads.
  const long triad_elements = quick ? (1L << 22) : (1L << 24);
  const int triad_passes = quick ? 5 : 10;
  const long compute_iterations = quick ? 10'000'000L : 50'000'000L;
  struct ProbeConfig {
    std::string name;
    int workers;
    bool threads;
  };
  const std::vector<ProbeConfig> probe_configs = {
      {"1 process", 1, false}, {"2 processes", 2, false}, {"2 threads", 2, true}};
  std::map<std::string, double> triad_rate, compute_rate;  // medians by "1 process", ...
  for (const ProbeKind kind : {ProbeKind::triad, ProbeKind::compute}) {
    const bool is_triad = kind == ProbeKind::triad;
    std::map<std::string, double>& rates = is_triad ? triad_rate : compute_rate;
    for (const ProbeConfig& c : probe_configs) {
      std::vector<double> values;
      for (int k = 0; k < repeat; ++k) {
        Measurement m;
        m.name = std::string(is_triad ? "triad " : "compute ") + c.name;
        m.probe = true;
        m.ranks = c.threads ? 1 : c.workers;
        m.threads = c.threads ? c.workers : 1;
        m.zones = static_cast<double>(is_triad ? triad_elements : compute_iterations);
        m.cycles = is_triad ? triad_passes : 1;
        m.load = load_average();
        std::cerr << "[scaling] " << m.name << " (" << k + 1 << "/" << repeat << "), load " << m.load << "\n";
        const ProbeResult r =
            run_probe(kind, c.workers, c.threads, is_triad ? triad_elements : compute_iterations, triad_passes);
        m.loop_seconds = r.seconds;
        m.status = r.ok ? "completed" : "failed";
        if (!r.ok) std::cerr << "stagger bench: scaling: " << m.name << ": " << r.message << "\n";
        (is_triad ? m.bandwidth : m.flops) = r.ok ? r.rate() : 0;
        if (r.ok) values.push_back(r.rate());
        all.push_back(m);
      }
      double median = 0;
      median_of(values, median);
      rates[c.name] = median;
    }
    const double one = rates["1 process"];
    const auto ratio = [&](const std::string& name) {
      std::ostringstream text;
      text.precision(3);
      text << (one > 0 ? rates[name] / one : 0.0);
      return text.str();
    };
    const double unit = 1e9;
    const auto precision = report.precision(4);
    report << (is_triad ? "  memory bandwidth (triad a = b + 3 c, 3 arrays of " +
                              std::to_string(triad_elements * 8 / (1 << 20)) + " MiB, 24 bytes per element): "
                        : std::string("  compute (32 chains x = x m + d in registers): "))
           << "1 process " << one / unit << (is_triad ? " GB/s" : " Gflop/s") << ", 2 processes "
           << rates["2 processes"] / unit << " (" << ratio("2 processes") << "x), 2 threads "
           << rates["2 threads"] / unit << " (" << ratio("2 threads") << "x), medians\n";
    report.precision(precision);
  }
  struct Config {
    std::string name;
    int ranks, threads;
  };
  const std::vector<Config> configs = {
      {"1 rank x 1 thread", 1, 1}, {"2 ranks x 1 thread", 2, 1}, {"1 rank x 2 threads", 1, 2}};
  std::map<std::string, double> median_rate;
  std::map<std::string, double> peak;
  // Rounds, each running every configuration once: on a shared machine the load drifts over
  // minutes, and runs of one configuration back to back would each see a different part of it.
  // Each round also gives a paired speed-up (the two runs next to each other in time).
  std::map<std::string, std::vector<double>> rates;   // completed runs by configuration, in round order
  std::map<std::string, std::vector<double>> paired;  // per round: rate / the round's 1-rank rate
  for (int k = 0; k < repeat; ++k) {
    std::map<std::string, double> round;
    for (const Config& c : configs) {
      Measurement m;
      m.name = c.name;
      std::cerr << "[scaling] sedov " << n << "x" << n << " " << c.name << " (" << k + 1 << "/" << repeat << "), load "
                << load_average() << "\n";
      // Appended, not `"r" + ...`: g++ 12 warns (-Wrestrict) wrongly on that sum once inlined here.
      std::string dir = "r";
      dir += std::to_string(c.ranks);
      dir += 't';
      dir += std::to_string(c.threads);
      run(stagger, sedov, sets, c.ranks, c.threads, out_dir / "scaling_runs" / dir, m);
      if (m.status == "completed" && m.loop_seconds > 0) {
        round[c.name] = m.zones * m.cycles / m.loop_seconds;
        rates[c.name].push_back(round[c.name]);
      }
      if (m.status == "completed") peak[c.name] = std::max(peak[c.name], m.peak_bytes / m.zones);
      all.push_back(m);
    }
    const double base = round["1 rank x 1 thread"];
    if (base > 0)
      for (const Config& c : configs)
        if (round[c.name] > 0) paired[c.name].push_back(round[c.name] / base);
  }
  for (const Config& c : configs) {
    double median = 0;
    const std::string list = median_of(rates[c.name], median);
    median_rate[c.name] = median;
    report << "  " << c.name << ": median " << median << " zone-cycles/s (runs: " << list << "), peak memory "
           << peak[c.name] << " bytes per zone\n";
  }
  for (const Config& c : configs) {
    if (c.name == "1 rank x 1 thread") continue;
    double median = 0;
    const std::string list = median_of(paired[c.name], median);
    report << "  " << c.name << " / 1 rank x 1 thread, run beside it in each round: median " << median
           << " (rounds: " << list << ")\n";
  }
  // Correctness: 8 ranks oversubscribed against the serial run, bit for bit.
  const std::string small =
      "--set mesh.nx=40 --set mesh.ny=40 --set time.end=0.05 --set output.dumps=false --set output.checkpoints=false";
  Measurement serial, eight;
  serial.name = "correctness serial";
  eight.name = "correctness 8 ranks";
  std::cerr << "[scaling] sedov 40x40: serial and 8 ranks (oversubscribed), bitwise\n";
  run(stagger, sedov, small, 1, 1, out_dir / "scaling_runs" / "serial", serial);
  run(stagger, sedov, small, 8, 1, out_dir / "scaling_runs" / "np8", eight);
  const bool identical = serial.status == "completed" && eight.status == "completed" &&
                         read_text(out_dir / "scaling_runs" / "serial" / "history.csv") ==
                             read_text(out_dir / "scaling_runs" / "np8" / "history.csv");
  const bool both_ran = serial.status == "completed" && eight.status == "completed";
  eight.status = identical ? "bitwise_as_serial" : both_ran ? "DIFFERS_FROM_SERIAL" : "failed";
  all.push_back(serial);
  all.push_back(eight);

  std::ostringstream csv;
  csv.precision(10);
  csv << "run,ranks,threads,zones,cycles,loop_seconds,zone_cycles_per_second,load_average,messages_per_cycle,"
         "bytes_per_cycle,halo_seconds_per_cycle,ghost_fraction,peak_rss_bytes,status,bandwidth_bytes_per_second,"
         "compute_flops_per_second\n";
  for (const Measurement& m : all)
    csv << m.name << "," << m.ranks << "," << m.threads << "," << m.zones << "," << m.cycles << "," << m.loop_seconds
        << "," << (m.loop_seconds > 0 && !m.probe ? m.zones * m.cycles / m.loop_seconds : 0) << "," << m.load << ","
        << m.messages << "," << m.bytes << "," << m.halo_seconds << "," << m.ghost_fraction << "," << m.peak_bytes
        << "," << m.status << "," << m.bandwidth << "," << m.flops << "\n";
  const fs::path csv_path = out_dir / "scaling.csv";
  write_file_atomically(csv_path.string(), csv.str());
  const double one = median_rate["1 rank x 1 thread"];
  std::cout << "stagger bench: scaling: Sedov " << n << " x " << n << ", " << repeat << " run(s) each\n"
            << report.str();
  if (one > 0)
    std::cout << "  speed-up 2 ranks / 1 rank: " << median_rate["2 ranks x 1 thread"] / one
              << ", 2 threads / 1 thread: " << median_rate["1 rank x 2 threads"] / one << "\n";
  // The machine's ceilings beside them (docs/parallel.md, "Speed").
  const auto gain = [](std::map<std::string, double>& rate, const std::string& who) {
    return rate["1 process"] > 0 ? rate[who] / rate["1 process"] : 0.0;
  };
  std::cout << "  the machine from 1 to 2 cores: memory bandwidth " << gain(triad_rate, "2 processes")
            << "x (2 processes), " << gain(triad_rate, "2 threads") << "x (2 threads); compute "
            << gain(compute_rate, "2 processes") << "x (2 processes), " << gain(compute_rate, "2 threads")
            << "x (2 threads)\n";
  std::cout << "  8 ranks (oversubscribed) vs serial, Sedov 40 x 40: "
            << (identical  ? "history.csv identical"
                : both_ran ? "history.csv DIFFERS"
                           : "a run failed")
            << "\n"
            << "  -> " << csv_path.string() << "\n";
  int failed = identical ? 0 : 1;
  for (const Measurement& m : all)
    if (m.status == "failed") ++failed;
  return failed;
}

}  // namespace stagger::cli::bench
