// The ALE phase of a distributed run (distributed_remap.hpp, docs/parallel.md, "ALE").
#include "parallel/distributed_remap.hpp"

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "ale/ale_remap.hpp"
#include "ale/rezone.hpp"
#include "parallel/distributed_access.hpp"
#include "stagger/error.hpp"

namespace stagger::parallel {

namespace {

// AleRemap's rule (lib/src/ale/ale_remap.cpp): the cycle number, else the worst zone shape;
// a minimum is exact, so the decision is the serial one on any number of ranks.
bool remap_due(const Simulation::Impl& s, MPI_Comm comm) {
  const AleOptions& o = s.problem.ale;
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
  return due;
}

// Rank 0's whole state to every rank's part: every array the remap changes, at each of its
// points, zones and corners, owned or ghost (one message per rank).
void scatter_remapped(MpiCollective& c, Simulation::Impl& s) {
  std::vector<double> scatter_buffer;  // transient, as the gathers' (docs/parallel.md, "Memory")
  const auto size_of = [&](std::size_t points, std::size_t zones, std::size_t corners) {
    std::size_t n = 0;
    for (const StateField* f : c.remap_fields)
      n += f->entity == Entity::point ? points : f->entity == Entity::zone ? zones : corners;
    return n;
  };
  if (c.my_rank == 0) {
    const Simulation::Impl& w = DistributedAccess::impl(*c.whole);
    for (int q = c.size - 1; q >= 0; --q) {
      const std::vector<Index>&zones = c.part_zones[q], &points = c.part_points[q];
      std::size_t corners = 0;
      for (Index z : zones) corners += w.zone_corner_begin[z + 1] - w.zone_corner_begin[z];
      scatter_buffer.resize(size_of(points.size(), zones.size(), corners));
      double* out = scatter_buffer.data();
      for (const StateField* f : c.remap_fields) {
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
      MPI_Send(scatter_buffer.data(), static_cast<int>(scatter_buffer.size()), MPI_DOUBLE, q, kHaloTag, c.comm);
      ++c.messages;
      c.bytes += static_cast<double>(scatter_buffer.size() * sizeof(double));
    }
  } else {
    scatter_buffer.resize(size_of(s.x.size(), s.zone_mass.size(), s.corner_fx.size()));
    MPI_Recv(scatter_buffer.data(), static_cast<int>(scatter_buffer.size()), MPI_DOUBLE, 0, kHaloTag, c.comm,
             MPI_STATUS_IGNORE);
  }
  // A part's entities are in the serial order, as rank 0 packed them.
  const double* in = scatter_buffer.data();
  for (const StateField* f : c.remap_fields) {
    std::vector<double>& values = s.*(f->member);
    std::copy(in, in + values.size(), values.begin());
    in += values.size();
  }
}

// The ALE phase: whether a remap ran.
bool distributed_remap(MpiCollective& c, Simulation::Impl& s) {
  if (!remap_due(s, c.comm)) return false;
  // The ALE phase reads and writes only the remapped arrays and the positions: the other
  // arrays are the same before and after it, on rank 0 and in every part (ghosts included,
  // by the exchange after the step).
  c.gather_fields(s, c.remap_fields);
  std::string error;
  double result[3] = {0, 0, 0};  // changed, ale_fixup, have_previous_forces
  if (c.my_rank == 0) {
    Simulation::Impl& w = DistributedAccess::impl(*c.whole);
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
  if (error = c.agree(error); !error.empty()) throw Error(error);
  MPI_Bcast(result, 3, MPI_DOUBLE, 0, c.comm);
  if (result[0] == 0) return false;
  scatter_remapped(c, s);
  // rz: the axis corners' planar masses follow from the scattered subcell masses, as after a
  // serial remap (docs/ale.md, "ALE in rz").
  if (s.rz) ale_axis_masses(s);
  s.ale_fixup = result[1];
  s.have_previous_forces = result[2] != 0;
  return true;
}

class DistributedRemap final : public Remap {
 public:
  DistributedRemap(Simulation::Impl& s, MpiCollective& c) : s_(s), c_(c) {}
  bool remap(RemapState&) override { return distributed_remap(c_, s_); }

 private:
  Simulation::Impl& s_;
  MpiCollective& c_;
};

}  // namespace

std::shared_ptr<Remap> make_distributed_remap(Simulation::Impl& s, MpiCollective& c) {
  return std::make_shared<DistributedRemap>(s, c);
}

}  // namespace stagger::parallel
