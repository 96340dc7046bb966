#pragma once
/// @file output.hpp
/// Output writers: VTK .vtu dumps and the .pvd time series, history.csv and summary.json.
/// Every file is written to a temporary name in the same directory and renamed, so that a
/// crash never leaves a half-written file.
#include <string>
#include <utility>
#include <vector>

#include "stagger/mesh.hpp"

namespace stagger {

class Simulation;

/// Named scalar results (error norms, diagnostics), in insertion order.
using NamedValues = std::vector<std::pair<std::string, double>>;

/// Writes `text` to `path` atomically (temporary file + rename). Throws stagger::Error.
void write_file_atomically(const std::string& path, const std::string& text);

/// Writes the current state as an unstructured grid (appended raw, zlib): points in double
/// precision; zone fields density, pressure, specific_internal_energy,
/// artificial_viscosity, sound_speed, region, (deviatoric_stress_xx/yy/xy, von_mises,
/// plastic_strain, burn_fraction where present); point field velocity (3 components).
void write_vtu(const std::string& path, const Simulation& simulation);
/// Writes a bare mesh (zone field region, and per-tag boundary markers as point fields).
void write_mesh_vtu(const std::string& path, const Mesh& mesh);

/// A ParaView collection (.pvd) listing every dump; rewritten whole after each add().
class PvdWriter {
public:
  explicit PvdWriter(std::string pvd_path);
  /// Records `vtu_file` (relative to the .pvd's directory) at `time` and rewrites the .pvd.
  void add(double time, const std::string& vtu_file);
  const std::vector<std::pair<double, std::string>>& entries() const { return entries_; }
  void restore(std::vector<std::pair<double, std::string>> entries) { entries_ = std::move(entries); }

private:
  std::string path_;
  std::vector<std::pair<double, std::string>> entries_;
};

/// One row per recorded cycle: time, cycle, dt, kinetic, internal, boundary_work,
/// source_work, total, relative_energy_error, momentum_x, momentum_y. Kept in memory and
/// rewritten atomically by flush().
class HistoryWriter {
public:
  explicit HistoryWriter(std::string csv_path);
  void record(const Simulation& simulation);
  void flush() const;
  const std::string& text() const { return rows_; }
  void restore(std::string rows) { rows_ = std::move(rows); }

private:
  std::string path_;
  std::string rows_;
};

/// Everything summary.json reports beyond the simulation's own state.
struct RunSummary {
  std::string scene;
  double wall_seconds = 0;       ///< whole run
  double loop_seconds = 0;       ///< time loop alone (for zone_cycles_per_second)
  int threads = 1;
  std::string status = "completed";  ///< or the error message that stopped the run
  NamedValues errors;
  NamedValues diagnostics;
};

/// Writes summary.json: scene, zones, points, cycles, t_end (the problem's), time (reached),
/// dt, dt_limit, wall_seconds, loop_seconds, zone_cycles_per_second (zones x cycles /
/// loop_seconds), threads, status, energy {initial, final, kinetic, internal, boundary_work,
/// source_work, relative_error}, momentum [x, y], errors {...}, diagnostics {...}.
/// Numbers round-trip exactly; non-finite numbers are written as null. docs/output.md.
void write_summary(const std::string& path, const Simulation& simulation, const RunSummary& summary);

}  // namespace stagger
