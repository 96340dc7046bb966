// A part on its way from rank 0 to its rank (part_transfer.hpp, docs/parallel.md, "Memory").
#include "parallel/part_transfer.hpp"

#include <climits>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include "io/byte_stream.hpp"
#include "parallel/distributed_access.hpp"
#include "stagger/error.hpp"
#include "state/clock.hpp"
#include "state/state_table.hpp"

namespace stagger::parallel {

namespace {

using io_detail::ByteReader;
using io_detail::ByteWriter;

// What the errors of a malformed part name (a bug, never the user's input).
constexpr const char* kPartSource = "internal: the part received from rank 0";

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

void pack_mesh_names(ByteWriter& out, const Mesh& local) {
  out.bytes(local.source);
  out.u64(local.region_names.size());
  for (const std::string& name : local.region_names) out.bytes(name);
  out.u64(local.tags.size());
  for (const BoundaryTag& tag : local.tags)
    out.bytes(tag.name), out.native_array(tag.edges), out.native_array(tag.points);
}

void unpack_mesh_names(ByteReader& in, Mesh& m) {
  m.source = in.bytes();
  m.region_names.resize(in.count(8, "region names"));
  for (std::string& name : m.region_names) name = in.bytes();
  m.tags.resize(in.count(24, "boundary tags"));
  for (BoundaryTag& tag : m.tags)
    tag.name = in.bytes(), in.native_array(tag.edges, "tag edges"), in.native_array(tag.points, "tag points");
}

// The flags that decide which arrays exist and which kernel variants run: the whole
// problem's (a part may lack the region or boundary that sets one).
void pack_flags(ByteWriter& out, const Simulation::Impl& g) {
  out.native(static_cast<const StepConfig&>(g));
}

void unpack_flags(ByteReader& in, Simulation::Impl& s) {
  in.native(static_cast<StepConfig&>(s));
}

// The whole problem's clock, in the one format of checkpoints (state/clock.hpp).
void pack_clock(ByteWriter& out, const Simulation::Impl& g) {
  write_clock(out, g);
}

void unpack_clock(ByteReader& in, Simulation::Impl& s) {
  static_cast<Clock&>(s) = read_clock(in);
}

// The walls as fixed lines (the no-crossing check): the whole problem's, so that a point is
// tested against every wall as in the serial run (number_walls_locally()).
void pack_walls(ByteWriter& out, const Simulation::Impl& g) {
  out.native_array(g.wall_edges);
  out.native_array(g.wall_rays);
  const WallGrid& w = g.wall_grid;
  out.native(w.x0), out.native(w.y0), out.native(w.x1), out.native(w.y1), out.native(w.inv_h), out.native(w.nx);
  out.native(w.ny);
  out.native_array(w.cell_begin);
  out.native_array(w.items);
}

void unpack_walls(ByteReader& in, Simulation::Impl& s) {
  in.native_array(s.wall_edges, "wall edges");
  in.native_array(s.wall_rays, "wall rays");
  WallGrid& w = s.wall_grid;
  in.native(w.x0), in.native(w.y0), in.native(w.x1), in.native(w.y1), in.native(w.inv_h), in.native(w.nx);
  in.native(w.ny);
  in.native_array(w.cell_begin, "wall grid cells");
  in.native_array(w.items, "wall grid items");
}

// The packed rest, in the order set_up_part() reads it.
void pack_part(ByteWriter& out, const Simulation::Impl& g, const Mesh& local) {
  pack_mesh_names(out, local);
  pack_flags(out, g);
  pack_clock(out, g);
  pack_walls(out, g);
}

}  // namespace

std::string pack_part(const Simulation::Impl& g, const Mesh& local) {
  ByteWriter size = ByteWriter::counter();
  pack_part(size, g, local);
  ByteWriter out;
  out.reserve(size.size());
  pack_part(out, g, local);
  return out.take();
}

void send_part(const Simulation::Impl& g, const Part& part, int to, MPI_Comm comm) {
  const std::string packed = pack_part(g, part_names(g.mesh(), part));
  if (packed.size() > static_cast<std::size_t>(INT_MAX))
    throw Error("the part of rank " + std::to_string(to) + " is too large for one MPI message (" +
                std::to_string(packed.size()) + " bytes); run on more ranks");
  MPI_Send(packed.data(), static_cast<int>(packed.size()), MPI_BYTE, to, kHaloTag, comm);
  send_array(part.zones, to, comm);
  send_array(part.points, to, comm);
  part_mesh_arrays(g.mesh(), part, [&](auto, const auto& v) { send_array(v, to, comm); });
}

std::string receive_part(Part& part, Mesh& mesh, MPI_Comm comm) {
  MPI_Status status;
  MPI_Probe(0, kHaloTag, comm, &status);
  int count = 0;
  MPI_Get_count(&status, MPI_BYTE, &count);
  std::string packed(count, '\0');
  MPI_Recv(packed.data(), count, MPI_BYTE, 0, kHaloTag, comm, MPI_STATUS_IGNORE);
  part_arrays(part, mesh, [&](auto& v) { receive_array(v, comm); });
  return packed;
}

std::string unpack_mesh_names(std::string& packed, Mesh& mesh) {
  ByteReader names(packed, kPartSource);
  unpack_mesh_names(names, mesh);
  std::string rest = packed.substr(names.position());
  std::string().swap(packed);
  return rest;
}

std::unique_ptr<Simulation> set_up_part(Problem problem, std::string rest) {
  ByteReader in(rest, kPartSource);
  // ALE: the part gets no built-in remap (its work space would be the size of the part's
  // mesh): the distributed one (distributed_remap.cpp) runs the whole problem's on rank 0.
  // The part's ALE arrays come with the state.
  auto local = std::make_unique<Simulation>(DistributedAccess::lagrangian_only(std::move(problem)));
  Simulation::Impl& s = DistributedAccess::impl(*local);
  unpack_flags(in, s);
  allocate_state(s, s, s.mesh());  // the arrays of the whole problem's configuration
  unpack_clock(in, s);
  unpack_walls(in, s);
  in.expect_end();
  return local;
}

void number_walls_locally(Simulation::Impl& s) {
  for (auto* walls : {&s.wall_edges, &s.wall_rays})
    for (WallEdge& w : *walls) {
      const Index a = local_index(s.global_point, w.a);
      w.a = a >= 0 ? a : -2 - w.a;
      if (w.b >= 0) {
        const Index b = local_index(s.global_point, w.b);
        w.b = b >= 0 ? b : -2 - w.b;
      }
    }
}

}  // namespace stagger::parallel
