// The run driver: the time loop with its outputs (dumps, history, checkpoints, summary).
// It owns only the loop and the output schedule; the physics is Simulation::step().
#include "stagger/run.hpp"

#include <fcntl.h>
#include <omp.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <chrono>
#include <climits>
#include <cmath>
#include <csignal>
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

#include "driver/eta.hpp"
#include "driver/output_directory.hpp"
#include "io/atomic_file.hpp"
#include "io/byte_stream.hpp"
#include "stagger/error.hpp"
#include "stagger/simulation.hpp"

namespace stagger {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// ---- SIGINT / SIGTERM (RunControl::handle_signals): the handler only notes the signal; the
// loop ends after the cycle in progress. SA_RESETHAND: a second signal acts at once (the
// files stay whole: every write is atomic). ----

volatile std::sig_atomic_t pending_signal = 0;

extern "C" void note_signal(int number) {
  pending_signal = number;
}

/// Installs the handler for the life of a run and puts the previous handlers back after it.
class SignalGuard {
 public:
  explicit SignalGuard(bool enabled) : enabled_(enabled) {
    if (!enabled_) return;
    pending_signal = 0;
    struct sigaction action {};
    action.sa_handler = note_signal;
    action.sa_flags = SA_RESETHAND;
    sigemptyset(&action.sa_mask);
    ::sigaction(SIGINT, &action, &previous_int_);
    ::sigaction(SIGTERM, &action, &previous_term_);
  }
  ~SignalGuard() {
    if (!enabled_) return;
    ::sigaction(SIGINT, &previous_int_, nullptr);
    ::sigaction(SIGTERM, &previous_term_, nullptr);
  }
  SignalGuard(const SignalGuard&) = delete;
  SignalGuard& operator=(const SignalGuard&) = delete;

 private:
  bool enabled_;
  struct sigaction previous_int_ = {};
  struct sigaction previous_term_ = {};
};

// ---- checkpoint file (docs/output.md, "Checkpoints"): a text header, the format version,
// the fields in the binary format of io/byte_stream.hpp, then the FNV-1a 64 checksum of
// every byte before it ----

constexpr std::string_view checkpoint_magic = "stagger checkpoint\n";
constexpr std::uint64_t checkpoint_version = 2;
// A distributed run's checkpoint is a text manifest naming a file per rank (docs/output.md).
constexpr std::string_view manifest_magic = "stagger distributed checkpoint\n";

/// The run's own state beyond the simulation: what a restart needs to continue the same
/// output schedule (dump times and numbering, .pvd entries, history rows, timings).
struct DriverState {
  double next_dump_time = 0;    ///< time of the next scheduled dump
  std::int64_t dump_slot = 0;   ///< next_dump_time = dump_slot * dump_interval (or t_end)
  std::int64_t dump_count = 0;  ///< dumps written (the file number of the next one)
  double last_dump_time = -std::numeric_limits<double>::infinity();
  std::int64_t last_history_cycle = -1;
  double loop_seconds = 0;  ///< time loop, accumulated over restarts
  double wall_seconds = 0;  ///< whole run, accumulated over restarts (before this invocation)
};

// The name becomes file names in the output directory: no path separators, no "..", no
// control characters (the scene reader restricts it further, docs/scenes.md).
const std::string& checked_name(const std::string& name) {
  bool ok = !name.empty() && name.size() <= 255 && name.front() != '.' && name.find("..") == std::string::npos;
  for (char c : name) ok = ok && c != '/' && c != '\\' && static_cast<unsigned char>(c) >= 0x20 && c != 0x7f;
  if (!ok) throw Error("output name '" + name + "' is not usable as a file name (use letters, digits, '_', '-', '.')");
  return name;
}

class Driver {
 public:
  Driver(Simulation& simulation, const RunControl& control)
      : simulation_(simulation),
        control_(control),
        directory_(control.output_directory.empty() ? fs::path(".") : fs::path(control.output_directory)),
        root_(simulation.rank() == 0),
        // A distributed run: rank 0 writes every file; the others keep the series in memory.
        pvd_(root_ ? (directory_ / (checked_name(control.name) + ".pvd")).string()
                   : checked_name(control.name).substr(0, 0)),
        history_(root_ ? (directory_ / "history.csv").string() : std::string()),
        outputs_(directory_) {}
  Driver(const Driver&) = delete;
  Driver& operator=(const Driver&) = delete;

  /// Refuses a schedule with more than max_dumps dumps (before anything is written).
  void check_dump_count() const {
    const double t_end = simulation_.problem().t_end;
    const long count = estimated_dumps(control_, t_end);
    if (count > control_.max_dumps) {
      throw Error("output.dump_interval = " + format_number(control_.dump_interval) +
                  " with time.end = " + format_number(t_end) + " gives " + std::to_string(count) +
                  " dumps, more than output.max_dumps = " + std::to_string(control_.max_dumps) +
                  "; raise output.dump_interval (or output.max_dumps)");
    }
  }

  /// Rank 0 of the run takes the directory: made and probed, locked for the run, and refused
  /// if it holds another scene's results (docs/output.md, "One run per directory" and after).
  void take_directory(bool fresh) {
    outputs_.prepare();
    outputs_.lock();
    outputs_.claim(control_.name, scene_name(), control_.replace);
    if (fresh) outputs_.remove_outputs_of(control_.name);
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

  /// A checkpoint (serial) or the manifest of a distributed run's checkpoint (docs/output.md):
  /// loads this rank's file.
  void load_checkpoint(const std::string& path) {
    const std::string data = io_detail::read_file(path);
    const int ranks = simulation_.ranks();
    if (data.starts_with(manifest_magic)) {
      const Manifest manifest = read_manifest(path, data);
      if (manifest.ranks != ranks)
        throw Error("checkpoint '" + path + "' was written by a run on " + std::to_string(manifest.ranks) +
                    " ranks; restart it on as many (mpirun -np " + std::to_string(manifest.ranks) + ")" +
                    (ranks > 1 ? ", not " + std::to_string(ranks) : std::string(", not serially")));
      const fs::path piece = fs::path(path).parent_path() / piece_checkpoint_name(manifest.parity);
      load_checkpoint_file(piece.string());
      if (simulation_.cycle() != manifest.cycle)
        throw Error("checkpoint '" + piece.string() + "' is at cycle " + std::to_string(simulation_.cycle()) +
                    ", its manifest '" + path + "' at cycle " + std::to_string(manifest.cycle) +
                    ": the set is inconsistent; use another checkpoint or restart from t = 0");
      next_parity_ = 1 - manifest.parity;
      return;
    }
    if (ranks > 1 && data.starts_with(checkpoint_magic))
      throw Error("checkpoint '" + path + "' was written by a serial run; restart it on one rank, or run on " +
                  std::to_string(ranks) + " ranks from t = 0");
    load_checkpoint_file(path);
  }

  // The checks of a checkpoint file's own part (header, version, checksum, scene, driver
  // fields); returns the simulation state blob within `data`.
  std::string_view checked_driver_part(const std::string& data, const std::string& path, const std::string& source,
                                       DriverState& state, std::vector<std::pair<double, std::string>>& entries,
                                       std::string& history_rows) const {
    if (data.compare(0, checkpoint_magic.size(), checkpoint_magic) != 0) {
      throw Error("'" + path + "' is not a stagger checkpoint (wrong header)");
    }
    const std::string_view body = std::string_view(data).substr(checkpoint_magic.size());
    io_detail::ByteReader header(body, source);
    const std::uint64_t version = header.u64();
    // The checksum before anything else is believed; a file of another version has none
    // where this one's would be, so the version decides which error to give.
    bool intact = body.size() >= 16;
    if (intact) {
      io_detail::ByteReader trailer(body.substr(body.size() - 8), source);
      intact = trailer.u64() == io_detail::fnv1a64(std::string_view(data).substr(0, data.size() - 8));
    }
    if (version != checkpoint_version && (intact || version == 1)) {  // 1: before the checksum
      throw Error(source + " has format version " + std::to_string(version) + ", this build reads version " +
                  std::to_string(checkpoint_version) + "; restart from t = 0");
    }
    if (!intact) {
      throw Error(source +
                  " is corrupt or truncated (its checksum does not match); use another checkpoint or "
                  "restart from t = 0");
    }
    io_detail::ByteReader in(body.substr(0, body.size() - 8), source);
    in.u64();  // the version, checked above
    const std::string scene = in.bytes();
    if (scene != simulation_.problem().name) {
      throw Error(source + " was written by scene '" + scene + "', not '" + simulation_.problem().name +
                  "'; restart with the scene it came from");
    }
    state.next_dump_time = in.f64();
    state.dump_slot = in.i64();
    state.dump_count = in.i64();
    state.last_dump_time = in.f64();
    state.last_history_cycle = in.i64();
    state.loop_seconds = in.f64();
    state.wall_seconds = in.f64();
    entries.resize(in.count(16, ".pvd entries"));
    for (auto& [time, file] : entries) {
      time = in.f64();
      file = in.bytes();
    }
    history_rows = in.bytes();
    const std::string_view blob = in.bytes_view();
    in.expect_end();
    // The checksum guards against damage, not against a crafted file: every field that ends
    // up in the new run's files or schedule is checked against what a run can have written.
    check_driver_fields(source, state, entries, history_rows);
    return blob;
  }

  void load_checkpoint_file(const std::string& path) {
    // In a distributed run every rank reads its own piece: all of them reach the agreement
    // below, so that a missing, damaged or foreign piece on one rank stops every rank with its
    // message (docs/parallel.md) instead of leaving the others alone in the restore's collectives.
    std::string data, error;
    const std::string source = "checkpoint '" + path + "'";
    DriverState state;
    std::vector<std::pair<double, std::string>> entries;
    std::string history_rows;
    std::string_view blob;
    try {
      data = io_detail::read_file(path);
      blob = checked_driver_part(data, path, source, state, entries, history_rows);
    } catch (const Error& e) {
      error = e.what();
    }
    if (error = simulation_.agree(error); !error.empty()) throw Error(error);
    simulation_.restore(blob, source);
    const double t_end = simulation_.problem().t_end;
    if (!(t_end > simulation_.time())) {
      auto shortest = [](double value) {  // the digits that read back as `value`
        char text[32];
        return std::string(text, std::to_chars(text, text + sizeof text, value).ptr);
      };
      throw Error(source + " is at t = " + shortest(simulation_.time()) + ", but the scene's end time is " +
                  shortest(t_end) + ": a restart needs a later end time (time.end)");
    }
    state_ = state;
    pvd_.restore(std::move(entries));
    history_.restore(std::move(history_rows));
  }

  /// After a restart (rank 0): the .pvd names only the dumps that are in this directory (a
  /// restart into another directory starts its series at the restart).
  void keep_present_dumps() {
    std::vector<std::pair<double, std::string>> present;
    for (const auto& entry : pvd_.entries())
      if (outputs_.holds(entry.second)) present.push_back(entry);
    pvd_.restore(std::move(present));
  }

  void check_driver_fields(const std::string& source, const DriverState& state,
                           const std::vector<std::pair<double, std::string>>& entries,
                           const std::string& history_rows) const {
    auto refuse = [&](const std::string& what) {
      throw Error(source + " holds an impossible " + what +
                  "; it was not written by stagger (or was edited): use another checkpoint or restart from t = 0");
    };
    if (!std::isfinite(state.next_dump_time)) refuse("next dump time");
    if (state.dump_slot < 0) refuse("dump slot");
    // A run restarted into another directory lists fewer dumps than it has numbered.
    if (state.dump_count < static_cast<std::int64_t>(entries.size()))
      refuse("dump count (" + std::to_string(state.dump_count) + " for " + std::to_string(entries.size()) +
             " .pvd entries)");
    if (std::isnan(state.last_dump_time) || state.last_dump_time == std::numeric_limits<double>::infinity())
      refuse("last dump time");
    if (state.last_history_cycle < -1) refuse("history cycle");
    if (!(state.loop_seconds >= 0) || !(state.wall_seconds >= 0) || !std::isfinite(state.loop_seconds) ||
        !std::isfinite(state.wall_seconds))
      refuse("run time");
    for (const auto& [time, file] : entries) {
      if (!std::isfinite(time)) refuse(".pvd entry time");
      if (!driver_detail::is_output_of(control_.name, file)) refuse(".pvd entry '" + file + "'");
    }
    // history.csv: its header, then rows of numbers.
    const std::string header = HistoryWriter("").text();
    if (!history_rows.starts_with(header) ||
        history_rows.find_first_not_of("0123456789+-.,eEinfa\n", header.size()) != std::string::npos ||
        (history_rows.size() > header.size() && !history_rows.ends_with('\n')))
      refuse("history table");
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
    const SignalGuard signals(control_.handle_signals);
    int stopped_by = 0;

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
        bool by_time = control_.checkpoint_every_seconds > 0 &&
                       seconds_since(last_checkpoint) >= control_.checkpoint_every_seconds;
        // The ranks' clocks differ: a distributed run checkpoints when one rank's is due.
        if (control_.checkpoint_every_seconds > 0 && simulation_.ranks() > 1) by_time = simulation_.any_rank(by_time);
        if (by_cycles || by_time) {
          state_.loop_seconds = loop_seconds_before + seconds_since(loop_start);
          write_checkpoint();
          last_checkpoint = Clock::now();
        }
      }
      if (control_.progress && root_ && seconds_since(last_progress) >= progress_every) {
        print_progress(loop_start, loop_start_time, t_end, terminal);
        last_progress = Clock::now();
      }
      if (control_.handle_signals) {
        int number = pending_signal;
        // Every rank stops at the same cycle (mpirun forwards the signal, not always at once):
        // the ranks compare notes every 16th cycle, so the vote costs no collective on the others.
        if (simulation_.ranks() > 1) {
          const bool any = cycle % 16 == 0 && simulation_.any_rank(number != 0);
          number = !any ? 0 : number != 0 ? number : SIGTERM;
        }
        if (number != 0) {
          stopped_by = number;
          break;
        }
      }
    }
    state_.loop_seconds = loop_seconds_before + seconds_since(loop_start);
    if (control_.progress && root_ && terminal) {
      print_progress(loop_start, loop_start_time, t_end, terminal);
      std::fputc('\n', stderr);
    }

    if (stopped_by != 0) {
      // Interrupted: the state is a good one, so a checkpoint lets the run go on from here.
      char where[96];
      std::snprintf(where, sizeof where, "cycle %ld, t = %.9g", simulation_.cycle(), simulation_.time());
      failure = std::string("interrupted by ") + (stopped_by == SIGINT ? "SIGINT" : "SIGTERM") + " at " + where;
      if (control_.checkpoints) {
        write_checkpoint();
        failure += "; continue with --restart " + (directory_ / (control_.name + ".checkpoint")).string();
      }
    }
    // Final outputs: the last state is always recorded and dumped (also after a failure,
    // so that the user sees where it went wrong).
    if (state_.last_history_cycle != simulation_.cycle()) record_history();
    if (control_.dumps && state_.last_dump_time != simulation_.time()) dump();
    // A failed step commits nothing (docs/algorithm.md §9), so the state just dumped is the
    // last good one: say so in the .pvd, the summary and the message.
    if (!failure.empty() && stopped_by == 0 && control_.dumps && !pvd_.entries().empty()) {
      char where[96];
      std::snprintf(where, sizeof where, "cycle %ld, t = %.9g", simulation_.cycle(), simulation_.time());
      pvd_.mark_last_good_state(failure);
      failure += std::string("; the last good state (") + where + ") is dumped as '" +
                 (directory_ / pvd_.entries().back().second).string() + "'";
    }

    RunResult result;
    result.completed = failure.empty();
    result.message = failure;
    result.signal = stopped_by;
    RunSummary& summary = result.summary;
    if (control_.dumps && !pvd_.entries().empty()) {
      summary.last_dump = pvd_.entries().back().second;
      summary.last_dump_time = pvd_.entries().back().first;
      summary.last_good_state = !result.completed;
    }
    summary.scene = scene_name();
    summary.loop_seconds = state_.loop_seconds;
    summary.threads = omp_get_max_threads();
    summary.ranks = simulation_.ranks();
    summary.status = failure.empty() ? "completed" : stopped_by != 0 ? "interrupted" : failure;
    const Simulation* whole = simulation_.gather();  // the whole state (rank 0; null elsewhere)
    if (control_.reference && whole) {
      try {
        control_.reference(*whole, summary.errors, summary.diagnostics);
      } catch (const Error& error) {
        summary.diagnostics.emplace_back("reference_failed", std::numeric_limits<double>::quiet_NaN());
        if (result.completed) summary.status = std::string("reference failed: ") + error.what();
      }
    }
    history_.flush();
    summary.wall_seconds = state_.wall_seconds + seconds_since(start_);
    if (whole) write_summary((directory_ / "summary.json").string(), *whole, summary);
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
    const int ranks = simulation_.ranks();
    std::string file = control_.name + number + ".vtu";
    if (ranks > 1 && !control_.gather_dumps) {
      // A piece per rank, then the .pvtu once every piece is written (docs/output.md).
      std::vector<std::string> pieces;
      for (int r = 0; r < ranks; ++r) {
        char piece[32];
        std::snprintf(piece, sizeof piece, "_r%04d.vtu", r);
        pieces.push_back(control_.name + number + piece);
      }
      file = control_.name + number + ".pvtu";
      std::string pvtu, error;
      try {
        pvtu = write_vtu_piece((directory_ / pieces[simulation_.rank()]).string(), simulation_, pieces);
      } catch (const Error& e) {
        error = e.what();
      }
      if (error = simulation_.agree(error); !error.empty()) throw Error(error);
      if (root_) write_file_atomically((directory_ / file).string(), pvtu);
    } else if (const Simulation* whole = simulation_.gather()) {
      write_vtu((directory_ / file).string(), *whole);
    }
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
    io_detail::ByteWriter out;
    out.raw(checkpoint_magic);
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
    out.u64(io_detail::fnv1a64(out.data()));
    const fs::path manifest = directory_ / (control_.name + ".checkpoint");
    if (simulation_.ranks() == 1) {
      write_file_atomically(manifest.string(), out.data());
      return;
    }
    // A distributed run: a file per rank, then the manifest naming them. The files alternate
    // between two sets, so the manifest always names a complete set (docs/output.md).
    std::string error;
    try {
      write_file_atomically((directory_ / piece_checkpoint_name(next_parity_)).string(), out.data());
    } catch (const Error& e) {
      error = e.what();
    }
    if (error = simulation_.agree(error); !error.empty()) throw Error(error);
    if (root_)
      write_file_atomically(manifest.string(),
                            std::string(manifest_magic) + "ranks " + std::to_string(simulation_.ranks()) + "\ncycle " +
                                std::to_string(simulation_.cycle()) + "\nset " + std::to_string(next_parity_) + "\n");
    next_parity_ = 1 - next_parity_;
  }

  /// This rank's checkpoint file of set `parity` (a distributed run).
  std::string piece_checkpoint_name(int parity) const {
    char suffix[48];
    std::snprintf(suffix, sizeof suffix, ".checkpoint.%d.r%04d", parity, simulation_.rank());
    return control_.name + suffix;
  }

  struct Manifest {
    int ranks = 0, parity = 0;
    long cycle = 0;
  };
  static Manifest read_manifest(const std::string& path, const std::string& data) {
    Manifest m;
    char tail = 0;
    const std::string body = data.substr(manifest_magic.size());
    if (std::sscanf(body.c_str(), "ranks %d\ncycle %ld\nset %d%c", &m.ranks, &m.cycle, &m.parity, &tail) != 4 ||
        tail != '\n' || m.ranks < 2 || (m.parity != 0 && m.parity != 1) || m.cycle < 0)
      throw Error("checkpoint manifest '" + path +
                  "' is corrupt (expected the lines 'ranks N', 'cycle C', 'set 0|1'); use another checkpoint or "
                  "restart from t = 0");
    return m;
  }

  void print_progress(Clock::time_point loop_start, double loop_start_time, double t_end, bool terminal) {
    const double t = simulation_.time();
    const double elapsed = seconds_since(loop_start);
    // The time to go from the recent trend of dt (driver/eta.hpp), the average rate so far
    // until there are samples enough.
    eta_.add(t, simulation_.dt(), simulation_.cycle(), elapsed);
    double remaining = eta_.seconds_to(t_end);
    if (remaining < 0 && t > loop_start_time && elapsed > 0) remaining = elapsed * (t_end - t) / (t - loop_start_time);
    char eta[32] = "?";
    if (remaining >= 0) std::snprintf(eta, sizeof eta, "%.0f s", remaining);
    std::fprintf(
        stderr,
        terminal ? "\rcycle %ld  t = %.6e  dt = %.3e  ETA %s      " : "cycle %ld  t = %.6e  dt = %.3e  ETA %s\n",
        simulation_.cycle(), t, simulation_.dt(), eta);
    std::fflush(stderr);
  }

  /// The scene's name as summary.json gives it.
  std::string scene_name() const {
    return simulation_.problem().name.empty() ? control_.name : simulation_.problem().name;
  }

  static std::string format_number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", value);
    return text;
  }

  Simulation& simulation_;
  const RunControl& control_;
  fs::path directory_;
  bool root_ = true;  // rank 0 of a distributed run (or a serial run): writes the files
  PvdWriter pvd_;
  HistoryWriter history_;
  driver_detail::OutputDirectory outputs_;  // declared after directory_: built from it
  DriverState state_;
  int next_parity_ = 0;  // the set of a distributed run's next checkpoint files
  Clock::time_point start_ = Clock::now();
  EtaEstimate eta_;  // the progress line's time to go
};

}  // namespace

long estimated_dumps(const RunControl& control, double t_end) {
  if (!control.dumps) return 0;
  if (!(control.dump_interval > 0) || !(t_end > 0)) return 2;
  const double between = std::floor(t_end / control.dump_interval);
  if (!(between < static_cast<double>(LONG_MAX) - 2)) return LONG_MAX;  // also NaN
  return static_cast<long>(between) + 2;
}

RunResult run(Simulation& simulation, const RunControl& control) {
  control.validate();
  Driver driver(simulation, control);
  driver.check_dump_count();
  std::string error;
  try {
    if (simulation.rank() == 0) {  // a distributed run's shared files are rank 0's
      driver.take_directory(true);
    }
  } catch (const Error& e) {
    error = e.what();
  }
  // Every rank waits for the directory (its pieces go there) and stops on its errors.
  if (error = simulation.agree(error); !error.empty()) throw Error(error);
  driver.start_fresh();
  return driver.loop();
}

RunResult resume(Simulation& simulation, const RunControl& control, const std::string& checkpoint) {
  control.validate();
  Driver driver(simulation, control);
  driver.check_dump_count();
  std::string error;
  try {
    driver.load_checkpoint(checkpoint);
    if (simulation.rank() == 0) {
      driver.take_directory(false);
      driver.keep_present_dumps();
    }
  } catch (const Error& e) {
    error = e.what();
  }
  // The same error on every rank of a distributed run (the lowest rank's).
  if (error = simulation.agree(error); !error.empty()) throw RestartError(error);
  return driver.loop();
}

}  // namespace stagger
