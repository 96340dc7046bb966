// Sod's shock tube set up in code, run with the library's driver, checked against the exact
// Riemann solution. Usage: embed_sod OUTPUT_DIRECTORY   (docs/api.md walks through it)
#include <cstdio>
#include <exception>
#include <string>
#include <utility>

#include "stagger/error.hpp"
#include "stagger/meshgen.hpp"
#include "stagger/problem.hpp"
#include "stagger/run.hpp"
#include "stagger/simulation.hpp"
#include "stagger/verify.hpp"

int main(int argc, char** argv) try {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_DIRECTORY\n", argv[0]);
    return 2;
  }
  // 1. Mesh: 200 x 5 quads on [0,1]x[0,0.1]; region "domain", tags left/right/bottom/top.
  stagger::Problem problem;
  problem.name = "sod";
  problem.mesh = stagger::build_mesh(stagger::meshgen::rectangle(0.0, 1.0, 0.0, 0.1, 200, 5));
  // 2. Material, initial state (callables of x, y), walls on every tag, end time.
  stagger::Material air;
  air.name = "gas";
  air.eos = stagger::IdealGas{1.4};
  problem.materials.push_back(air);
  stagger::RegionSetup gas;
  gas.region = "domain";
  gas.material = "gas";
  gas.density = [](double x, double) { return x < 0.5 ? 1.0 : 0.125; };
  gas.pressure = [](double x, double) { return x < 0.5 ? 1.0 : 0.1; };
  problem.regions.push_back(gas);
  for (const char* tag : {"left", "right", "bottom", "top"}) {
    stagger::BoundaryCondition wall;  // kind defaults to wall: v.n = 0
    wall.tag = tag;
    problem.boundaries.push_back(wall);
  }
  problem.options.hourglass_coefficient = 0;  // 1D flow: no hourglass modes to damp
  problem.t_end = 0.2;

  // 3. The Simulation takes the Problem (validated here: stagger::Error on bad input).
  stagger::Simulation simulation(std::move(problem));

  // 4. Run to t_end: .vtu dumps + sod.pvd, history.csv, summary.json with the exact errors.
  stagger::RunControl control;
  control.output_directory = argv[1];
  control.name = "sod";
  control.dump_interval = 0.05;
  control.checkpoints = false;
  control.reference = stagger::shock_tube_reference({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4, 0.5);
  const stagger::RunResult result = stagger::run(simulation, control);
  if (!result.completed) throw stagger::Error(result.message);

  // 5. Report: L1 density error against stagger::ExactRiemann, and the energy audit.
  for (const auto& [name, value] : result.summary.errors)
    if (name == "L1_density") std::printf("L1_density %.6e\n", value);
  std::printf("energy_audit %.3e\n", simulation.energy().relative_error);
  std::printf("cycles %ld time %.6g\n", simulation.cycle(), simulation.time());
  std::printf("pvd %s/sod.pvd\n", control.output_directory.c_str());
  return 0;
} catch (const std::exception& error) {
  std::fprintf(stderr, "embed_sod: %s\n", error.what());
  return 1;
}
