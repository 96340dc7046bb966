// The state of every part, from rank 0's serial set-up (state_transfer.hpp).
#include "parallel/state_transfer.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <string>

#include "parallel/distributed_access.hpp"
#include "stagger/error.hpp"
#include "state/state_table.hpp"

namespace stagger::parallel {

namespace {

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

void check_size(const StateField& f, std::size_t size, std::size_t expected) {
  if (size != expected) throw Error(std::string("internal: the part's state array '") + f.name + "' differs");
}

bool all_zero(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::bit_cast<std::uint64_t>(x) == 0; });
}

}  // namespace

OwnState send_state(Simulation::Impl& whole, const std::vector<std::vector<Index>>& part_zones,
                    const std::vector<std::vector<Index>>& part_points, const Part& own, MPI_Comm comm) {
  const int size = static_cast<int>(part_zones.size());
  std::vector<double> values;
  OwnState kept;
  for (const StateField& f : state_fields()) {
    if (!present(whole, f.presence)) continue;
    for (int q = 1; q < size; ++q) {
      part_values(whole, f, part_zones[q], part_points[q], values);
      MPI_Send(values.data(), static_cast<int>(values.size()), MPI_DOUBLE, q, kHaloTag, comm);
    }
    if (whole.remap) continue;
    kept.values.emplace_back();
    part_values(whole, f, own.zones, own.points, kept.values.back());
    kept.zero.push_back(all_zero(kept.values.back()) ? 1 : 0);
    if (kept.zero.back()) std::vector<double>().swap(kept.values.back());
    std::vector<double>().swap(whole.*f.member);
  }
  return kept;
}

void receive_state(Simulation::Impl& s, MPI_Comm comm) {
  for (const StateField& f : state_fields()) {
    if (!present(s, f.presence)) continue;
    std::vector<double>& to = s.*f.member;
    MPI_Status status;
    MPI_Recv(to.data(), static_cast<int>(to.size()), MPI_DOUBLE, 0, kHaloTag, comm, &status);
    int count = 0;
    MPI_Get_count(&status, MPI_DOUBLE, &count);
    check_size(f, static_cast<std::size_t>(count), to.size());
  }
}

void fill_own_state(Simulation::Impl& s, const Simulation::Impl& whole, const Part& own, OwnState& kept) {
  std::size_t k = 0;
  for (const StateField& f : state_fields()) {
    if (!present(s, f.presence)) continue;
    std::vector<double>& to = s.*f.member;
    const std::size_t expected = to.size();
    if (whole.remap) {
      part_values(whole, f, own.zones, own.points, to);
    } else if (kept.zero.at(k)) {
      to.assign(expected, 0.0);
      ++k;
    } else {
      to.swap(kept.values.at(k));
      std::vector<double>().swap(kept.values[k++]);  // freed now: the maps that follow reuse it
    }
    check_size(f, to.size(), expected);
  }
}

}  // namespace stagger::parallel
