// Zone profiles as CSV (write_zone_csv): one row per zone, for figure scripts that plot
// numerical against exact profiles (scripts/verification, docs/verification.md).
#include <cmath>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "io/text_format.hpp"
#include "mesh/polygon.hpp"
#include "stagger/output.hpp"
#include "stagger/simulation.hpp"

namespace stagger {

namespace {

struct Column {
  const char* name;
  std::span<const double> values;
};

}  // namespace

void write_zone_csv(const std::string& path, const Simulation& simulation) {
  using io_detail::format_double;
  const Mesh& mesh = simulation.mesh();
  const auto nzones = static_cast<std::size_t>(mesh.num_zones());
  const auto x = simulation.x();
  const auto y = simulation.y();
  const auto vx = simulation.velocity_x();
  const auto vy = simulation.velocity_y();

  // Zone centre = vertex average (docs/algorithm.md §2); velocity = mean of the zone's points
  // (the staggered scheme has no zone velocity; this is for plotting only).
  std::vector<double> cx(nzones), cy(nzones), ux(nzones), uy(nzones);
  for (std::size_t z = 0; z < nzones; ++z) {
    const Index begin = mesh.zone_corner_begin[z];
    const int n = static_cast<int>(mesh.zone_corner_begin[z + 1] - begin);
    const auto point = [&](int k) {
      return static_cast<std::size_t>(mesh.corner_point[static_cast<std::size_t>(begin + k)]);
    };
    const auto centre = polygon_centre(
        n, [&](int k) { return x[point(k)]; }, [&](int k) { return y[point(k)]; });
    const auto velocity = polygon_centre(
        n, [&](int k) { return vx[point(k)]; }, [&](int k) { return vy[point(k)]; });
    cx[z] = centre[0];
    cy[z] = centre[1];
    ux[z] = velocity[0];
    uy[z] = velocity[1];
  }

  std::vector<Column> columns = {{"area", simulation.zone_area()},
                                 {"density", simulation.density()},
                                 {"pressure", simulation.pressure()},
                                 {"specific_internal_energy", simulation.specific_internal_energy()},
                                 {"velocity_x", ux},
                                 {"velocity_y", uy},
                                 {"artificial_viscosity", simulation.artificial_viscosity()},
                                 {"sound_speed", simulation.sound_speed()}};
  std::vector<double> von_mises;
  if (simulation.has_strength() && simulation.stress_xx().size() == nzones) {
    const auto sxx = simulation.stress_xx(), syy = simulation.stress_yy(), sxy = simulation.stress_xy();
    von_mises.resize(nzones);
    for (std::size_t z = 0; z < nzones; ++z) {
      // sqrt(3/2 S:S) with the out-of-plane S_zz = -(S_xx + S_yy) (docs/algorithm.md §7).
      const double szz = -(sxx[z] + syy[z]);
      von_mises[z] = std::sqrt(1.5 * (sxx[z] * sxx[z] + syy[z] * syy[z] + szz * szz + 2.0 * sxy[z] * sxy[z]));
    }
    columns.push_back({"deviatoric_stress_xx", sxx});
    columns.push_back({"deviatoric_stress_yy", syy});
    columns.push_back({"deviatoric_stress_xy", sxy});
    columns.push_back({"von_mises", von_mises});
    if (simulation.plastic_strain().size() == nzones)
      columns.push_back({"plastic_strain", simulation.plastic_strain()});
  }
  if (simulation.has_burn() && simulation.burn_fraction().size() == nzones)
    columns.push_back({"burn_fraction", simulation.burn_fraction()});

  std::string text = "zone,region,x,y,r";
  for (const auto& column : columns) text += std::string(",") + column.name;
  text += '\n';
  text.reserve(text.size() + nzones * 24 * (columns.size() + 5));
  for (std::size_t z = 0; z < nzones; ++z) {
    text += std::to_string(z);
    text += ',';
    text += mesh.region_names[static_cast<std::size_t>(mesh.zone_region[z])];
    for (const double value : {cx[z], cy[z], std::hypot(cx[z], cy[z])}) {
      text += ',';
      text += format_double(value);
    }
    for (const auto& column : columns) {
      text += ',';
      text += format_double(column.values[z]);
    }
    text += '\n';
  }
  write_file_atomically(path, text);
}

}  // namespace stagger
