// The ALE rezone (docs/ale.md, "Rezone"): fixed points, smoothing, boundary sliding,
// interfaces, relaxation and the validity guarantee.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "ale/rezone.hpp"
#include "hydro/kernels/zone_validity.hpp"
#include "stagger/error.hpp"
#include "stagger/mesh.hpp"
#include "stagger/meshgen.hpp"

namespace stagger {
namespace {

struct Positions {
  std::vector<double> x, y;
};

Mesh rectangle_mesh(int nx, int ny, double width = 1, double height = 1) {
  MeshBuildOptions o;
  o.check_topology = false;
  return build_mesh(meshgen::rectangle(0, width, 0, height, nx, ny), o);
}

// Zone z crosses (not positive area or crossing edges) at (x, y).
bool crosses(const Mesh& mesh, Index z, const std::vector<double>& x, const std::vector<double>& y) {
  ZoneVertices v;
  const Index b = mesh.zone_corner_begin[z];
  v.n = static_cast<int>(mesh.zone_corner_begin[z + 1] - b);
  for (int k = 0; k < v.n; ++k) {
    v.x[k] = x[mesh.corner_point[b + k]];
    v.y[k] = y[mesh.corner_point[b + k]];
  }
  return zone_crosses(v);
}

Index crossing_zones(const Mesh& mesh, const std::vector<double>& x, const std::vector<double>& y) {
  Index n = 0;
  for (Index z = 0; z < mesh.num_zones(); ++z) n += crosses(mesh, z, x, y);
  return n;
}

// Moves every interior point by up to `amplitude` (times the local spacing h) at random.
Positions perturb_interior(const Mesh& mesh, const RezoneConstraints& rc, double amplitude, double h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Positions p{mesh.x, mesh.y};
  for (Index i = 0; i < mesh.num_points(); ++i) {
    const double dx = u(rng), dy = u(rng);
    if (rc.kind[i] != RezonePointKind::interior) continue;
    p.x[i] += amplitude * h * dx;
    p.y[i] += amplitude * h * dy;
  }
  return p;
}

struct Rezoned {
  Positions pos;
  RezoneResult result;
};

Rezoned run_rezone(const Mesh& mesh, const RezoneConstraints& rc, const RezoneOptions& o, const Positions& lag) {
  Rezoned r;
  r.pos.x.assign(mesh.num_points(), 0.0);
  r.pos.y.assign(mesh.num_points(), 0.0);
  RezoneWorkspace ws;
  r.result = rezone(mesh, rc, o, lag.x, lag.y, mesh.x, mesh.y, r.pos.x, r.pos.y, ws);
  return r;
}

TEST(Rezone, UniformCartesianMeshIsAFixedPointOfWinslow) {
  for (const auto& [nx, ny, w, h] : {std::tuple{12, 9, 1.0, 0.75}, std::tuple{10, 10, 0.3, 0.3}}) {
    const Mesh mesh = rectangle_mesh(nx, ny, w, h);
    const RezoneConstraints rc = make_rezone_constraints(mesh, {});
    EXPECT_EQ(rc.num_fixed, 4);  // the four corners
    EXPECT_EQ(rc.num_slide, 2 * (nx - 1) + 2 * (ny - 1));
    RezoneOptions o;
    o.relaxation = 1;
    o.iterations = 10;
    for (const RezoneMethod m : {RezoneMethod::winslow, RezoneMethod::reference_jacobian}) {
      o.method = m;
      const Rezoned r = run_rezone(mesh, rc, o, {mesh.x, mesh.y});
      for (Index p = 0; p < mesh.num_points(); ++p) {
        EXPECT_NEAR(r.pos.x[p], mesh.x[p], 1e-14 * w) << "point " << p;
        EXPECT_NEAR(r.pos.y[p], mesh.y[p], 1e-14 * h) << "point " << p;
      }
      EXPECT_LE(r.result.max_displacement, 1e-14);
    }
  }
}

TEST(Rezone, ReferenceJacobianKeepsAGradedMesh) {
  // A graded mesh (spacing growing geometrically in x) is its own reference: a fixed point of
  // reference_jacobian, while Winslow pulls it toward equal spacing.
  Mesh mesh = rectangle_mesh(10, 6);
  for (double& x : mesh.x) x = (std::pow(1.3, 10 * x) - 1) / (std::pow(1.3, 10) - 1);
  const RezoneConstraints rc = make_rezone_constraints(mesh, {});
  RezoneOptions o;
  o.relaxation = 1;
  o.iterations = 5;
  o.method = RezoneMethod::reference_jacobian;
  const Rezoned r = run_rezone(mesh, rc, o, {mesh.x, mesh.y});
  EXPECT_LE(r.result.max_displacement, 1e-13);
  o.method = RezoneMethod::winslow;
  const Rezoned w = run_rezone(mesh, rc, o, {mesh.x, mesh.y});
  EXPECT_GT(w.result.max_displacement, 1e-3);
  EXPECT_EQ(crossing_zones(mesh, w.pos.x, w.pos.y), 0);
}

// Smallest and largest zone area relative to the reference zone's.
std::pair<double, double> relative_area_range(const Mesh& mesh, const std::vector<double>& x,
                                              const std::vector<double>& y) {
  const auto area = [&](Index z, const std::vector<double>& px, const std::vector<double>& py) {
    double a = 0;
    const Index b = mesh.zone_corner_begin[z], e = mesh.zone_corner_begin[z + 1];
    for (Index c = b; c < e; ++c) {
      const Index p = mesh.corner_point[c], q = mesh.corner_point[c + 1 == e ? b : c + 1];
      a += px[p] * py[q] - px[q] * py[p];
    }
    return 0.5 * a;
  };
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (Index z = 0; z < mesh.num_zones(); ++z) {
    const double r = area(z, x, y) / area(z, mesh.x, mesh.y);
    lo = std::min(lo, r);
    hi = std::max(hi, r);
  }
  return {lo, hi};
}

TEST(Rezone, SizeTermKeepsZonesOfAThinningSheetLong) {
  // reference_jacobian's shape functional is scale-invariant: in a sheet that thins out (here
  // a square squeezed into a wedge, 1 high at x = 0 and 0.1 at x = 1) it makes the zones
  // square again by shortening them toward the thin end, so they shrink with the sheet's
  // thickness (the tip of a Taylor bar's foot, docs/ale.md). The size term (size_weight)
  // pulls each zone's area relative to its reference area toward its neighbours', so the
  // zones keep more of their length.
  const int n = 16;
  const Mesh mesh = rectangle_mesh(n, n);
  const RezoneConstraints rc = make_rezone_constraints(mesh, {});
  RezoneOptions o;
  o.method = RezoneMethod::reference_jacobian;
  o.relaxation = 1;
  o.iterations = 4;
  o.size_weight = 1;
  // The reference mesh (relative size 1 everywhere) is a fixed point.
  const Rezoned at_rest = run_rezone(mesh, rc, o, {mesh.x, mesh.y});
  EXPECT_LE(at_rest.result.max_displacement, 1e-14);
  Positions lag{mesh.x, mesh.y};
  for (Index p = 0; p < mesh.num_points(); ++p) lag.y[p] = mesh.y[p] * (1 - 0.9 * mesh.x[p]);
  // Rezones in a row, each from the last one's mesh (a point moves at most max_move of its
  // shortest edge per rezone).
  const auto repeated = [&](double size_weight) {
    o.size_weight = size_weight;
    Rezoned r{lag, {}};
    for (int k = 0; k < 30; ++k) r = run_rezone(mesh, rc, o, r.pos);
    return r;
  };
  const Rezoned shape = repeated(0);
  const Rezoned sized = repeated(1);
  const auto [lag_lo, lag_hi] = relative_area_range(mesh, lag.x, lag.y);
  const auto [shape_lo, shape_hi] = relative_area_range(mesh, shape.pos.x, shape.pos.y);
  const auto [sized_lo, sized_hi] = relative_area_range(mesh, sized.pos.x, sized.pos.y);
  std::printf("relative area: lagrangian %.4g..%.4g, shapes only %.4g..%.4g, size term %.4g..%.4g\n", lag_lo, lag_hi,
              shape_lo, shape_hi, sized_lo, sized_hi);
  EXPECT_EQ(crossing_zones(mesh, shape.pos.x, shape.pos.y), 0);
  EXPECT_EQ(crossing_zones(mesh, sized.pos.x, sized.pos.y), 0);
  EXPECT_GT(sized_lo, 1.5 * shape_lo);
  EXPECT_LT(sized_hi / sized_lo, 0.7 * (shape_hi / shape_lo));
  // Points of the straight sides stay on them: the bottom and the left wall bitwise, the
  // sloped top on its line.
  for (Index p = 0; p < mesh.num_points(); ++p) {
    if (mesh.y[p] == 0) {
      EXPECT_EQ(sized.pos.y[p], 0.0) << p;
    }
    if (mesh.x[p] == 0 || mesh.x[p] == 1) {
      EXPECT_EQ(sized.pos.x[p], mesh.x[p]) << p;
    }
    if (mesh.y[p] == 1) {
      EXPECT_NEAR(sized.pos.y[p], 1 - 0.9 * sized.pos.x[p], 1e-14) << p;
    }
  }
}

TEST(Rezone, PerturbedMeshGetsSmootherAndStaysValid) {
  const int n = 16;
  const Mesh mesh = rectangle_mesh(n, n);
  const RezoneConstraints rc = make_rezone_constraints(mesh, {});
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Positions lag = perturb_interior(mesh, rc, 0.35, 1.0 / n, seed);
    ASSERT_EQ(crossing_zones(mesh, lag.x, lag.y), 0);
    const QualitySummary before =
        mesh_quality_summary(mesh, QualityMeasure::scaled_jacobian, lag.x, lag.y, mesh.x, mesh.y);
    for (const RezoneMethod m : {RezoneMethod::winslow, RezoneMethod::reference_jacobian}) {
      RezoneOptions o;
      o.method = m;
      o.relaxation = 1;
      o.iterations = 4;
      const Rezoned r = run_rezone(mesh, rc, o, lag);
      EXPECT_EQ(crossing_zones(mesh, r.pos.x, r.pos.y), 0);
      const QualitySummary after =
          mesh_quality_summary(mesh, QualityMeasure::scaled_jacobian, r.pos.x, r.pos.y, mesh.x, mesh.y);
      EXPECT_GT(after.worst, before.worst + 0.1) << "seed " << seed;
      EXPECT_GT(after.mean, before.mean) << "seed " << seed;
      // Closer to the uniform mesh than the perturbed one (L2 over points).
      double d_lag = 0, d_new = 0;
      for (Index p = 0; p < mesh.num_points(); ++p) {
        d_lag += std::pow(lag.x[p] - mesh.x[p], 2) + std::pow(lag.y[p] - mesh.y[p], 2);
        d_new += std::pow(r.pos.x[p] - mesh.x[p], 2) + std::pow(r.pos.y[p] - mesh.y[p], 2);
      }
      EXPECT_LT(d_new, 0.5 * d_lag) << "seed " << seed;
      // Relaxation 0.5 lies between: every point halfway (no back-off needed here) to the
      // sweeps' mesh, whose moves are bounded by max_move / relaxation = 1 edge (the bound
      // max_move = 0.5 is on the relaxed move): the relaxation-1 rezone with max_move = 1.
      RezoneOptions sweeps = o;
      sweeps.max_move = 1;
      const Rezoned full = run_rezone(mesh, rc, sweeps, lag);
      o.relaxation = 0.5;
      const Rezoned half = run_rezone(mesh, rc, o, lag);
      EXPECT_EQ(half.result.backed_off_points, 0);
      for (Index p = 0; p < mesh.num_points(); ++p)
        EXPECT_NEAR(half.pos.x[p], lag.x[p] + 0.5 * (full.pos.x[p] - lag.x[p]), 1e-15);
      // ... and no relaxed move exceeds max_move = 0.5 of the point's shortest Lagrangian edge.
      bool cap_reached = false;
      for (Index p = 0; p < mesh.num_points(); ++p) {
        double shortest = std::numeric_limits<double>::infinity();
        for (Index k = mesh.point_corner_begin[p]; k < mesh.point_corner_begin[p + 1]; ++k) {
          const Index c = mesh.point_corners[k], z = mesh.corner_zone[c];
          const Index b = mesh.zone_corner_begin[z], e = mesh.zone_corner_begin[z + 1];
          for (const Index q : {mesh.corner_point[c + 1 == e ? b : c + 1], mesh.corner_point[c == b ? e - 1 : c - 1]})
            shortest = std::min(shortest, std::hypot(lag.x[q] - lag.x[p], lag.y[q] - lag.y[p]));
        }
        const double move = std::hypot(half.pos.x[p] - lag.x[p], half.pos.y[p] - lag.y[p]);
        EXPECT_LE(move, 0.5 * shortest * (1 + 1e-12)) << "point " << p;
        cap_reached = cap_reached || move > 0.25 * shortest * (1 + 1e-9);
      }
      if (m == RezoneMethod::winslow) {
        EXPECT_TRUE(cap_reached) << "seed " << seed;
      }
    }
  }
}

// relaxation = w moves every point by w of the way from the Lagrangian mesh to the sweeps'
// mesh (RezoneOptions::relaxation), on a graded mesh with walls (boundary points sliding) for
// both smoothers: the w = 1 rezone with the same cap on the smoothed move (max_move = w, i.e.
// one edge for the sweeps) gives the sweeps' mesh.
TEST(Rezone, RelaxationMovesEachPointByItsFraction) {
  Mesh mesh = rectangle_mesh(12, 10);
  for (Index p = 0; p < mesh.num_points(); ++p) mesh.x[p] = mesh.x[p] * mesh.x[p];  // graded in x
  const RezoneConstraints rc = make_rezone_constraints(mesh, {});
  const Positions lag = perturb_interior(mesh, rc, 0.3, 1.0 / 144, 11);
  for (const RezoneMethod m : {RezoneMethod::winslow, RezoneMethod::reference_jacobian})
    for (const double w : {0.25, 0.75}) {
      RezoneOptions full;
      full.method = m;
      full.relaxation = 1;
      full.iterations = 3;
      full.max_move = 1;
      RezoneOptions relaxed = full;
      relaxed.relaxation = w;
      relaxed.max_move = w;
      const Rezoned a = run_rezone(mesh, rc, full, lag), b = run_rezone(mesh, rc, relaxed, lag);
      ASSERT_EQ(b.result.backed_off_points, 0);
      double moved = 0;
      for (Index p = 0; p < mesh.num_points(); ++p) {
        moved = std::max(moved, std::hypot(a.pos.x[p] - lag.x[p], a.pos.y[p] - lag.y[p]));
        EXPECT_NEAR(b.pos.x[p] - lag.x[p], w * (a.pos.x[p] - lag.x[p]), 1e-15) << "point " << p << " w " << w;
        EXPECT_NEAR(b.pos.y[p] - lag.y[p], w * (a.pos.y[p] - lag.y[p]), 1e-15) << "point " << p << " w " << w;
      }
      EXPECT_GT(moved, 1e-3) << "the sweeps must move the mesh for the test to mean anything";
    }
}

TEST(Rezone, RelaxationZeroAndNoIterationsReturnTheLagrangianMeshBitwise) {
  const Mesh mesh = rectangle_mesh(8, 8);
  const RezoneConstraints rc = make_rezone_constraints(mesh, {});
  const Positions lag = perturb_interior(mesh, rc, 0.3, 1.0 / 8, 7);
  for (const auto& [relax, iters] : {std::pair{0.0, 3}, std::pair{0.7, 0}}) {
    RezoneOptions o;
    o.relaxation = relax;
    o.iterations = iters;
    const Rezoned r = run_rezone(mesh, rc, o, lag);
    EXPECT_EQ(r.pos.x, lag.x);
    EXPECT_EQ(r.pos.y, lag.y);
    EXPECT_EQ(r.result.max_displacement, 0.0);
  }
}

TEST(Rezone, BoundaryPointsSlideAlongWallsAndCornersStay) {
  const int n = 10;
  const Mesh mesh = rectangle_mesh(n, n, 2, 1);
  const RezoneConstraints rc = make_rezone_constraints(mesh, {});
  // Crowd the boundary points toward one end of each wall and perturb the interior.
  Positions lag = perturb_interior(mesh, rc, 0.3, 0.1, 3);
  for (Index p = 0; p < mesh.num_points(); ++p) {
    if (rc.kind[p] != RezonePointKind::slide) continue;
    const double x = mesh.x[p], y = mesh.y[p];
    if (y == 0 || y == 1) lag.x[p] = 2 * std::pow(x / 2, 1.6);
    if (x == 0 || x == 2) lag.y[p] = std::pow(y, 1.6);
  }
  RezoneOptions o;
  o.relaxation = 1;
  o.iterations = 6;
  const Rezoned r = run_rezone(mesh, rc, o, lag);
  EXPECT_EQ(crossing_zones(mesh, r.pos.x, r.pos.y), 0);
  double slide_moved = 0;
  for (Index p = 0; p < mesh.num_points(); ++p) {
    const double x = mesh.x[p], y = mesh.y[p];
    if (rc.kind[p] == RezonePointKind::fixed) {
      EXPECT_EQ(r.pos.x[p], lag.x[p]);
      EXPECT_EQ(r.pos.y[p], lag.y[p]);
      EXPECT_TRUE((x == 0 || x == 2) && (y == 0 || y == 1)) << "point " << p << " fixed";
    }
    if (rc.kind[p] != RezonePointKind::slide) continue;
    // Bitwise on its wall, strictly between the corners.
    if (x == 0 || x == 2) {
      EXPECT_EQ(r.pos.x[p], x);
      EXPECT_GT(r.pos.y[p], 0);
      EXPECT_LT(r.pos.y[p], 1);
    } else {
      EXPECT_EQ(r.pos.y[p], y);
      EXPECT_GT(r.pos.x[p], 0);
      EXPECT_LT(r.pos.x[p], 2);
    }
    slide_moved = std::max(slide_moved, std::hypot(r.pos.x[p] - lag.x[p], r.pos.y[p] - lag.y[p]));
  }
  EXPECT_GT(slide_moved, 0.01);  // the crowded boundary points did spread out
}

TEST(Rezone, SlopedBoundaryPointsStayOnTheirSegment) {
  // A parallelogram: left and right walls slope; boundary points stay on the line.
  Mesh mesh = rectangle_mesh(8, 8);
  for (Index p = 0; p < mesh.num_points(); ++p) mesh.x[p] += 0.4 * mesh.y[p];
  const RezoneConstraints rc = make_rezone_constraints(mesh, {});
  Positions lag = perturb_interior(mesh, rc, 0.3, 1.0 / 8, 11);
  for (Index p = 0; p < mesh.num_points(); ++p)  // crowd the left wall toward the bottom
    if (rc.kind[p] == RezonePointKind::slide && mesh.x[p] == 0.4 * mesh.y[p]) {
      lag.y[p] = std::pow(mesh.y[p], 1.5);
      lag.x[p] = 0.4 * lag.y[p];
    }
  RezoneOptions o;
  o.relaxation = 1;
  o.iterations = 5;
  const Rezoned r = run_rezone(mesh, rc, o, lag);
  EXPECT_EQ(crossing_zones(mesh, r.pos.x, r.pos.y), 0);
  for (Index p = 0; p < mesh.num_points(); ++p)
    if (rc.kind[p] == RezonePointKind::slide && mesh.x[p] == 0.4 * mesh.y[p]) {
      EXPECT_NEAR(r.pos.x[p], 0.4 * r.pos.y[p], 1e-15) << "point " << p;
    }
}

TEST(Rezone, MaterialInterfacePointsStayLagrangian) {
  PolygonSoup soup = meshgen::rectangle(0, 1, 0, 1, 10, 10);
  soup.region_names = {"left", "right"};
  for (std::size_t z = 0; z < soup.num_polygons(); ++z) {
    double cx = 0;
    for (auto k = soup.polygon_begin[z]; k < soup.polygon_begin[z + 1]; ++k) cx += soup.x[soup.polygon_points[k]];
    soup.polygon_region[z] = cx / 4 < 0.42 ? 0 : 1;
  }
  const Mesh mesh = build_mesh(soup);
  const RezoneConstraints rc = make_rezone_constraints(mesh, {});
  Positions lag = perturb_interior(mesh, rc, 0.3, 0.1, 5);
  // Interface points (x = 0.4) are fixed: perturb them too, they must stay where they are.
  for (Index p = 0; p < mesh.num_points(); ++p)
    if (std::abs(mesh.x[p] - 0.4) < 1e-12 && mesh.y[p] > 0 && mesh.y[p] < 1) {
      EXPECT_EQ(rc.kind[p], RezonePointKind::fixed) << "point " << p;
      lag.x[p] += 0.02 * std::sin(30 * mesh.y[p]);
    }
  RezoneOptions o;
  o.relaxation = 1;
  o.iterations = 4;
  const Rezoned r = run_rezone(mesh, rc, o, lag);
  EXPECT_EQ(crossing_zones(mesh, r.pos.x, r.pos.y), 0);
  Index interface_points = 0;
  for (Index p = 0; p < mesh.num_points(); ++p)
    if (std::abs(mesh.x[p] - 0.4) < 1e-12) {
      ++interface_points;
      EXPECT_EQ(r.pos.x[p], lag.x[p]);
      EXPECT_EQ(r.pos.y[p], lag.y[p]);
    }
  EXPECT_EQ(interface_points, 11);
  // The same mesh with one material for both regions: the interface points move.
  const std::vector<Index> one_material(mesh.num_zones(), 0);
  const RezoneConstraints rc1 = make_rezone_constraints(mesh, {}, one_material);
  EXPECT_EQ(rc1.num_fixed, 4);
  EXPECT_THROW(make_rezone_constraints(mesh, {}, std::vector<Index>(3, 0)), Error);
}

TEST(Rezone, PeriodicTagsAndTagJunctionsAreFixed) {
  const Mesh mesh = rectangle_mesh(6, 4);
  BoundaryCondition bc;
  bc.tag = "left";
  bc.kind = BoundaryKind::periodic;
  bc.partner = "right";
  const std::vector<BoundaryCondition> bcs{bc};
  const RezoneConstraints rc = make_rezone_constraints(mesh, bcs);
  for (const char* name : {"left", "right"})
    for (const Index p : mesh.tags[mesh.tag_index(name)].points) EXPECT_EQ(rc.kind[p], RezonePointKind::fixed);
  for (const Index p : mesh.tags[mesh.tag_index("bottom")].points)
    if (mesh.x[p] > 0 && mesh.x[p] < 1) {
      EXPECT_EQ(rc.kind[p], RezonePointKind::slide);
    }
}

TEST(Rezone, CurvedBoundaryPointsAreCorners) {
  // An annulus sector: the arcs turn by 90/8 degrees at every point, more than the corner
  // angle, so their points stay; the straight radial sides slide.
  MeshBuildOptions mo;
  mo.check_topology = false;
  const Mesh mesh = build_mesh(meshgen::annulus_sector(1, 2, 0, std::numbers::pi / 2, 8, 6), mo);
  const RezoneConstraints rc = make_rezone_constraints(mesh, {});
  std::vector<double> xn(mesh.num_points()), yn(mesh.num_points());
  Positions lag = perturb_interior(mesh, rc, 0.2, 0.15, 2);
  RezoneOptions o;
  o.relaxation = 1;
  o.iterations = 3;
  RezoneWorkspace ws;
  rezone(mesh, rc, o, lag.x, lag.y, mesh.x, mesh.y, xn, yn, ws);
  for (const char* name : {"inner", "outer"})
    for (const Index p : mesh.tags[mesh.tag_index(name)].points) {
      EXPECT_EQ(xn[p], lag.x[p]);
      EXPECT_EQ(yn[p], lag.y[p]);
    }
  EXPECT_EQ(crossing_zones(mesh, xn, yn), 0);
  // A corner angle above the arcs' turn lets them slide (along their chords).
  o.corner_angle_degrees = 20;
  rezone(mesh, rc, o, lag.x, lag.y, mesh.x, mesh.y, xn, yn, ws);
  EXPECT_EQ(crossing_zones(mesh, xn, yn), 0);
}

TEST(Rezone, NeverReturnsAnInvalidMesh) {
  // Violent random meshes (many zones close to folding, some non-convex): whatever the
  // method and relaxation, every zone valid in the Lagrangian mesh is valid afterwards.
  const int n = 12;
  const Mesh mesh = rectangle_mesh(n, n);
  const RezoneConstraints rc = make_rezone_constraints(mesh, {});
  int nonconvex_inputs = 0, guard_rounds = 0;
  Index backed_off = 0;
  for (unsigned seed = 1; seed <= 20; ++seed) {
    Positions lag = perturb_interior(mesh, rc, 0.49, 1.0 / n, 100 + seed);
    // Zones that cross in the input: give their points back the uniform positions.
    for (Index z = 0; z < mesh.num_zones(); ++z)
      if (crosses(mesh, z, lag.x, lag.y))
        for (Index c = mesh.zone_corner_begin[z]; c < mesh.zone_corner_begin[z + 1]; ++c) {
          lag.x[mesh.corner_point[c]] = mesh.x[mesh.corner_point[c]];
          lag.y[mesh.corner_point[c]] = mesh.y[mesh.corner_point[c]];
        }
    if (crossing_zones(mesh, lag.x, lag.y) != 0) continue;
    if (mesh_quality_summary(mesh, QualityMeasure::scaled_jacobian, lag.x, lag.y, {}, {}).worst < 0) ++nonconvex_inputs;
    for (const RezoneMethod m : {RezoneMethod::winslow, RezoneMethod::reference_jacobian})
      for (const double relax : {0.3, 1.0}) {
        RezoneOptions o;
        o.method = m;
        o.relaxation = relax;
        o.iterations = 3;
        const Rezoned r = run_rezone(mesh, rc, o, lag);
        EXPECT_EQ(crossing_zones(mesh, r.pos.x, r.pos.y), 0) << "seed " << seed;
        guard_rounds += r.result.backoff_rounds;
        backed_off += r.result.backed_off_points;
        EXPECT_GT(mesh_quality_summary(mesh, QualityMeasure::scaled_jacobian, r.pos.x, r.pos.y, {}, {}).worst,
                  mesh_quality_summary(mesh, QualityMeasure::scaled_jacobian, lag.x, lag.y, {}, {}).worst);
      }
  }
  EXPECT_GT(nonconvex_inputs, 5);  // the test does exercise non-convex zones
  // Winslow and the safeguarded Newton rarely need the guard on such meshes; it is tested on
  // its own below (Rezone.GuardBacksOffToAValidMesh).
  EXPECT_GE(guard_rounds, 0);
  EXPECT_GE(backed_off, 0);
}

TEST(Rezone, UnstructuredGmshMeshWithTriangles) {
  // The blast box meshed by gmsh (triangles, and recombined quads): a perturbed copy
  // gets smoother with both methods, stays valid, and its boundary points stay on the walls.
  meshgen::GeoOptions go;
  go.parameters = {{"n", 8}};
  go.recombine = false;  // all triangles, then gmsh's recombined quads
  const Mesh tri = build_mesh(meshgen::read_geo(std::string(STAGGER_SOURCE_DIR) + "/geometries/blast_box.geo", go));
  go.recombine = true;
  const Mesh quad = build_mesh(meshgen::read_geo(std::string(STAGGER_SOURCE_DIR) + "/geometries/blast_box.geo", go));
  for (const Mesh* mesh : {&tri, &quad}) {
    const RezoneConstraints rc = make_rezone_constraints(*mesh, {});
    EXPECT_EQ(rc.num_fixed, 4);
    const Positions lag = perturb_interior(*mesh, rc, 0.25, 1.0 / 8 / 2, 9);
    ASSERT_EQ(crossing_zones(*mesh, lag.x, lag.y), 0);
    for (const RezoneMethod m : {RezoneMethod::winslow, RezoneMethod::reference_jacobian}) {
      RezoneOptions o;
      o.method = m;
      o.relaxation = 1;
      o.iterations = 4;
      const Rezoned r = run_rezone(*mesh, rc, o, lag);
      EXPECT_EQ(crossing_zones(*mesh, r.pos.x, r.pos.y), 0);
      // Winslow pulls toward its logical shapes, not the gmsh ones: judged by corner angles.
      const QualityMeasure measure =
          m == RezoneMethod::winslow ? QualityMeasure::scaled_jacobian : QualityMeasure::reference_shape;
      const auto quality = [&](const Positions& p) {
        return mesh_quality_summary(*mesh, measure, p.x, p.y, mesh->x, mesh->y);
      };
      EXPECT_GT(quality(r.pos).mean, quality(lag).mean);
      EXPECT_GT(quality(r.pos).worst, quality(lag).worst);
      for (Index p = 0; p < mesh->num_points(); ++p) {
        if (rc.kind[p] == RezonePointKind::interior) continue;
        const double x = mesh->x[p], y = mesh->y[p];
        if (x == 0 || x == 2) {
          EXPECT_EQ(r.pos.x[p], x);
        }
        if (y == 0 || y == 1) {
          EXPECT_EQ(r.pos.y[p], y);
        }
      }
    }
  }
}

TEST(Rezone, GmshMeshAtRest) {
  // An unstructured mesh that does not move: reference_jacobian leaves it where it is;
  // Winslow moves it toward its own fixed point, keeping every zone convex, and the moves
  // shrink from one rezone to the next.
  meshgen::GeoOptions go;
  go.parameters = {{"n", 10}};
  const Mesh mesh = build_mesh(meshgen::read_geo(std::string(STAGGER_SOURCE_DIR) + "/geometries/blast_box.geo", go));
  const RezoneConstraints rc = make_rezone_constraints(mesh, {});
  for (const RezoneMethod m : {RezoneMethod::winslow, RezoneMethod::reference_jacobian}) {
    RezoneOptions o;
    o.method = m;
    Positions pos{mesh.x, mesh.y};
    std::vector<double> xn(mesh.num_points()), yn(mesh.num_points());
    RezoneWorkspace ws;
    std::vector<double> moves;
    for (int call = 0; call < 40; ++call) {
      moves.push_back(rezone(mesh, rc, o, pos.x, pos.y, mesh.x, mesh.y, xn, yn, ws).max_displacement);
      pos.x = xn;
      pos.y = yn;
    }
    const QualitySummary q = mesh_quality_summary(mesh, QualityMeasure::scaled_jacobian, pos.x, pos.y, {}, {});
    EXPECT_GT(q.worst, 0.4);
    if (m == RezoneMethod::reference_jacobian) {
      EXPECT_LE(*std::max_element(moves.begin(), moves.end()), 1e-12);
    } else {
      EXPECT_LT(moves.back(), 0.1 * moves.front());
    }
  }
}

TEST(Rezone, ReferenceLayoutWinslowKeepsTheInitialMesh) {
  // Winslow with the initial mesh as logical space: a graded mesh and a gmsh mesh are fixed
  // points, a uniform Cartesian mesh gets the regular layout's result (and shares a handful
  // of weight sets), and a perturbed gmsh mesh is pulled back toward the initial one.
  Mesh graded = rectangle_mesh(10, 6);
  for (double& x : graded.x) x = (std::pow(1.3, 10 * x) - 1) / (std::pow(1.3, 10) - 1);
  meshgen::GeoOptions go;
  go.parameters = {{"n", 10}};
  const Mesh gmsh = build_mesh(meshgen::read_geo(std::string(STAGGER_SOURCE_DIR) + "/geometries/blast_box.geo", go));
  RezoneOptions o;
  o.relaxation = 1;
  o.iterations = 10;
  for (const Mesh* mesh : {static_cast<const Mesh*>(&graded), &gmsh}) {
    const RezoneConstraints rc = make_rezone_constraints(*mesh, {}, {}, WinslowLayout::reference);
    const Rezoned r = run_rezone(*mesh, rc, o, {mesh->x, mesh->y});
    EXPECT_LE(r.result.max_displacement, 1e-12);
  }
  const RezoneConstraints rc = make_rezone_constraints(gmsh, {}, {}, WinslowLayout::reference);
  const Positions lag = perturb_interior(gmsh, rc, 0.25, 1.0 / 10 / 2, 3);
  double d_lag = 0, d_new = 0;
  const Rezoned r = run_rezone(gmsh, rc, o, lag);
  EXPECT_EQ(crossing_zones(gmsh, r.pos.x, r.pos.y), 0);
  for (Index p = 0; p < gmsh.num_points(); ++p) {
    d_lag += std::pow(lag.x[p] - gmsh.x[p], 2) + std::pow(lag.y[p] - gmsh.y[p], 2);
    d_new += std::pow(r.pos.x[p] - gmsh.x[p], 2) + std::pow(r.pos.y[p] - gmsh.y[p], 2);
  }
  EXPECT_LT(d_new, 0.1 * d_lag);

  const Mesh uniform = rectangle_mesh(16, 12, 2, 1.5);
  const RezoneConstraints regular = make_rezone_constraints(uniform, {});
  const RezoneConstraints reference = make_rezone_constraints(uniform, {}, {}, WinslowLayout::reference);
  EXPECT_LE(reference.weights_begin.size() - 1, 5u);  // interior points and the four walls
  o.iterations = 3;
  const Positions perturbed = perturb_interior(uniform, regular, 0.3, 1.0 / 8, 5);
  const Rezoned a = run_rezone(uniform, regular, o, perturbed), b = run_rezone(uniform, reference, o, perturbed);
  for (Index p = 0; p < uniform.num_points(); ++p) {
    EXPECT_NEAR(a.pos.x[p], b.pos.x[p], 1e-13);
    EXPECT_NEAR(a.pos.y[p], b.pos.y[p], 1e-13);
  }
}

TEST(Rezone, PolygonSoupWithHexagonsAndTriangles) {
  // Rows of hexagons (two quads merged), quads, and triangles (quads split) in one mesh.
  const int n = 8;
  PolygonSoup grid = meshgen::rectangle(0, 1, 0, 1, n, n);
  PolygonSoup soup;
  soup.x = grid.x;
  soup.y = grid.y;
  soup.region_names = {"domain"};
  const auto pt = [&](int i, int j) { return std::int64_t(j * (n + 1) + i); };
  ASSERT_EQ(grid.x[pt(3, 2)], 3.0 / n);
  ASSERT_EQ(grid.y[pt(3, 2)], 2.0 / n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (j % 3 == 0 && i % 2 == 0) {
        soup.add_polygon({pt(i, j), pt(i + 1, j), pt(i + 2, j), pt(i + 2, j + 1), pt(i + 1, j + 1), pt(i, j + 1)}, 0);
        ++i;
      } else if (j % 3 == 1) {
        soup.add_polygon({pt(i, j), pt(i + 1, j), pt(i + 1, j + 1)}, 0);
        soup.add_polygon({pt(i, j), pt(i + 1, j + 1), pt(i, j + 1)}, 0);
      } else {
        soup.add_polygon({pt(i, j), pt(i + 1, j), pt(i + 1, j + 1), pt(i, j + 1)}, 0);
      }
    }
  const Mesh mesh = build_mesh(soup);
  const RezoneConstraints rc = make_rezone_constraints(mesh, {});
  // The middle of a hexagon's bottom side has one zone and a straight angle: its logical
  // neighbours are collinear, so it gets no Winslow stencil (and does not move under Winslow).
  Index hanging = -1;
  for (Index p = 0; p < mesh.num_points(); ++p)
    if (mesh.x[p] == 1.0 / n && mesh.y[p] == 0) hanging = p;
  ASSERT_GE(hanging, 0);
  EXPECT_EQ(rc.stencil_id[hanging], -1);
  EXPECT_EQ(rc.kind[hanging], RezonePointKind::slide);
  const Positions lag = perturb_interior(mesh, rc, 0.25, 1.0 / n, 4);
  ASSERT_EQ(crossing_zones(mesh, lag.x, lag.y), 0);
  for (const RezoneMethod m : {RezoneMethod::winslow, RezoneMethod::reference_jacobian}) {
    RezoneOptions o;
    o.method = m;
    o.relaxation = 1;
    o.iterations = 4;
    const Rezoned r = run_rezone(mesh, rc, o, lag);
    EXPECT_EQ(crossing_zones(mesh, r.pos.x, r.pos.y), 0);
    // reference_jacobian restores the reference shapes; Winslow pulls every zone toward its
    // logical (regular) shape, so it is judged by the smallest corner angle instead.
    const QualityMeasure measure =
        m == RezoneMethod::winslow ? QualityMeasure::scaled_jacobian : QualityMeasure::reference_shape;
    const auto quality = [&](const Positions& p) {
      return mesh_quality_summary(mesh, measure, p.x, p.y, mesh.x, mesh.y);
    };
    EXPECT_GT(quality(r.pos).worst, quality(lag).worst);
  }
}

TEST(Rezone, ResultDoesNotDependOnTheThreadCount) {
  // Large enough for the colour loops to run in parallel (more than 20000 points a colour).
  const int n = 300;
  const Mesh mesh = rectangle_mesh(n, n);
  const RezoneConstraints rc = make_rezone_constraints(mesh, {});
  ASSERT_GT(rc.colour_begin[1] - rc.colour_begin[0], 20000);
  const Positions lag = perturb_interior(mesh, rc, 0.3, 1.0 / n, 8);
  for (const RezoneMethod m : {RezoneMethod::winslow, RezoneMethod::reference_jacobian}) {
    RezoneOptions o;
    o.method = m;
    o.relaxation = 0.8;
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    const Rezoned one = run_rezone(mesh, rc, o, lag);
    omp_set_num_threads(3);
    const Rezoned three = run_rezone(mesh, rc, o, lag);
    omp_set_num_threads(threads);
    EXPECT_EQ(one.pos.x, three.pos.x);
    EXPECT_EQ(one.pos.y, three.pos.y);
    EXPECT_GT(one.result.max_displacement, 0.0);
  }
}

TEST(Rezone, GuardBacksOffToAValidMesh) {
  // A "smoothed" mesh that folds: one interior point pushed through its right neighbour.
  const int n = 4;
  const Mesh mesh = rectangle_mesh(n, n);
  const RezoneConstraints rc = make_rezone_constraints(mesh, {});
  Index p = -1;
  for (Index q = 0; q < mesh.num_points(); ++q)
    if (mesh.x[q] == 0.25 && mesh.y[q] == 0.5) p = q;
  ASSERT_GE(p, 0);
  std::vector<double> xn(mesh.num_points()), yn(mesh.num_points());
  RezoneWorkspace ws;
  for (const auto& [push, rounds] : {std::pair{1.5, 1}, std::pair{1000.0, 9}}) {
    std::vector<double> xs = mesh.x;
    xs[p] += push * 0.25;  // 1.5 h: past the neighbour; 1000 h: past everything
    ASSERT_GT(crossing_zones(mesh, xs, mesh.y), 0);
    const RezoneResult r = relax_and_guard(mesh, rc, 1.0, mesh.x, mesh.y, xs, mesh.y, xn, yn, ws);
    EXPECT_EQ(crossing_zones(mesh, xn, yn), 0);
    EXPECT_EQ(r.backoff_rounds, rounds);
    EXPECT_EQ(r.backed_off_points, 6);  // the points of the two folded zones (to the right of p)
    if (push < 2) {
      EXPECT_EQ(xn[p], 0.25 + 0.5 * push * 0.25);  // halved once: 0.75 h, valid
    } else {
      EXPECT_EQ(xn[p], mesh.x[p]);  // back to the Lagrangian position after eight halvings
    }
    for (Index q = 0; q < mesh.num_points(); ++q) {
      if (q != p) {
        EXPECT_EQ(xn[q], mesh.x[q]);
      }
    }
  }
  // A zone already folded in the Lagrangian mesh is not the guard's: it is left as it is.
  std::vector<double> xl = mesh.x;
  xl[p] += 0.4;
  ASSERT_GT(crossing_zones(mesh, xl, mesh.y), 0);
  const RezoneResult r = relax_and_guard(mesh, rc, 1.0, xl, mesh.y, xl, mesh.y, xn, yn, ws);
  EXPECT_EQ(r.backoff_rounds, 0);
  EXPECT_EQ(xn, xl);
}

// A valid zone can have a median-mesh corner of non-positive area: a dart whose vertex mean
// lies past its reflex vertex. Those corners are the hydro's point volumes and the remap's
// subcells (a remap could give such a corner no mass), so the guard treats it as folded.
TEST(Rezone, GuardKeepsTheMedianCornersOfAValidZonePositive) {
  const Mesh mesh = rectangle_mesh(2, 2, 2, 2);
  const RezoneConstraints rc = make_rezone_constraints(mesh, {});
  Index p = -1, dart = -1;
  for (Index q = 0; q < mesh.num_points(); ++q)
    if (mesh.x[q] == 1 && mesh.y[q] == 1) p = q;
  for (Index z = 0; z < mesh.num_zones(); ++z)
    if (mesh.x[mesh.corner_point[mesh.zone_corner_begin[z]]] < 1 &&
        mesh.y[mesh.corner_point[mesh.zone_corner_begin[z]]] < 1)
      dart = z;
  ASSERT_GE(p, 0);
  ASSERT_GE(dart, 0);
  const auto smallest_corner = [&](Index z, const std::vector<double>& x, const std::vector<double>& y) {
    ZoneVertices v;
    const Index b = mesh.zone_corner_begin[z];
    v.n = static_cast<int>(mesh.zone_corner_begin[z + 1] - b);
    for (int k = 0; k < v.n; ++k) v.x[k] = x[mesh.corner_point[b + k]], v.y[k] = y[mesh.corner_point[b + k]];
    double a[kMaxZoneVertices];
    return PlanarGeometry::corner_areas(v, a);
  };
  std::vector<double> xs = mesh.x, ys = mesh.y;
  xs[p] = ys[p] = 0.3;                         // zone [0, 1]^2 becomes the dart (0, 0), (1, 0), (0.3, 0.3), (0, 1)
  ASSERT_EQ(crossing_zones(mesh, xs, ys), 0);  // valid: the crossing test alone accepts it
  EXPECT_NEAR(smallest_corner(dart, xs, ys), -0.0125, 1e-15);
  std::vector<double> xn(mesh.num_points()), yn(mesh.num_points());
  RezoneWorkspace ws;
  const RezoneResult r = relax_and_guard(mesh, rc, 1.0, mesh.x, mesh.y, xs, ys, xn, yn, ws);
  EXPECT_EQ(r.backoff_rounds, 1);
  EXPECT_EQ(r.backed_off_points, 4);  // the dart's
  EXPECT_DOUBLE_EQ(xn[p], 0.65);
  EXPECT_DOUBLE_EQ(yn[p], 0.65);
  for (Index z = 0; z < mesh.num_zones(); ++z) EXPECT_GT(smallest_corner(z, xn, yn), 0.1) << z;
  // A corner already non-positive in the Lagrangian mesh is not the guard's: left as it is.
  const RezoneResult kept = relax_and_guard(mesh, rc, 1.0, xs, ys, xs, ys, xn, yn, ws);
  EXPECT_EQ(kept.backoff_rounds, 0);
  EXPECT_EQ(xn, xs);
}

TEST(Rezone, QualityMeasures) {
  Mesh mesh = rectangle_mesh(4, 3, 2, 1);
  const QualitySummary sj = mesh_quality_summary(mesh, QualityMeasure::scaled_jacobian, mesh.x, mesh.y, {}, {});
  EXPECT_DOUBLE_EQ(sj.worst, 1.0);
  // Shear the mesh: the reference shape measure of the sheared mesh against the original is
  // 2 det T / |T|^2 with T = [[1, 0.5], [0, 1]]: 2 / 2.25.
  std::vector<double> xs = mesh.x;
  for (Index p = 0; p < mesh.num_points(); ++p) xs[p] += 0.5 * mesh.y[p];
  const QualitySummary rs = mesh_quality_summary(mesh, QualityMeasure::reference_shape, xs, mesh.y, mesh.x, mesh.y);
  EXPECT_NEAR(rs.worst, 2 / 2.25, 1e-14);
  EXPECT_NEAR(rs.mean, 2 / 2.25, 1e-14);
  EXPECT_NEAR(mesh_quality_summary(mesh, QualityMeasure::reference_shape, mesh.x, mesh.y, mesh.x, mesh.y).worst, 1.0,
              1e-15);
  // Fold one zone: its quality goes negative and it is reported as the worst.
  std::vector<double> xf = mesh.x;
  const Index z = 5, p = mesh.corner_point[mesh.zone_corner_begin[z] + 2];
  xf[p] -= 0.9;
  const QualitySummary folded = mesh_quality_summary(mesh, QualityMeasure::scaled_jacobian, xf, mesh.y, {}, {});
  EXPECT_LT(folded.worst, 0);
  EXPECT_LT(zone_quality(mesh, folded.worst_zone, QualityMeasure::scaled_jacobian, xf, mesh.y, {}, {}), 0);
  EXPECT_THROW(zone_quality(mesh, 99, QualityMeasure::scaled_jacobian, xf, mesh.y, {}, {}), Error);
}

TEST(Rezone, BadOptionsAndSizesAreOneClearError) {
  const Mesh mesh = rectangle_mesh(3, 3);
  const RezoneConstraints rc = make_rezone_constraints(mesh, {});
  std::vector<double> xn(mesh.num_points()), yn(mesh.num_points());
  RezoneWorkspace ws;
  const auto message = [&](RezoneOptions o, std::span<double> xo) {
    try {
      rezone(mesh, rc, o, mesh.x, mesh.y, mesh.x, mesh.y, xo, yn, ws);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  RezoneOptions o;
  o.relaxation = 1.5;
  EXPECT_NE(message(o, xn).find("relaxation"), std::string::npos);
  o = {};
  o.iterations = -1;
  EXPECT_NE(message(o, xn).find("iterations"), std::string::npos);
  o = {};
  o.corner_angle_degrees = 90;
  EXPECT_NE(message(o, xn).find("corner_angle"), std::string::npos);
  o = {};
  o.max_move = 0;
  EXPECT_NE(message(o, xn).find("max_move"), std::string::npos);
  o = {};
  o.size_weight = -1;
  EXPECT_NE(message(o, xn).find("size_weight"), std::string::npos);
  std::vector<double> short_x(3);
  EXPECT_NE(message({}, short_x).find("x_new"), std::string::npos);
  std::vector<double> x_lag = mesh.x;
  EXPECT_THROW(rezone(mesh, rc, {}, x_lag, mesh.y, mesh.x, mesh.y, x_lag, yn, ws), Error);  // in place
}

}  // namespace
}  // namespace stagger
