// The state table (docs/architecture.md, "The state table"): on every example scene, each
// array is sized to its entity exactly when the scene needs it, the swap pairs are
// consistent, and the dumps' field list is the documented one in the documented order.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "hydro/simulation_impl.hpp"
#include "stagger/scene.hpp"
#include "state/state_table.hpp"

namespace stagger {
namespace {

std::vector<std::string> example_scenes() {
  std::vector<std::string> scenes;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(STAGGER_SOURCE_DIR) + "/apps/scenes"))
    if (entry.path().extension() == ".toml") scenes.push_back(entry.path().string());
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

TEST(StateTable, EntriesAreDistinctAndTheirSwapPartnersListed) {
  std::set<std::string> names;
  const auto fields = state_fields();
  for (std::size_t i = 0; i < fields.size(); ++i) {
    EXPECT_TRUE(names.insert(fields[i].name).second) << fields[i].name << " listed twice";
    for (std::size_t j = 0; j < i; ++j)
      EXPECT_NE(fields[i].member, fields[j].member) << fields[i].name << " and " << fields[j].name << ": one member";
    if (fields[i].flags & kDumped) {
      EXPECT_NE(fields[i].output_name, nullptr) << fields[i].name;
    }
  }
  for (const StateField& f : state_fields()) {
    if (!f.next) continue;
    bool found = false;
    for (const StateField& g : state_fields()) {
      if (g.member != f.next) continue;
      found = true;
      EXPECT_EQ(g.entity, f.entity) << f.name << " and " << g.name;
      EXPECT_EQ(g.presence, f.presence) << f.name << " and " << g.name;
      EXPECT_EQ(g.flags, 0u) << g.name << " is scratch: only " << f.name << " is checkpointed, remapped or dumped";
    }
    EXPECT_TRUE(found) << f.name << ": its new-value array is not in the table";
  }
}

TEST(StateTable, EverySceneHasExactlyTheArraysItNeeds) {
  const auto scenes = example_scenes();
  ASSERT_GE(scenes.size(), 10u);
  std::set<Presence> seen;
  for (const auto& path : scenes) {
    Simulation::Impl s(load_scene(path).problem);
    for (const StateField& f : state_fields()) {
      const auto size = (s.*f.member).size();
      if (present(s, f.presence)) {
        seen.insert(f.presence);
        EXPECT_EQ(size, static_cast<std::size_t>(entity_size(s.mesh(), f.entity))) << path << ": " << f.name;
      } else {
        EXPECT_EQ(size, 0u) << path << ": " << f.name << " is allocated but the scene does not need it";
      }
    }
  }
  // The scenes exercise every kind of presence, so the loop above checked each.
  for (const Presence p :
       {Presence::always, Presence::strength, Presence::burn, Presence::edge_viscosity, Presence::half_step,
        Presence::external, Presence::momentum_source, Presence::energy_source, Presence::subzonal})
    EXPECT_TRUE(seen.count(p)) << "no example scene has presence " << static_cast<int>(p);
}

TEST(StateTable, SwapExchangesExactlyThePresentPairs) {
  Simulation::Impl s(load_scene(std::string(STAGGER_SOURCE_DIR) + "/apps/scenes/piston.toml").problem);
  ASSERT_TRUE(s.any_strength);
  ASSERT_FALSE(s.any_burn);
  s.vx_new.assign(s.vx_new.size(), 7.0);
  s.sxx_new.assign(s.sxx_new.size(), 8.0);
  const std::vector<double> e_before = s.e;
  swap_new_into_current(s, s);
  EXPECT_EQ(s.vx, std::vector<double>(s.vx.size(), 7.0));
  EXPECT_EQ(s.sxx, std::vector<double>(s.sxx.size(), 8.0));
  EXPECT_EQ(s.e_new, e_before);
  EXPECT_TRUE(s.burn.empty() && s.burn_new.empty());
}

TEST(StateTable, DumpedFieldsAreTheDocumentedOnesInOrder) {
  // he_plate: strength and burn, so every dumped array is present.
  Simulation simulation(load_scene(std::string(STAGGER_SOURCE_DIR) + "/apps/scenes/he_plate.toml").problem);
  ASSERT_TRUE(simulation.has_strength() && simulation.has_burn());
  std::vector<std::string> zone, point;
  for (const auto& f : simulation.output_fields()) {
    (f.on_points ? point : zone).emplace_back(f.name);
    EXPECT_EQ(f.values.size(),
              static_cast<std::size_t>(f.on_points ? simulation.mesh().num_points() : simulation.mesh().num_zones()))
        << f.name;
  }
  const std::vector<std::string> expected_zone = {"density",
                                                  "pressure",
                                                  "specific_internal_energy",
                                                  "artificial_viscosity",
                                                  "sound_speed",
                                                  "deviatoric_stress_xx",
                                                  "deviatoric_stress_yy",
                                                  "deviatoric_stress_xy",
                                                  "plastic_strain",
                                                  "burn_fraction"};
  EXPECT_EQ(zone, expected_zone);
  EXPECT_EQ(point, (std::vector<std::string>{"velocity", "velocity"}));
}

}  // namespace
}  // namespace stagger
