// Results are bitwise identical for any thread count (fixed-order gathers, no atomics).
#include <gtest/gtest.h>
#include <omp.h>

#include <cstring>
#include <vector>

#include "stagger/mesh.hpp"
#include "stagger/meshgen.hpp"
#include "stagger/simulation.hpp"

namespace stagger {

namespace {
std::vector<double> run_sedov(int threads) {
  omp_set_num_threads(threads);
  Problem p;
  p.name = "sedov";
  MeshBuildOptions options;
  options.check_topology = false;
  p.mesh = build_mesh(meshgen::rectangle(0, 1.2, 0, 1.2, 70, 70), options);  // 4900 zones: threads engage (> 4096)
  Material gas;
  gas.name = "gas";
  gas.eos = IdealGas{1.4};
  p.materials.push_back(gas);
  RegionSetup r;
  r.region = "domain";
  r.material = "gas";
  r.density = constant_field(1.0);
  r.specific_internal_energy = constant_field(1e-10);
  p.regions.push_back(r);
  for (const char* tag : {"left", "right", "bottom", "top"}) {
    BoundaryCondition bc;
    bc.tag = tag;
    p.boundaries.push_back(bc);
  }
  p.deposits.push_back({0, 0, 0.244816});
  p.options.viscosity = Viscosity::edge;
  p.options.check_corner_areas = false;
  p.t_end = 1.0;
  Simulation sim(std::move(p));
  for (int i = 0; i < 100; ++i) sim.step();
  std::vector<double> state;
  for (auto field :
       {sim.x(), sim.y(), sim.velocity_x(), sim.velocity_y(), sim.specific_internal_energy(), sim.pressure()})
    state.insert(state.end(), field.begin(), field.end());
  state.push_back(sim.energy().relative_error);
  state.push_back(sim.dt());
  return state;
}
}  // namespace

TEST(Determinism, OneAndTwoThreadsGiveBitwiseTheSameState) {
  const auto one = run_sedov(1), two = run_sedov(2);
  ASSERT_EQ(one.size(), two.size());
  EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(double)), 0);
}

}  // namespace stagger
