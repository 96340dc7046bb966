// The plane-strain Taylor bar scene (docs/solids.md §8), coarse and short: the taylor_bar
// diagnostics describe the bar and the impact face stays on the wall.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "stagger/scene.hpp"
#include "stagger/simulation.hpp"
#include "support/named_values.hpp"

namespace stagger {
namespace {

using testing::value_of;

}  // namespace

TEST(TaylorBar, DiagnosticsDescribeTheFlatteningBar) {
  // 5 zones across, 10 us at 200 m/s: the face has spread and the bar has shortened.
  Scene scene = load_scene(std::string(STAGGER_SOURCE_DIR) + "/apps/scenes/taylor_bar_200.toml",
                           {{"mesh.parameters.n", "5"}, {"time.end", "10e-6"}});
  const Reference reference = scene.control.reference;
  ASSERT_TRUE(reference);
  Simulation sim(std::move(scene.problem));
  sim.advance_to(10e-6);
  NamedValues errors, diagnostics;
  reference(sim, errors, diagnostics);
  const auto x = sim.x(), y = sim.y();
  const double top = *std::max_element(y.begin(), y.end()), bottom = *std::min_element(y.begin(), y.end());
  EXPECT_NEAR(bottom, 0.0, 1e-15);  // the wall's points stay on it
  EXPECT_EQ(value_of(diagnostics, "final_length"), top);
  EXPECT_NEAR(value_of(diagnostics, "length_ratio"), top / 0.05, 1e-15);
  // 200 m/s for 10 us moves the top 2 mm at most; the elastic-plastic wave slows it first.
  EXPECT_LT(top, 0.05 - 1e-4);
  EXPECT_GT(top, 0.05 - 2e-3);
  const double face = value_of(diagnostics, "impact_face_width"), width = value_of(diagnostics, "max_width");
  EXPECT_GT(face, 0.01);
  EXPECT_LE(face, width);
  EXPECT_NEAR(width, *std::max_element(x.begin(), x.end()) - *std::min_element(x.begin(), x.end()), 1e-15);
  EXPECT_GT(value_of(diagnostics, "max_plastic_strain"), 0.01);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);
}

}  // namespace stagger
