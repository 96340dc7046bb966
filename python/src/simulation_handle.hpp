#pragma once
// The state behind a Python Simulation: the C++ Simulation, the scene's run settings, and the
// history and timings of the runs made from Python.
#include <optional>
#include <string>

#include "bindings.hpp"
#include "stagger/output.hpp"
#include "stagger/run.hpp"
#include "stagger/simulation.hpp"

namespace stagger_python {

struct SimulationHandle {
  explicit SimulationHandle(const stagger::Scene& scene);

  stagger::Simulation simulation;
  stagger::RunControl control;  ///< the scene's [output] settings and reference
  std::string scene_file;
  stagger::HistoryWriter history{""};  ///< the rows of the in-memory runs (memory only)
  long last_history_cycle = -1;
  /// What summary() reports beyond the state: timings and status of the last run, the last
  /// dump of a run that wrote files.
  stagger::RunSummary run_summary;
  std::string history_file;  ///< history.csv of the last run that wrote files ("" if none)

  void record_history();
  /// Starts the in-memory history afresh at the current state (set-up, restore).
  void restart_history();
};

/// Steps in memory to t_end or `until`, calling `callback(simulation)` after every cycle (a true
/// result stops the run); the GIL is released during each step. Returns the status text.
std::string advance(py::object self, std::optional<double> until, py::object callback, bool progress);

/// stagger::run() (or resume() from `restart`) into `directory`, the driver of `stagger run`:
/// the same files and bits as the CLI. The GIL is released; the callback runs after every cycle.
py::dict run_with_files(py::object self, const std::string& directory, const std::string& restart, py::object callback,
                        bool progress);

}  // namespace stagger_python
