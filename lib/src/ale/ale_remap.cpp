// The built-in ALE phase (ale_remap.hpp; docs/ale.md): when to remap, the new mesh, the
// remap of the state table's remapped fields, the kinetic-energy fix-up, the radial return.
#include "ale/ale_remap.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "ale/remap.hpp"
#include "ale/rezone.hpp"
#include "hydro/boundary.hpp"
#include "hydro/kernels/subzonal_pressure.hpp"
#include "hydro/kernels/zone_status.hpp"
#include "stagger/error.hpp"
#include "state/state_table.hpp"
#include "strength/strength_models.hpp"

namespace stagger {

namespace {

// A point's displacement per remap sub-step stays below this fraction of its shortest edge,
// so that each swept region lies within the zones next to its face.
constexpr double kSubstepFraction = 0.25;
constexpr int kMaxSubsteps = 64;

class AleRemap final : public Remap {
 public:
  explicit AleRemap(Simulation::Impl& s);
  bool remap(RemapState& state) override;

 private:
  bool due() const;
  void new_positions();
  void remap_substeps(int steps);
  void remap_once(const double* xo, const double* yo, const double* xn, const double* yn);
  void fixup();
  double kinetic_losses();
  void pay_deficits_locally();
  void pay_deficits_globally();
  void share_to_zones();
  void bound_zone_shares();

  Simulation::Impl& s_;
  std::vector<int> zone_material_;
  Remapper remapper_;
  std::vector<char> lagrangian_;   // eulerian mode: points that follow the material
  RezoneConstraints constraints_;  // ale mode
  RezoneOptions rezone_options_;
  RezoneWorkspace workspace_;
  std::vector<StateArray> specific_;  // the zone fields carried per unit mass
  RemapFields fields_;                // kept so that a remap allocates nothing after the first
  std::vector<double> xn_, yn_, xa_, ya_, xb_, yb_, kinetic_, dk_, dE_;
  std::vector<std::int64_t> stamp_;  // fix-up: points already visited around a point (2 p, 2 p + 1)
  // The arrays a remap writes (those the state table marks remapped) as they were before it:
  // a remap whose fix-up cannot be paid puts them back, so that the run's final dump is the
  // last good state, not the failed remap's (docs/ale.md, "The kinetic-energy fix-up").
  std::vector<StateArray> written_;
  std::vector<std::vector<double>> before_;
};

std::vector<int> zone_materials(const Simulation::Impl& s) {
  std::vector<int> material(s.mesh().num_zones(), 0);
  for (const ZoneRange& r : s.ranges)
    for (Index z = r.begin; z < r.end; ++z) material[z] = r.material;
  return material;
}

AleRemap::AleRemap(Simulation::Impl& s)
    : s_(s), zone_material_(zone_materials(s)), remapper_(s.mesh(), zone_material_, s.rz) {
  const Mesh& m = s.mesh();
  const Index np = m.num_points(), nz = m.num_zones();
  // Every field the state table marks remapped is carried: the masses and velocities by
  // construction, every other zone field per unit mass.
  for (const StateField& f : state_fields()) {
    if (!(f.flags & kRemapped) || !present(s, f.presence)) continue;
    written_.push_back(f.member);
    before_.emplace_back();
    const std::string name = f.name;
    if (name == "vx" || name == "vy" || name == "point_mass" || name == "zone_mass" || name == "ale_corner_mass" ||
        name == "corner_mass")
      continue;
    if (f.entity != Entity::zone)
      throw Error(std::string("the ALE remap cannot carry the ") + f.name + " state array (not a zone field)");
    specific_.push_back(f.member);
  }
  // Eulerian mode: points on material interfaces, on periodic, free, pressure or velocity
  // boundaries follow the material; the others go back to their initial position.
  lagrangian_.assign(np, 0);
  for (Index p = 0; p < np; ++p) {
    const Index first = m.corner_zone[m.point_corners[m.point_corner_begin[p]]];
    for (Index k = m.point_corner_begin[p]; k < m.point_corner_begin[p + 1]; ++k)
      if (zone_material_[m.corner_zone[m.point_corners[k]]] != zone_material_[first]) lagrangian_[p] = 1;
  }
  for (const BoundaryCondition& bc : s.problem.boundaries) {
    if (bc.kind == BoundaryKind::wall) continue;
    for (Index p : m.tags[m.tag_index(bc.tag)].points) lagrangian_[p] = 1;
  }
  if (s.problem.ale.mode == AleMode::ale) {
    const AleOptions& o = s.problem.ale;
    if (o.remap_every == 0 && o.quality_trigger == 0)
      throw Error(
          "[ale] mode = \"ale\" with remap_every = 0 and quality_trigger = 0 would never remap: set one of them "
          "(docs/ale.md)");
    const std::vector<Index> material(zone_material_.begin(), zone_material_.end());
    constraints_ = make_rezone_constraints(
        m, s.problem.boundaries, material,
        o.rezone == AleRezone::winslow_regular ? WinslowLayout::regular : WinslowLayout::reference);
    rezone_options_.method =
        o.rezone == AleRezone::reference_jacobian ? RezoneMethod::reference_jacobian : RezoneMethod::winslow;
    rezone_options_.relaxation = o.relaxation;
    rezone_options_.iterations = o.rezone_iterations;
    rezone_options_.corner_angle_degrees = o.corner_angle;
    rezone_options_.max_move = o.max_move;
    rezone_options_.size_weight = o.size_weight;
  }
  if (s.rz) ale_axis_masses(s);
  for (auto* v : {&xn_, &yn_, &xa_, &ya_, &xb_, &yb_, &kinetic_, &dk_}) v->assign(np, 0.0);
  stamp_.assign(np, -1);
  dE_.assign(nz, 0.0);
}

bool AleRemap::due() const {
  const AleOptions& o = s_.problem.ale;
  if (o.mode == AleMode::eulerian) return true;
  // By the cycle number and the state alone, so that a restart remaps where the
  // uninterrupted run does.
  if (o.remap_every > 0 && s_.cycle % o.remap_every == 0) return true;
  if (o.quality_trigger <= 0) return false;
  // Only the worst zone matters: a min over the zones, the same in any order (and on any
  // number of threads), evaluated every cycle.
  const Mesh& m = s_.mesh();
  const Index nz = m.num_zones();
  double worst = std::numeric_limits<double>::infinity();
#pragma omp parallel for schedule(static) reduction(min : worst) if (nz > kParallelMin)
  for (Index z = 0; z < nz; ++z)
    worst = std::min(worst, zone_quality(m, z, QualityMeasure::reference_shape, s_.x, s_.y, m.x, m.y));
  return worst < o.quality_trigger;
}

void AleRemap::new_positions() {
  const Mesh& m = s_.mesh();
  const Index np = m.num_points();
  if (s_.problem.ale.mode == AleMode::ale) {
    rezone(m, constraints_, rezone_options_, s_.x, s_.y, m.x, m.y, xn_, yn_, workspace_);
    // rz: the axis points slide along the axis (exactly on it: the projection onto the
    // boundary segment may leave round-off).
    for (Index p : s_.axis_points) xn_[p] = 0;
    return;
  }
  // Eulerian: back to the initial mesh where the point may leave the material.
  for (Index p = 0; p < np; ++p) {
    xn_[p] = lagrangian_[p] ? s_.x[p] : m.x[p];
    yn_[p] = lagrangian_[p] ? s_.y[p] : m.y[p];
  }
}

// The remap from the current positions to (xn_, yn_), in `steps` sub-steps along the straight
// paths from the old to the new positions.
void AleRemap::remap_substeps(int steps) {
  if (steps == 1) {
    remap_once(s_.x.data(), s_.y.data(), xn_.data(), yn_.data());
    return;
  }
  const Index np = s_.mesh().num_points();
  std::copy(s_.x.begin(), s_.x.end(), xa_.begin());
  std::copy(s_.y.begin(), s_.y.end(), ya_.begin());
  for (int j = 1; j <= steps; ++j) {
    const double f = static_cast<double>(j) / steps;
    for (Index p = 0; p < np; ++p) {
      xb_[p] = j == steps ? xn_[p] : s_.x[p] + f * (xn_[p] - s_.x[p]);
      yb_[p] = j == steps ? yn_[p] : s_.y[p] + f * (yn_[p] - s_.y[p]);
    }
    remap_once(xa_.data(), ya_.data(), xb_.data(), yb_.data());
    std::swap(xa_, xb_);
    std::swap(ya_, yb_);
  }
}

void AleRemap::remap_once(const double* xo, const double* yo, const double* xn, const double* yn) {
  RemapFields& f = fields_;
  f.zone_mass = s_.zone_mass.data();
  f.corner_mass = s_.ale_corner_mass.data();
  f.point_mass = s_.point_mass.data();
  f.vx = s_.vx.data();
  f.vy = s_.vy.data();
  // The step swaps the current and new arrays: take the current buffers now.
  f.specific.clear();
  for (StateArray a : specific_) f.specific.push_back((s_.*a).data());
  f.point_kinetic = kinetic_.data();
  remapper_.remap(xo, yo, xn, yn, f, s_.problem.ale.limiter == AleLimiter::barth_jespersen);
  fixup();
}

// The kinetic-energy fix-up (DeBar 1974; Vachal & Shashkov): the kinetic energy the remap
// carried into each point's dual cell, minus the kinetic energy of its remapped (and
// constrained) momentum, goes to the internal energy of the zones around the point in
// proportion to their corner masses. Total energy is then conserved to round-off.
void AleRemap::fixup() {
  // The constraints (walls, pistons, periodic groups) act on the remapped velocities; the
  // kinetic energy they remove is part of the fix-up.
  apply_constraints(s_, s_.vx, s_.vy, s_.t);
  std::fill(dE_.begin(), dE_.end(), 0.0);
  const double moved = kinetic_losses();
  pay_deficits_locally();
  pay_deficits_globally();
  share_to_zones();
  bound_zone_shares();
  const Index nz = s_.mesh().num_zones();
  for (Index z = 0; z < nz; ++z)
    if (dE_[z] != 0) s_.e[z] = (s_.zone_mass[z] * s_.e[z] + dE_[z]) / s_.zone_mass[z];
  s_.ale_fixup += moved;
}

// Per point, the kinetic energy the remap carried minus that of its new momentum (dK); returns
// their sum, the kinetic energy moved to the internal energy.
double AleRemap::kinetic_losses() {
  const Index np = s_.mesh().num_points();
  double moved = 0;
  for (Index p = 0; p < np; ++p) {
    const double u = s_.vx[p], w = s_.vy[p];
    dk_[p] = kinetic_[p] - 0.5 * s_.point_mass[p] * (u * u + w * w);
    moved += dk_[p];
  }
  return moved;
}

// A second-order reconstruction can make dK_p negative at one point and positive at its
// neighbours (the total is a loss of kinetic energy, dK >= 0, for a first-order remap). A
// point's deficit is first paid by the positive dK of the points sharing a zone with it, in
// proportion to them, so that the fix-up stays local and no zone is cooled by a mere
// oscillation of the reconstruction. Points in order: the result is the same on any thread
// count.
void AleRemap::pay_deficits_locally() {
  const Mesh& m = s_.mesh();
  const Index np = m.num_points();
  // The visit tags 2 p and 2 p + 1 repeat from one fix-up to the next: a tag left by the last
  // call (a point whose neighbours had nothing to give) would skip a neighbour in this one.
  std::fill(stamp_.begin(), stamp_.end(), -1);
  const auto around = [&](Index p, std::int64_t tag, auto&& visit) {
    for (Index k = m.point_corner_begin[p]; k < m.point_corner_begin[p + 1]; ++k) {
      const Index z = m.corner_zone[m.point_corners[k]];
      for (Index c = m.zone_corner_begin[z]; c < m.zone_corner_begin[z + 1]; ++c) {
        const Index q = m.corner_point[c];
        if (q == p || stamp_[q] == tag) continue;
        stamp_[q] = tag;
        visit(q);
      }
    }
  };
  for (Index p = 0; p < np; ++p) {
    if (!(dk_[p] < 0)) continue;
    double supply = 0;
    around(p, 2 * std::int64_t(p), [&](Index q) { supply += std::max(dk_[q], 0.0); });
    if (!(supply > 0)) continue;
    const double take = std::min(-dk_[p], supply) / supply;
    double got = 0;
    around(p, 2 * std::int64_t(p) + 1, [&](Index q) {
      if (!(dk_[q] > 0)) return;
      const double g = take * dk_[q];
      dk_[q] -= g;
      got += g;
    });
    dk_[p] += got;
  }
}

// What the neighbours could not pay is paid by every point whose dK is still positive, in
// proportion to it: a move of kinetic-energy error between points, where the alternative is
// to cool the zones around the point (a cold zone by half its internal energy, remap after
// remap). When the remap as a whole lost kinetic energy (sum dK >= 0) every dK is then >= 0
// and no zone is cooled; otherwise the positive dK are used up and the zones pay the rest
// (bound_zone_shares). Sums in point order: the same on any thread count.
void AleRemap::pay_deficits_globally() {
  const Index np = s_.mesh().num_points();
  double owed = 0, supply = 0;
  for (Index p = 0; p < np; ++p) {
    if (dk_[p] < 0) owed -= dk_[p];
    if (dk_[p] > 0) supply += dk_[p];
  }
  if (!(owed > 0) || !(supply > 0)) return;
  const double paid = std::min(owed, supply);
  const double keep_supply = 1 - paid / supply, keep_owed = 1 - paid / owed;
  for (Index p = 0; p < np; ++p) dk_[p] *= dk_[p] > 0 ? keep_supply : keep_owed;
}

// Each point's dK to the zones around it, in proportion to their corner masses (dE per zone).
void AleRemap::share_to_zones() {
  const Mesh& m = s_.mesh();
  const Index np = m.num_points();
  for (Index p = 0; p < np; ++p) {
    const double dk = dk_[p];
    if (dk == 0) continue;
    double mass = 0;
    for (Index k = m.point_corner_begin[p]; k < m.point_corner_begin[p + 1]; ++k)
      mass += s_.ale_corner_mass[m.point_corners[k]];
    for (Index k = m.point_corner_begin[p]; k < m.point_corner_begin[p + 1]; ++k) {
      const Index c = m.point_corners[k];
      dE_[m.corner_zone[c]] += dk * (s_.ale_corner_mass[c] / mass);
    }
  }
}

// A zone may take a negative share only down to half of its internal energy above the
// floor (0 for an ideal gas; for other equations of state 0 or their min_energy if higher:
// the fix-up must not cool a cold solid into tension); the rest of the deficit is taken
// from all zones in proportion to their energy above the floor. Nothing is clipped: the
// total moved is exactly what the kinetic energy lost. Throws if the zones cannot pay it.
void AleRemap::bound_zone_shares() {
  const auto energy_floor = [&](const ZoneRange& r) {
    const Material& mat = s_.problem.materials[r.material];
    return std::holds_alternative<IdealGas>(mat.eos) ? 0.0 : std::max(mat.min_energy, 0.0);
  };
  double deficit = 0, capacity = 0;
  for (const ZoneRange& r : s_.ranges) {
    const double floor = energy_floor(r);
    for (Index z = r.begin; z < r.end; ++z) {
      const double room = s_.zone_mass[z] * std::max(s_.e[z] - floor, 0.0);
      if (dE_[z] < -0.5 * room) {
        deficit += dE_[z] + 0.5 * room;
        dE_[z] = -0.5 * room;
      }
      capacity += std::max(0.0, room + dE_[z]);
    }
  }
  if (!(deficit < 0)) return;
  if (!(capacity > -deficit)) {
    std::ostringstream msg;
    msg << "cycle " << s_.cycle << ", t = " << s_.t << ": the ALE remap's kinetic-energy fix-up must take " << -deficit
        << " from an internal energy of only " << capacity
        << " above the equations of state's floors (docs/ale.md): remap more often or relax less";
    throw Error(msg.str());
  }
  for (const ZoneRange& r : s_.ranges) {
    const double floor = energy_floor(r);
    for (Index z = r.begin; z < r.end; ++z) {
      const double room = std::max(0.0, s_.zone_mass[z] * std::max(s_.e[z] - floor, 0.0) + dE_[z]);
      dE_[z] += deficit * (room / capacity);
    }
  }
}

bool AleRemap::remap(RemapState&) {
  if (!due()) return false;
  const Mesh& m = s_.mesh();
  const Index np = m.num_points(), nz = m.num_zones();
  new_positions();
  bool moved = false;
  for (Index p = 0; p < np && !moved; ++p) moved = xn_[p] != s_.x[p] || yn_[p] != s_.y[p];
  if (!moved) return false;
  const int steps = remapper_.substeps(s_.x.data(), s_.y.data(), xn_.data(), yn_.data(), kSubstepFraction);
  if (steps > kMaxSubsteps) {
    std::ostringstream msg;
    msg << "cycle " << s_.cycle << ", t = " << s_.t << ": the ALE rezone moved points by more than "
        << kMaxSubsteps * kSubstepFraction << " of their shortest edge in one remap (docs/ale.md)";
    throw Error(msg.str());
  }
  for (std::size_t k = 0; k < written_.size(); ++k) {
    const std::vector<double>& now = s_.*written_[k];
    before_[k].assign(now.begin(), now.end());  // allocates at the first remap only
  }
  const double fixup_before = s_.ale_fixup;
  try {
    remap_substeps(steps);
  } catch (const Error&) {
    for (std::size_t k = 0; k < written_.size(); ++k) {
      std::vector<double>& now = s_.*written_[k];
      std::copy(before_[k].begin(), before_[k].end(), now.begin());
    }
    s_.ale_fixup = fixup_before;
    throw;
  }
  // The wall check's budgets (docs/algorithm.md §10) stay lower bounds of each point's
  // clearance if the move is subtracted from them, rounded down as a step's is: the next step
  // then tests only the points near a wall instead of all of them (docs/ale.md, "Remap cost").
  WallClearance& walls = s_.wall_clearance;
  if (walls.valid && walls.budget.size() == static_cast<std::size_t>(np)) {
    float* budget = walls.budget.data();
    const double *x = s_.x.data(), *y = s_.y.data(), *xn = xn_.data(), *yn = yn_.data();
#pragma omp parallel for schedule(static) if (np > kParallelMin)
    for (Index p = 0; p < np; ++p) {
      const double left = budget[p] - (std::abs(xn[p] - x[p]) + std::abs(yn[p] - y[p]));
      budget[p] = static_cast<float>(left - std::abs(left) * 0x1p-22);
    }
    walls.charged = true;
  }
  std::copy(xn_.begin(), xn_.end(), s_.x.begin());
  std::copy(yn_.begin(), yn_.end(), s_.y.begin());
  // The remapped deviatoric stress may lie outside the yield surface (a mix of stresses
  // inside a convex set stays inside it, but the linear reconstruction may step out):
  // radial return, without plastic work (nothing deformed): onto the zone's yield stress
  // Y0 + H eps_p as it is, adding no plastic strain (docs/algorithm.md §7).
  if (s_.any_strength) {
    for (const ZoneRange& r : s_.ranges) {
      const Material& mat = s_.problem.materials[r.material];
      if (!mat.strength) continue;
      return_to_yield_surface(*mat.strength, r.begin, r.end, s_.plastic.data(), s_.sxx.data(), s_.syy.data(),
                              s_.sxy.data());
    }
  }
  // Subzonal masses (the subzonal hourglass options): reset to the zone's remapped density on
  // the new subzones. Scaling the old ones by the zone's mass ratio would leave subzonal
  // densities that belong to the old mesh, whose pressure perturbations c^2 (rho_k - rho_z)
  // are large for a stiff material and push the next steps' corner forces (docs/algorithm.md
  // §18): the rezoned mesh has no hourglass distortion to resist.
  if (s_.rz) ale_axis_masses(s_);
  if (!s_.corner_mass.empty()) {
    const Subzones shape =
        s_.problem.options.hourglass == Hourglass::subzonal ? Subzones::corners : Subzones::triangles;
    for (Index z = 0; z < nz; ++z) {
      const Index b = m.zone_corner_begin[z];
      ZoneVertices v;
      v.n = static_cast<int>(m.zone_corner_begin[z + 1] - b);
      for (int k = 0; k < v.n; ++k) {
        v.x[k] = s_.x[m.corner_point[b + k]];
        v.y[k] = s_.y[m.corner_point[b + k]];
      }
      double cx, cy, t[kMaxZoneVertices], area = 0;
      subzonal_side_triangles(v, cx, cy, t);
      for (int k = 0; k < v.n; ++k) area += t[k];
      // rz: the planar subzone masses of the true density M / V (docs/algorithm.md §18, §19).
      subzonal_masses(v, s_.zone_mass[z] / (s_.rz ? RzGeometry::volume(v) : area), shape, s_.corner_mass.data() + b);
    }
  }
  // The lagged corner forces belong to the old mesh: the next predictor evaluates afresh.
  // Reusing them saves half a step per remap but a remap on the quality trigger moves points
  // far, and the stale predictor then folds zones (docs/ale.md, "Remap cost").
  s_.have_previous_forces = false;
  return true;
}

}  // namespace

// The planar mass of an axis corner is rho_c A_c = k_c A_c / V_c with its rz subcell mass k_c
// (carried by the remap, constant between remaps); A_c s_c / V_c is a shape factor (4 for a
// rectangle on the axis), taken from the initial mesh so that the result depends on the
// state table alone (a restart gives the same bits).
void ale_axis_masses(Simulation::Impl& s) {
  const Mesh& m = s.mesh();
  for (std::size_t i = 0; i < s.axis_points.size(); ++i) {
    for (Index j = s.axis_corner_begin[i]; j < s.axis_corner_begin[i + 1]; ++j) {
      const Index c = s.axis_corner[j], z = m.corner_zone[c], b = m.zone_corner_begin[z];
      ZoneVertices v;
      v.n = static_cast<int>(m.zone_corner_begin[z + 1] - b);
      for (int k = 0; k < v.n; ++k) {
        v.x[k] = m.x[m.corner_point[b + k]];
        v.y[k] = m.y[m.corner_point[b + k]];
      }
      double area[kMaxZoneVertices], volume[kMaxZoneVertices];
      PlanarGeometry::corner_areas(v, area);
      RzGeometry::corner_volumes(v, volume);
      const double shape = area[c - b] * (m.x[s.axis_ref_a[j]] + m.x[s.axis_ref_b[j]]) / volume[c - b];
      s.axis_moment[j] = s.ale_corner_mass[c] * shape;
    }
  }
}

std::shared_ptr<Remap> make_ale_remap(Simulation::Impl& s) {
  return std::make_shared<AleRemap>(s);
}

}  // namespace stagger
