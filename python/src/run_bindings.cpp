// The two ways a Python Simulation runs: stepping in memory with a per-cycle callback, or the
// library's run driver writing the output directory (docs/python.md, "Running").
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <utility>

#include "simulation_handle.hpp"

namespace stagger_python {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

bool truthy(const py::object& value) {
  const int result = PyObject_IsTrue(value.ptr());
  if (result < 0) throw py::error_already_set();
  return result == 1;
}

// A progress line on sys.stderr (so notebooks show it), redrawn twice a second.
class ProgressLine {
 public:
  ProgressLine(bool enabled, double t_stop) : enabled_(enabled), t_stop_(t_stop) {}
  void update(const stagger::Simulation& simulation, bool last = false) {
    if (!enabled_ || (!last && seconds_since(shown_) < 0.5)) return;
    char text[160];
    std::snprintf(text, sizeof text, "\rstagger: cycle %ld, t = %.6g of %.6g (%.0f%%), dt %.3g%s", simulation.cycle(),
                  simulation.time(), t_stop_, t_stop_ > 0 ? 100 * simulation.time() / t_stop_ : 100.0, simulation.dt(),
                  last ? "\n" : "");
    py::object stderr_stream = py::module_::import("sys").attr("stderr");
    stderr_stream.attr("write")(text);
    stderr_stream.attr("flush")();
    shown_ = Clock::now();
  }

 private:
  bool enabled_;
  double t_stop_;
  Clock::time_point shown_ = Clock::now() - std::chrono::seconds(1);
};

}  // namespace

std::string advance(py::object self, std::optional<double> until, py::object callback, bool progress) {
  SimulationHandle& handle = self.cast<SimulationHandle&>();
  stagger::Simulation& simulation = handle.simulation;
  const double t_stop = until ? std::min(*until, simulation.problem().t_end) : simulation.problem().t_end;
  ProgressLine line(progress, t_stop);
  const auto start = Clock::now();
  std::string failure;
  bool stopped = false;
  // The time and the last row are kept whatever ends the loop (callback error, Ctrl-C too).
  auto finish = [&] {
    handle.run_summary.loop_seconds += seconds_since(start);
    handle.run_summary.wall_seconds = handle.run_summary.loop_seconds;
    if (handle.last_history_cycle != simulation.cycle()) handle.record_history();
    line.update(simulation, true);
  };
  try {
    while (!simulation.finished() && simulation.time() < t_stop) {
      const double t_before = simulation.time();
      try {
        py::gil_scoped_release release;
        simulation.step(t_stop);
      } catch (const stagger::Error& error) {
        failure = error.what();
        break;
      }
      if (!(simulation.time() > t_before)) {  // never loop on a step that does not advance
        failure = "the step at t = " + std::to_string(t_before) + " did not advance the time";
        break;
      }
      const int every = handle.control.history_every;
      if (every > 0 && simulation.cycle() % every == 0) handle.record_history();
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // Ctrl-C
      line.update(simulation);
      if (!callback.is_none() && truthy(callback(self))) {
        stopped = true;
        break;
      }
    }
  } catch (...) {
    finish();
    throw;
  }
  finish();
  if (!failure.empty()) {
    handle.run_summary.status = failure;
    throw stagger::Error(failure);
  }
  handle.run_summary.status = simulation.finished() ? "completed" : stopped ? "stopped by the callback" : "paused";
  return handle.run_summary.status;
}

py::dict run_with_files(py::object self, const std::string& directory, const std::string& restart, py::object callback,
                        bool progress) {
  SimulationHandle& handle = self.cast<SimulationHandle&>();
  stagger::RunControl control = handle.control;
  if (!directory.empty()) control.output_directory = directory;
  control.progress = progress;
  // The observer runs inside the driver's loop with the GIL released: it takes the GIL, runs the
  // callback, and stops the run (a stagger::Error, which the driver reports as the run's status)
  // on a true result, a Python exception or Ctrl-C; the Python exception is raised afterwards.
  std::optional<py::error_already_set> python_error;
  handle.simulation.set_observer([&](const stagger::Simulation&) {
    py::gil_scoped_acquire acquire;
    bool stop = false;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      stop = !callback.is_none() && truthy(callback(self));
    } catch (py::error_already_set& error) {
      python_error.emplace(std::move(error));
      stop = true;
    }
    if (stop) throw stagger::Error(python_error ? "stopped by a Python exception" : "stopped by the callback");
  });
  stagger::RunResult result;
  try {
    py::gil_scoped_release release;
    result = restart.empty() ? stagger::run(handle.simulation, control)
                             : stagger::resume(handle.simulation, control, restart);
  } catch (...) {
    handle.simulation.set_observer(nullptr);
    throw;
  }
  handle.simulation.set_observer(nullptr);
  if (python_error) throw std::move(*python_error);
  handle.run_summary = result.summary;
  handle.history_file = control.output_directory + "/history.csv";
  py::dict outcome;
  outcome["completed"] = result.completed;
  outcome["message"] = result.message;
  outcome["directory"] = control.output_directory;
  return outcome;
}

}  // namespace stagger_python
