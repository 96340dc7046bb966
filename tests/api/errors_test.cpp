// Bad user data through the API throws stagger::Error whose message names the offending item.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <string>

#include "api_support.hpp"
#include "stagger/error.hpp"
#include "stagger/meshgen.hpp"
#include "stagger/run.hpp"
#include "stagger/simulation.hpp"

namespace stagger {
namespace {

using api_test::shock_tube;

// Runs `action`, expects a stagger::Error whose message holds every one of `words`.
void expect_error(const std::function<void()>& action, std::initializer_list<std::string> words) {
  try {
    action();
    ADD_FAILURE() << "no stagger::Error thrown (expected one mentioning '" << *words.begin() << "')";
  } catch (const Error& error) {
    const std::string message = error.what();
    for (const auto& word : words) EXPECT_NE(message.find(word), std::string::npos) << "message: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "a one-line message: " << message;
  }
}

// Builds a Simulation from a Sod problem edited by `edit`.
std::function<void()> simulate(const std::function<void(Problem&)>& edit) {
  return [edit] {
    Problem problem = shock_tube(20, 0.1);
    edit(problem);
    Simulation simulation(std::move(problem));
  };
}

TEST(ApiErrors, UnknownMaterialIsNamedWithTheDefinedOnes) {
  expect_error(simulate([](Problem& p) { p.regions[0].material = "copper"; }), {"copper", "domain", "gas"});
}

TEST(ApiErrors, RegionMissingFromTheMeshIsNamedWithTheMeshRegions) {
  expect_error(simulate([](Problem& p) { p.regions[0].region = "core"; }), {"core", "domain"});
}

TEST(ApiErrors, MeshRegionWithoutSetUpIsNamed) {
  expect_error(simulate([](Problem& p) { p.regions.clear(); }), {"domain", "no material"});
}

TEST(ApiErrors, NegativeDensityIsNamedWithRegionAndZone) {
  expect_error(simulate([](Problem& p) { p.regions[0].density = constant_field(-1.0); }),
               {"domain", "density", "-1", "zone"});
}

TEST(ApiErrors, CflOutOfRangeIsNamedWithItsValue) {
  expect_error(simulate([](Problem& p) { p.options.cfl = 0; }), {"cfl"});
  expect_error(simulate([](Problem& p) { p.options.cfl = 1.5; }), {"cfl", "1.5"});
}

TEST(ApiErrors, UnknownBoundaryTagIsNamedWithTheMeshTags) {
  expect_error(simulate([](Problem& p) { p.boundaries.push_back(api_test::wall("inlet")); }),
               {"inlet", "left", "right", "bottom", "top"});
}

TEST(ApiErrors, OtherBadSetUpsAreNamed) {
  expect_error(simulate([](Problem& p) { p.materials.push_back(p.materials[0]); }), {"gas", "twice"});
  expect_error(simulate([](Problem& p) { p.regions[0].specific_internal_energy = constant_field(1.0); }),
               {"domain", "pressure", "specific_internal_energy"});
  expect_error(simulate([](Problem& p) { p.t_end = 0; }), {"end time"});
  expect_error(simulate([](Problem& p) { p.materials[0].eos = IdealGas{0.9}; }), {"gas", "gamma"});
  // Problem::validate() alone gives the same messages as the Simulation constructor.
  Problem problem = shock_tube(20, 0.1);
  problem.regions[0].material = "copper";
  expect_error([&] { problem.validate(); }, {"copper"});
}

TEST(ApiErrors, MeshgenAndDriverRejectUnusableInput) {
  expect_error([] { meshgen::rectangle(0, 1, 0, 1, 0, 3); }, {"rectangle", "nx"});
  expect_error([] { meshgen::read_mesh_file("/nonexistent/shape.geo"); }, {"/nonexistent/shape.geo"});
  // A checkpoint of another mesh is refused.
  Simulation small(shock_tube(20, 0.1)), large(shock_tube(30, 0.1));
  const std::string blob = small.checkpoint();
  EXPECT_THROW(large.restore(blob), Error);
  // An output directory that is a file.
  const std::filesystem::path file = std::filesystem::path(STAGGER_BINARY_DIR) / "api-not-a-directory";
  std::ofstream(file) << "x";
  RunControl control;
  control.output_directory = file.string();
  expect_error([&] { run(small, control); }, {file.string()});
}

}  // namespace
}  // namespace stagger
