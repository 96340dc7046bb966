// Simulation set-up: masses (constant in time), initial state, boundary conditions and the
// choice of kernels (docs/algorithm.md §2, §10, §12): features a scene does not use are not set up.
#include <algorithm>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "hydro/boundary.hpp"
#include "hydro/boundary_checks.hpp"
#include "hydro/kernels/geometry.hpp"
#include "hydro/kernels/heat_flux.hpp"
#include "hydro/kernels/subzonal_pressure.hpp"
#include "hydro/physics_digest.hpp"
#include "hydro/simulation_impl.hpp"
#include "stagger/error.hpp"
#include "state/state_table.hpp"

namespace stagger {

namespace {

ZoneVertices load_vertices(const Mesh& m, Index z) {
  ZoneVertices v;
  const Index b = m.zone_corner_begin[z];
  v.n = m.zone_corner_begin[z + 1] - b;
  for (int k = 0; k < v.n; ++k) {
    v.x[k] = m.x[m.corner_point[b + k]];
    v.y[k] = m.y[m.corner_point[b + k]];
  }
  return v;
}

std::string zone_label(const Mesh& m, Index z) {
  std::ostringstream out;
  out << "zone " << z << " (region '" << m.region_names[m.zone_region[z]] << "', points";
  for (Index c = m.zone_corner_begin[z]; c < m.zone_corner_begin[z + 1]; ++c) out << ' ' << m.corner_point[c];
  out << ")";
  return out.str();
}

// Points that continue each zone edge into the neighbouring zones (edge viscosity limiter).
void setup_edge_continuation(Simulation::Impl& s) {
  const Mesh& m = s.mesh();
  const std::vector<Index> twin = side_twins(m);  // per corner: the corner across its side
  const auto across = [&](Index c) { return twin[c] < 0 ? -1 : m.corner_zone[twin[c]]; };
  // Ratio used where an edge has no neighbour: 1 (mirror image) at walls, symmetry planes,
  // pistons and periodic sides; 0 at free and pressure boundaries (docs/algorithm.md §5).
  std::map<std::pair<Index, Index>, float> boundary_ratio;
  std::set<std::pair<Index, Index>> mirror_edges;  // walls, symmetry planes, pistons
  for (const auto& bc : s.problem.boundaries) {
    const float r =
        (bc.kind == BoundaryKind::free || bc.kind == BoundaryKind::pressure || bc.kind == BoundaryKind::transmitting)
            ? 0.f
            : 1.f;
    const bool mirror =
        bc.kind == BoundaryKind::wall || bc.kind == BoundaryKind::velocity || bc.kind == BoundaryKind::fixed;
    for (const auto& e : m.tags[m.tag_index(bc.tag)].edges) {
      boundary_ratio[{e[0], e[1]}] = r;
      if (mirror) mirror_edges.insert({e[0], e[1]});
    }
  }
  // The vertex of zone zn adjacent to point p other than `other`.
  auto other_neighbour = [&](Index zn, Index p, Index other) -> Index {
    const Index b = m.zone_corner_begin[zn], n = m.zone_corner_begin[zn + 1] - b;
    for (Index k = 0; k < n; ++k)
      if (m.corner_point[b + k] == p) {
        const Index next = m.corner_point[b + (k + 1) % n], prev = m.corner_point[b + (k + n - 1) % n];
        return next == other ? prev : next;
      }
    return -1;
  };
  s.continuation.assign(m.num_corners(), {});
  for (Index z = 0; z < m.num_zones(); ++z) {
    const Index b = m.zone_corner_begin[z], n = m.zone_corner_begin[z + 1] - b;
    for (Index k = 0; k < n; ++k) {
      const Index p0 = m.corner_point[b + k], p1 = m.corner_point[b + (k + 1) % n];
      const Index p2 = m.corner_point[b + (k + 2) % n], pm = m.corner_point[b + (k + n - 1) % n];
      EdgeContinuation& ec = s.continuation[b + k];
      // Ahead: beyond p1, in the zone across edge (p1, p2) (it holds that edge as (p2, p1)).
      if (const Index zn = across(b + (k + 1) % n); zn >= 0) {
        ec.ahead = other_neighbour(zn, p1, p2);
      } else if (mirror_edges.count({p1, p2})) {
        ec.ahead = mirror_code(p2);
      } else {
        auto r = boundary_ratio.find({p1, p2});
        ec.ahead = (r != boundary_ratio.end() && r->second > 0) ? kContinuationOpen : kContinuationFree;
      }
      // Behind: beyond p0, in the zone across edge (pm, p0).
      if (const Index zn = across(b + (k + n - 1) % n); zn >= 0) {
        ec.behind = other_neighbour(zn, p0, pm);
      } else if (mirror_edges.count({pm, p0})) {
        ec.behind = mirror_code(pm);
      } else {
        auto r = boundary_ratio.find({pm, p0});
        ec.behind = (r != boundary_ratio.end() && r->second > 0) ? kContinuationOpen : kContinuationFree;
      }
    }
  }
}

// The zone across each zone edge for the heat flux (docs/algorithm.md §21), same material only.
void setup_heat_neighbours(Simulation::Impl& s) {
  std::vector<int> material(s.mesh().num_zones(), -1);
  for (const ZoneRange& r : s.ranges)
    for (Index z = r.begin; z < r.end; ++z) material[z] = r.material;
  s.heat_neighbour = heat_flux_neighbours(s.mesh(), material);
}

// rz (docs/algorithm.md §19): x is the radius. Points within round-off of the axis (a polar
// mesh's cos 90 degrees) are put on it; a point at x < 0 is an error.
void setup_axis(Mesh& m) {
  const double tolerance = axis_tolerance(m);
  for (Index p = 0; p < m.num_points(); ++p) {
    if (std::abs(m.x[p]) <= tolerance) {
      m.x[p] = 0;
    } else if (m.x[p] < 0) {
      Index zone = -1;
      for (Index c = 0; c < m.num_corners() && zone < 0; ++c)
        if (m.corner_point[c] == p) zone = m.corner_zone[c];
      std::ostringstream msg;
      msg << "geometry = \"rz\": point " << p << " (" << m.x[p] << ", " << m.y[p] << ")";
      if (zone >= 0) msg << " of " << zone_label(m, zone);
      msg << " has a negative radius x < 0: an axisymmetric mesh lies in x >= 0 (x = r, y = z)";
      throw Error(msg.str());
    }
  }
}

}  // namespace

// rz (docs/algorithm.md §19): point_mass holds the planar masses sum_c rho^0 A_c^0; the true
// point mass is that times r_p^0 (zero on the axis). The axis points' corners keep
// k_c = rho^0 A_c^0 s_c^0, s_c the radii of the corner's neighbours in its zone (the next
// vertices off the axis when both are on it).
void Simulation::Impl::setup_rz_masses() {
  const Mesh& m = mesh();
  for (Index p = 0; p < m.num_points(); ++p) {
    if (m.x[p] != 0) {
      point_mass[p] *= m.x[p];
      continue;
    }
    axis_points.push_back(p);
    for (Index j = m.point_corner_begin[p]; j < m.point_corner_begin[p + 1]; ++j) {
      const Index c = m.point_corners[j], z = m.corner_zone[c];
      const Index b = m.zone_corner_begin[z];
      const int n = m.zone_corner_begin[z + 1] - b, k = c - b;
      // The two neighbours of k; if both are on the axis, the nearest vertices off it.
      int back = 1, ahead = 1;
      if (m.x[m.corner_point[b + (k + n - 1) % n]] == 0 && m.x[m.corner_point[b + (k + 1) % n]] == 0) {
        while (back < n && m.x[m.corner_point[b + (k - back + n) % n]] == 0) ++back;
        while (ahead < n && m.x[m.corner_point[b + (k + ahead) % n]] == 0) ++ahead;
      }
      const Index ra = m.corner_point[b + (k - (back < n ? back : 1) + n) % n];
      const Index rb = m.corner_point[b + (k + (ahead < n ? ahead : 1)) % n];
      const ZoneVertices v = load_vertices(m, z);
      double ca[kMaxZoneVertices];
      PlanarGeometry::corner_areas(v, ca);
      const double s = m.x[ra] + m.x[rb];
      if (!(s > 0)) {
        std::ostringstream msg;
        msg << "geometry = \"rz\": " << zone_label(m, z) << " lies on the axis x = 0 (every vertex has x = 0)";
        throw Error(msg.str());
      }
      axis_corner.push_back(c);
      axis_ref_a.push_back(ra);
      axis_ref_b.push_back(rb);
      axis_moment.push_back(rho[z] * ca[k] * s);
    }
    axis_corner_begin.push_back(static_cast<Index>(axis_corner.size()));
    point_mass[p] = 0;
  }
}

// The set-up of each region and its material (indices into problem.regions and
// problem.materials), the zone ranges (zones are sorted by region in the Mesh), and whether
// any material has strength or a burn.
Simulation::Impl::RegionIndex Simulation::Impl::assign_materials() {
  const Mesh& m = mesh();
  RegionIndex index{std::vector<int>(m.num_regions(), -1), std::vector<int>(m.num_regions(), -1)};
  for (std::size_t i = 0; i < problem.regions.size(); ++i) {
    const int r = m.region_index(problem.regions[i].region);
    index.setup[r] = static_cast<int>(i);
    for (std::size_t k = 0; k < problem.materials.size(); ++k)
      if (problem.materials[k].name == problem.regions[i].material) index.material[r] = static_cast<int>(k);
  }
  for (Index r = 0; r < m.num_regions(); ++r) {
    if (m.region_zone_begin[r] < m.region_zone_begin[r + 1])
      ranges.push_back({m.region_zone_begin[r], m.region_zone_begin[r + 1], index.material[r]});
    const Material& mat = problem.materials[index.material[r]];
    any_strength = any_strength || mat.strength.has_value();
    any_burn = any_burn || mat.burn.has_value();
  }
  return index;
}

// Density, energy, masses and stress of every zone at t = 0 from its region's set-up.
void Simulation::Impl::set_initial_zones(const RegionIndex& regions) {
  const Mesh& m = mesh();
  const Index nz = m.num_zones();
  const HydroOptions& opt = problem.options;
  // Initial density and energy at zone centres; corner masses rho^0 A_c^0 (docs/algorithm.md §2).
  std::vector<double> corner_area(kMaxZoneVertices), corner_volume(kMaxZoneVertices);
  const Subzones subzones = opt.hourglass == Hourglass::subzonal ? Subzones::corners : Subzones::triangles;
  for (Index z = 0; z < nz; ++z) {
    const ZoneVertices v = load_vertices(m, z);
    const auto [cx, cy] = PlanarGeometry::centre(v);
    const int r = m.zone_region[z];
    const RegionSetup& setup = problem.regions[regions.setup[r]];
    const Material& mat = problem.materials[regions.material[r]];
    const double rho0 = setup.density(cx, cy);
    if (!(rho0 > 0) || !std::isfinite(rho0)) {
      std::ostringstream msg;
      msg << "region '" << setup.region << "': initial density " << rho0 << " at (" << cx << ", " << cy << ") in "
          << zone_label(m, z) << " must be positive and finite";
      throw Error(msg.str());
    }
    double e0 = 0;
    if (setup.specific_internal_energy) {
      e0 = setup.specific_internal_energy(cx, cy);
    } else {
      const double p0 = setup.pressure(cx, cy);
      try {
        e0 = eos_energy_from_pressure(mat.eos, rho0, p0);
      } catch (const Error& err) {
        throw Error("region '" + setup.region + "', " + zone_label(m, z) + ": " + err.what());
      }
    }
    if (!std::isfinite(e0))
      throw Error("region '" + setup.region + "': initial energy is not finite in " + zone_label(m, z));
    if (std::holds_alternative<IdealGas>(mat.eos) && e0 < 0) {
      std::ostringstream msg;
      msg << "region '" << setup.region << "': an ideal gas needs a non-negative pressure and energy, but "
          << zone_label(m, z) << " at (" << cx << ", " << cy << ") gets specific internal energy " << e0
          << ": give a pressure >= 0";
      throw Error(msg.str());
    }
    e[z] = e0;
    rho[z] = rho0;
    PlanarGeometry::corner_areas(v, corner_area.data());
    // rz: the zone mass is rho^0 V (per radian), the point mass r_p^0 sum_c rho^0 A_c^0
    // (times r_p^0 below; zero on the axis); docs/algorithm.md §19.
    if (rz) RzGeometry::corner_volumes(v, corner_volume.data());
    if (subzonal) subzonal_masses(v, rho0, subzones, corner_mass.data() + m.zone_corner_begin[z]);
    for (int k = 0; k < v.n; ++k) {
      const Index c = m.zone_corner_begin[z] + k;
      const double mc = rho0 * corner_area[k];
      zone_mass[z] += rz ? rho0 * corner_volume[k] : mc;
      point_mass[m.corner_point[c]] += mc;
      // The ALE subcell masses: rz ones (per radian) in rz (docs/ale.md, "ALE in rz").
      if (!ale_corner_mass.empty()) ale_corner_mass[c] = rz ? rho0 * corner_volume[k] : mc;
    }
    if (mat.strength) {
      if (setup.stress_xx) sxx[z] = setup.stress_xx(cx, cy);
      if (setup.stress_yy) syy[z] = setup.stress_yy(cx, cy);
      if (setup.stress_xy) sxy[z] = setup.stress_xy(cx, cy);
      if (!std::isfinite(sxx[z]) || !std::isfinite(syy[z]) || !std::isfinite(sxy[z]))
        throw Error("region '" + setup.region + "': initial deviatoric stress is not finite in " + zone_label(m, z));
    }
  }
}

// rz masses and the check that every point has mass.
void Simulation::Impl::check_point_masses() {
  const Mesh& m = mesh();
  const Index np = m.num_points();
  if (rz) setup_rz_masses();
  // ALE in rz: the point masses are the sums of the rz subcell masses the remap carries
  // (docs/ale.md, "ALE in rz"); the axis points stay massless.
  if (rz && !ale_corner_mass.empty())
    for (Index p = 0; p < np; ++p) {
      if (m.x[p] == 0) continue;
      double mass = 0;
      for (Index k = m.point_corner_begin[p]; k < m.point_corner_begin[p + 1]; ++k)
        mass += ale_corner_mass[m.point_corners[k]];
      point_mass[p] = mass;
    }
  for (Index p = 0; p < np; ++p) {
    if (rz && m.x[p] == 0) continue;
    if (!(point_mass[p] > 0)) {
      std::ostringstream msg;
      msg << "point " << p << " (" << m.x[p] << ", " << m.y[p] << ") has no mass: a zone around it is degenerate";
      throw Error(msg.str());
    }
  }
}

// The scene's energy deposits.
void Simulation::Impl::deposit_energy() {
  const Mesh& m = mesh();
  const Index nz = m.num_zones(), np = m.num_points();
  // Energy deposits (Sedov): shared by mass among the zones around the nearest point, or a
  // Gaussian in specific energy. A single zone's deposit on a Cartesian mesh starts the blast
  // square, and the entropy that imprint leaves in the inner gas scatters the density at
  // fixed radius (docs/verification.md §3).
  for (const auto& d : problem.deposits) {
    if (d.radius > 0) {
      std::vector<double> weight(nz);
      double total = 0;
      for (Index z = 0; z < nz; ++z) {
        const auto [cx, cy] = PlanarGeometry::centre(load_vertices(m, z));
        const double r = std::hypot(cx - d.x, cy - d.y) / d.radius;
        weight[z] = std::exp(-r * r);
        total += zone_mass[z] * weight[z];
      }
      if (!(total > 0)) {
        std::ostringstream msg;
        msg << "deposit at (" << d.x << ", " << d.y << ") with radius " << d.radius
            << ": no zone centre is close enough to get a share (make the radius at least a zone width)";
        throw Error(msg.str());
      }
      for (Index z = 0; z < nz; ++z) e[z] += d.energy * weight[z] / total;
      continue;
    }
    Index nearest = 0;
    double best = std::numeric_limits<double>::max();
    for (Index p = 0; p < np; ++p) {
      const double dist = std::hypot(m.x[p] - d.x, m.y[p] - d.y);
      if (dist < best) best = dist, nearest = p;
    }
    double mass = 0;
    for (Index k = m.point_corner_begin[nearest]; k < m.point_corner_begin[nearest + 1]; ++k)
      mass += zone_mass[m.corner_zone[m.point_corners[k]]];
    for (Index k = m.point_corner_begin[nearest]; k < m.point_corner_begin[nearest + 1]; ++k)
      e[m.corner_zone[m.point_corners[k]]] += d.energy / mass;
  }
}

// The point velocities at t = 0.
void Simulation::Impl::set_initial_velocities() {
  const Mesh& m = mesh();
  const Index np = m.num_points();
  // Point velocities: the first region set-up (in problem order) whose zones touch the point.
  std::vector<char> done(np, 0);
  for (const auto& setup : problem.regions) {
    const int r = m.region_index(setup.region);
    for (Index z = m.region_zone_begin[r]; z < m.region_zone_begin[r + 1]; ++z)
      for (Index c = m.zone_corner_begin[z]; c < m.zone_corner_begin[z + 1]; ++c) {
        const Index p = m.corner_point[c];
        if (done[p]) continue;
        done[p] = 1;
        vx[p] = setup.velocity_x(m.x[p], m.y[p]);
        vy[p] = setup.velocity_y(m.x[p], m.y[p]);
        if (!std::isfinite(vx[p]) || !std::isfinite(vy[p])) {
          std::ostringstream msg;
          msg << "region '" << setup.region << "': initial velocity is not finite at point " << p << " (" << m.x[p]
              << ", " << m.y[p] << ")";
          throw Error(msg.str());
        }
      }
  }
}

// The programmed burn's constants.
void Simulation::Impl::set_up_burn() {
  const Mesh& m = mesh();
  // Programmed burn: lighting time and burn length per zone (fixed at t = 0).
  if (any_burn) {
    for (const auto& range : ranges) {
      const Material& mat = problem.materials[range.material];
      for (Index z = range.begin; z < range.end; ++z) {
        if (!mat.burn) {
          burn[z] = burn_new[z] = 1.0;  // inert zones: no burn factor
          continue;
        }
        const ZoneVertices v = load_vertices(m, z);
        const auto [cx, cy] = PlanarGeometry::centre(v);
        double longest_edge = 0;
        for (int k = 0; k < v.n; ++k) {
          const int k1 = (k + 1) % v.n;
          longest_edge = std::max(longest_edge, std::hypot(v.x[k1] - v.x[k], v.y[k1] - v.y[k]));
        }
        double distance = std::numeric_limits<double>::infinity();
        for (const auto& pt : mat.burn->points) distance = std::min(distance, std::hypot(cx - pt[0], cy - pt[1]));
        if (mat.burn->plane) {
          const auto& pl = *mat.burn->plane;
          const double nn = std::hypot(pl[2], pl[3]);
          distance = std::min(distance, std::abs((cx - pl[0]) * pl[2] + (cy - pl[1]) * pl[3]) / nn);
        }
        lighting_time[z] = mat.burn->time_offset + distance / mat.burn->detonation_speed;
        // LS-DYNA's F1 = 2 (t - t_l) D A_max / (3 V): in 2D, A_max -> longest edge, V -> area.
        burn_length[z] = 1.5 * PlanarGeometry::area(v) / longest_edge;
      }
    }
  }
}

Simulation::Impl::Impl(Problem prob) : problem(std::move(prob)) {
  problem.validate();
  rz = problem.options.geometry == CoordinateSystem::rz;
  if (rz) setup_axis(problem.mesh);
  const Mesh& m = mesh();
  const Index nz = m.num_zones();
  const HydroOptions& opt = problem.options;

  zone_corner_begin = m.zone_corner_begin;
  corner_point = m.corner_point;
  point_corner_begin = m.point_corner_begin;
  point_corners = m.point_corners;
  all_quads = m.all_quads();
  for (Index z = 0; z < nz; ++z) {
    const Index n = m.zone_corner_begin[z + 1] - m.zone_corner_begin[z];
    if (n < 3 || n > kMaxZoneVertices) {
      throw Error(zone_label(m, z) + " has " + std::to_string(n) + " vertices; zones must have 3 to " +
                  std::to_string(kMaxZoneVertices));
    }
  }

  const RegionIndex regions = assign_materials();
  edge_viscosity = opt.viscosity == Viscosity::edge;
  heat_flux = opt.heat_flux_c1 > 0 || opt.heat_flux_c2 > 0;
  dt_min = opt.dt_min > 0 ? opt.dt_min : 1e-8 * problem.t_end;
  setup_boundaries(*this);
  has_external = !pressure_edges.empty() || (problem.sources && problem.sources->momentum);
  has_sources = problem.sources.has_value();
  has_momentum_source = problem.sources && problem.sources->momentum;
  has_energy_source = problem.sources && problem.sources->energy;
  subzonal = opt.hourglass == Hourglass::subzonal || opt.hourglass == Hourglass::subzonal_triangles;
  ale = problem.ale.mode != AleMode::lagrangian;
  compensated = opt.compensated_update;
  // Every state array, sized by the state table (what the scene needs, nothing more).
  allocate_state(*this, *this, m);

  set_initial_zones(regions);
  // Transmitting boundaries: the far-field pressure of each edge, its zone's EOS pressure at
  // t = 0 from the region's set-up, before any deposit (a distributed part, set up without the
  // deposits, agrees).
  for (PressureEdge& edge : pressure_edges)
    if (edge.zone >= 0)
      edge.ambient =
          eos_pressure(problem.materials[regions.material[m.zone_region[edge.zone]]].eos, rho[edge.zone], e[edge.zone]);
  check_point_masses();
  deposit_energy();
  set_initial_velocities();
  set_up_burn();

  if (edge_viscosity) setup_edge_continuation(*this);
  if (heat_flux) setup_heat_neighbours(*this);
  constrained = constrained_points(*this);
  free_vx.assign(constrained.size(), 0.0);
  free_vy.assign(constrained.size(), 0.0);

  x = m.x;
  y = m.y;

  // Constrained points carry their prescribed velocity from t = 0 (no impulse in step one).
  apply_constraints(*this, vx, vy, 0.0);
  recompute_state();
  energy_initial = kinetic_energy() + internal_energy();
  digest = setup_digest(*this);
#ifdef __GLIBC__
  malloc_trim(0);  // hand the set-up's temporaries back to the OS before the long run
#endif
}

}  // namespace stagger
