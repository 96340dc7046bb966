#pragma once
/// @file output.hpp
/// Output writers: VTK .vtu dumps and the .pvd time series, history.csv and summary.json.
/// Every file is written to a temporary name in the same directory and renamed, so that a
/// crash never leaves a half-written file.
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "stagger/mesh.hpp"

namespace stagger {

class Simulation;

/// Named scalar results (error norms, diagnostics), in insertion order.
using NamedValues = std::vector<std::pair<std::string, double>>;

/// Writes `text` to `path` atomically (temporary file, fdatasync, rename). Every write,
/// flush, close and rename is checked: a full disk throws stagger::Error naming `path`.
void write_file_atomically(const std::string& path, const std::string& text);
/// The same for a file written by someone else's code: `write(temporary)` writes it under a
/// temporary name in the same directory; if `expected_tail` is given, the file must end
/// with it (a writer that does not report its write errors leaves a truncated file on a full
/// disk); then it is flushed and renamed onto `path`. The temporary is removed on failure.
void write_file_atomically(const std::string& path, const std::function<void(const std::string&)>& write,
                           std::string_view expected_tail = {});

/// Writes the current state as an unstructured grid (appended raw, zlib): points in double
/// precision; zone fields density, pressure, specific_internal_energy,
/// artificial_viscosity, sound_speed, region, (deviatoric_stress_xx/yy/xy, von_mises,
/// plastic_strain, burn_fraction where present); point field velocity (3 components).
void write_vtu(const std::string& path, const Simulation& simulation);
/// A distributed run's dump (docs/output.md, "Distributed runs"): writes this rank's piece of
/// the state to `path` (atomically): the zones it owns and their points, the arrays of
/// write_vtu, then the zone fields `rank` and `zone_id` and the point field `point_id` (the
/// serial numbers). Returns the text of the .pvtu listing `pieces` (file names relative to
/// it) with the pieces' arrays, for rank 0 to write once every piece is written. On a serial
/// Simulation the piece is the whole mesh.
std::string write_vtu_piece(const std::string& path, const Simulation& part, const std::vector<std::string>& pieces);
/// Writes a bare mesh (zone field region, and per-tag boundary markers as point fields).
void write_mesh_vtu(const std::string& path, const Mesh& mesh);

/// A ParaView collection (.pvd) listing every dump; rewritten whole after each add().
class PvdWriter {
 public:
  /// An empty path keeps the series in memory only (a distributed run's ranks other than 0).
  explicit PvdWriter(std::string pvd_path);
  /// Records `vtu_file` (relative to the .pvd's directory) at `time` and rewrites the .pvd.
  void add(double time, const std::string& vtu_file);
  /// The (time, file) entries recorded so far.
  const std::vector<std::pair<double, std::string>>& entries() const { return entries_; }
  /// Replaces the entries (restart from a checkpoint); the file is rewritten on the next add().
  void restore(std::vector<std::pair<double, std::string>> entries) { entries_ = std::move(entries); }
  /// Marks the last entry as the last good state of a run that stopped (an XML comment after
  /// it, with `why`) and rewrites the .pvd.
  void mark_last_good_state(const std::string& why);

 private:
  void write() const;
  std::string path_;
  std::vector<std::pair<double, std::string>> entries_;
  std::string last_good_note_;
};

/// One row per recorded cycle: time, cycle, dt, kinetic, internal, boundary_work,
/// source_work, total, relative_energy_error, momentum_x, momentum_y, ale_fixup. Kept in memory and
/// rewritten atomically by flush().
class HistoryWriter {
 public:
  /// An empty path keeps the table in memory only (a distributed run's ranks other than 0).
  explicit HistoryWriter(std::string csv_path);
  /// Appends one row for the simulation's current state (in memory).
  void record(const Simulation& simulation);
  /// Writes the whole table to the .csv (atomically). Throws stagger::Error.
  void flush() const;
  /// The table so far (header line and rows), e.g. for a checkpoint.
  const std::string& text() const { return rows_; }
  /// Replaces the rows (restart from a checkpoint).
  void restore(std::string rows) { rows_ = std::move(rows); }

 private:
  std::string path_;
  std::string rows_;
};

/// Everything summary.json reports beyond the simulation's own state.
struct RunSummary {
  std::string scene;                 ///< scene file (or problem name)
  double wall_seconds = 0;           ///< whole run
  double loop_seconds = 0;           ///< time loop alone (for zone_cycles_per_second)
  int threads = 1;                   ///< OpenMP threads used (per rank)
  int ranks = 1;                     ///< MPI ranks (docs/parallel.md)
  std::string status = "completed";  ///< or the error message that stopped the run
  std::string last_dump;             ///< the last .vtu written (empty: dumps off)
  double last_dump_time = 0;         ///< its time
  /// The run stopped and the last dump holds its last good state (what was committed
  /// before the step that failed); docs/output.md.
  bool last_good_state = false;
  NamedValues errors;       ///< error norms from the reference (L1_density, ...)
  NamedValues diagnostics;  ///< other reference figures (shock position, ...)
};

/// Writes one CSV row per zone, in mesh order: zone, region (name), x, y (centre = vertex
/// average, docs/algorithm.md §2), r (= sqrt(x^2 + y^2)), area, density, pressure,
/// specific_internal_energy, velocity_x, velocity_y (mean of the zone's point velocities),
/// artificial_viscosity, sound_speed, then deviatoric_stress_xx/yy/xy, von_mises and
/// plastic_strain when the simulation has strength, and burn_fraction when it has a burn.
/// For profile plots and figure scripts (docs/verification.md). Written atomically.
void write_zone_csv(const std::string& path, const Simulation& simulation);

/// Writes summary.json: scene, zones, points, cycles, t_end (the problem's), time (reached),
/// dt, dt_limit, wall_seconds, loop_seconds, zone_cycles_per_second (zones x cycles /
/// loop_seconds), threads, status, energy {initial, final, kinetic, internal, boundary_work,
/// source_work, ale_fixup, relative_error}, momentum [x, y], errors {...}, diagnostics {...}.
/// Numbers round-trip exactly; non-finite numbers are written as null. docs/output.md.
void write_summary(const std::string& path, const Simulation& simulation, const RunSummary& summary);

}  // namespace stagger
