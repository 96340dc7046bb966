#pragma once
/// @file simulation.hpp
/// A running problem: the compatible staggered Lagrangian step (NUMERICS.md section 5),
/// time-step control, boundary conditions, the energy audit, and read-only views of the state.
#include <array>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "stagger/problem.hpp"
#include "stagger/remap.hpp"

namespace stagger {

/// Total energy bookkeeping: relative_error = (E - E0 - W) / max(E0, |W|, E).
struct EnergyAudit {
  double kinetic = 0, internal = 0, total = 0, initial = 0;
  double boundary_work = 0, source_work = 0;
  double relative_error = 0;
};

class Simulation {
public:
  /// Validates the problem (stagger::Error on bad input) and sets up the state at t = 0.
  explicit Simulation(Problem problem);
  ~Simulation();
  Simulation(Simulation&&) noexcept;
  Simulation& operator=(Simulation&&) noexcept;
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  /// One cycle with the controlled dt, never stepping past `t_stop` (default t_end).
  /// Throws stagger::Error when dt collapses, a zone tangles beyond retries, a state
  /// leaves its EOS domain or turns NaN; the state is then that of the last good cycle.
  void step(double t_stop = -1);
  /// Steps until time() == t (exactly).
  void advance_to(double t);
  bool finished() const;  ///< time() >= t_end

  double time() const;
  long cycle() const;
  double dt() const;             ///< the last step's dt (0 before the first)
  std::string dt_limit() const;  ///< what limited the last dt ("cfl zone 12", ...)

  const Problem& problem() const;
  const Mesh& mesh() const;

  // Point fields.
  std::span<const double> x() const;
  std::span<const double> y() const;
  std::span<const double> velocity_x() const;
  std::span<const double> velocity_y() const;
  std::span<const double> point_mass() const;
  // Zone fields.
  std::span<const double> zone_mass() const;
  std::span<const double> zone_area() const;
  std::span<const double> density() const;
  std::span<const double> pressure() const;
  std::span<const double> specific_internal_energy() const;
  std::span<const double> artificial_viscosity() const;
  std::span<const double> sound_speed() const;
  bool has_strength() const;
  std::span<const double> stress_xx() const;  ///< empty without strength
  std::span<const double> stress_yy() const;
  std::span<const double> stress_xy() const;
  std::span<const double> plastic_strain() const;
  bool has_burn() const;
  std::span<const double> burn_fraction() const;  ///< empty without burn

  EnergyAudit energy() const;
  std::array<double, 2> momentum() const;

  /// Installs a remap phase, called after each Lagrangian step (nullptr: none).
  void set_remap(std::shared_ptr<Remap> remap);
  /// Called after every completed cycle.
  void set_observer(std::function<void(const Simulation&)> observer);

  /// Everything the next cycle reads (state, t, cycle, dt, previous forces, work, E(0)),
  /// as a binary blob, for a bitwise restart.
  std::string checkpoint() const;
  /// Restores a blob from checkpoint(); throws stagger::Error if it belongs to another mesh.
  void restore(std::string_view blob);

  /// Implementation detail (opaque outside the library).
  struct Impl;

private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace stagger
