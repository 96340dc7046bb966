// Distributed runs (docs/parallel.md): the problem split over MPI ranks by METIS, each rank
// stepping its own zones and a few layers of ghost zones with the serial kernels, and the
// collective operations the step asks for (lib/src/hydro/collective.hpp).
//
// Why the bits are the serial ones (docs/parallel.md, "Determinism"):
//  - rank 0 sets up the whole problem as the serial run does and sends each rank its part of
//    that state, so the initial state is the serial one bit for bit;
//  - a rank's zones, points and corners keep the serial (global) order, so each point sums
//    its corner forces in the serial order;
//  - ghost layers are deep enough that a rank's own zones and points see only correct
//    values during a step; after the step the owners' values overwrite the ghosts' (the
//    exchange iterates over the state table, so a new state array is exchanged too);
//  - failures and the time step are global minima (ties to the lowest global zone), and
//    totals are exact sums (hydro/exact_sum.hpp).
#include <malloc.h>
#include <metis.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "ale/ale_remap.hpp"
#include "ale/rezone.hpp"
#include "hydro/collective.hpp"
#include "hydro/kernels/zone_status.hpp"
#include "hydro/physics_digest.hpp"
#include "hydro/simulation_impl.hpp"
#include "stagger/error.hpp"
#include "stagger/parallel.hpp"
#include "stagger/remap.hpp"
#include "state/state_table.hpp"

namespace stagger {

struct DistributedAccess {
  static Simulation::Impl& impl(Simulation& s) { return *s.impl_; }
  static const Simulation::Impl& impl(const Simulation& s) { return *s.impl_; }
};

namespace {

constexpr int kHaloTag = 1717;

int comm_rank(MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  return rank;
}
int comm_size(MPI_Comm comm) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  return size;
}

// The zone graph (zones sharing a point), partitioned by METIS into `parts` (rank 0 only).
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

// The state arrays the whole state on rank 0 keeps for the gathers (dumps, summary,
// references): the dumped ones and those behind Simulation's accessors. The rest (the step's
// scratch, the corner forces, set-up constants) nothing reads from it.
bool gathered(const StateField& f) {
  using I = Simulation::Impl;
  return (f.flags & kDumped) || f.member == &I::x || f.member == &I::y || f.member == &I::point_mass ||
         f.member == &I::zone_mass || f.member == &I::area;
}

// One rank's part: its zones and the ghost layers, in global order.
struct Part {
  std::vector<Index> zones, points;            // local -> global (ascending)
  std::vector<Index> zone_local, point_local;  // global -> local, -1 when absent
};

// Owned zones and `layers` layers of zones around them (a layer: the zones sharing a point
// with the previous ones). docs/parallel.md, "Ghost layers", gives the depth the step needs.
Part make_part(const Mesh& m, const std::vector<int>& owner, int rank, int layers) {
  const Index nz = m.num_zones(), np = m.num_points();
  std::vector<unsigned char> in(nz, 0), point_done(np, 0);
  std::vector<Index> frontier, next;
  for (Index z = 0; z < nz; ++z)
    if (owner[z] == rank) in[z] = 1, frontier.push_back(z);
  for (int layer = 0; layer < layers; ++layer) {
    next.clear();
    for (Index z : frontier)
      for (Index c = m.zone_corner_begin[z]; c < m.zone_corner_begin[z + 1]; ++c) {
        const Index p = m.corner_point[c];
        if (point_done[p]) continue;
        point_done[p] = 1;
        for (Index k = m.point_corner_begin[p]; k < m.point_corner_begin[p + 1]; ++k) {
          const Index other = m.corner_zone[m.point_corners[k]];
          if (!in[other]) in[other] = 1, next.push_back(other);
        }
      }
    frontier.swap(next);
  }
  Part part;
  part.zone_local.assign(nz, -1);
  part.point_local.assign(np, -1);
  std::vector<unsigned char> point_in(np, 0);
  for (Index z = 0; z < nz; ++z) {
    if (!in[z]) continue;
    part.zone_local[z] = static_cast<Index>(part.zones.size());
    part.zones.push_back(z);
    for (Index c = m.zone_corner_begin[z]; c < m.zone_corner_begin[z + 1]; ++c) point_in[m.corner_point[c]] = 1;
  }
  for (Index p = 0; p < np; ++p)
    if (point_in[p]) part.point_local[p] = static_cast<Index>(part.points.size()), part.points.push_back(p);
  return part;
}

// The mesh of a part: the same arrays as the serial mesh, restricted and renumbered in the
// same order (so each point's corners stay in the serial order). They are made one at a time
// and handed to `each(member, array)` in the order part_arrays() sends them, so that rank 0
// holds one array of a part beside the whole problem, not the part's mesh
// (docs/parallel.md, "Memory").
template <class F>
void part_mesh_arrays(const Mesh& m, const Part& part, F&& each) {
  const auto np = static_cast<Index>(part.points.size());
  {
    std::vector<double> v;
    v.reserve(part.points.size());
    for (Index p : part.points) v.push_back(m.x[p]);
    each(&Mesh::x, v);
    v.clear();
    for (Index p : part.points) v.push_back(m.y[p]);
    each(&Mesh::y, v);
  }
  std::vector<Index> v;
  v.reserve(part.zones.size() + 1);
  v.push_back(0);
  for (Index z : part.zones) v.push_back(v.back() + m.zone_corner_begin[z + 1] - m.zone_corner_begin[z]);
  const std::size_t corners = static_cast<std::size_t>(v.back());
  each(&Mesh::zone_corner_begin, v);
  const auto for_corners = [&](auto&& body) {  // (local zone, whole-mesh corner)
    for (std::size_t i = 0; i < part.zones.size(); ++i)
      for (Index c = m.zone_corner_begin[part.zones[i]]; c < m.zone_corner_begin[part.zones[i] + 1]; ++c)
        body(static_cast<Index>(i), c);
  };
  v.clear();
  v.reserve(corners);
  for_corners([&](Index, Index c) { v.push_back(part.point_local[m.corner_point[c]]); });
  each(&Mesh::corner_point, v);
  v.clear();
  for_corners([&](Index z, Index) { v.push_back(z); });
  each(&Mesh::corner_zone, v);
  std::vector<Index> begin(np + 1, 0);
  for_corners([&](Index, Index c) { ++begin[part.point_local[m.corner_point[c]] + 1]; });
  for (Index p = 0; p < np; ++p) begin[p + 1] += begin[p];
  v = begin;
  each(&Mesh::point_corner_begin, v);
  v.assign(corners, 0);
  Index local_corner = 0;
  for_corners([&](Index, Index c) { v[begin[part.point_local[m.corner_point[c]]]++] = local_corner++; });
  begin = {};
  each(&Mesh::point_corners, v);
  v.clear();
  for (Index z : part.zones) v.push_back(m.zone_region[z]);
  each(&Mesh::zone_region, v);
  v.assign(m.num_regions() + 1, 0);
  for (Index z : part.zones) ++v[m.zone_region[z] + 1];
  for (Index r = 0; r < m.num_regions(); ++r) v[r + 1] += v[r];
  each(&Mesh::region_zone_begin, v);
}

// A part's mesh without its arrays: the source, the region names and the tags (the edges of
// the part's zones, in the serial order).
Mesh part_names(const Mesh& m, const Part& part) {
  Mesh local;
  local.source = m.source;
  local.region_names = m.region_names;
  for (const BoundaryTag& tag : m.tags) {
    BoundaryTag t;
    t.name = tag.name;
    for (const auto& e : tag.edges) {
      const Index a = part.point_local[e[0]], b = part.point_local[e[1]];
      if (a < 0 || b < 0) continue;
      bool mine = false;
      for (Index k = m.point_corner_begin[e[0]]; k < m.point_corner_begin[e[0] + 1] && !mine; ++k) {
        const Index c = m.point_corners[k], z = m.corner_zone[c];
        const Index next = c + 1 == m.zone_corner_begin[z + 1] ? m.zone_corner_begin[z] : c + 1;
        mine = part.zone_local[z] >= 0 && m.corner_point[next] == e[1];
      }
      if (mine) t.edges.push_back({a, b});
    }
    if (tag.edges.empty()) {
      for (Index p : tag.points)
        if (part.point_local[p] >= 0) t.points.push_back(part.point_local[p]);
    } else {
      for (const auto& e : t.edges) t.points.push_back(e[0]), t.points.push_back(e[1]);
      std::sort(t.points.begin(), t.points.end());
      t.points.erase(std::unique(t.points.begin(), t.points.end()), t.points.end());
    }
    local.tags.push_back(std::move(t));
  }
  return local;
}

// Values of one rank's entities that another rank holds as ghosts (or the reverse).
struct Neighbour {
  int rank = 0;
  std::vector<Index> send_points, send_zones, send_corners;  // this rank's owned ones (local)
  std::vector<Index> recv_points, recv_zones, recv_corners;  // this rank's ghosts (local)
  std::vector<double> send, recv;
};

void append_corners(const Simulation::Impl& s, const std::vector<Index>& zones, std::vector<Index>& corners) {
  for (Index z : zones)
    for (Index c = s.zone_corner_begin[z]; c < s.zone_corner_begin[z + 1]; ++c) corners.push_back(c);
}

class MpiCollective final : public Collective {
 public:
  MPI_Comm comm = MPI_COMM_NULL;
  int my_rank = 0, size = 1;
  std::vector<Neighbour> neighbours;
  std::vector<const StateField*> fields;           // the present state arrays, in table order
  std::vector<const StateField*> gathered_fields;  // those the whole state on rank 0 serves
  std::vector<const StateField*> remap_fields;     // those an ALE remap changes: the remapped ones, x and y
  std::vector<Index> own_corners;  // ALE only (the corner masses); own points and zones: the ghost flags
  // Rank 0: the whole state (only its gathered arrays, or all of them for an ALE remap), and
  // every rank's owned points, zones and (ALE) corners, global; the gather's buffers are
  // transient (docs/parallel.md, "Memory").
  std::unique_ptr<Simulation> whole;
  std::vector<std::vector<Index>> rank_points, rank_zones, rank_corners;
  // The ALE remap (docs/parallel.md, "ALE"): rank 0 keeps every rank's whole part (owned and
  // ghost points and zones, global) to send it the remapped state.
  std::vector<std::vector<Index>> part_points, part_zones;
  std::vector<MPI_Request> requests;
  // Halo statistics (docs/parallel.md): exchanges, messages and bytes sent, seconds.
  long exchanges = 0, messages = 0;
  double bytes = 0, halo_seconds = 0;

  ~MpiCollective() override {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized && comm != MPI_COMM_NULL) MPI_Comm_free(&comm);
  }

  int rank() const override { return my_rank; }
  int ranks() const override { return size; }

  std::int64_t min_failure(const Simulation::Impl& s, std::int64_t local_code) override {
    std::int64_t code = local_code == kNoFailure
                            ? kNoFailure
                            : failure_code(s.global_zone[failure_zone(local_code)], failure_kind(local_code));
    std::int64_t result = kNoFailure;
    MPI_Allreduce(&code, &result, 1, MPI_INT64_T, MPI_MIN, comm);
    return result;
  }

  DtChoice min_dt(const Simulation::Impl& s, DtChoice local) override {
    // MINLOC: the smallest dt, and on a tie the smallest index (the serial tie-break).
    struct {
      double dt;
      int zone;
    } in{local.dt, local.zone >= 0 ? s.global_zone[local.zone] : INT_MAX}, out{};
    MPI_Allreduce(&in, &out, 1, MPI_DOUBLE_INT, MPI_MINLOC, comm);
    return {out.dt, out.zone == INT_MAX ? -1 : out.zone};
  }

  // The text of a global zone or point, worded by its owner: the rank holding it as its own
  // (a part's global numbers ascend, so a binary search finds it; no map of the whole problem).
  std::string owner_text(const std::vector<Index>& global, const std::vector<unsigned char>& ghost, Index id,
                         const std::function<std::string(Index)>& text) {
    const auto at = std::lower_bound(global.begin(), global.end(), id);
    const Index local = at != global.end() && *at == id ? static_cast<Index>(at - global.begin()) : -1;
    int mine = local >= 0 && !ghost[local] ? my_rank : INT_MAX, owner = INT_MAX;
    MPI_Allreduce(&mine, &owner, 1, MPI_INT, MPI_MIN, comm);
    if (owner == INT_MAX) owner = 0;  // no such zone or point: rank 0's empty text
    std::string result;
    if (my_rank == owner && local >= 0) result = text(local);
    int length = static_cast<int>(result.size());
    MPI_Bcast(&length, 1, MPI_INT, owner, comm);
    result.resize(length);
    MPI_Bcast(result.data(), length, MPI_CHAR, owner, comm);
    return result;
  }

  std::string zone_text(const Simulation::Impl& s, Index zone, const std::function<std::string(Index)>& text) override {
    return owner_text(s.global_zone, s.ghost_zone, zone, text);
  }

  Index min_point(const Simulation::Impl& s, Index local_point) override {
    int point = local_point >= 0 ? s.global_point[local_point] : INT_MAX, result = INT_MAX;
    MPI_Allreduce(&point, &result, 1, MPI_INT, MPI_MIN, comm);
    return result == INT_MAX ? -1 : result;
  }

  std::string point_text(const Simulation::Impl& s, Index point,
                         const std::function<std::string(Index)>& text) override {
    return owner_text(s.global_point, s.ghost_point, point, text);
  }

  void sum(std::span<ExactSum> sums) override {
    // One integer sum of every accumulator's words: exact, so any reduction order gives the same.
    const std::size_t n = sums.size(), words = ExactSum::kWords;
    std::vector<std::int64_t> in(n * words), out(n * words);
    for (std::size_t i = 0; i < n; ++i)
      std::copy(sums[i].words().begin(), sums[i].words().end(), in.begin() + i * words);
    MPI_Allreduce(in.data(), out.data(), static_cast<int>(in.size()), MPI_INT64_T, MPI_SUM, comm);
    for (std::size_t i = 0; i < n; ++i)
      std::copy(out.begin() + i * words, out.begin() + (i + 1) * words, sums[i].words().begin());
  }

  std::string agree(const std::string& text) override {
    int mine = text.empty() ? INT_MAX : my_rank, lowest = INT_MAX;
    MPI_Allreduce(&mine, &lowest, 1, MPI_INT, MPI_MIN, comm);
    if (lowest == INT_MAX) return {};
    std::string result = text;
    int length = static_cast<int>(result.size());
    MPI_Bcast(&length, 1, MPI_INT, lowest, comm);
    result.resize(length);
    MPI_Bcast(result.data(), length, MPI_CHAR, lowest, comm);
    return result;
  }

  bool any(bool local) override {
    int mine = local ? 1 : 0, result = 0;
    MPI_Allreduce(&mine, &result, 1, MPI_INT, MPI_MAX, comm);
    return result != 0;
  }

  void exchange(Simulation::Impl& s) override {
    const auto start = std::chrono::steady_clock::now();
    requests.clear();
    for (Neighbour& n : neighbours) {
      MPI_Request r;
      MPI_Irecv(n.recv.data(), static_cast<int>(n.recv.size()), MPI_DOUBLE, n.rank, kHaloTag, comm, &r);
      requests.push_back(r);
    }
    for (Neighbour& n : neighbours) {
      double* out = n.send.data();
      for (const StateField* f : fields) {
        const double* values = (s.*(f->member)).data();
        const auto& list = f->entity == Entity::point  ? n.send_points
                           : f->entity == Entity::zone ? n.send_zones
                                                       : n.send_corners;
        for (Index i : list) *out++ = values[i];
      }
      MPI_Request r;
      MPI_Isend(n.send.data(), static_cast<int>(n.send.size()), MPI_DOUBLE, n.rank, kHaloTag, comm, &r);
      requests.push_back(r);
      ++messages;
      bytes += static_cast<double>(n.send.size() * sizeof(double));
    }
    MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
    for (Neighbour& n : neighbours) {
      const double* in = n.recv.data();
      for (const StateField* f : fields) {
        double* values = (s.*(f->member)).data();
        const auto& list = f->entity == Entity::point  ? n.recv_points
                           : f->entity == Entity::zone ? n.recv_zones
                                                       : n.recv_corners;
        for (Index i : list) values[i] = *in++;
      }
    }
    ++exchanges;
    halo_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  // Rank 0's whole state gets every rank's owned values of the arrays `list` (of `fields`),
  // one array at a time: the buffers stay one array of the whole problem long.
  void gather_fields(const Simulation::Impl& s, const std::vector<const StateField*>& list) {
    std::vector<double> send, recv;
    std::vector<int> counts, offsets;
    for (const StateField* f : list) {
      const auto& ids = [&](int q) -> const std::vector<Index>& {
        return f->entity == Entity::point  ? rank_points[q]
               : f->entity == Entity::zone ? rank_zones[q]
                                           : rank_corners[q];
      };
      const double* values = (s.*(f->member)).data();
      // This rank's owned values, in its (ascending global) order.
      const auto each_owned = [&](auto&& use) {
        if (f->entity == Entity::corner) {
          for (Index i : own_corners) use(values[i]);
        } else {
          const std::vector<unsigned char>& ghost = f->entity == Entity::point ? s.ghost_point : s.ghost_zone;
          for (std::size_t i = 0; i < ghost.size(); ++i)
            if (!ghost[i]) use(values[i]);
        }
      };
      send.clear();
      if (my_rank != 0) {
        send.reserve(f->entity == Entity::corner  ? own_corners.size()
                     : f->entity == Entity::point ? s.ghost_point.size()
                                                  : s.ghost_zone.size());
        each_owned([&](double v) { send.push_back(v); });
      } else {
        // Rank 0 writes its own values straight into the whole array (no buffer of them).
        counts.assign(size, 0), offsets.assign(size, 0);
        for (int q = 1; q < size; ++q) {
          counts[q] = static_cast<int>(ids(q).size());
          offsets[q] = offsets[q - 1] + counts[q - 1];
        }
        recv.resize(static_cast<std::size_t>(offsets[size - 1]) + counts[size - 1]);
      }
      MPI_Gatherv(send.data(), static_cast<int>(send.size()), MPI_DOUBLE, recv.data(), counts.data(), offsets.data(),
                  MPI_DOUBLE, 0, comm);
      if (my_rank != 0) continue;
      // The whole state's arrays are empty until the first gather (distribute() frees them).
      Simulation::Impl& w = DistributedAccess::impl(*whole);
      const Mesh& m = w.mesh();
      std::vector<double>& whole_array = w.*(f->member);
      const Index n = f->entity == Entity::point  ? m.num_points()
                      : f->entity == Entity::zone ? m.num_zones()
                                                  : m.num_corners();
      if (whole_array.size() != static_cast<std::size_t>(n)) whole_array.assign(n, 0.0);
      double* whole_values = whole_array.data();
      const Index* mine = ids(0).data();
      each_owned([&](double v) { whole_values[*mine++] = v; });
      const double* in = recv.data();
      for (int q = 1; q < size; ++q)
        for (Index i : ids(q)) whole_values[i] = *in++;
    }
    if (my_rank != 0) return;
    Simulation::Impl& w = DistributedAccess::impl(*whole);
    // The scalars are the same on every rank (dt_zone is already global).
    static_cast<Clock&>(w) = static_cast<const Clock&>(s);
  }

  const Simulation* gather(const Simulation::Impl& s) override {
    gather_fields(s, gathered_fields);
    return my_rank == 0 ? whole.get() : nullptr;
  }

  // The ALE phase of a distributed run (docs/parallel.md, "ALE"): the decision from this
  // rank's zones and a global minimum; the rezone and remap by the serial code on rank 0's
  // gathered state; every rank's part (ghosts included) then gets the remapped state.
  bool remap(Simulation::Impl& s) {
    const AleOptions& o = s.problem.ale;
    // AleRemap's rule (lib/src/ale/ale_remap.cpp): the cycle number, else the worst zone
    // shape; a minimum is exact, so the decision is the serial one on any number of ranks.
    bool due = o.mode == AleMode::eulerian || (o.remap_every > 0 && s.cycle % o.remap_every == 0);
    if (!due && o.quality_trigger > 0) {
      const Mesh& m = s.mesh();
      double worst = std::numeric_limits<double>::infinity();
      for (Index z = 0; z < static_cast<Index>(s.ghost_zone.size()); ++z) {
        if (s.ghost_zone[z]) continue;
        const double q = zone_quality(m, z, QualityMeasure::reference_shape, s.x, s.y, m.x, m.y);
        if (q < worst) worst = q;
      }
      MPI_Allreduce(MPI_IN_PLACE, &worst, 1, MPI_DOUBLE, MPI_MIN, comm);
      due = worst < o.quality_trigger;
    }
    if (!due) return false;
    // The ALE phase reads and writes only the remapped arrays and the positions: the other
    // arrays are the same before and after it, on rank 0 and in every part (ghosts included,
    // by the exchange after the step).
    gather_fields(s, remap_fields);
    std::string error;
    double result[3] = {0, 0, 0};  // changed, ale_fixup, have_previous_forces
    if (my_rank == 0) {
      Simulation::Impl& w = DistributedAccess::impl(*whole);
      try {
        RemapState state{w.mesh(), w.t,   w.cycle, w.x,   w.y,         w.vx,         w.vy,
                         w.e,      w.sxx, w.syy,   w.sxy, w.zone_mass, w.point_mass, w.area};
        result[0] = w.remap->remap(state) ? 1 : 0;
      } catch (const Error& e) {
        error = e.what();
      }
      result[1] = w.ale_fixup;
      result[2] = w.have_previous_forces ? 1 : 0;
    }
    if (error = agree(error); !error.empty()) throw Error(error);
    MPI_Bcast(result, 3, MPI_DOUBLE, 0, comm);
    if (result[0] == 0) return false;
    scatter(s);
    // rz: the axis corners' planar masses follow from the scattered subcell masses, as after a
    // serial remap (docs/ale.md, "ALE in rz").
    if (s.rz) ale_axis_masses(s);
    s.ale_fixup = result[1];
    s.have_previous_forces = result[2] != 0;
    return true;
  }

  // Rank 0's whole state to every rank's part: every array the remap changes, at each of its
  // points, zones and corners, owned or ghost (one message per rank).
  void scatter(Simulation::Impl& s) {
    std::vector<double> scatter_buffer;  // transient, as the gathers' (docs/parallel.md, "Memory")
    const auto size_of = [&](std::size_t points, std::size_t zones, std::size_t corners) {
      std::size_t n = 0;
      for (const StateField* f : remap_fields)
        n += f->entity == Entity::point ? points : f->entity == Entity::zone ? zones : corners;
      return n;
    };
    if (my_rank == 0) {
      const Simulation::Impl& w = DistributedAccess::impl(*whole);
      for (int q = size - 1; q >= 0; --q) {
        const std::vector<Index>&zones = part_zones[q], &points = part_points[q];
        std::size_t corners = 0;
        for (Index z : zones) corners += w.zone_corner_begin[z + 1] - w.zone_corner_begin[z];
        scatter_buffer.resize(size_of(points.size(), zones.size(), corners));
        double* out = scatter_buffer.data();
        for (const StateField* f : remap_fields) {
          const double* values = (w.*(f->member)).data();
          switch (f->entity) {
            case Entity::point:
              for (Index p : points) *out++ = values[p];
              break;
            case Entity::zone:
              for (Index z : zones) *out++ = values[z];
              break;
            case Entity::corner:
              for (Index z : zones)
                for (Index k = w.zone_corner_begin[z]; k < w.zone_corner_begin[z + 1]; ++k) *out++ = values[k];
              break;
          }
        }
        if (q == 0) break;
        MPI_Send(scatter_buffer.data(), static_cast<int>(scatter_buffer.size()), MPI_DOUBLE, q, kHaloTag, comm);
        ++messages;
        bytes += static_cast<double>(scatter_buffer.size() * sizeof(double));
      }
    } else {
      scatter_buffer.resize(size_of(s.x.size(), s.zone_mass.size(), s.corner_fx.size()));
      MPI_Recv(scatter_buffer.data(), static_cast<int>(scatter_buffer.size()), MPI_DOUBLE, 0, kHaloTag, comm,
               MPI_STATUS_IGNORE);
    }
    // A part's entities are in the serial order, as rank 0 packed them.
    const double* in = scatter_buffer.data();
    for (const StateField* f : remap_fields) {
      std::vector<double>& values = s.*(f->member);
      std::copy(in, in + values.size(), values.begin());
      in += values.size();
    }
  }
};

// The remap hook of a distributed part (MpiCollective::remap).
class DistributedRemap final : public Remap {
 public:
  DistributedRemap(Simulation::Impl& s, MpiCollective& c) : s_(s), c_(c) {}
  bool remap(RemapState&) override { return c_.remap(s_); }

 private:
  Simulation::Impl& s_;
  MpiCollective& c_;
};

// A part on the wire (rank 0 to its rank): plain bytes, sizes before arrays.
// A counting pass first (`counting`) sizes the buffer, so that packing never doubles it.
struct Packer {
  std::string data;
  bool counting = false;
  std::size_t size = 0;
  void append(const char* bytes, std::size_t n) {
    size += n;
    if (!counting) data.append(bytes, n);
  }
  template <class T>
  void value(const T& x) {
    static_assert(std::is_trivially_copyable_v<T>);
    append(reinterpret_cast<const char*>(&x), sizeof x);
  }
  template <class T>
  void put(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    value(static_cast<std::uint64_t>(v.size()));
    append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void put(const std::string& text) {
    value(static_cast<std::uint64_t>(text.size()));
    append(text.data(), text.size());
  }
};

struct Unpacker {
  explicit Unpacker(const std::string& d) : data(d) {}
  const std::string& data;
  std::size_t at = 0;
  void need(std::size_t n) const {
    if (n > data.size() - at) throw Error("internal: a part received from rank 0 is truncated");
  }
  template <class T>
  void value(T& x) {
    need(sizeof x);
    std::memcpy(&x, data.data() + at, sizeof x);
    at += sizeof x;
  }
  std::uint64_t count(std::size_t element) {
    std::uint64_t n = 0;
    value(n);
    if (n > (data.size() - at) / element) throw Error("internal: a part received from rank 0 is truncated");
    return n;
  }
  template <class T>
  void get(std::vector<T>& v) {
    v.resize(count(sizeof(T)));
    if (!v.empty()) std::memcpy(v.data(), data.data() + at, v.size() * sizeof(T));
    at += v.size() * sizeof(T);
  }
  void get(std::string& text) {
    text.assign(data.data() + at, count(1));
    at += text.size();
  }
  void expect_end() const {
    if (at != data.size()) throw Error("internal: a part received from rank 0 has trailing bytes");
  }
};

// One state array's values on a part (its zones, points, or the corners of its zones).
void part_values(const Simulation::Impl& g, const StateField& f, const std::vector<Index>& zones,
                 const std::vector<Index>& points, std::vector<double>& values) {
  const std::vector<double>& from = g.*f.member;
  values.clear();
  switch (f.entity) {
    case Entity::point:
      for (Index p : points) values.push_back(from[p]);
      break;
    case Entity::zone:
      for (Index z : zones) values.push_back(from[z]);
      break;
    case Entity::corner:
      for (Index z : zones)
        for (Index k = g.zone_corner_begin[z]; k < g.zone_corner_begin[z + 1]; ++k) values.push_back(from[k]);
      break;
  }
}

// The large arrays of a part (its global numbers and its mesh's arrays), in the order they
// travel: one message each, straight into the receiver's vectors, so that no packed copy of
// them exists on either side (docs/parallel.md, "Memory").
template <class F>
void part_arrays(Part& part, Mesh& m, F&& each) {
  each(part.zones), each(part.points), each(m.x), each(m.y), each(m.zone_corner_begin), each(m.corner_point);
  each(m.corner_zone), each(m.point_corner_begin), each(m.point_corners), each(m.zone_region);
  each(m.region_zone_begin);  // the order of part_mesh_arrays()
}

template <class T>
void send_array(const std::vector<T>& v, int to, MPI_Comm comm) {
  static_assert(std::is_trivially_copyable_v<T>);
  const std::size_t bytes = v.size() * sizeof(T);
  if (bytes > static_cast<std::size_t>(INT_MAX))
    throw Error("an array of rank " + std::to_string(to) + "'s part is too large for one MPI message (" +
                std::to_string(bytes) + " bytes); run on more ranks");
  MPI_Send(v.data(), static_cast<int>(bytes), MPI_BYTE, to, kHaloTag, comm);
}

template <class T>
void receive_array(std::vector<T>& v, MPI_Comm comm) {
  MPI_Status status;
  MPI_Probe(0, kHaloTag, comm, &status);
  int count = 0;
  MPI_Get_count(&status, MPI_BYTE, &count);
  if (count % sizeof(T) != 0) throw Error("internal: an array received from rank 0 has a partial element");
  v.resize(static_cast<std::size_t>(count) / sizeof(T));
  MPI_Recv(v.data(), count, MPI_BYTE, 0, kHaloTag, comm, MPI_STATUS_IGNORE);
}

// The rest of a part (distribute() unpacks it in this order): the mesh's names and tags, then
// what follows the set-up (flags, scalars, walls).
void pack_part(Packer& out, const Simulation::Impl& g, const Mesh& local) {
  out.put(local.source);
  out.value(static_cast<std::uint64_t>(local.region_names.size()));
  for (const std::string& name : local.region_names) out.put(name);
  out.value(static_cast<std::uint64_t>(local.tags.size()));
  for (const BoundaryTag& tag : local.tags) out.put(tag.name), out.put(tag.edges), out.put(tag.points);
  out.value(static_cast<const StepConfig&>(g));
  io_detail::ByteWriter clock;
  write_clock(clock, g);
  out.put(clock.data());
  out.put(g.wall_edges);
  out.put(g.wall_rays);
  const WallGrid& w = g.wall_grid;
  out.value(w.x0), out.value(w.y0), out.value(w.x1), out.value(w.y1), out.value(w.inv_h), out.value(w.nx);
  out.value(w.ny);
  out.put(w.cell_begin);
  out.put(w.items);
}

std::string pack_part(const Simulation::Impl& g, const Mesh& local) {
  Packer out;
  out.counting = true;
  pack_part(out, g, local);
  out.data.reserve(out.size);
  out.counting = false;
  pack_part(out, g, local);
  return std::move(out.data);
}

void unpack_mesh(Unpacker& in, Mesh& m) {
  in.get(m.source);
  std::uint64_t n = 0;
  in.value(n);
  m.region_names.resize(n);
  for (std::string& name : m.region_names) in.get(name);
  in.value(n);
  m.tags.resize(n);
  for (BoundaryTag& tag : m.tags) in.get(tag.name), in.get(tag.edges), in.get(tag.points);
}

}  // namespace

HaloStatistics halo_statistics(const Simulation& part) {
  HaloStatistics h;
  const Simulation::Impl& s = DistributedAccess::impl(part);
  const auto* c = dynamic_cast<const MpiCollective*>(s.collective.get());
  if (!c) return h;
  for (unsigned char g : s.ghost_zone) (g ? h.ghost_zones : h.owned_zones) += 1;
  for (unsigned char g : s.ghost_point) (g ? h.ghost_points : h.owned_points) += 1;
  h.neighbours = static_cast<int>(c->neighbours.size());
  h.exchanges = c->exchanges;
  h.messages = c->messages;
  h.bytes = c->bytes;
  h.seconds = c->halo_seconds;
  return h;
}

void on_every_rank(MPI_Comm comm, const std::function<void()>& work) {
  const int rank = comm_rank(comm);
  std::string message;
  int failed = INT_MAX;
  try {
    work();
  } catch (const Error& error) {
    message = error.what();
    failed = rank;
  }
  int lowest = INT_MAX;
  MPI_Allreduce(&failed, &lowest, 1, MPI_INT, MPI_MIN, comm);
  if (lowest == INT_MAX) return;
  int length = static_cast<int>(message.size());
  MPI_Bcast(&length, 1, MPI_INT, lowest, comm);
  message.resize(length);
  MPI_Bcast(message.data(), length, MPI_CHAR, lowest, comm);
  throw Error(message);
}

Simulation distribute(Problem problem, MPI_Comm comm) {
  const int size = comm_size(comm), rank = comm_rank(comm);
  if (size == 1) return Simulation(std::move(problem));
  for (const auto& bc : problem.boundaries)
    if (bc.kind == BoundaryKind::periodic)
      throw Error("periodic boundary '" + bc.tag + "': a distributed run cannot take periodic boundaries yet " +
                  "(docs/parallel.md); run on one rank");
  // The part's problem: everything but the mesh and the energy deposits (their energy comes
  // with the copied state).
  Problem part_problem;
  part_problem.name = problem.name;
  part_problem.materials = problem.materials;
  part_problem.regions = problem.regions;
  part_problem.boundaries = problem.boundaries;
  part_problem.sources = problem.sources;
  part_problem.options = problem.options;
  part_problem.t_end = problem.t_end;
  part_problem.ale = problem.ale;

  auto collective = std::make_unique<MpiCollective>();
  MPI_Comm_dup(comm, &collective->comm);
  MPI_Comm c = collective->comm;
  collective->my_rank = rank;
  collective->size = size;
  // Rank 0 partitions the scene's mesh, sets up the whole problem as the serial run does (its
  // errors reach every rank) and sends every other rank its part; the other ranks drop their
  // copy of the mesh first, so they never hold more than the scene's mesh and their part.
  // METIS runs before the set-up (which keeps the mesh's connectivity), so that its work
  // space is handed back before the whole state is built (docs/parallel.md, "Memory").
  std::vector<int> owner;  // global zone -> rank (rank 0; the others get it once set up)
  on_every_rank(c, [&] {
    if (rank != 0) return;  // the other ranks' mesh may be an outline (load_scene_without_mesh)
    if (problem.mesh.num_zones() < size)
      throw Error("the mesh has " + std::to_string(problem.mesh.num_zones()) + " zones, fewer than the " +
                  std::to_string(size) + " ranks");
    owner = partition_zones(problem.mesh, size);
  });
  malloc_trim(0);
  std::unique_ptr<Simulation> whole;
  on_every_rank(c, [&] {
    if (rank == 0) whole = std::make_unique<Simulation>(std::move(problem));
  });
  problem = Problem{};
  malloc_trim(0);  // the other ranks' copy of the mesh, before their part arrives
  const Simulation::Impl* g = rank == 0 ? &DistributedAccess::impl(*whole) : nullptr;
  int sizes[3] = {g ? g->mesh().num_zones() : 0, g ? g->mesh().num_points() : 0, -1};
  if (g) {
    std::vector<Index> per_rank(size, 0);
    for (int o : owner) ++per_rank[o];
    for (int q = size - 1; q >= 0; --q)
      if (per_rank[q] == 0) sizes[2] = q;
  }
  MPI_Bcast(sizes, 3, MPI_INT, 0, c);
  const Index global_zones = sizes[0], global_points = sizes[1];
  if (sizes[2] >= 0) throw Error("METIS left rank " + std::to_string(sizes[2]) + " without zones; run on fewer ranks");

  // Rank 0 cuts each other rank's part (mesh, walls, configuration) and sends it; its own
  // part's mesh it cuts once the whole state is gone (below). The state arrays follow once
  // every rank has set its part up, one message per array, so that no rank holds its part's
  // state twice (docs/parallel.md, "Memory").
  std::string packed;
  std::vector<std::vector<Index>> part_zones, part_points;  // rank 0: every other part's, global
  Part part;
  // Two layers: the corner forces of the zones around this rank's points and their predicted
  // velocities; a third for the edge viscosity's neighbours (docs/parallel.md).
  const int layers = g && g->edge_viscosity ? 3 : 2;
  if (g) {
    part_zones.resize(size);
    part_points.resize(size);
    for (int q = size - 1; q >= 1; --q) {
      part = make_part(g->mesh(), owner, q, layers);
      std::string().swap(packed);  // (a move from an empty string keeps the buffer)
      packed = pack_part(*g, part_names(g->mesh(), part));
      if (packed.size() > static_cast<std::size_t>(INT_MAX))
        throw Error("the part of rank " + std::to_string(q) + " is too large for one MPI message (" +
                    std::to_string(packed.size()) + " bytes); run on more ranks");
      MPI_Send(packed.data(), static_cast<int>(packed.size()), MPI_BYTE, q, kHaloTag, c);
      send_array(part.zones, q, c);
      send_array(part.points, q, c);
      part_mesh_arrays(g->mesh(), part, [&](auto, const auto& v) { send_array(v, q, c); });
      part_zones[q] = std::move(part.zones);
      part_points[q] = std::move(part.points);
      part = Part{};
      std::string().swap(packed);
    }
    // Rank 0's own zones and points; the global-to-local maps are rebuilt for its mesh.
    part = make_part(g->mesh(), owner, 0, layers);
    part.zone_local = {};
    part.point_local = {};
    malloc_trim(0);  // the parts' meshes and the other ranks' packed parts
  } else {
    MPI_Status status;
    MPI_Probe(0, kHaloTag, c, &status);
    int count = 0;
    MPI_Get_count(&status, MPI_BYTE, &count);
    packed.resize(count);
    MPI_Recv(packed.data(), count, MPI_BYTE, 0, kHaloTag, c, MPI_STATUS_IGNORE);
    part_arrays(part, part_problem.mesh, [&](auto& v) { receive_array(v, c); });
  }
  std::string rest;  // what follows the mesh (flags, scalars, walls): read after the set-up
  const auto unpack_names = [&] {
    Unpacker names(packed);
    unpack_mesh(names, part_problem.mesh);
    rest = packed.substr(names.at);
    std::string().swap(packed);
  };
  if (!g) unpack_names();
  Unpacker in(rest);
  // A part's set-up, then the whole problem's configuration read from `rest`.
  std::unique_ptr<Simulation> local;
  const auto set_up_part = [&] {
    // ALE: the part's set-up builds no remap of its own (its work space is the size of the
    // part's mesh): the distributed one (MpiCollective::remap) runs the whole problem's on
    // rank 0. The part's ALE arrays come with the state below; the digest is the ALE one.
    const AleOptions ale = part_problem.ale;
    part_problem.ale.mode = AleMode::lagrangian;
    local = std::make_unique<Simulation>(std::move(part_problem));
    Simulation::Impl& s = DistributedAccess::impl(*local);
    s.problem.ale = ale;
    if (ale.mode != AleMode::lagrangian) s.digest = setup_digest(s);
    // The flags that decide which arrays exist and which kernel variants run: the whole
    // problem's (a part may lack the region or boundary that sets one).
    in.value(static_cast<StepConfig&>(s));
    allocate_state(s, s, s.mesh());  // the arrays of the whole problem's configuration
    std::string clock;
    in.get(clock);
    io_detail::ByteReader clock_bytes(clock, "the clock of a part received from rank 0");
    static_cast<Clock&>(s) = read_clock(clock_bytes);
    // The walls as fixed lines (the no-crossing check): the whole problem's, so that a point is
    // tested against every wall as in the serial run; a wall point off this part becomes -2 - its number.
    in.get(s.wall_edges);
    in.get(s.wall_rays);
    in.value(s.wall_grid.x0), in.value(s.wall_grid.y0), in.value(s.wall_grid.x1), in.value(s.wall_grid.y1);
    in.value(s.wall_grid.inv_h), in.value(s.wall_grid.nx), in.value(s.wall_grid.ny);
    in.get(s.wall_grid.cell_begin);
    in.get(s.wall_grid.items);
    in.expect_end();
    std::string().swap(rest);
  };
  // The state: the serial set-up's, bit for bit, one array at a time. The other ranks set
  // their parts up and receive; rank 0 sets its own up last, once the whole state has dropped
  // its arrays, its own values of them set aside (an array that is all +0.0 is not copied:
  // its part gets zeros): the whole state and rank 0's part are never both
  // complete (docs/parallel.md, "Memory"). An ALE scene's whole state keeps every array: the
  // serial remap runs on it (docs/parallel.md, "ALE").
  on_every_rank(c, [&] {
    if (rank != 0) set_up_part();
  });
  const auto check = [](const StateField& f, std::size_t size, std::size_t expected) {
    if (size != expected) throw Error(std::string("internal: the part's state array '") + f.name + "' differs");
  };
  const auto all_zero = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::bit_cast<std::uint64_t>(x) == 0; });
  };
  std::vector<double> values;
  std::vector<std::vector<double>> own;  // rank 0: its part's values of the arrays the whole drops
  std::vector<unsigned char> own_zero;   // rank 0: those all +0.0 (not kept)
  for (const StateField& f : state_fields()) {
    if (g) {
      if (!present(*g, f.presence)) continue;
      for (int q = 1; q < size; ++q) {
        part_values(*g, f, part_zones[q], part_points[q], values);
        MPI_Send(values.data(), static_cast<int>(values.size()), MPI_DOUBLE, q, kHaloTag, c);
      }
      if (g->remap) continue;
      own.emplace_back();
      part_values(*g, f, part.zones, part.points, own.back());
      own_zero.push_back(all_zero(own.back()) ? 1 : 0);
      if (own_zero.back()) std::vector<double>().swap(own.back());
      std::vector<double>().swap(DistributedAccess::impl(*whole).*f.member);
    } else {
      Simulation::Impl& s = DistributedAccess::impl(*local);
      if (!present(s, f.presence)) continue;
      std::vector<double>& to = s.*f.member;
      MPI_Status status;
      MPI_Recv(to.data(), static_cast<int>(to.size()), MPI_DOUBLE, 0, kHaloTag, c, &status);
      int count = 0;
      MPI_Get_count(&status, MPI_DOUBLE, &count);
      check(f, static_cast<std::size_t>(count), to.size());
    }
  }
  values = std::vector<double>();
  malloc_trim(0);
  if (g) {
    // Rank 0's own mesh, cut now that the whole state's arrays are gone.
    part.zone_local.assign(global_zones, -1);
    part.point_local.assign(global_points, -1);
    for (std::size_t i = 0; i < part.zones.size(); ++i) part.zone_local[part.zones[i]] = static_cast<Index>(i);
    for (std::size_t i = 0; i < part.points.size(); ++i) part.point_local[part.points[i]] = static_cast<Index>(i);
    packed = pack_part(*g, part_names(g->mesh(), part));
    unpack_names();
    Mesh& mine = part_problem.mesh;
    part_mesh_arrays(g->mesh(), part, [&](auto member, auto& v) { (mine.*member).swap(v); });
    part.zone_local = {};
    part.point_local = {};
  }
  on_every_rank(c, [&] {
    if (rank == 0) set_up_part();
  });
  Simulation::Impl& s = DistributedAccess::impl(*local);
  if (g) {
    std::size_t k = 0;
    for (const StateField& f : state_fields()) {
      if (!present(s, f.presence)) continue;
      std::vector<double>& to = s.*f.member;
      const std::size_t expected = to.size();
      if (g->remap) {
        part_values(*g, f, part.zones, part.points, to);
      } else if (own_zero.at(k)) {
        to.assign(expected, 0.0);
        ++k;
      } else {
        to.swap(own.at(k));
        std::vector<double>().swap(own[k++]);  // freed now: the maps below reuse it
      }
      check(f, to.size(), expected);
    }
  }
  own = {};
  // The part's global numbers (ascending): a binary search finds a global zone or point in it.
  s.global_zone = std::move(part.zones);
  s.global_point = std::move(part.points);
  part = Part{};
  const auto local_of = [](const std::vector<Index>& global, Index id) -> Index {
    const auto at = std::lower_bound(global.begin(), global.end(), id);
    return at != global.end() && *at == id ? static_cast<Index>(at - global.begin()) : -1;
  };
  if (g && g->remap) {
    // The ALE remap sends every part its remapped state (MpiCollective::scatter).
    part_zones[0] = s.global_zone;
    part_points[0] = s.global_point;
    collective->part_zones = std::move(part_zones);
    collective->part_points = std::move(part_points);
  }
  part_zones = {};
  part_points = {};
  for (auto* walls : {&s.wall_edges, &s.wall_rays})
    for (WallEdge& w : *walls) {
      const Index a = local_of(s.global_point, w.a);
      w.a = a >= 0 ? a : -2 - w.a;
      if (w.b >= 0) {
        const Index b = local_of(s.global_point, w.b);
        w.b = b >= 0 ? b : -2 - w.b;
      }
    }

  // Ownership: the owner of every zone, and of every point (the lowest rank among its zones'
  // owners), from rank 0 in chunks, so that no other rank holds a map of the whole problem.
  std::vector<int> point_owner;
  if (g) {
    const Mesh& m = g->mesh();
    point_owner.assign(global_points, INT_MAX);
    for (Index z = 0; z < m.num_zones(); ++z)
      for (Index k = m.zone_corner_begin[z]; k < m.zone_corner_begin[z + 1]; ++k)
        point_owner[m.corner_point[k]] = std::min(point_owner[m.corner_point[k]], owner[z]);
  }
  const Index nz = static_cast<Index>(s.global_zone.size()), np = static_cast<Index>(s.global_point.size());
  s.ghost_zone.assign(nz, 0);
  s.ghost_point.assign(np, 0);
  // This rank's ghosts by owner; the owners learn them as global numbers (the halo lists below).
  std::vector<std::vector<Index>> ghost_points(size), ghost_zones(size);
  const auto owners = [&](const std::vector<int>& all, Index total, const std::vector<Index>& mine,
                          std::vector<unsigned char>& ghost, std::vector<std::vector<Index>>& by_owner) {
    constexpr Index kChunk = 1 << 16;
    std::vector<int> chunk;
    std::size_t i = 0;
    for (Index first = 0; first < total; first += kChunk) {
      const Index n = std::min(kChunk, total - first);
      if (g)
        chunk.assign(all.begin() + first, all.begin() + first + n);
      else
        chunk.resize(n);
      MPI_Bcast(chunk.data(), n, MPI_INT, 0, c);
      for (; i < mine.size() && mine[i] < first + n; ++i) {
        const int o = chunk[mine[i] - first];
        ghost[i] = o != rank;
        if (o != rank) by_owner[o].push_back(static_cast<Index>(i));
      }
    }
  };
  owners(owner, global_zones, s.global_zone, s.ghost_zone, ghost_zones);
  owners(point_owner, global_points, s.global_point, s.ghost_point, ghost_points);

  // The ranges split into own and ghost runs.
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
  const bool ale = s.problem.ale.mode != AleMode::lagrangian;
  if (ale)  // the corner masses
    for (Index z = 0; z < nz; ++z)
      if (!s.ghost_zone[z])
        for (Index k = s.zone_corner_begin[z]; k < s.zone_corner_begin[z + 1]; ++k)
          collective->own_corners.push_back(k);

  // Halo lists: this rank's ghosts by owner (above), as global numbers to their owners.
  std::vector<int> send_counts(2 * size), recv_counts(2 * size);
  for (int q = 0; q < size; ++q)
    send_counts[2 * q] = static_cast<int>(ghost_points[q].size()),
                    send_counts[2 * q + 1] = static_cast<int>(ghost_zones[q].size());
  MPI_Alltoall(send_counts.data(), 2, MPI_INT, recv_counts.data(), 2, MPI_INT, c);
  std::vector<int> sc(size), sd(size), rc(size), rd(size);
  std::vector<Index> send_ids, recv_ids;
  for (int q = 0; q < size; ++q) {
    sd[q] = static_cast<int>(send_ids.size());
    for (Index p : ghost_points[q]) send_ids.push_back(s.global_point[p]);
    for (Index z : ghost_zones[q]) send_ids.push_back(s.global_zone[z]);
    sc[q] = static_cast<int>(send_ids.size()) - sd[q];
    rc[q] = recv_counts[2 * q] + recv_counts[2 * q + 1];
    rd[q] = q == 0 ? 0 : rd[q - 1] + rc[q - 1];
  }
  recv_ids.resize(rd[size - 1] + rc[size - 1]);
  MPI_Alltoallv(send_ids.data(), sc.data(), sd.data(), MPI_INT32_T, recv_ids.data(), rc.data(), rd.data(), MPI_INT32_T,
                c);
  for (const StateField& f : state_fields())
    if (present(s, f.presence)) {
      collective->fields.push_back(&f);
      if ((f.flags & kRemapped) || f.member == &Simulation::Impl::x || f.member == &Simulation::Impl::y)
        collective->remap_fields.push_back(&f);
    }
  std::size_t per_point = 0, per_zone = 0, per_corner = 0;
  for (const StateField* f : collective->fields)
    (f->entity == Entity::point ? per_point : f->entity == Entity::zone ? per_zone : per_corner) += 1;
  for (int q = 0; q < size; ++q) {
    if (q == rank || (sc[q] == 0 && rc[q] == 0)) continue;
    Neighbour n;
    n.rank = q;
    n.recv_points = ghost_points[q];
    n.recv_zones = ghost_zones[q];
    append_corners(s, n.recv_zones, n.recv_corners);
    for (int i = 0; i < recv_counts[2 * q]; ++i) n.send_points.push_back(local_of(s.global_point, recv_ids[rd[q] + i]));
    for (int i = 0; i < recv_counts[2 * q + 1]; ++i)
      n.send_zones.push_back(local_of(s.global_zone, recv_ids[rd[q] + recv_counts[2 * q] + i]));
    append_corners(s, n.send_zones, n.send_corners);
    n.send.resize(per_point * n.send_points.size() + per_zone * n.send_zones.size() +
                  per_corner * n.send_corners.size());
    n.recv.resize(per_point * n.recv_points.size() + per_zone * n.recv_zones.size() +
                  per_corner * n.recv_corners.size());
    collective->neighbours.push_back(std::move(n));
  }

  // Gather to rank 0 (dumps, summary, references): every rank's owned points and zones, in
  // global order, of the arrays the whole state serves (gathered()); for an ALE remap also
  // every rank's owned corners (the remapped corner masses).
  for (const StateField* f : collective->fields)
    if (gathered(*f)) collective->gathered_fields.push_back(f);
  if (rank == 0) {
    const Mesh& m = g->mesh();
    collective->rank_points.resize(size);
    collective->rank_zones.resize(size);
    std::vector<std::size_t> points_of(size, 0), zones_of(size, 0);  // exact sizes: no doubling slack
    for (int o : point_owner) ++points_of[o];
    for (int o : owner) ++zones_of[o];
    for (int q = 0; q < size; ++q) collective->rank_points[q].reserve(points_of[q]);
    for (int q = 0; q < size; ++q) collective->rank_zones[q].reserve(zones_of[q]);
    for (Index p = 0; p < m.num_points(); ++p) collective->rank_points[point_owner[p]].push_back(p);
    for (Index z = 0; z < m.num_zones(); ++z) collective->rank_zones[owner[z]].push_back(z);
    if (g->remap) {
      collective->rank_corners.resize(size);
      for (Index z = 0; z < m.num_zones(); ++z)
        for (Index k = m.zone_corner_begin[z]; k < m.zone_corner_begin[z + 1]; ++k)
          collective->rank_corners[owner[z]].push_back(k);
    }
    collective->whole = std::move(whole);
  }
  whole.reset();
  part = Part{};
  owner = {};
  point_owner = {};
  // ALE: the distributed remap, which runs the whole problem's on rank 0.
  if (ale) s.remap = std::make_shared<DistributedRemap>(s, *collective);
  s.collective = std::move(collective);
  malloc_trim(0);  // hand the set-up's and the distribution's temporaries back to the OS
  return std::move(*local);
}

}  // namespace stagger
