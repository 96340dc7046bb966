// A part's halo: its ghosts, their owners and the exchange's lists (halo.hpp).
#include "parallel/halo.hpp"

#include <algorithm>
#include <utility>

#include "parallel/part.hpp"

namespace stagger::parallel {

namespace {

// The ghost flags of one entity (zones or points) from its owners, broadcast from rank 0 in
// chunks; this rank's ghosts by owner.
void mark_entity_ghosts(const std::vector<int>& all, Index total, const std::vector<Index>& mine,
                        std::vector<unsigned char>& ghost, std::vector<std::vector<Index>>& by_owner, int rank,
                        MPI_Comm comm) {
  constexpr Index kChunk = 1 << 16;
  std::vector<int> chunk;
  std::size_t i = 0;
  for (Index first = 0; first < total; first += kChunk) {
    const Index n = std::min(kChunk, total - first);
    if (rank == 0)
      chunk.assign(all.begin() + first, all.begin() + first + n);
    else
      chunk.resize(n);
    MPI_Bcast(chunk.data(), n, MPI_INT, 0, comm);
    for (; i < mine.size() && mine[i] < first + n; ++i) {
      const int o = chunk[mine[i] - first];
      ghost[i] = o != rank;
      if (o != rank) by_owner[o].push_back(static_cast<Index>(i));
    }
  }
}

void append_corners(const Simulation::Impl& s, const std::vector<Index>& zones, std::vector<Index>& corners) {
  for (Index z : zones)
    for (Index c = s.zone_corner_begin[z]; c < s.zone_corner_begin[z + 1]; ++c) corners.push_back(c);
}

}  // namespace

GhostsByOwner mark_ghosts(Simulation::Impl& s, const std::vector<int>& zone_owner, const std::vector<int>& point_owner,
                          Index global_zones, Index global_points, int rank, int size, MPI_Comm comm) {
  s.ghost_zone.assign(s.global_zone.size(), 0);
  s.ghost_point.assign(s.global_point.size(), 0);
  GhostsByOwner ghosts;
  ghosts.points.resize(size);
  ghosts.zones.resize(size);
  mark_entity_ghosts(zone_owner, global_zones, s.global_zone, s.ghost_zone, ghosts.zones, rank, comm);
  mark_entity_ghosts(point_owner, global_points, s.global_point, s.ghost_point, ghosts.points, rank, comm);
  return ghosts;
}

void split_ranges(Simulation::Impl& s) {
  std::vector<ZoneRange> ranges;
  for (const ZoneRange& r : s.ranges)
    for (Index z = r.begin; z < r.end;) {
      const bool ghost = s.ghost_zone[z] != 0;
      Index e = z;
      while (e < r.end && (s.ghost_zone[e] != 0) == ghost) ++e;
      ranges.push_back({z, e, r.material, ghost});
      z = e;
    }
  s.ranges = std::move(ranges);
}

void list_own_corners(MpiCollective& c, const Simulation::Impl& s) {
  const Index nz = static_cast<Index>(s.global_zone.size());
  for (Index z = 0; z < nz; ++z)
    if (!s.ghost_zone[z])
      for (Index k = s.zone_corner_begin[z]; k < s.zone_corner_begin[z + 1]; ++k) c.own_corners.push_back(k);
}

void connect_neighbours(MpiCollective& c, const Simulation::Impl& s, const GhostsByOwner& ghosts) {
  const int size = c.size;
  std::vector<int> send_counts(2 * size), recv_counts(2 * size);
  for (int q = 0; q < size; ++q)
    send_counts[2 * q] = static_cast<int>(ghosts.points[q].size()),
                    send_counts[2 * q + 1] = static_cast<int>(ghosts.zones[q].size());
  MPI_Alltoall(send_counts.data(), 2, MPI_INT, recv_counts.data(), 2, MPI_INT, c.comm);
  std::vector<int> sc(size), sd(size), rc(size), rd(size);
  std::vector<Index> send_ids, recv_ids;
  for (int q = 0; q < size; ++q) {
    sd[q] = static_cast<int>(send_ids.size());
    for (Index p : ghosts.points[q]) send_ids.push_back(s.global_point[p]);
    for (Index z : ghosts.zones[q]) send_ids.push_back(s.global_zone[z]);
    sc[q] = static_cast<int>(send_ids.size()) - sd[q];
    rc[q] = recv_counts[2 * q] + recv_counts[2 * q + 1];
    rd[q] = q == 0 ? 0 : rd[q - 1] + rc[q - 1];
  }
  recv_ids.resize(rd[size - 1] + rc[size - 1]);
  MPI_Alltoallv(send_ids.data(), sc.data(), sd.data(), MPI_INT32_T, recv_ids.data(), rc.data(), rd.data(), MPI_INT32_T,
                c.comm);
  std::size_t per_point = 0, per_zone = 0, per_corner = 0;
  for (const StateField* f : c.fields)
    (f->entity == Entity::point ? per_point : f->entity == Entity::zone ? per_zone : per_corner) += 1;
  for (int q = 0; q < size; ++q) {
    if (q == c.my_rank || (sc[q] == 0 && rc[q] == 0)) continue;
    Neighbour n;
    n.rank = q;
    n.recv_points = ghosts.points[q];
    n.recv_zones = ghosts.zones[q];
    append_corners(s, n.recv_zones, n.recv_corners);
    for (int i = 0; i < recv_counts[2 * q]; ++i)
      n.send_points.push_back(local_index(s.global_point, recv_ids[rd[q] + i]));
    for (int i = 0; i < recv_counts[2 * q + 1]; ++i)
      n.send_zones.push_back(local_index(s.global_zone, recv_ids[rd[q] + recv_counts[2 * q] + i]));
    append_corners(s, n.send_zones, n.send_corners);
    n.send.resize(per_point * n.send_points.size() + per_zone * n.send_zones.size() +
                  per_corner * n.send_corners.size());
    n.recv.resize(per_point * n.recv_points.size() + per_zone * n.recv_zones.size() +
                  per_corner * n.recv_corners.size());
    c.neighbours.push_back(std::move(n));
  }
}

}  // namespace stagger::parallel
