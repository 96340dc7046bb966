// The meshes of the rezone figures of docs/ale.md (scripts/rezone_figures.py): each case is
// checked here (valid, smoother), and written as CSV when STAGGER_REZONE_FIGURE_DIR is set.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "ale/rezone.hpp"
#include "stagger/mesh.hpp"
#include "stagger/meshgen.hpp"

namespace stagger {
namespace {

// One CSV row per zone vertex: zone, region, kind of the point (0 interior, 1 slide, 2 fixed), x, y.
void write_csv(const std::string& name, const Mesh& mesh, const RezoneConstraints& rc, const std::vector<double>& x,
               const std::vector<double>& y) {
  const char* dir = std::getenv("STAGGER_REZONE_FIGURE_DIR");
  if (!dir) return;
  std::ofstream out(std::string(dir) + "/" + name + ".csv");
  out.precision(17);
  out << "zone,region,kind,x,y\n";
  for (Index z = 0; z < mesh.num_zones(); ++z)
    for (Index c = mesh.zone_corner_begin[z]; c < mesh.zone_corner_begin[z + 1]; ++c) {
      const Index p = mesh.corner_point[c];
      out << z << ',' << mesh.zone_region[z] << ',' << int(rc.kind[p]) << ',' << x[p] << ',' << y[p] << '\n';
    }
}

// Rezones (x, y) with `options` and writes before and after; checks the mean scaled Jacobian
// got better, and the worst one too unless `interface_bound` (zones along a bent interface
// whose points stay Lagrangian may get worse while the rest gets smoother).
void rezone_case(const std::string& name, const Mesh& mesh, const RezoneConstraints& rc, const RezoneOptions& options,
                 const std::vector<double>& x, const std::vector<double>& y, bool interface_bound = false) {
  std::vector<double> xn(x.size()), yn(y.size());
  RezoneWorkspace ws;
  rezone(mesh, rc, options, x, y, mesh.x, mesh.y, xn, yn, ws);
  const QualitySummary before = mesh_quality_summary(mesh, QualityMeasure::scaled_jacobian, x, y, {}, {});
  const QualitySummary after = mesh_quality_summary(mesh, QualityMeasure::scaled_jacobian, xn, yn, {}, {});
  EXPECT_GT(after.mean, before.mean) << name;
  if (!interface_bound) {
    EXPECT_GT(after.worst, before.worst) << name;
  }
  std::printf("%s: worst scaled Jacobian %.3f -> %.3f, mean %.3f -> %.3f\n", name.c_str(), before.worst, after.worst,
              before.mean, after.mean);
  write_csv(name + "_before", mesh, rc, x, y);
  write_csv(name + "_after", mesh, rc, xn, yn);
}

TEST(RezoneFigure, VortexCartesianAndGmshMeshes) {
  MeshBuildOptions mo;
  mo.check_topology = false;
  RezoneOptions o;
  o.relaxation = 1;
  o.iterations = 20;

  // 1. A Lagrangian-looking mesh: a Cartesian 24 x 24 mesh turned by a vortex (angle
  //    decaying with radius) that also bends the interface between two materials at x = 5/12
  //    (whose points the rezone keeps where they are).
  PolygonSoup soup = meshgen::rectangle(0, 1, 0, 1, 24, 24);
  soup.region_names = {"light", "heavy"};
  for (std::size_t z = 0; z < soup.num_polygons(); ++z)
    soup.polygon_region[z] = soup.x[soup.polygon_points[soup.polygon_begin[z]]] < 0.4 ? 0 : 1;
  const Mesh vortex = build_mesh(soup, mo);
  const RezoneConstraints rcv = make_rezone_constraints(vortex, {});
  std::vector<double> x = vortex.x, y = vortex.y;
  for (Index p = 0; p < vortex.num_points(); ++p) {
    if (rcv.kind[p] == RezonePointKind::slide || vortex.x[p] == 0 || vortex.x[p] == 1) continue;
    const double dx = vortex.x[p] - 0.55, dy = vortex.y[p] - 0.5, r2 = dx * dx + dy * dy;
    const double turn = 1.6 * std::exp(-r2 / 0.04);
    x[p] = 0.55 + std::cos(turn) * dx - std::sin(turn) * dy;
    y[p] = 0.5 + std::sin(turn) * dx + std::cos(turn) * dy;
  }
  rezone_case("rezone_vortex", vortex, rcv, o, x, y, true);

  // 2. The gmsh-unstructured blast box with random interior motion and crowded walls.
  meshgen::GeoOptions go;
  go.parameters = {{"n", 12}};
  const Mesh box = build_mesh(meshgen::read_geo(std::string(STAGGER_SOURCE_DIR) + "/geometries/blast_box.geo", go));
  const RezoneConstraints rcb = make_rezone_constraints(box, {});
  x = box.x;
  y = box.y;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (Index p = 0; p < box.num_points(); ++p) {
    const double a = u(rng), b = u(rng);
    if (rcb.kind[p] == RezonePointKind::interior) {
      x[p] += 0.3 / 12 * a;
      y[p] += 0.3 / 12 * b;
    } else if (rcb.kind[p] == RezonePointKind::slide && (box.y[p] == 0 || box.y[p] == 1)) {
      x[p] = 2 * std::pow(box.x[p] / 2, 1.3);  // crowd the walls toward x = 0
    }
  }
  rezone_case("rezone_gmsh_winslow", box, rcb, o, x, y);
  o.method = RezoneMethod::reference_jacobian;
  rezone_case("rezone_gmsh_reference", box, rcb, o, x, y);
}

}  // namespace
}  // namespace stagger
