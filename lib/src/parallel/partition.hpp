#pragma once
// Ownership of a distributed run (docs/parallel.md): the zones partitioned by METIS, and the
// owner of every point derived from its zones' owners.
#include <vector>

#include "stagger/mesh.hpp"

namespace stagger::parallel {

// The zone graph (zones sharing a point), partitioned by METIS into `parts`: the owner of
// every zone (rank 0 only; the same partition on every run).
std::vector<int> partition_zones(const Mesh& m, int parts);

// The owner of every point: the lowest rank among its zones' owners.
std::vector<int> point_owners(const Mesh& m, const std::vector<int>& zone_owner);

}  // namespace stagger::parallel
