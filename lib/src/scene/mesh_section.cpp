// [mesh]: a .geo/.msh file or a built-in generator, refined, transformed, perturbed, built.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <numbers>
#include <random>

#include "scene_internal.hpp"
#include "stagger/error.hpp"
#include "stagger/meshgen.hpp"

namespace stagger::scene_detail {

namespace {

// Stated limits (docs/scenes.md): a count of the generators, the zones of one generated mesh
// (4 corners a zone must fit the 32-bit Index: 5.3e8; 1e8 zones already need ~100 GB), and
// the refinement factor.
constexpr long kMaxCount = 10'000'000;
constexpr long kMaxZones = 100'000'000;
constexpr double kMaxRefine = 1000;
// .geo parameters (docs/mesh.md): a zone count listed in mesh.refined, after refine, and any
// value at all (a length or a count; gmsh's doubles cannot separate points at 1e15).
constexpr double kMaxGeoCount = static_cast<double>(kMaxCount);
constexpr double kMaxGeoParameter = 1e15;

std::string join(const std::vector<std::string>& names) {
  std::string list;
  for (const auto& name : names) list += (list.empty() ? "" : ", ") + name;
  return list.empty() ? "(none)" : list;
}

// An integer count of the generator, multiplied by `refine` if `refined` names it.
struct Counts {
  std::map<std::string, long> values;
};

// Uniform double in [0, 1) from the top 53 bits: the same on every standard library.
double uniform01(std::mt19937_64& generator) {
  return static_cast<double>(generator() >> 11) * 0x1.0p-53;
}

// Moves every interior point by up to `fraction` of its shortest incident edge in x and
// y, reproducibly from `seed` (the stress tests of docs/robustness.md §2). Boundary points stay.
void perturb_mesh(Mesh& mesh, double fraction, std::uint64_t seed, Section& section) {
  const Index npoints = mesh.num_points();
  std::vector<double> shortest(npoints, std::numeric_limits<double>::infinity());
  std::map<std::pair<Index, Index>, int> edge_count;
  for (Index z = 0; z < mesh.num_zones(); ++z) {
    const Index begin = mesh.zone_corner_begin[z], end = mesh.zone_corner_begin[z + 1];
    for (Index c = begin; c < end; ++c) {
      const Index a = mesh.corner_point[c], b = mesh.corner_point[c + 1 < end ? c + 1 : begin];
      const double length = std::hypot(mesh.x[b] - mesh.x[a], mesh.y[b] - mesh.y[a]);
      shortest[a] = std::min(shortest[a], length);
      shortest[b] = std::min(shortest[b], length);
      ++edge_count[{std::min(a, b), std::max(a, b)}];
    }
  }
  std::vector<char> on_boundary(npoints, 0);
  for (const auto& [edge, count] : edge_count)
    if (count == 1) on_boundary[edge.first] = on_boundary[edge.second] = 1;
  std::mt19937_64 generator(seed);
  for (Index p = 0; p < npoints; ++p) {
    const double dx = (2 * uniform01(generator) - 1) * fraction * shortest[p];
    const double dy = (2 * uniform01(generator) - 1) * fraction * shortest[p];
    if (on_boundary[p] || !std::isfinite(shortest[p])) continue;
    mesh.x[p] += dx;
    mesh.y[p] += dy;
  }
  for (Index z = 0; z < mesh.num_zones(); ++z)
    if (!(zone_area(mesh, z) > 0))
      section.fail(
          "perturb",
          "zone " + std::to_string(z) + " is inverted after the perturbation (seed " + std::to_string(seed) + ")",
          "use a smaller perturb or another seed");
}

}  // namespace

Mesh read_mesh_section(Section& section, const std::string& scene_file, std::vector<std::string>& notes) {
  const bool has_file = section.has("file"), has_generator = section.has("generator");
  if (has_file == has_generator)
    section.fail(has_file ? "generator" : "file",
                 has_file ? "give either file or generator, not both" : "missing: the mesh needs a file or a generator",
                 "write file = \"shape.geo\" or generator = \"rectangle\"");
  const double refine = section.number("refine", 1.0);
  if (!(refine > 0)) section.fail("refine", "must be > 0, got " + show(refine));
  if (refine > kMaxRefine) section.fail("refine", "must be at most " + show(kMaxRefine) + ", got " + show(refine));
  const std::vector<std::string> refined =
      section.has("refined") ? section.strings("refined") : std::vector<std::string>{};
  const bool quads_only = section.boolean("quads_only", false);

  // The product is formed in double and checked before any conversion, so that no count
  // wraps around (nx = 4294967297 once ran one zone wide) or reads as negative.
  auto refined_count = [&](const std::string& key, long base) {
    const bool listed = !section.has("refined") || std::find(refined.begin(), refined.end(), key) != refined.end();
    const double value = listed ? std::round(static_cast<double>(base) * refine) : static_cast<double>(base);
    if (value < 1)
      section.fail(key,
                   show(static_cast<double>(base)) + " refined by " + show(refine) + " gives " + show(value) +
                       " zones; must be >= 1",
                   "raise mesh.refine or the count");
    if (value > static_cast<double>(kMaxCount))
      section.fail(key,
                   show(static_cast<double>(base)) + " refined by " + show(refine) + " gives " + show(value) +
                       " zones, above the limit of " + std::to_string(kMaxCount),
                   "lower mesh.refine or the count");
    return static_cast<int>(value);
  };
  auto check_zone_total = [&](const char* first, int a, const char* second, int b) {
    const double total = static_cast<double>(a) * static_cast<double>(b);
    if (total > static_cast<double>(kMaxZones))
      section.fail(first,
                   std::string(first) + " x " + second + " = " + std::to_string(a) + " x " + std::to_string(b) + " = " +
                       show(total) + " zones, above the limit of " + std::to_string(kMaxZones) + " zones per mesh",
                   "use fewer zones");
  };
  auto check_refined = [&](const std::vector<std::string>& allowed) {
    for (const auto& name : refined)
      if (std::find(allowed.begin(), allowed.end(), name) == allowed.end())
        section.fail("refined", "'" + name + "' is not a parameter of this mesh", "use some of " + join(allowed));
  };

  PolygonSoup soup;
  std::string mesh_label;
  if (has_generator) {
    const std::string generator = section.choice("generator", {"rectangle", "annulus_sector", "annulus"});
    mesh_label = generator;
    auto positive_count = [&](const std::string& key) { return section.integer_in(key, 1, kMaxCount); };
    auto radii = [&]() {
      const auto r = section.numbers("r", 2);
      if (!(r[0] >= 0 && r[1] > r[0])) section.fail("r", "needs 0 <= r0 < r1", "write r = [r0, r1]");
      return r;
    };
    if (generator == "rectangle") {
      const auto x = section.numbers("x", 2), y = section.numbers("y", 2);
      if (!(x[1] > x[0])) section.fail("x", "needs x0 < x1", "write x = [x0, x1]");
      if (!(y[1] > y[0])) section.fail("y", "needs y0 < y1", "write y = [y0, y1]");
      // The extent and the zone widths must be finite numbers, not overflow to inf.
      if (!std::isfinite(x[1] - x[0])) section.fail("x", "the extent x1 - x0 overflows", "use smaller coordinates");
      if (!std::isfinite(y[1] - y[0])) section.fail("y", "the extent y1 - y0 overflows", "use smaller coordinates");
      check_refined({"nx", "ny"});
      const int nx = refined_count("nx", positive_count("nx")), ny = refined_count("ny", positive_count("ny"));
      check_zone_total("nx", nx, "ny", ny);
      soup = meshgen::rectangle(x[0], x[1], y[0], y[1], nx, ny);
    } else if (generator == "annulus_sector") {
      const auto r = radii();
      const auto theta = section.numbers("theta", 2);
      if (!(theta[1] > theta[0] && theta[1] - theta[0] <= 360))
        section.fail("theta", "needs theta0 < theta1 <= theta0 + 360 (degrees)");
      check_refined({"n_theta", "n_r"});
      const int n_theta = refined_count("n_theta", positive_count("n_theta"));
      const int n_r = refined_count("n_r", positive_count("n_r"));
      check_zone_total("n_theta", n_theta, "n_r", n_r);
      const double degree = std::numbers::pi / 180;
      soup = meshgen::annulus_sector(r[0], r[1], theta[0] * degree, theta[1] * degree, n_theta, n_r);
    } else {
      const auto r = radii();
      if (!(r[0] > 0)) section.fail("r", "a full annulus needs r0 > 0", "use annulus_sector for a disc");
      check_refined({"n_theta", "n_r"});
      const int n_theta = refined_count("n_theta", positive_count("n_theta"));
      const int n_r = refined_count("n_r", positive_count("n_r"));
      check_zone_total("n_theta", n_theta, "n_r", n_r);
      soup = meshgen::annulus(r[0], r[1], n_theta, n_r);
    }
  } else {
    const std::string file = section.string("file");
    const std::filesystem::path resolved =
        std::filesystem::path(scene_file).parent_path() / std::filesystem::path(file);
    mesh_label = file;
    const std::string extension = resolved.extension().string();
    if (extension != ".geo" && extension != ".msh")
      section.fail("file", "'" + file + "' is neither a .geo nor a .msh file");
    if (const std::string problem = meshgen::file_problem(resolved.string()); !problem.empty())
      section.fail("file",
                   "'" + file + "' " + problem + (problem.rfind("not found", 0) == 0 ? "" : ", not a regular file") +
                       " (looked for " + resolved.lexically_normal().string() + ")",
                   "paths are relative to the scene file");
    meshgen::GeoOptions options;
    const std::string triangles = section.choice("triangles", {"accept", "subdivide", "reject"}, "accept");
    options.triangles = triangles == "accept"      ? meshgen::TrianglePolicy::accept
                        : triangles == "subdivide" ? meshgen::TrianglePolicy::subdivide
                                                   : meshgen::TrianglePolicy::reject;
    // gmsh runs in a child process with these limits (docs/mesh.md, "gmsh in a child process").
    options.time_limit_seconds = section.number("gmsh_time_limit", options.time_limit_seconds);
    if (!(options.time_limit_seconds >= 0 && std::isfinite(options.time_limit_seconds)))
      section.fail("gmsh_time_limit", "must be >= 0 seconds (0: no limit), got " + show(options.time_limit_seconds));
    options.memory_limit_mib = section.number("gmsh_memory_limit", options.memory_limit_mib);
    if (!(options.memory_limit_mib >= 0 && std::isfinite(options.memory_limit_mib)))
      section.fail("gmsh_memory_limit", "must be >= 0 MiB (0: no limit), got " + show(options.memory_limit_mib));
    options.max_points = section.number("max_points", options.max_points);
    if (!(options.max_points >= 0 && std::isfinite(options.max_points)))
      section.fail("max_points", "must be >= 0 (0: no limit), got " + show(options.max_points));
    options.allow_commands = section.boolean("allow_geo_commands", false);
    std::vector<std::string> parameter_names;
    if (auto parameters = section.subtable("parameters")) {
      for (const auto& [key, node] : parameters->table()) {
        const std::string name(key.str());
        parameter_names.push_back(name);
        double value = parameters->number(name);
        // A .geo parameter is a length or a count: 1e308 or a negative count makes no sense.
        if (!(std::abs(value) <= kMaxGeoParameter))
          parameters->fail(name,
                           "must be within +-" + show(kMaxGeoParameter) + ", got " + show(value) +
                               ": no length or count of a mesh is that large",
                           "check the value and its units");
        if (std::find(refined.begin(), refined.end(), name) != refined.end()) {
          value *= refine;
          if (!(value >= 1 && value <= kMaxGeoCount))
            parameters->fail(name,
                             "is a zone count (listed in mesh.refined): must be in [1, " + show(kMaxGeoCount) +
                                 "], got " + show(value) + (refine != 1 ? " after mesh.refine = " + show(refine) : ""),
                             "give a positive count");
        }
        options.parameters.emplace_back(name, value);
      }
      parameters->finish();
    }
    if (extension == ".msh" && !parameter_names.empty())
      section.fail("parameters", "a .msh file takes no parameters", "remove [mesh.parameters]");
    check_refined(parameter_names);
    if (refine != 1 && refined.empty())
      section.fail("refine", "refine = " + show(refine) + " but mesh.refined lists no parameter",
                   "list the [mesh.parameters] that set the zone counts, e.g. refined = [\"n\"]");
    try {
      soup = meshgen::read_mesh_file(resolved.string(), options);
    } catch (const Error& failure) {
      section.fail("file", failure.what());
    }
  }

  // Coordinate transform of the generated points (e.g. the Saltzman mesh).
  bool transformed = false;
  if (auto transform = section.subtable("transform")) {
    transformed = true;
    std::optional<Expression> fx, fy;
    if (transform->has("x")) fx = transform->value_or_expression("x", {"x", "y"}).expression;
    if (transform->has("y")) fy = transform->value_or_expression("y", {"x", "y"}).expression;
    transform->finish();
    for (std::size_t p = 0; p < soup.x.size(); ++p) {
      const double x = soup.x[p], y = soup.y[p];
      const double new_x = fx ? (*fx)(x, y) : x, new_y = fy ? (*fy)(x, y) : y;
      if (!std::isfinite(new_x) || !std::isfinite(new_y))
        transform->fail(std::isfinite(new_x) ? "y" : "x", "not finite at the point (" + show(x) + ", " + show(y) + ")",
                        "guard the expression, e.g. with ?:");
      soup.x[p] = new_x;
      soup.y[p] = new_y;
    }
  }

  const double perturb = section.number("perturb", 0.0);
  if (!(perturb >= 0 && perturb < 0.5)) section.fail("perturb", "must be in [0, 0.5), got " + show(perturb));
  const long seed = section.integer_in("seed", 1, 0, std::numeric_limits<long>::max());
  section.finish();

  MeshBuildOptions build_options;
  build_options.quads_only = quads_only;
  // Untransformed generators are valid by construction: skip CGAL's halfedge build (time and
  // peak memory); a transform may fold the mesh, so it gets the full check (the overlap test
  // runs for every mesh).
  build_options.check_topology = has_file || transformed;
  MeshBuildReport report;
  Mesh mesh;
  try {
    mesh = build_mesh(soup, build_options, &report);
  } catch (const Error& failure) {
    if (has_file) section.fail("file", failure.what());
    if (transformed) section.fail("transform", std::string("the transformed mesh is invalid: ") + failure.what());
    section.fail("generator", failure.what());
  }
  // The report's notes already count reoriented zones and dropped points.
  for (const auto& note : report.notes) notes.push_back("mesh " + mesh_label + ": " + note);
  if (perturb > 0) perturb_mesh(mesh, perturb, static_cast<std::uint64_t>(seed), section);
  return mesh;
}

}  // namespace stagger::scene_detail
