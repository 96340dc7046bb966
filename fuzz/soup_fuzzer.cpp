// libFuzzer target: the polygon-soup import (stagger::build_mesh). The fuzzed bytes build a
// soup with few, coarse coordinates (so that duplicate points, collinear corners, shared
// edges and bow-ties are common), arbitrary polygons, regions and tagged edges, and now and
// then a corrupt structure (offsets, ids). build_mesh must return a valid mesh or throw
// stagger::Error; a valid mesh is then checked (counter-clockwise zones, CSR consistency).
#include <fuzzer/FuzzedDataProvider.h>

#include <cstdint>
#include <cstdlib>

#include "stagger/error.hpp"
#include "stagger/mesh.hpp"

namespace {

void check_mesh(const stagger::Mesh& mesh) {
  using stagger::Index;
  // Invariants promised by mesh.hpp; a violation aborts (a finding).
  if (mesh.zone_corner_begin.back() != mesh.num_corners()) std::abort();
  for (Index z = 0; z < mesh.num_zones(); ++z) {
    if (mesh.zone_corner_begin[z + 1] - mesh.zone_corner_begin[z] < 3) std::abort();
    if (!(stagger::zone_area(mesh, z) > 0)) std::abort();
  }
  for (Index c = 0; c < mesh.num_corners(); ++c)
    if (mesh.corner_point[c] < 0 || mesh.corner_point[c] >= mesh.num_points()) std::abort();
  if (mesh.point_corner_begin.back() != mesh.num_corners()) std::abort();
  for (const auto& tag : mesh.tags)
    for (const auto& edge : tag.edges)
      if (edge[0] < 0 || edge[0] >= mesh.num_points() || edge[1] < 0 || edge[1] >= mesh.num_points()) std::abort();
  static_cast<void>(stagger::mesh_quality(mesh));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  stagger::PolygonSoup soup;
  soup.source = "fuzz";
  const int npoints = in.ConsumeIntegralInRange(0, 40);
  const bool fine = in.ConsumeBool();  // coarse grid (many coincidences) or arbitrary doubles
  for (int p = 0; p < npoints; ++p) {
    if (fine) {
      soup.x.push_back(in.ConsumeFloatingPoint<double>());
      soup.y.push_back(in.ConsumeFloatingPoint<double>());
    } else {
      soup.x.push_back(0.5 * in.ConsumeIntegralInRange(0, 8));
      soup.y.push_back(0.5 * in.ConsumeIntegralInRange(0, 8));
    }
  }
  const int npolygons = in.ConsumeIntegralInRange(0, 24);
  const int nregions = in.ConsumeIntegralInRange(0, 3);
  for (int r = 0; r < nregions; ++r) soup.region_names.push_back("r" + std::to_string(r));
  for (int f = 0; f < npolygons; ++f) {
    const int n = in.ConsumeIntegralInRange(2, 7);
    for (int k = 0; k < n; ++k) soup.polygon_points.push_back(in.ConsumeIntegralInRange<std::int64_t>(-1, npoints));
    soup.polygon_begin.push_back(static_cast<std::int64_t>(soup.polygon_points.size()));
    soup.polygon_region.push_back(in.ConsumeIntegralInRange(-1, 4));
  }
  const int ntags = in.ConsumeIntegralInRange(0, 3);
  for (int t = 0; t < ntags; ++t) soup.tag_names.push_back("t" + std::to_string(t));
  const int nedges = in.ConsumeIntegralInRange(0, 16);
  for (int e = 0; e < nedges; ++e)
    soup.tagged_edges.push_back({in.ConsumeIntegralInRange<std::int64_t>(-1, npoints),
                                 in.ConsumeIntegralInRange<std::int64_t>(-1, npoints),
                                 in.ConsumeIntegralInRange(-1, ntags)});
  // Sometimes corrupt the structure itself: an offset, or the size of a coordinate array.
  switch (in.ConsumeIntegralInRange(0, 7)) {
    case 0:
      if (soup.polygon_begin.size() > 1)
        soup.polygon_begin[in.ConsumeIntegralInRange<std::size_t>(0, soup.polygon_begin.size() - 1)] =
            in.ConsumeIntegralInRange<std::int64_t>(-2, 200);
      break;
    case 1:
      if (!soup.y.empty()) soup.y.pop_back();
      break;
    case 2:
      if (!soup.polygon_region.empty()) soup.polygon_region.pop_back();
      break;
    default:
      break;
  }
  stagger::MeshBuildOptions options;
  options.quads_only = in.ConsumeBool();
  try {
    stagger::MeshBuildReport report;
    const stagger::Mesh mesh = stagger::build_mesh(soup, options, &report);
    check_mesh(mesh);
  } catch (const stagger::Error&) {
  }
  return 0;
}
