// The run driver: the time loop with its outputs (dumps, history, checkpoints, summary).
// It owns only the loop and the output schedule; the physics is Simulation::step().
#include "stagger/run.hpp"

#include <omp.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/atomic_file.hpp"
#include "stagger/error.hpp"
#include "stagger/simulation.hpp"

namespace stagger {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// ---- checkpoint file: a text header, then length-prefixed binary fields ----

constexpr std::string_view checkpoint_magic = "stagger checkpoint\n";
constexpr std::uint32_t checkpoint_version = 1;

class ByteWriter {
public:
  void u64(std::uint64_t value) { raw(&value, sizeof value); }
  void i64(std::int64_t value) { raw(&value, sizeof value); }
  void f64(double value) { raw(&value, sizeof value); }  // bit pattern: bitwise restart
  void bytes(std::string_view text) {
    u64(text.size());
    out_.append(text.data(), text.size());
  }
  std::string& text() { return out_; }

private:
  void raw(const void* data, std::size_t size) { out_.append(static_cast<const char*>(data), size); }
  std::string out_;
};

class ByteReader {
public:
  ByteReader(std::string_view data, std::string path) : data_(data), path_(std::move(path)) {}
  std::uint64_t u64() { return pod<std::uint64_t>(); }
  std::int64_t i64() { return pod<std::int64_t>(); }
  double f64() { return pod<double>(); }
  std::string bytes() {
    const std::uint64_t size = u64();
    need(size);
    std::string text(data_.substr(position_, size));
    position_ += size;
    return text;
  }
  bool at_end() const { return position_ == data_.size(); }

private:
  template <class T>
  T pod() {
    need(sizeof(T));
    T value;
    std::memcpy(&value, data_.data() + position_, sizeof(T));
    position_ += sizeof(T);
    return value;
  }
  void need(std::uint64_t size) const {
    if (size > data_.size() - position_) {
      throw Error("checkpoint '" + path_ + "' is truncated or corrupt; use another checkpoint or restart from t = 0");
    }
  }
  std::string_view data_;
  std::size_t position_ = 0;
  std::string path_;
};

/// The run's own state beyond the simulation: what a restart needs to continue the same
/// output schedule (dump times and numbering, .pvd entries, history rows, timings).
struct DriverState {
  double next_dump_time = 0;   ///< time of the next scheduled dump
  std::int64_t dump_slot = 0;  ///< next_dump_time = dump_slot * dump_interval (or t_end)
  std::int64_t dump_count = 0;  ///< dumps written (the file number of the next one)
  double last_dump_time = -std::numeric_limits<double>::infinity();
  std::int64_t last_history_cycle = -1;
  double loop_seconds = 0;  ///< time loop, accumulated over restarts
  double wall_seconds = 0;  ///< whole run, accumulated over restarts (before this invocation)
};

class Driver {
public:
  Driver(Simulation& simulation, const RunControl& control)
      : simulation_(simulation),
        control_(control),
        directory_(control.output_directory.empty() ? fs::path(".") : fs::path(control.output_directory)),
        pvd_((directory_ / (control.name + ".pvd")).string()),
        history_((directory_ / "history.csv").string()) {}

  void prepare_directory() const {
    std::error_code ec;
    fs::create_directories(directory_, ec);
    if (ec || !fs::is_directory(directory_)) {
      throw Error("cannot create output directory '" + directory_.string() + "': " +
                  (ec ? ec.message() : std::string("a file of that name exists")) +
                  "; choose a writable output directory (--out)");
    }
    // Permissions alone do not tell (read-only mounts, ACLs): write and remove a probe.
    const fs::path probe = directory_ / (".stagger-write-probe." + std::to_string(::getpid()));
    {
      std::ofstream out(probe, std::ios::binary | std::ios::trunc);
      out << "probe\n";
      out.close();
      if (!out) {
        std::error_code ignored;
        fs::remove(probe, ignored);
        throw Error("output directory '" + directory_.string() + "' is not writable (a test file could not be "
                    "created in it); choose a writable output directory (--out)");
      }
    }
    fs::remove(probe, ec);
    remove_stale_temporaries();
  }

  /// A process killed while writing leaves `.<name>.tmp.<pid>` behind: remove those whose
  /// process is gone (never another live writer's).
  void remove_stale_temporaries() const {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(directory_, ec)) {
      const std::string name = entry.path().filename().string();
      const bool ours = name.starts_with('.') && (name.find(".tmp.") != std::string::npos ||
                                                  name.starts_with(".stagger-write-probe."));
      if (!ours) continue;
      const std::string pid_text = name.substr(name.rfind('.') + 1);
      if (pid_text.empty() || pid_text.find_first_not_of("0123456789") != std::string::npos) continue;
      const long pid = std::stol(pid_text);
      if (pid == ::getpid()) continue;
      if (::kill(static_cast<pid_t>(pid), 0) == -1 && errno == ESRCH) {
        std::error_code ignored;
        fs::remove(entry.path(), ignored);
      }
    }
  }

  void start_fresh() {
    state_ = DriverState{};
    if (control_.dumps) {
      schedule_next_dump();
      dump();
    }
    record_history();
    history_.flush();
  }

  void load_checkpoint(const std::string& path) {
    const std::string data = io_detail::read_file(path);
    if (data.compare(0, checkpoint_magic.size(), checkpoint_magic) != 0) {
      throw Error("'" + path + "' is not a stagger checkpoint (wrong header)");
    }
    ByteReader in(std::string_view(data).substr(checkpoint_magic.size()), path);
    const auto version = in.u64();
    if (version != checkpoint_version) {
      throw Error("checkpoint '" + path + "' has version " + std::to_string(version) + ", this build reads version " +
                  std::to_string(checkpoint_version));
    }
    const std::string scene = in.bytes();
    if (scene != simulation_.problem().name) {
      throw Error("checkpoint '" + path + "' was written by scene '" + scene + "', not '" +
                  simulation_.problem().name + "'; restart with the scene it came from");
    }
    DriverState state;
    state.next_dump_time = in.f64();
    state.dump_slot = in.i64();
    state.dump_count = in.i64();
    state.last_dump_time = in.f64();
    state.last_history_cycle = in.i64();
    state.loop_seconds = in.f64();
    state.wall_seconds = in.f64();
    std::vector<std::pair<double, std::string>> entries(in.u64());
    for (auto& [time, file] : entries) {
      time = in.f64();
      file = in.bytes();
    }
    std::string history_rows = in.bytes();
    const std::string blob = in.bytes();
    if (!in.at_end()) throw Error("checkpoint '" + path + "' has trailing data; it is corrupt");
    simulation_.restore(blob);
    state_ = state;
    pvd_.restore(std::move(entries));
    history_.restore(std::move(history_rows));
  }

  RunResult loop() {
    const double t_end = simulation_.problem().t_end;
    const double loop_start_time = simulation_.time();
    const auto loop_start = Clock::now();
    const double loop_seconds_before = state_.loop_seconds;
    auto last_checkpoint = loop_start;
    // On a terminal the progress line is redrawn in place; in a log, one line every 10 s.
    const bool terminal = ::isatty(::fileno(stderr)) != 0;
    const double progress_every = terminal ? 0.2 : 10.0;
    auto last_progress = terminal ? loop_start - std::chrono::seconds(1) : loop_start;
    std::string failure;

    while (!simulation_.finished()) {
      const double t_stop = control_.dumps ? std::min(state_.next_dump_time, t_end) : t_end;
      try {
        simulation_.step(t_stop);
      } catch (const Error& error) {
        failure = error.what();
        break;
      }
      const long cycle = simulation_.cycle();
      if (control_.history_every > 0 && cycle % control_.history_every == 0) record_history();
      if (control_.dumps && dump_due()) {
        dump();
        schedule_next_dump();
      }
      if (control_.checkpoints) {
        const bool by_cycles = control_.checkpoint_every_cycles > 0 && cycle % control_.checkpoint_every_cycles == 0;
        const bool by_time =
            control_.checkpoint_every_seconds > 0 && seconds_since(last_checkpoint) >= control_.checkpoint_every_seconds;
        if (by_cycles || by_time) {
          state_.loop_seconds = loop_seconds_before + seconds_since(loop_start);
          write_checkpoint();
          last_checkpoint = Clock::now();
        }
      }
      if (control_.progress && seconds_since(last_progress) >= progress_every) {
        print_progress(loop_start, loop_start_time, t_end, terminal);
        last_progress = Clock::now();
      }
    }
    state_.loop_seconds = loop_seconds_before + seconds_since(loop_start);
    if (control_.progress && terminal) {
      print_progress(loop_start, loop_start_time, t_end, terminal);
      std::fputc('\n', stderr);
    }

    // Final outputs: the last state is always recorded and dumped (also after a failure,
    // so that the user sees where it went wrong).
    if (state_.last_history_cycle != simulation_.cycle()) record_history();
    if (control_.dumps && state_.last_dump_time != simulation_.time()) dump();

    RunResult result;
    result.completed = failure.empty();
    result.message = failure;
    RunSummary& summary = result.summary;
    summary.scene = simulation_.problem().name.empty() ? control_.name : simulation_.problem().name;
    summary.loop_seconds = state_.loop_seconds;
    summary.threads = omp_get_max_threads();
    summary.status = failure.empty() ? "completed" : failure;
    if (control_.reference) {
      try {
        control_.reference(simulation_, summary.errors, summary.diagnostics);
      } catch (const Error& error) {
        summary.diagnostics.emplace_back("reference_failed", std::numeric_limits<double>::quiet_NaN());
        if (result.completed) summary.status = std::string("reference failed: ") + error.what();
      }
    }
    history_.flush();
    summary.wall_seconds = state_.wall_seconds + seconds_since(start_);
    write_summary((directory_ / "summary.json").string(), simulation_, summary);
    return result;
  }

private:
  /// The time of dump slot k: k * dump_interval, or t_end for the last one (a slot closer
  /// to t_end than a millionth of the interval is merged with the final dump).
  double slot_time(std::int64_t k) const {
    const double t_end = simulation_.problem().t_end;
    const double interval = control_.dump_interval;
    if (interval <= 0) return t_end;
    const double t = static_cast<double>(k) * interval;
    return t >= t_end - 1e-6 * interval ? t_end : t;
  }

  /// Advances the schedule to the first slot strictly after the current time.
  void schedule_next_dump() {
    const double now = simulation_.time();
    const double t_end = simulation_.problem().t_end;
    while (slot_time(state_.dump_slot) <= now && slot_time(state_.dump_slot) < t_end) ++state_.dump_slot;
    state_.next_dump_time = slot_time(state_.dump_slot);
  }

  bool dump_due() const {
    // step(t_stop) lands on t_stop; allow a few ulps in case the time is accumulated.
    const double next = state_.next_dump_time;
    return simulation_.time() >= next - 8 * std::numeric_limits<double>::epsilon() * std::abs(next);
  }

  void dump() {
    char number[32];
    std::snprintf(number, sizeof number, "_%06lld", static_cast<long long>(state_.dump_count));
    const std::string file = control_.name + number + ".vtu";
    write_vtu((directory_ / file).string(), simulation_);
    pvd_.add(simulation_.time(), file);
    ++state_.dump_count;
    state_.last_dump_time = simulation_.time();
    history_.flush();
  }

  void record_history() {
    history_.record(simulation_);
    state_.last_history_cycle = simulation_.cycle();
  }

  void write_checkpoint() {
    history_.flush();
    ByteWriter out;
    out.text() = std::string(checkpoint_magic);
    out.u64(checkpoint_version);
    out.bytes(simulation_.problem().name);
    out.f64(state_.next_dump_time);
    out.i64(state_.dump_slot);
    out.i64(state_.dump_count);
    out.f64(state_.last_dump_time);
    out.i64(state_.last_history_cycle);
    out.f64(state_.loop_seconds);
    out.f64(state_.wall_seconds + seconds_since(start_));
    out.u64(pvd_.entries().size());
    for (const auto& [time, file] : pvd_.entries()) {
      out.f64(time);
      out.bytes(file);
    }
    out.bytes(history_.text());
    out.bytes(simulation_.checkpoint());
    write_file_atomically((directory_ / (control_.name + ".checkpoint")).string(), out.text());
  }

  void print_progress(Clock::time_point loop_start, double loop_start_time, double t_end, bool terminal) const {
    const double t = simulation_.time();
    const double elapsed = seconds_since(loop_start);
    char eta[32] = "?";
    if (t > loop_start_time && elapsed > 0) {
      const double remaining = elapsed * (t_end - t) / (t - loop_start_time);
      std::snprintf(eta, sizeof eta, "%.0f s", remaining);
    }
    std::fprintf(stderr, terminal ? "\rcycle %ld  t = %.6e  dt = %.3e  ETA %s      " : "cycle %ld  t = %.6e  dt = %.3e  ETA %s\n",
                 simulation_.cycle(), t, simulation_.dt(), eta);
    std::fflush(stderr);
  }

  Simulation& simulation_;
  const RunControl& control_;
  fs::path directory_;
  PvdWriter pvd_;
  HistoryWriter history_;
  DriverState state_;
  Clock::time_point start_ = Clock::now();
};

}  // namespace

RunResult run(Simulation& simulation, const RunControl& control) {
  Driver driver(simulation, control);
  driver.prepare_directory();
  driver.start_fresh();
  return driver.loop();
}

RunResult resume(Simulation& simulation, const RunControl& control, const std::string& checkpoint) {
  Driver driver(simulation, control);
  driver.load_checkpoint(checkpoint);
  driver.prepare_directory();
  return driver.loop();
}

}  // namespace stagger
