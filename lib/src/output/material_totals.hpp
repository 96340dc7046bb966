#pragma once
// Per-material totals of a whole (serial or gathered) state, for summary.json's "materials"
// object (docs/output.md): mass, volume, internal and kinetic energy of each material.
#include <string>
#include <vector>

namespace stagger {

class Simulation;

struct MaterialTotals {
  std::string name;
  double mass = 0, volume = 0, internal_energy = 0, kinetic_energy = 0;
};

// One entry per material of the problem, in the problem's order. Zone sums are exact sums
// (hydro/exact_sum.hpp). A point's kinetic energy is shared among the materials of its zones
// in proportion to m_z / n_z, the zone's median-mesh share of the point (docs/output.md), so
// the materials' kinetic energies add up to the audit's to round-off.
std::vector<MaterialTotals> material_totals(const Simulation& simulation);

}  // namespace stagger
