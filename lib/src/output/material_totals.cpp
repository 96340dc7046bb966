// Per-material totals (material_totals.hpp).
#include "output/material_totals.hpp"

#include <array>
#include <map>
#include <string>
#include <vector>

#include "hydro/exact_sum.hpp"
#include "stagger/simulation.hpp"

namespace stagger {

namespace {

// The material index of every zone, through its region's set-up.
std::vector<int> zone_materials(const Simulation& simulation) {
  const Problem& problem = simulation.problem();
  const Mesh& mesh = simulation.mesh();
  std::map<std::string, int> material_of_name;
  for (std::size_t m = 0; m < problem.materials.size(); ++m)
    material_of_name[problem.materials[m].name] = static_cast<int>(m);
  std::vector<int> region_material(mesh.region_names.size(), -1);
  for (const RegionSetup& setup : problem.regions) {
    const Index region = mesh.region_index(setup.region);
    const auto found = material_of_name.find(setup.material);
    if (region >= 0 && found != material_of_name.end()) region_material[region] = found->second;
  }
  std::vector<int> material(mesh.num_zones(), -1);
  for (Index z = 0; z < mesh.num_zones(); ++z) material[z] = region_material[mesh.zone_region[z]];
  return material;
}

}  // namespace

std::vector<MaterialTotals> material_totals(const Simulation& simulation) {
  const Mesh& mesh = simulation.mesh();
  const std::vector<int> material = zone_materials(simulation);
  const std::size_t n = simulation.problem().materials.size();
  const auto zone_mass = simulation.zone_mass();
  const auto rho = simulation.density();
  const auto e = simulation.specific_internal_energy();
  const auto vx = simulation.velocity_x(), vy = simulation.velocity_y();
  const auto point_mass = simulation.point_mass();
  // Each point's share denominator: the sum of m_z / n_z over its zones.
  std::vector<double> share_total(mesh.num_points(), 0.0);
  for (Index z = 0; z < mesh.num_zones(); ++z) {
    const Index begin = mesh.zone_corner_begin[z], end = mesh.zone_corner_begin[z + 1];
    for (Index c = begin; c < end; ++c) share_total[mesh.corner_point[c]] += zone_mass[z] / double(end - begin);
  }
  std::vector<std::array<ExactSum, 4>> sums(n);
  for (Index z = 0; z < mesh.num_zones(); ++z) {
    if (material[z] < 0) continue;
    auto& s = sums[material[z]];
    s[0].add(zone_mass[z]);
    s[1].add(zone_mass[z] / rho[z]);
    s[2].add(zone_mass[z] * e[z]);
    const Index begin = mesh.zone_corner_begin[z], end = mesh.zone_corner_begin[z + 1];
    for (Index c = begin; c < end; ++c) {
      const Index p = mesh.corner_point[c];
      const double share = zone_mass[z] / double(end - begin) / share_total[p];
      s[3].add(share * 0.5 * point_mass[p] * (vx[p] * vx[p] + vy[p] * vy[p]));
    }
  }
  std::vector<MaterialTotals> totals(n);
  for (std::size_t m = 0; m < n; ++m) {
    totals[m].name = simulation.problem().materials[m].name;
    totals[m].mass = sums[m][0].value();
    totals[m].volume = sums[m][1].value();
    totals[m].internal_energy = sums[m][2].value();
    totals[m].kinetic_energy = sums[m][3].value();
  }
  return totals;
}

}  // namespace stagger
