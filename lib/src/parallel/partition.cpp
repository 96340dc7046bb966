// Ownership of a distributed run (docs/parallel.md): METIS's partition of the zone graph.
#include "parallel/partition.hpp"

#include <metis.h>

#include <algorithm>
#include <climits>
#include <string>

#include "stagger/error.hpp"

namespace stagger::parallel {

std::vector<int> partition_zones(const Mesh& m, int parts) {
  const Index nz = m.num_zones();
  std::vector<idx_t> xadj(nz + 1, 0), adjncy;
  adjncy.reserve(static_cast<std::size_t>(nz) * 8);
  std::vector<Index> seen(nz, -1);
  for (Index z = 0; z < nz; ++z) {
    for (Index c = m.zone_corner_begin[z]; c < m.zone_corner_begin[z + 1]; ++c) {
      const Index p = m.corner_point[c];
      for (Index k = m.point_corner_begin[p]; k < m.point_corner_begin[p + 1]; ++k) {
        const Index other = m.corner_zone[m.point_corners[k]];
        if (other == z || seen[other] == z) continue;
        seen[other] = z;
        adjncy.push_back(other);
      }
    }
    xadj[z + 1] = static_cast<idx_t>(adjncy.size());
  }
  idx_t vertices = nz, constraints = 1, nparts = parts, cut = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 1;  // the same partition on every run
  options[METIS_OPTION_NUMBERING] = 0;
  std::vector<idx_t> part(nz, 0);
  const int status = METIS_PartGraphKway(&vertices, &constraints, xadj.data(), adjncy.data(), nullptr, nullptr, nullptr,
                                         &nparts, nullptr, nullptr, options, &cut, part.data());
  if (status != METIS_OK)
    throw Error("METIS could not partition the " + std::to_string(nz) + " zones of " + m.source + " into " +
                std::to_string(parts) + " parts (status " + std::to_string(status) + ")");
  return std::vector<int>(part.begin(), part.end());
}

std::vector<int> point_owners(const Mesh& m, const std::vector<int>& zone_owner) {
  std::vector<int> owner(m.num_points(), INT_MAX);
  for (Index z = 0; z < m.num_zones(); ++z)
    for (Index k = m.zone_corner_begin[z]; k < m.zone_corner_begin[z + 1]; ++k)
      owner[m.corner_point[k]] = std::min(owner[m.corner_point[k]], zone_owner[z]);
  return owner;
}

}  // namespace stagger::parallel
