#pragma once
/// @file run.hpp
/// The run driver: advances a Simulation to t_end, writing dumps (.vtu + .pvd), history.csv,
/// checkpoints and summary.json into an output directory. The `stagger run` command and
/// embedding codes use the same driver. Files (docs/output.md): `<name>_NNNNNN.vtu`,
/// `<name>.pvd`, `history.csv`, `summary.json`, `<name>.checkpoint`.
#include <functional>
#include <string>

#include "stagger/error.hpp"
#include "stagger/output.hpp"
#include "stagger/verify.hpp"

namespace stagger {

class Simulation;

/// What run() writes and where (a scene file's [output] section).
struct RunControl {
  std::string output_directory = "output";
  std::string name = "problem";          ///< base name of the .pvd and .vtu files
  double dump_interval = 0;              ///< time between dumps; 0 = only first and last
  bool dumps = true;                     ///< false: no .vtu/.pvd (benchmarks)
  int history_every = 1;                 ///< record history every N cycles
  long checkpoint_every_cycles = 500;    ///< 0 = never (by cycles)
  double checkpoint_every_seconds = 60;  ///< wall-clock; 0 = never (by time)
  bool checkpoints = true;
  /// A distributed run: rank 0 gathers each dump into one .vtu (the serial run's file)
  /// instead of a piece per rank and a .pvtu (docs/output.md).
  bool gather_dumps = false;
  /// Refuse a run whose schedule gives more dumps than this (a typo such as dump_interval
  /// = 1e-9 would otherwise write files until the disk is full). See estimated_dumps().
  long max_dumps = 10000;
  bool progress = false;  ///< a progress line on stderr
  /// Take an output directory that holds another scene's results by removing them (the CLI's
  /// --replace); without it such a directory is refused (docs/output.md).
  bool replace = false;
  /// SIGINT and SIGTERM end the run cleanly: the cycle finishes, a checkpoint and a final dump
  /// are written, the status says so (RunResult::signal). For programs that own their signals
  /// (the CLI); off by default, so that an embedding program's handlers are left alone.
  bool handle_signals = false;
  Reference reference;  ///< errors/diagnostics for summary.json (may be empty)
  /// Checks the ranges of output_option_table() (option_table.hpp); throws stagger::Error
  /// naming the option. run() and resume() call it.
  void validate() const;
};

/// The outcome of run() / resume().
struct RunResult {
  bool completed = false;  ///< t_end reached without error
  std::string message;     ///< the error that stopped the run, if any
  int signal = 0;          ///< SIGINT or SIGTERM if one ended the run early (handle_signals)
  RunSummary summary;      ///< what summary.json holds beyond the state (timings, errors)
};

/// The number of dumps the schedule gives up to `t_end`: the first and the last, and one
/// per dump_interval between (0 if dumps are off). Never overflows (saturates at LONG_MAX).
long estimated_dumps(const RunControl& control, double t_end);

/// Runs to t_end. On a stagger::Error mid-run it writes a final dump and the summary with
/// the error as status, and returns completed = false (it does not throw for run failures;
/// it throws for unusable output directories, a directory locked by another run, and more
/// than control.max_dumps dumps). The output directory is locked for the run (flock on
/// `.stagger.lock`); the previous run's `<name>.pvd` and `<name>_NNNNNN.vtu` there are
/// removed before the first dump (docs/output.md).
RunResult run(Simulation& simulation, const RunControl& control);

/// A checkpoint resume() cannot use (or an output directory it cannot take); in a
/// distributed run every rank throws the same one.
struct RestartError : Error {
  using Error::Error;
};

/// Resumes from a checkpoint written by run() and continues to t_end: `simulation` must be
/// built from the same scene (its name is checked, the mesh by Simulation::restore). The
/// output schedule, .pvd entries and history rows continue where the checkpoint left them,
/// so the result is bitwise that of an uninterrupted run. Throws stagger::Error for an
/// unreadable, corrupt or foreign checkpoint.
RunResult resume(Simulation& simulation, const RunControl& control, const std::string& checkpoint);

}  // namespace stagger
