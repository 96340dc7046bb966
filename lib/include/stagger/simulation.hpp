#pragma once
/// @file simulation.hpp
/// A running problem: the compatible staggered Lagrangian step (docs/algorithm.md §1),
/// time-step control, boundary conditions, the energy audit, and read-only views of the state.
#include <array>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stagger/problem.hpp"
#include "stagger/remap.hpp"

namespace stagger {

/// Total energy bookkeeping: relative_error = (E - E0 - W) / max(E0, |W|, E).
struct EnergyAudit {
  double kinetic = 0, internal = 0;  ///< sum_p m_p |v_p|^2 / 2 and sum_z m_z e_z
  double total = 0, initial = 0;     ///< E = kinetic + internal, and E at t = 0 (E0)
  double boundary_work = 0;          ///< work done on the mesh by boundary conditions
  double source_work = 0;            ///< work of the manufactured sources
  /// Kinetic energy the ALE remap's fix-up moved into internal energy, cumulative (docs/ale.md);
  /// an exchange inside E, so not part of the error below. 0 for a Lagrangian run.
  double ale_fixup = 0;
  double relative_error = 0;  ///< round-off (~1e-15) for the compatible scheme
};

/// A problem being solved: owns the Problem, the state arrays and the per-cycle hooks.
/// Movable, not copyable. Independent Simulations share no mutable state, so several can
/// run in parallel threads; one Simulation must not be used from two threads at once.
/// The spans returned by the field accessors stay valid until the next step(),
/// advance_to() or restore(); mesh() and problem() as long as this object (not moved from).
class Simulation {
 public:
  /// Validates the problem (stagger::Error on bad input) and sets up the state at t = 0.
  explicit Simulation(Problem problem);
  ~Simulation();
  /// Moves the whole state, remap and observer included.
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

  double time() const;           ///< current time t
  long cycle() const;            ///< completed cycles (0 at set-up)
  double dt() const;             ///< the last step's dt (0 before the first)
  std::string dt_limit() const;  ///< what limited the last dt ("cfl zone 12", ...)

  const Problem& problem() const;  ///< the validated set-up (mesh positions as at t = 0)
  const Mesh& mesh() const;        ///< topology, tags and regions (positions: x(), y())

  /// @name Point fields (size mesh().num_points())
  ///@{
  std::span<const double> x() const;           ///< current point x
  std::span<const double> y() const;           ///< current point y
  std::span<const double> velocity_x() const;  ///< point velocity, x component
  std::span<const double> velocity_y() const;  ///< point velocity, y component
  std::span<const double> point_mass() const;  ///< Lagrangian point mass (constant)
  ///@}
  /// @name Zone fields (size mesh().num_zones(), zones in mesh order)
  ///@{
  std::span<const double> zone_mass() const;                 ///< Lagrangian zone mass (constant)
  std::span<const double> zone_area() const;                 ///< zone area of the current positions
  std::span<const double> density() const;                   ///< zone density m_z / A_z
  std::span<const double> pressure() const;                  ///< zone pressure from the EOS
  std::span<const double> specific_internal_energy() const;  ///< zone specific internal energy e
  std::span<const double> artificial_viscosity() const;      ///< zone artificial viscosity q of the last step
  std::span<const double> sound_speed() const;               ///< zone sound speed
  bool has_strength() const;                                 ///< some material has strength (stress arrays exist)
  std::span<const double> stress_xx() const;                 ///< deviatoric S_xx; empty without strength
  std::span<const double> stress_yy() const;                 ///< deviatoric S_yy; empty without strength
  std::span<const double> stress_xy() const;                 ///< deviatoric S_xy; empty without strength
  std::span<const double> plastic_strain() const;            ///< equivalent plastic strain; empty without strength
  bool has_burn() const;                                     ///< some material has a programmed burn
  std::span<const double> burn_fraction() const;             ///< empty without burn
  ///@}

  /// How a dumped array is written: a scalar, a component of a point vector (z = 0), or a
  /// component of the deviatoric stress (the dumps add its von Mises invariant after xy).
  enum class OutputRole { scalar, vector_x, vector_y, deviator_xx, deviator_yy, deviator_xy };
  /// One state array as the dumps write it (docs/output.md).
  struct OutputField {
    std::string_view name;   ///< array name in the .vtu files (a vector's two components carry its name)
    bool on_points = false;  ///< point array (else zone array)
    bool always = true;      ///< in every run (else only with strength or burn)
    OutputRole role = OutputRole::scalar;
    std::span<const double> values;  ///< valid as the field accessors above
  };
  /// The dumped arrays present in this run, in the order of the dumps (the state table,
  /// docs/architecture.md).
  std::vector<OutputField> output_fields() const;

  /// Energy audit of the current state (deterministic fixed-order sums).
  EnergyAudit energy() const;
  /// Total momentum sum_p m_p v_p.
  std::array<double, 2> momentum() const;

  /// @name Distributed runs (docs/parallel.md)
  /// A Simulation made by distribute() (stagger/parallel.hpp) holds one rank's zones and
  /// their ghosts: its field accessors and mesh() are that rank's part; step(), energy(),
  /// momentum() and gather() are collective (every rank calls them, in the same order).
  ///@{
  int rank() const;   ///< this rank (0 in a serial run)
  int ranks() const;  ///< the number of ranks (1 in a serial run)
  /// The whole state: this Simulation in a serial run; in a distributed run, on rank 0 a
  /// serial Simulation holding the gathered state (valid until the next gather()), null on
  /// the other ranks. A gathered state serves the field accessors, mesh(), energy(),
  /// momentum() and output_fields(); it does not carry the step's scratch or corner forces,
  /// so it is no source for checkpoint() (docs/parallel.md, "Memory").
  const Simulation* gather() const;
  /// The serial numbers of this part's zones and points, and which of its zones are ghosts
  /// (another rank's); empty in a serial run.
  std::span<const Index> global_zones() const;
  std::span<const Index> global_points() const;
  std::span<const unsigned char> ghost_zones() const;
  /// Collective: every rank passes a text (an error met, a decision; "" for none) and gets the
  /// text of the lowest rank whose text is not empty ("" when none is). Serial: `text`.
  std::string agree(const std::string& text) const;
  /// Collective: whether `local` is true on any rank (one integer reduction). Serial: `local`.
  bool any_rank(bool local) const;
  ///@}

  /// Installs a remap phase, called after each Lagrangian step (nullptr: none).
  void set_remap(std::shared_ptr<Remap> remap);
  /// Called after every completed cycle (after the remap), with this simulation; nullptr
  /// removes it. The observer moves with the state: after `Simulation b(std::move(a))` it is
  /// called with `b`.
  void set_observer(std::function<void(const Simulation&)> observer);

  /// Everything the next cycle reads (state, t, cycle, dt, previous forces, work, E(0)),
  /// as a binary blob, for a bitwise restart, with a digest of what defines the physics
  /// (mesh, materials, regions, boundary conditions, sources, numerics; docs/output.md).
  std::string checkpoint() const;
  /// Restores a blob from checkpoint(). Throws stagger::Error, naming `source` and leaving the
  /// state as it was, if the blob is malformed or its physics digest differs from this
  /// problem's (the message names each differing entry); the end time may differ.
  void restore(std::string_view blob, const std::string& source = "checkpoint");

  /// Implementation detail (opaque outside the library).
  struct Impl;
  friend struct DistributedAccess;  ///< the distributed runs' set-up (lib/src/parallel)

 private:
  /// The Lagrangian phase alone, without the built-in ALE (a distributed run's parts, whose
  /// ALE phase is the distributed one).
  struct LagrangianOnly {};
  Simulation(Problem problem, LagrangianOnly);
  std::unique_ptr<Impl> impl_;
};

}  // namespace stagger
