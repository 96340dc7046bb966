// The collective operations of a distributed run on MPI (mpi_collective.hpp).
#include "parallel/mpi_collective.hpp"

#include <algorithm>
#include <chrono>
#include <climits>
#include <string>

#include "hydro/kernels/zone_status.hpp"
#include "parallel/distributed_access.hpp"
#include "parallel/part.hpp"
#include "stagger/parallel.hpp"
#include "state/clock.hpp"

namespace stagger {

namespace parallel {

namespace {

// The state arrays the whole state on rank 0 keeps for the gathers (dumps, summary,
// references): the dumped ones and those behind Simulation's accessors. The rest (the step's
// scratch, the corner forces, set-up constants) nothing reads from it.
bool gathered(const StateField& f) {
  using I = Simulation::Impl;
  return (f.flags & kDumped) || f.member == &I::x || f.member == &I::y || f.member == &I::point_mass ||
         f.member == &I::zone_mass || f.member == &I::area;
}

}  // namespace

MpiCollective::~MpiCollective() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized && comm != MPI_COMM_NULL) MPI_Comm_free(&comm);
}

std::int64_t MpiCollective::min_failure(const Simulation::Impl& s, std::int64_t local_code) {
  std::int64_t code = local_code == kNoFailure
                          ? kNoFailure
                          : failure_code(s.global_zone[failure_zone(local_code)], failure_kind(local_code));
  std::int64_t result = kNoFailure;
  MPI_Allreduce(&code, &result, 1, MPI_INT64_T, MPI_MIN, comm);
  return result;
}

DtChoice MpiCollective::min_dt(const Simulation::Impl& s, DtChoice local) {
  // MINLOC: the smallest dt, and on a tie the smallest index (the serial tie-break).
  struct {
    double dt;
    int zone;
  } in{local.dt, local.zone >= 0 ? s.global_zone[local.zone] : INT_MAX}, out{};
  MPI_Allreduce(&in, &out, 1, MPI_DOUBLE_INT, MPI_MINLOC, comm);
  return {out.dt, out.zone == INT_MAX ? -1 : out.zone};
}

std::string MpiCollective::owner_text(const std::vector<Index>& global, const std::vector<unsigned char>& ghost,
                                      Index id, const std::function<std::string(Index)>& text) {
  // A part's global numbers ascend, so a binary search finds it; no map of the whole problem.
  const Index local = local_index(global, id);
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

std::string MpiCollective::zone_text(const Simulation::Impl& s, Index zone,
                                     const std::function<std::string(Index)>& text) {
  return owner_text(s.global_zone, s.ghost_zone, zone, text);
}

Index MpiCollective::min_point(const Simulation::Impl& s, Index local_point) {
  int point = local_point >= 0 ? s.global_point[local_point] : INT_MAX, result = INT_MAX;
  MPI_Allreduce(&point, &result, 1, MPI_INT, MPI_MIN, comm);
  return result == INT_MAX ? -1 : result;
}

std::string MpiCollective::point_text(const Simulation::Impl& s, Index point,
                                      const std::function<std::string(Index)>& text) {
  return owner_text(s.global_point, s.ghost_point, point, text);
}

void MpiCollective::sum(std::span<ExactSum> sums) {
  // One integer sum of every accumulator's words: exact, so any reduction order gives the same.
  const std::size_t n = sums.size(), words = ExactSum::kWords;
  std::vector<std::int64_t> in(n * words), out(n * words);
  for (std::size_t i = 0; i < n; ++i) std::copy(sums[i].words().begin(), sums[i].words().end(), in.begin() + i * words);
  MPI_Allreduce(in.data(), out.data(), static_cast<int>(in.size()), MPI_INT64_T, MPI_SUM, comm);
  for (std::size_t i = 0; i < n; ++i)
    std::copy(out.begin() + i * words, out.begin() + (i + 1) * words, sums[i].words().begin());
}

std::string MpiCollective::agree(const std::string& text) {
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

bool MpiCollective::any(bool local) {
  int mine = local ? 1 : 0, result = 0;
  MPI_Allreduce(&mine, &result, 1, MPI_INT, MPI_MAX, comm);
  return result != 0;
}

void MpiCollective::exchange(Simulation::Impl& s) {
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

void MpiCollective::gather_fields(const Simulation::Impl& s, const std::vector<const StateField*>& list) {
  std::vector<double> send, recv;
  std::vector<int> counts, offsets;
  for (const StateField* f : list) {
    const auto& ids = [&](int q) -> const std::vector<Index>& {
      return f->entity == Entity::point ? rank_points[q] : f->entity == Entity::zone ? rank_zones[q] : rank_corners[q];
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
    // The whole state's arrays are empty until the first gather (send_state() frees them).
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
  // The scalars are the same on every rank (dt_zone is already global).
  static_cast<Clock&>(DistributedAccess::impl(*whole)) = s;
}

const Simulation* MpiCollective::gather(const Simulation::Impl& s) {
  gather_fields(s, gathered_fields);
  return my_rank == 0 ? whole.get() : nullptr;
}

void list_fields(MpiCollective& c, const Simulation::Impl& s) {
  for (const StateField& f : state_fields())
    if (present(s, f.presence)) {
      c.fields.push_back(&f);
      if ((f.flags & kRemapped) || f.member == &Simulation::Impl::x || f.member == &Simulation::Impl::y)
        c.remap_fields.push_back(&f);
    }
  for (const StateField* f : c.fields)
    if (gathered(*f)) c.gathered_fields.push_back(f);
}

void set_up_gather(MpiCollective& c, std::unique_ptr<Simulation> whole, const std::vector<int>& zone_owner,
                   const std::vector<int>& point_owner) {
  const Simulation::Impl& g = DistributedAccess::impl(*whole);
  const Mesh& m = g.mesh();
  const int size = c.size;
  c.rank_points.resize(size);
  c.rank_zones.resize(size);
  std::vector<std::size_t> points_of(size, 0), zones_of(size, 0);  // exact sizes: no doubling slack
  for (int o : point_owner) ++points_of[o];
  for (int o : zone_owner) ++zones_of[o];
  for (int q = 0; q < size; ++q) c.rank_points[q].reserve(points_of[q]);
  for (int q = 0; q < size; ++q) c.rank_zones[q].reserve(zones_of[q]);
  for (Index p = 0; p < m.num_points(); ++p) c.rank_points[point_owner[p]].push_back(p);
  for (Index z = 0; z < m.num_zones(); ++z) c.rank_zones[zone_owner[z]].push_back(z);
  if (g.remap) {
    c.rank_corners.resize(size);
    for (Index z = 0; z < m.num_zones(); ++z)
      for (Index k = m.zone_corner_begin[z]; k < m.zone_corner_begin[z + 1]; ++k)
        c.rank_corners[zone_owner[z]].push_back(k);
  }
  c.whole = std::move(whole);
}

}  // namespace parallel

HaloStatistics halo_statistics(const Simulation& part) {
  HaloStatistics h;
  const Simulation::Impl& s = DistributedAccess::impl(part);
  const auto* c = dynamic_cast<const parallel::MpiCollective*>(s.collective.get());
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

}  // namespace stagger
