// Scene files: every error names the file, the line and the key; overrides; every scene loads.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>

#include "stagger/error.hpp"
#include "stagger/scene.hpp"
#include "support/scene_toml.hpp"
#include "support/scratch_directory.hpp"

namespace fs = std::filesystem;

namespace {

namespace toml = stagger::testing::toml;

// A tiny valid scene; line numbers below refer to this text: 1-2 [time] (2: end), 3-8 [mesh]
// (4: generator, 7: nx), 9-12 [[material]], 13-17 [[region]] (14: name, 15: material,
// 16: density, 17: pressure), 18-20 [[boundary]] (19: tags, 20: type).
const std::string base_scene = toml::time("0.1") + toml::rectangle("[0.0, 1.0]", "[0.0, 0.1]", 10, 2) +
                               toml::ideal_gas() + toml::gas_region() + toml::walls();

class SceneFile : public ::testing::Test {
 protected:
  std::string write(const std::string& text, const std::string& name = "scene.toml") {
    return scratch_.write(name, text);
  }
  // Replaces the first occurrence of `from` in the base scene.
  static std::string edit(const std::string& from, const std::string& to) {
    std::string text = base_scene;
    const auto position = text.find(from);
    EXPECT_NE(position, std::string::npos) << from;
    return text.replace(position, from.size(), to);
  }
  // The message of the Error that loading `text` throws ("" if none).
  std::string error_of(const std::string& text,
                       const std::vector<std::pair<std::string, std::string>>& overrides = {}) {
    const std::string path = write(text);
    try {
      stagger::load_scene(path, overrides);
    } catch (const stagger::Error& error) {
      EXPECT_EQ(std::string(error.what()).find('\n'), std::string::npos) << "one line: " << error.what();
      return error.what();
    }
    return "";
  }
  std::string located(int line) const { return (directory_ / "scene.toml").string() + ":" + std::to_string(line); }

  const stagger::testing::ScratchDirectory scratch_{"scene_test_" +
                                                    std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                                                    "_" + stagger::testing::current_test_name()};
  const fs::path directory_ = scratch_.path();
};

#define EXPECT_CONTAINS(text, part) EXPECT_NE(std::string(text).find(part), std::string::npos) << (text)

TEST_F(SceneFile, ValidSceneLoadsWithDefaults) {
  const stagger::Scene scene = stagger::load_scene(write(base_scene));
  EXPECT_EQ(scene.problem.mesh.num_zones(), 20);
  EXPECT_EQ(scene.problem.name, "scene");  // the file stem
  EXPECT_EQ(scene.control.output_directory, "output/scene");
  EXPECT_DOUBLE_EQ(scene.problem.t_end, 0.1);
  EXPECT_DOUBLE_EQ(scene.problem.options.cfl, 0.15);
  EXPECT_EQ(scene.problem.boundaries.size(), 4u);
  EXPECT_FALSE(stagger::describe(scene).empty());
}

// A distributed run's other ranks (docs/parallel.md): the scene read against rank 0's outline
// of the mesh gives the same set-up without a zone, and the names the outline lacks are errors.
TEST_F(SceneFile, SceneReadWithoutMeshMatchesTheFullReadButTheZones) {
  const std::string path = write(base_scene);
  const stagger::Scene full = stagger::load_scene(path);
  stagger::Mesh outline = full.problem.mesh;  // load_scene_without_mesh keeps only the names
  const stagger::Scene part = stagger::load_scene_without_mesh(path, {}, outline);
  EXPECT_EQ(part.problem.mesh.num_zones(), 0);
  EXPECT_EQ(part.problem.mesh.num_points(), 0);
  EXPECT_EQ(part.problem.mesh.region_names, full.problem.mesh.region_names);
  ASSERT_EQ(part.problem.mesh.tags.size(), full.problem.mesh.tags.size());
  for (const auto& tag : part.problem.mesh.tags) EXPECT_TRUE(tag.edges.empty() && tag.points.empty());
  EXPECT_EQ(part.problem.regions.size(), full.problem.regions.size());
  EXPECT_EQ(part.problem.boundaries.size(), full.problem.boundaries.size());
  EXPECT_DOUBLE_EQ(part.problem.t_end, full.problem.t_end);
  EXPECT_EQ(part.control.output_directory, full.control.output_directory);
  outline.tags.pop_back();
  try {
    stagger::load_scene_without_mesh(path, {}, outline);
    ADD_FAILURE() << "a boundary tag missing from the outline was accepted";
  } catch (const stagger::Error& error) {
    EXPECT_CONTAINS(error.what(), "the mesh has no boundary tag '" + full.problem.mesh.tags.back().name + "'");
  }
}

TEST_F(SceneFile, MalformedTomlNamesLineAndColumn) {
  const std::string message = error_of(edit("nx = 10", "nx = = 10"));
  EXPECT_CONTAINS(message, located(7) + ":");
  EXPECT_CONTAINS(message, "malformed TOML");
}

TEST_F(SceneFile, UnknownKeyNamesLineKeyAndTheKnownKeys) {
  const std::string message = error_of(edit("ny = 2", "ny = 2\nnz = 3"));
  EXPECT_CONTAINS(message, located(9) + ": key 'mesh.nz': unknown key");
  EXPECT_CONTAINS(message, "ny");
}

TEST_F(SceneFile, UnknownSectionIsRejectedBeforeMeshing) {
  const std::string message = error_of(std::string(base_scene) + "[numerix]\ncfl = 0.1\n");
  EXPECT_CONTAINS(message, located(21) + ": key 'numerix': unknown key");
}

TEST_F(SceneFile, WrongTypeNamesTheKey) {
  const std::string message = error_of(edit("nx = 10", "nx = \"ten\""));
  EXPECT_CONTAINS(message, located(7) + ": key 'mesh.nx': expected an integer, got a string");
}

TEST_F(SceneFile, MissingRequiredKeyNamesTheSection) {
  const std::string message = error_of(edit("end = 0.1\n", ""));
  EXPECT_CONTAINS(message, located(1) + ": key 'time.end': missing");
}

TEST_F(SceneFile, UnknownRegionListsTheMeshRegions) {
  const std::string message = error_of(edit("name = \"domain\"", "name = \"dome\""));
  EXPECT_CONTAINS(message, located(14) + ": key 'region[0].name': the mesh has no region 'dome'");
  EXPECT_CONTAINS(message, "domain");
}

TEST_F(SceneFile, UnknownTagListsTheMeshTags) {
  const std::string message = error_of(edit("\"top\"]", "\"roof\"]"));
  EXPECT_CONTAINS(message, located(19) + ": key 'boundary[0].tags': the mesh has no boundary tag 'roof'");
  EXPECT_CONTAINS(message, "left, right, bottom, top");
}

TEST_F(SceneFile, TagWithoutBoundaryIsNamed) {
  const std::string message = error_of(edit(", \"top\"]", "]"));
  EXPECT_CONTAINS(message, "key 'boundary': mesh tag(s) top have no [[boundary]]");
}

TEST_F(SceneFile, UnknownMaterialListsTheMaterials) {
  const std::string message = error_of(edit("material = \"gas\"", "material = \"air\""));
  EXPECT_CONTAINS(message, located(15) + ": key 'region[0].material': unknown material 'air'");
  EXPECT_CONTAINS(message, "materials: gas");
}

TEST_F(SceneFile, MeshRegionWithoutSetupIsNamed) {
  std::ofstream(directory_ / "two.geo") << R"(
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {2, 0, 0};
Point(4) = {2, 1, 0}; Point(5) = {1, 1, 0}; Point(6) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 5}; Line(3) = {5, 6}; Line(4) = {6, 1};
Line(5) = {2, 3}; Line(6) = {3, 4}; Line(7) = {4, 5};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, -2}; Plane Surface(2) = {2};
Transfinite Curve{1:7} = 3; Transfinite Surface{1, 2}; Recombine Surface{1, 2};
Physical Surface("gas") = {1}; Physical Surface("metal") = {2};
Physical Curve("outside") = {1, 3, 4, 5, 6, 7};
)";
  std::string text = base_scene;
  text.replace(text.find("generator"), text.find("[[material]]") - text.find("generator"), "file = \"two.geo\"\n");
  text.replace(text.find("name = \"domain\""), 15, "name = \"gas\"");
  text.replace(text.find("tags = ["), text.find("type = \"wall\"") - text.find("tags = ["), "tag = \"outside\"\n");
  const std::string message = error_of(text);
  EXPECT_CONTAINS(message, "mesh region(s) metal have no [[region]]");
}

TEST_F(SceneFile, ExpressionThatDoesNotParseIsNamed) {
  const std::string message = error_of(edit("density = 1.0", "density = \"1 + * x\""));
  EXPECT_CONTAINS(message, located(16) + ": key 'region[0].density': expression \"1 + * x\" does not parse");
}

TEST_F(SceneFile, UnknownVariableInExpressionIsNamed) {
  const std::string message = error_of(edit("density = 1.0", "density = \"1 + z\""));
  EXPECT_CONTAINS(message, located(16) + ": key 'region[0].density'");
  EXPECT_CONTAINS(message, "\"z\"");
}

TEST_F(SceneFile, DivisionByZeroNamesThePoint) {
  const std::string message = error_of(edit("pressure = 1.0", "pressure = \"1 / (x - 0.05)\""));
  EXPECT_CONTAINS(message, located(17) + ": key 'region[0].pressure': evaluates to inf at (0.05, 0.025)");
}

TEST_F(SceneFile, NegativeDensityIsRejected) {
  EXPECT_CONTAINS(error_of(edit("density = 1.0", "density = -1.0")),
                  located(16) + ": key 'region[0].density': must be > 0");
  EXPECT_CONTAINS(error_of(edit("density = 1.0", "density = \"x < 0.5 ? 1 : -1\"")), "must be > 0, got -1");
}

TEST_F(SceneFile, NegativeIdealGasPressureIsRejected) {
  EXPECT_CONTAINS(error_of(edit("pressure = 1.0", "pressure = -1.0")), "must be >= 0 for an ideal gas");
}

TEST_F(SceneFile, CflOutsideTheUnitIntervalIsRejected) {
  EXPECT_CONTAINS(error_of(std::string(base_scene) + "[numerics]\ncfl = 1.5\n"),
                  located(22) + ": key 'numerics.cfl': must be in (0, 1");
  EXPECT_CONTAINS(error_of(std::string(base_scene) + "[numerics]\ncfl = 0\n"), "key 'numerics.cfl'");
}

TEST_F(SceneFile, NonPositiveEndTimeIsRejected) {
  EXPECT_CONTAINS(error_of(edit("end = 0.1", "end = 0.0")), located(2) + ": key 'time.end': must be > 0");
  EXPECT_CONTAINS(error_of(edit("end = 0.1", "end = -1")), "key 'time.end': must be > 0");
}

TEST_F(SceneFile, UnknownChoiceListsTheOptions) {
  const std::string message = error_of(edit("type = \"wall\"", "type = \"mirror\""));
  EXPECT_CONTAINS(message, located(20) + ": key 'boundary[0].type': unknown value \"mirror\"");
  EXPECT_CONTAINS(message, "\"periodic\"");
}

TEST_F(SceneFile, MissingMeshFileIsNamed) {
  std::string text = base_scene;
  text.replace(text.find("generator = \"rectangle\""), 23, "file = \"nowhere.geo\"");
  const std::string message = error_of(text);
  EXPECT_CONTAINS(message, located(4) + ": key 'mesh.file': 'nowhere.geo' not found");
}

TEST_F(SceneFile, SetOverridesRefineEveryCountByDefault) {
  const stagger::Scene scene = stagger::load_scene(write(base_scene), {{"mesh.refine", "2"}});
  EXPECT_EQ(scene.problem.mesh.num_zones(), 80);
}

TEST_F(SceneFile, RefinedListsWhichCountsRefineMultiplies) {
  const stagger::Scene scene =
      stagger::load_scene(write(edit("ny = 2", "ny = 2\nrefined = [\"nx\"]")), {{"mesh.refine", "3"}});
  EXPECT_EQ(scene.problem.mesh.num_zones(), 60);
  EXPECT_CONTAINS(error_of(edit("ny = 2", "ny = 2\nrefined = [\"nz\"]")), "'nz' is not a parameter of this mesh");
}

TEST_F(SceneFile, SetCreatesMissingSectionsAndParsesValues) {
  const stagger::Scene scene = stagger::load_scene(write(base_scene), {{"numerics.cfl", "0.3"},
                                                                       {"numerics.viscosity", "edge"},
                                                                       {"output.dumps", "false"},
                                                                       {"region[0].density", "\"2 + x\""},
                                                                       {"time.end", "0.05"}});
  EXPECT_DOUBLE_EQ(scene.problem.options.cfl, 0.3);
  EXPECT_EQ(scene.problem.options.viscosity, stagger::Viscosity::edge);
  EXPECT_FALSE(scene.control.dumps);
  EXPECT_DOUBLE_EQ(scene.problem.regions[0].density(0.5, 0.0), 2.5);
  EXPECT_DOUBLE_EQ(scene.problem.t_end, 0.05);
}

TEST_F(SceneFile, SetWithAnUnknownPathIsAnErrorNamingTheOverride) {
  EXPECT_CONTAINS(error_of(base_scene, {{"numerics.cfll", "0.3"}}),
                  "--set numerics.cfll=0.3: key 'numerics.cfll': unknown key");
  EXPECT_CONTAINS(error_of(base_scene, {{"nonsense.key", "1"}}), "--set nonsense.key=1: key 'nonsense': unknown key");
  EXPECT_CONTAINS(error_of(base_scene, {{"region[3].density", "1"}}), "'region' has 1 entries");
  EXPECT_CONTAINS(error_of(base_scene, {{"region.density", "1"}}), "pick one entry, e.g. region[0].density");
  EXPECT_CONTAINS(error_of(base_scene, {{"numerics.cfl", "2"}}),
                  "--set numerics.cfl=2: key 'numerics.cfl': must be in");
}

TEST_F(SceneFile, ExpressionsAreEvaluatedWithPiAndTernary) {
  const stagger::Scene scene = stagger::load_scene(
      write(edit("density = 1.0", "density = \"x < 0.5 ? 1 + sin(pi * x) : 0.125\"\nvelocity = [\"y\", 2]")));
  const auto& region = scene.problem.regions[0];
  EXPECT_NEAR(region.density(0.25, 0.0), 1 + std::sin(M_PI / 4), 1e-15);
  EXPECT_DOUBLE_EQ(region.density(0.75, 0.0), 0.125);
  EXPECT_DOUBLE_EQ(region.velocity_x(0.0, 0.07), 0.07);
  EXPECT_DOUBLE_EQ(region.velocity_y(0.3, 0.07), 2.0);
}

TEST_F(SceneFile, TimeDependentBoundaryVelocity) {
  const std::string text = edit("tags = [\"left\", \"right\", \"bottom\", \"top\"]\ntype = \"wall\"",
                                "tag = \"left\"\ntype = \"velocity\"\nvelocity = [\"t < 0.05 ? 2 * t : 0.1\", 0]\n"
                                "[[boundary]]\ntags = [\"right\", \"bottom\", \"top\"]\ntype = \"wall\"");
  const stagger::Scene scene = stagger::load_scene(write(text));
  ASSERT_EQ(scene.problem.boundaries.size(), 4u);
  EXPECT_EQ(scene.problem.boundaries[0].kind, stagger::BoundaryKind::velocity);
  EXPECT_DOUBLE_EQ(scene.problem.boundaries[0].velocity_x(0.01), 0.02);
  EXPECT_DOUBLE_EQ(scene.problem.boundaries[0].velocity_x(0.09), 0.1);
}

TEST_F(SceneFile, TransformMovesThePoints) {
  const stagger::Scene plain = stagger::load_scene(write(base_scene));
  const stagger::Scene skewed =
      stagger::load_scene(write(edit("ny = 2", "ny = 2\ntransform = { x = \"x + (0.1 - y) * sin(pi * x)\" }")));
  const auto& a = plain.problem.mesh;
  const auto& b = skewed.problem.mesh;
  ASSERT_EQ(a.num_points(), b.num_points());
  EXPECT_EQ(b.num_zones(), 20);
  // Every point is the image of the same point of the untransformed mesh: x moves by
  // (0.1 - y) sin(pi x), y stays. Interior points of the bottom and middle rows move.
  int moved = 0;
  for (stagger::Index p = 0; p < a.num_points(); ++p) {
    EXPECT_NEAR(b.x[p], a.x[p] + (0.1 - a.y[p]) * std::sin(M_PI * a.x[p]), 1e-14) << "point " << p;
    EXPECT_EQ(b.y[p], a.y[p]) << "point " << p;
    if (std::abs(b.x[p] - a.x[p]) > 1e-3) ++moved;
  }
  EXPECT_EQ(moved, 9 + 9);  // x0 = 0.1 ... 0.9 on y = 0 and y = 0.05; the top row y = 0.1 stays
}

// The Saltzman scene end to end: its mesh is the skewed one of docs/verification.md §4,
// x = x0 + (0.1 - y0) sin(pi x0), not the logical 100 x 10 grid (which would make the problem
// one-dimensional and hide the mesh imprint the scene exists to test).
TEST_F(SceneFile, SaltzmanSceneHasTheSkewedMesh) {
  const stagger::Scene scene = stagger::load_scene(std::string(STAGGER_SOURCE_DIR) + "/apps/scenes/saltzman.toml");
  const auto& mesh = scene.problem.mesh;
  ASSERT_EQ(mesh.num_zones(), 1000);
  ASSERT_EQ(mesh.num_points(), 101 * 11);
  std::multiset<long> bottom, top;  // x in units of 1e-9, rows y = 0 and y = 0.1
  for (stagger::Index p = 0; p < mesh.num_points(); ++p) {
    const long key = std::lround(mesh.x[p] * 1e9);
    if (mesh.y[p] == 0) bottom.insert(key);
    if (std::abs(mesh.y[p] - 0.1) < 1e-12) top.insert(key);
  }
  ASSERT_EQ(bottom.size(), 101u);
  ASSERT_EQ(top.size(), 101u);
  for (int i = 0; i <= 100; ++i) {
    const double x0 = i / 100.0;
    EXPECT_EQ(bottom.count(std::lround((x0 + 0.1 * std::sin(M_PI * x0)) * 1e9)), 1u) << "bottom, x0 = " << x0;
    EXPECT_EQ(top.count(std::lround(x0 * 1e9)), 1u) << "top, x0 = " << x0;
  }
  // The logical point x0 = 0.5 of the bottom row moved to 0.6.
  EXPECT_EQ(bottom.count(std::lround(0.5 * 1e9)), 0u);
}

TEST_F(SceneFile, PerturbMovesInteriorPointsOnly) {
  const stagger::Scene plain = stagger::load_scene(write(edit("ny = 2", "ny = 4")));
  const stagger::Scene shaken = stagger::load_scene(write(edit("ny = 2", "ny = 4\nperturb = 0.3\nseed = 7")));
  const auto& a = plain.problem.mesh;
  const auto& b = shaken.problem.mesh;
  ASSERT_EQ(a.num_points(), b.num_points());
  int moved = 0;
  for (stagger::Index p = 0; p < a.num_points(); ++p) {
    const bool boundary = a.x[p] == 0 || a.x[p] == 1 || a.y[p] == 0 || std::abs(a.y[p] - 0.1) < 1e-15;
    const double shift = std::hypot(b.x[p] - a.x[p], b.y[p] - a.y[p]);
    if (boundary) {
      EXPECT_EQ(shift, 0.0);
    }
    if (shift > 0) ++moved;
    EXPECT_LE(shift, 0.3 * 0.025 * std::sqrt(2.0) + 1e-15);  // shortest edge 0.025
  }
  EXPECT_EQ(moved, 9 * 3);
}

TEST_F(SceneFile, ClockwiseGeoIsRepairedWithANote) {
  std::string text = base_scene;
  const fs::path geometry = fs::path(STAGGER_SOURCE_DIR) / "geometries" / "clockwise_square.geo";
  text.replace(text.find("generator"), text.find("[[material]]") - text.find("generator"),
               "file = \"" + geometry.string() + "\"\n");
  text.replace(text.find("name = \"domain\""), 15, "name = \"square\"");
  const auto path = write(text);
  // An absolute path also works: it is joined to the scene's directory by path rules.
  const stagger::Scene scene = stagger::load_scene(path);
  ASSERT_FALSE(scene.notes.empty());
  EXPECT_CONTAINS(scene.notes.front(), "zones were clockwise");
}

TEST_F(SceneFile, PeriodicPartnersCoverBothTags) {
  const std::string text = edit("tags = [\"left\", \"right\", \"bottom\", \"top\"]\ntype = \"wall\"",
                                "tag = \"left\"\ntype = \"periodic\"\npartner = \"right\"\n"
                                "[[boundary]]\ntags = [\"bottom\", \"top\"]\ntype = \"wall\"");
  const stagger::Scene scene = stagger::load_scene(write(text));
  ASSERT_EQ(scene.problem.boundaries.size(), 3u);
  EXPECT_EQ(scene.problem.boundaries[0].partner, "right");
}

TEST_F(SceneFile, UnknownVerificationReferenceIsAnError) {
  EXPECT_CONTAINS(error_of(std::string(base_scene) + "[verification]\nreference = \"blast\"\n"),
                  located(22) + ": key 'verification.reference': unknown value \"blast\"");
}

TEST_F(SceneFile, ShockTubeReferenceIsInstalled) {
  const stagger::Scene scene =
      stagger::load_scene(write(std::string(base_scene) +
                                "[verification]\nreference = \"shock_tube\"\nleft = { density = 1.0, pressure = 1.0 }\n"
                                "right = { density = 0.125, pressure = 0.1 }\nx0 = 0.5\n"));
  EXPECT_TRUE(static_cast<bool>(scene.control.reference));
}

TEST(Scenes, EveryExampleSceneLoadsAndValidates) {
  const fs::path directory = fs::path(STAGGER_SOURCE_DIR) / "apps" / "scenes";
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(directory)) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().string());
    names.insert(entry.path().stem().string());
    stagger::Scene scene;
    ASSERT_NO_THROW(scene = stagger::load_scene(entry.path().string())) << [&] {
      try {
        stagger::load_scene(entry.path().string());
      } catch (const std::exception& error) {
        return std::string(error.what());
      }
      return std::string();
    }();
    EXPECT_EQ(scene.problem.name, entry.path().stem().string());
    EXPECT_GT(scene.problem.t_end, 0);
    EXPECT_GT(scene.problem.mesh.num_zones(), 0);
    // The verification problems carry their reference; demonstrations (he_plate,
    // elastic_wave) may have none.
    const std::set<std::string> verification = {"sod",    "noh",      "noh_polar", "sedov",  "saltzman", "smooth",
                                                "piston", "be_shell", "accuracy",  "noh_rz", "sedov_rz", "detonation"};
    if (verification.count(entry.path().stem().string())) {
      EXPECT_TRUE(static_cast<bool>(scene.control.reference)) << "a verification scene has a [verification]";
    }
    // Every scene is on a ladder: mesh.refine = 2 must give more zones.
    const stagger::Scene finer = stagger::load_scene(entry.path().string(), {{"mesh.refine", "2"}});
    EXPECT_GT(finer.problem.mesh.num_zones(), scene.problem.mesh.num_zones());
  }
  for (const char* name :
       {"sod", "noh", "noh_polar", "sedov", "saltzman", "smooth", "piston", "be_shell", "accuracy", "detonation"})
    EXPECT_EQ(names.count(name), 1u) << name;
}

TEST(Scenes, SodHasTheVerificationSetUp) {
  const stagger::Scene scene =
      stagger::load_scene(std::string(STAGGER_SOURCE_DIR) + "/apps/scenes/sod.toml", {{"mesh.refine", "2"}});
  EXPECT_EQ(scene.problem.mesh.num_zones(), 200 * 5);
  EXPECT_DOUBLE_EQ(scene.problem.t_end, 0.2);
  EXPECT_DOUBLE_EQ(scene.problem.options.hourglass_coefficient, 0.0);
  EXPECT_DOUBLE_EQ(scene.problem.regions[0].density(0.25, 0.05), 1.0);
  EXPECT_DOUBLE_EQ(scene.problem.regions[0].density(0.75, 0.05), 0.125);
}

// rz scenes: `stagger check` prints the masses per radian (the run's), and the whole 2 pi:
// rho = 1 on [0, 1] x [0, 0.1] is 0.1 / 2 = 0.05 per radian (it printed the planar 0.1).
TEST_F(SceneFile, CheckPrintsRzMassesPerRadian) {
  const std::string rz = stagger::describe(stagger::load_scene(write(base_scene + "[numerics]\ngeometry = \"rz\"\n")));
  EXPECT_CONTAINS(rz, "mass ~ 0.05 per radian (0.314159 in the full 2 pi)");
  const std::string planar = stagger::describe(stagger::load_scene(write(base_scene)));
  EXPECT_CONTAINS(planar, "mass ~ 0.1, pressure given");
}

// [ale] keys the mode never reads are warned, naming the key and why (docs/scenes.md "Warnings").
TEST_F(SceneFile, AleKeysTheModeIgnoresGetAWarning) {
  const auto warnings_of = [&](const std::string& ale) {
    std::string all;
    for (const std::string& w : stagger::load_scene(write(base_scene + "[ale]\n" + ale)).warnings) all += w + "\n";
    return all;
  };
  EXPECT_CONTAINS(warnings_of("relaxation = 0.3\n"),
                  "key 'ale.relaxation': is ignored: [ale] has no mode, so the run is Lagrangian");
  EXPECT_CONTAINS(warnings_of("mode = \"lagrangian\"\nremap_every = 5\n"),
                  "key 'ale.remap_every': is ignored: mode = \"lagrangian\" never rezones or remaps");
  const std::string eulerian =
      warnings_of("mode = \"eulerian\"\nquality_trigger = 0.3\nmax_move = 0.2\nlimiter = \"none\"\n");
  EXPECT_CONTAINS(eulerian, "key 'ale.quality_trigger': is ignored: mode = \"eulerian\" remaps after every cycle");
  EXPECT_CONTAINS(eulerian, "key 'ale.max_move': is ignored: mode = \"eulerian\" returns to the initial mesh");
  EXPECT_EQ(eulerian.find("ale.limiter"), std::string::npos) << eulerian;  // read by every remap
  EXPECT_CONTAINS(warnings_of("mode = \"ale\"\nsize_weight = 2\n"),
                  "key 'ale.size_weight': is ignored: it weighs a term of rezone = \"reference_jacobian\" only");
  EXPECT_EQ(warnings_of("mode = \"ale\"\nrelaxation = 0.3\nrezone = \"reference_jacobian\"\nsize_weight = 2\n"), "");
}

// Points shared by regions with different initial velocities take the first [[region]]'s: the
// order of the blocks decides their momentum, which is warned (0.9 % of the kinetic energy in
// the finding); the same velocity on both sides is not.
TEST_F(SceneFile, SharedPointsOfRegionsWithDifferentVelocitiesGetAWarning) {
  const auto scene = [&](const std::string& air_velocity) {
    return toml::time("0.1") + "[mesh]\nfile = \"" + STAGGER_SOURCE_DIR +
           "/geometries/water_air.geo\"\nquads_only = true\n[mesh.parameters]\nn_water = 7\nn_air = 3\nn_y = 1\n" +
           toml::ideal_gas() +
           "[[region]]\nname = \"water\"\nmaterial = \"gas\"\ndensity = 1.0\npressure = 1.0\nvelocity = [0.1, 0.0]\n"
           "[[region]]\nname = \"air\"\nmaterial = \"gas\"\ndensity = 1.0\npressure = 1.0\nvelocity = " +
           air_velocity + "\n" + toml::walls();
  };
  const stagger::Scene differing = stagger::load_scene(write(scene("[0.0, 0.0]")));
  ASSERT_EQ(differing.warnings.size(), 1u);
  EXPECT_CONTAINS(differing.warnings[0],
                  "key 'region[1].velocity': 2 point(s) shared with region 'water' (region[0]) "
                  "get different initial velocities");
  EXPECT_CONTAINS(differing.warnings[0], "up to |dv| = 0.1); the first [[region]] in the file wins there");
  EXPECT_TRUE(stagger::load_scene(write(scene("[0.1, 0.0]"))).warnings.empty());
}

// type = "fixed": a clamped boundary (docs/scenes.md), read and described.
TEST_F(SceneFile, FixedBoundaryIsReadAndDescribed) {
  const stagger::Scene scene = stagger::load_scene(write(edit("type = \"wall\"", "type = \"fixed\"")));
  ASSERT_EQ(scene.problem.boundaries.size(), 4u);
  EXPECT_EQ(scene.problem.boundaries[0].kind, stagger::BoundaryKind::fixed);
  EXPECT_CONTAINS(stagger::describe(scene), "left (2 edges): fixed (v = 0, clamped)");
}

// A burn that lights no zone before time.end (lit after the end, or too slow to arrive)
// never burns: warned, naming the key (docs/scenes.md "Warnings").
TEST_F(SceneFile, ABurnLitAfterTheEndGetsAWarning) {
  const auto warnings_of = [&](const std::string& burn) {
    const std::string text = toml::time("0.5") + toml::rectangle("[0.0, 1.0]", "[0.0, 0.5]", 4, 2) +
                             "[[material]]\nname = \"he\"\neos = \"jwl\"\nA = 8.545\nB = 0.205\nR1 = 4.6\nR2 = "
                             "1.35\nomega = 0.25\nrho0 = 1.84\n[material.burn]\n" +
                             burn + toml::region("he", "1.84", "1e-6") + toml::walls();
    std::string all;
    for (const std::string& w : stagger::load_scene(write(text)).warnings) all += w + "\n";
    return all;
  };
  EXPECT_CONTAINS(warnings_of("detonation_speed = 0.88\npoints = [[0.0, 0.0]]\ntime_offset = 1.0\n"),
                  "key 'material[0].burn.time_offset': no zone of material 'he' lights before time.end = 0.5");
  EXPECT_CONTAINS(warnings_of("detonation_speed = 1e-3\npoints = [[-1.0, 0.0]]\n"),
                  "key 'material[0].burn.detonation_speed': no zone of material 'he' lights before time.end");
  EXPECT_EQ(warnings_of("detonation_speed = 0.88\npoints = [[0.0, 0.0]]\n"), "");
}

// Unit slips (docs/scenes.md "Warnings"): constants implausible for the units a scene states in
// scene.units, and, whatever the units, a JWL A far from rho0 D^2 or a region density far from
// its material's rho0.
TEST_F(SceneFile, ConstantsImplausibleForTheSceneUnitsGetAWarning) {
  const auto warnings_of = [&](const std::string& units, const std::string& he, const std::string& density) {
    const std::string text =
        "[scene]\nunits = \"" + units + "\"\n" + toml::time("0.5") + toml::rectangle("[0.0, 1.0]", "[0.0, 0.5]", 4, 2) +
        "[[material]]\nname = \"he\"\neos = \"jwl\"\n" + he +
        "R1 = 4.6\nR2 = 1.35\nomega = 0.25\n[material.burn]\ndetonation_speed = 0.88\npoints = [[0.0, 0.0]]\n" +
        toml::region("he", density, "1e-6") + toml::walls();
    std::string all;
    for (const std::string& w : stagger::load_scene(write(text)).warnings) all += w + "\n";
    return all;
  };
  const std::string mbar = "A = 8.545\nB = 0.205\nrho0 = 1.84\n";
  EXPECT_EQ(warnings_of("cm, g, us, Mbar", mbar, "1.84"), "");
  const std::string pascal = warnings_of("cm, g, us, Mbar", "A = 8.545e11\nB = 2.05e10\nrho0 = 1.84\n", "1.84");
  EXPECT_CONTAINS(pascal,
                  "key 'material[0].A': 8.545e+11 is implausible for a JWL constant in the scene's units "
                  "(scene.units = \"cm, g, us, Mbar\": 1e-06 to 100 Mbar)");
  EXPECT_CONTAINS(pascal, "key 'material[0].B': 2.05e+10 is implausible");
  // Without stated units: A against rho0 D^2 of the burn.
  EXPECT_CONTAINS(warnings_of("", "A = 8.545e11\nB = 0.205\nrho0 = 1.84\n", "1.84"),
                  "key 'material[0].A': 8.545e+11 is 5.99");
  // An SI scene with the density in g/cm^3 (rho0 too), and a region density rho0 / 1000.
  EXPECT_CONTAINS(warnings_of("SI (m, kg, s, Pa)", "A = 8.545e11\nB = 2.05e10\nrho0 = 1.84\n", "1.84"),
                  "key 'material[0].rho0': 1.84 is implausible for the density of a condensed material");
  EXPECT_CONTAINS(warnings_of("cm, g, us, Mbar", "A = 8.545\nB = 0.205\nrho0 = 1.84\n", "0.00184"),
                  "key 'region[0].density': 0.00184 at (0.125, 0.125) is 0.001 times the rho0 = 1.84");
}

// type = "transmitting": the far-field pressure is the adjacent zone's at t = 0, or `pressure`.
TEST_F(SceneFile, TransmittingBoundaryIsReadAndDescribed) {
  const stagger::Scene initial = stagger::load_scene(write(edit("type = \"wall\"", "type = \"transmitting\"")));
  EXPECT_EQ(initial.problem.boundaries[0].kind, stagger::BoundaryKind::transmitting);
  EXPECT_TRUE(initial.problem.boundaries[0].far_field_from_initial_state);
  EXPECT_CONTAINS(stagger::describe(initial), "left (2 edges): transmitting (p = p0 + rho c u.n)");
  const stagger::Scene given =
      stagger::load_scene(write(edit("type = \"wall\"", "type = \"transmitting\"\npressure = \"1 + t\"")));
  EXPECT_FALSE(given.problem.boundaries[0].far_field_from_initial_state);
  EXPECT_DOUBLE_EQ(given.problem.boundaries[0].pressure(0.5), 1.5);
}

}  // namespace
