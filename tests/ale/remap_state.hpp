// The remap tests' state on a mesh: zone, corner and point masses, the point velocities and
// kinetic energies, and two specific zone fields (an energy e and a stress-like s), handed to
// Remapper::remap as RemapFields.
#pragma once

#include <vector>

#include "ale/remap.hpp"
#include "stagger/mesh.hpp"

namespace stagger::testing {

struct RemapState {
  std::vector<double> zone_mass, corner_mass, point_mass, vx, vy, e, s, kinetic;
  /// Every array sized for the mesh and zero.
  void zero(const Mesh& m) {
    zone_mass.assign(m.num_zones(), 0);
    e.assign(m.num_zones(), 0);
    s.assign(m.num_zones(), 0);
    corner_mass.assign(m.num_corners(), 0);
    for (auto* point : {&point_mass, &vx, &vy, &kinetic}) point->assign(m.num_points(), 0);
  }
  RemapFields fields() {
    RemapFields f;
    f.zone_mass = zone_mass.data();
    f.corner_mass = corner_mass.data();
    f.point_mass = point_mass.data();
    f.vx = vx.data();
    f.vy = vy.data();
    f.specific = {e.data(), s.data()};
    f.point_kinetic = kinetic.data();
    return f;
  }
};

}  // namespace stagger::testing
