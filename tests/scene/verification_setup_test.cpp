// Scene::verification: the reference parameters the reader resolved (material constants,
// defaults, --set overrides), which stagger-profile builds its exact fields from.
#include <gtest/gtest.h>

#include <string>
#include <variant>

#include "stagger/scene.hpp"

namespace {

std::string scene_path(const char* name) {
  return std::string(STAGGER_SOURCE_DIR) + "/apps/scenes/" + name;
}

}  // namespace

TEST(VerificationSetup, ShockTubeTakesTheTableTheMaterialAndOverrides) {
  const stagger::Scene scene = stagger::load_scene(scene_path("sod.toml"), {{"verification.x0", "0.4"}});
  EXPECT_EQ(scene.verification.name, "shock_tube");
  const auto* tube = std::get_if<stagger::ShockTubeReference>(&scene.verification.parameters);
  ASSERT_NE(tube, nullptr);
  EXPECT_EQ(tube->left.density, 1.0);
  EXPECT_EQ(tube->left.pressure, 1.0);
  EXPECT_EQ(tube->right.density, 0.125);
  EXPECT_EQ(tube->right.pressure, 0.1);
  EXPECT_EQ(tube->gamma, 1.4);  // the material's
  EXPECT_EQ(tube->x0, 0.4);     // the override
}

TEST(VerificationSetup, SedovTakesTheTableAndOverrides) {
  const stagger::Scene scene = stagger::load_scene(scene_path("sedov.toml"), {{"verification.energy", "0.5"}});
  const auto* sedov = std::get_if<stagger::SedovReference>(&scene.verification.parameters);
  ASSERT_NE(sedov, nullptr);
  EXPECT_EQ(sedov->energy_quarter, 0.5);
  EXPECT_EQ(sedov->density, 1.0);
  EXPECT_EQ(sedov->gamma, 1.4);
}

TEST(VerificationSetup, SolidReferencesTakeTheMaterialConstants) {
  const stagger::Scene piston =
      stagger::load_scene(scene_path("piston.toml"), {{"material[0].strength.yield_stress", "1.2e8"}});
  const auto* parameters = std::get_if<stagger::PistonParameters>(&piston.verification.parameters);
  ASSERT_NE(parameters, nullptr);
  EXPECT_EQ(parameters->yield_stress, 1.2e8);
  EXPECT_EQ(parameters->piston_velocity, 20.0);

  const stagger::Scene accuracy = stagger::load_scene(scene_path("accuracy.toml"), {{"sources.s1", "3e7"}});
  const auto* smooth = std::get_if<stagger::AccuracyParameters>(&accuracy.verification.parameters);
  ASSERT_NE(smooth, nullptr);
  EXPECT_EQ(smooth->s1, 3e7);  // [sources] feeds the run and the reference alike
}

TEST(VerificationSetup, NoVerificationSectionLeavesItEmpty) {
  // elastic_wave has no [verification].
  const stagger::Scene wave = stagger::load_scene(scene_path("elastic_wave.toml"), {});
  EXPECT_TRUE(wave.verification.name.empty());
  EXPECT_TRUE(std::holds_alternative<std::monostate>(wave.verification.parameters));
}
