// VTK .vtu output (the only translation units that include VTK are in lib/src/output).
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkStringArray.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "io/atomic_file.hpp"
#include "io/text_format.hpp"
#include "stagger/error.hpp"
#include "stagger/output.hpp"
#include "stagger/simulation.hpp"

namespace stagger {

namespace {

/// Points (double precision, z = 0) and cells (quads, triangles, polygons) of the mesh with
/// the given point positions: all of them, or (a distributed run's piece) the listed zones
/// and points, local[p] being point p's number in the piece.
vtkNew<vtkUnstructuredGrid> make_grid(const Mesh& mesh, std::span<const double> x, std::span<const double> y,
                                      const std::vector<Index>* zones = nullptr,
                                      const std::vector<Index>* points = nullptr,
                                      const std::vector<Index>* local = nullptr) {
  vtkNew<vtkUnstructuredGrid> grid;
  vtkNew<vtkPoints> xy;
  xy->SetDataTypeToDouble();
  const Index npoints = points ? static_cast<Index>(points->size()) : mesh.num_points();
  xy->SetNumberOfPoints(npoints);
  for (Index i = 0; i < npoints; ++i) {
    const Index p = points ? (*points)[i] : i;
    xy->SetPoint(i, x[p], y[p], 0.0);
  }
  grid->SetPoints(xy);

  const Index nzones = zones ? static_cast<Index>(zones->size()) : mesh.num_zones();
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  vtkNew<vtkUnsignedCharArray> types;
  offsets->SetNumberOfValues(nzones + 1);
  types->SetNumberOfValues(nzones);
  vtkIdType corners = 0;
  offsets->SetValue(0, 0);
  for (Index i = 0; i < nzones; ++i) {
    const Index z = zones ? (*zones)[i] : i;
    const Index n = mesh.zone_corner_begin[z + 1] - mesh.zone_corner_begin[z];
    corners += n;
    offsets->SetValue(i + 1, corners);
    // Zones are counter-clockwise, which is VTK's ordering for 2D cells.
    types->SetValue(i, n == 4 ? VTK_QUAD : (n == 3 ? VTK_TRIANGLE : VTK_POLYGON));
  }
  connectivity->SetNumberOfValues(corners);
  vtkIdType k = 0;
  for (Index i = 0; i < nzones; ++i) {
    const Index z = zones ? (*zones)[i] : i;
    for (Index c = mesh.zone_corner_begin[z]; c < mesh.zone_corner_begin[z + 1]; ++c)
      connectivity->SetValue(k++, local ? (*local)[mesh.corner_point[c]] : mesh.corner_point[c]);
  }
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);
  grid->SetCells(types, cells);
  return grid;
}

void add_zone_field(vtkUnstructuredGrid* grid, const char* name, std::span<const double> values) {
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->SetNumberOfComponents(1);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i) array->SetValue(static_cast<vtkIdType>(i), values[i]);
  grid->GetCellData()->AddArray(array);
}

void add_region_field(vtkUnstructuredGrid* grid, const Mesh& mesh) {
  vtkNew<vtkIntArray> region;
  region->SetName("region");
  region->SetNumberOfValues(mesh.num_zones());
  for (Index z = 0; z < mesh.num_zones(); ++z) region->SetValue(z, mesh.zone_region[z]);
  grid->GetCellData()->AddArray(region);
}

/// Writes `grid` to a temporary name beside `path`, then renames it onto `path`.
void write_grid(vtkUnstructuredGrid* grid, const std::string& path) {
  const std::filesystem::path target(path);
  io_detail::require_directory_of(target);
  io_detail::PrivateTemporary scratch(target);
  const std::filesystem::path& temporary = scratch.path();
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetFileName(temporary.string().c_str());
  writer->SetInputData(grid);
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();  // raw binary
  writer->SetCompressorTypeToZLib();
  writer->SetHeaderTypeToUInt64();  // large meshes
  if (writer->Write() != 1 || writer->GetErrorCode() != 0) {
    throw Error("cannot write '" + path +
                "': the VTK writer failed; check that the output directory is writable "
                "and the disk is not full");
  }
  scratch.commit();
}

void add_von_mises(vtkUnstructuredGrid* grid, std::span<const double> sxx, std::span<const double> syy,
                   std::span<const double> sxy) {
  vtkNew<vtkDoubleArray> von_mises;
  von_mises->SetName("von_mises");
  von_mises->SetNumberOfValues(static_cast<vtkIdType>(sxy.size()));
  for (std::size_t z = 0; z < sxy.size(); ++z) {
    // sigma_vm = sqrt(3/2 S:S) with the out-of-plane S_zz = -(S_xx + S_yy) (trace-free S).
    const double szz = -(sxx[z] + syy[z]);
    const double contraction = sxx[z] * sxx[z] + syy[z] * syy[z] + szz * szz + 2.0 * sxy[z] * sxy[z];
    von_mises->SetValue(static_cast<vtkIdType>(z), std::sqrt(1.5 * contraction));
  }
  grid->GetCellData()->AddArray(von_mises);
}

/// The dumped state of `simulation` on a grid: every zone and point (`zones` and `points`
/// null), or the listed ones (a distributed run's piece: its owned zones and their points,
/// `local_point` mapping the part's points to the piece's).
void add_state(vtkUnstructuredGrid* grid, const Simulation& simulation, const std::vector<Index>* zones,
               const std::vector<Index>* points) {
  const Mesh& mesh = simulation.mesh();
  using Role = Simulation::OutputRole;
  const Index nz = zones ? static_cast<Index>(zones->size()) : mesh.num_zones();
  const Index np = points ? static_cast<Index>(points->size()) : mesh.num_points();
  std::vector<double> picked;
  auto zone_values = [&](std::span<const double> values) -> std::span<const double> {
    if (!zones) return values;
    picked.resize(zones->size());
    for (std::size_t i = 0; i < zones->size(); ++i) picked[i] = values[(*zones)[i]];
    return picked;
  };

  // The state table's dumped arrays (Simulation::output_fields): the zone arrays of every
  // run, the region (from the mesh), then those of the material models, the deviatoric
  // stress followed by its von Mises invariant; then the point vectors.
  const auto fields = simulation.output_fields();
  for (const auto& f : fields)
    if (!f.on_points && f.always) add_zone_field(grid, std::string(f.name).c_str(), zone_values(f.values));
  vtkNew<vtkIntArray> region;
  region->SetName("region");
  region->SetNumberOfValues(nz);
  for (Index z = 0; z < nz; ++z) region->SetValue(z, mesh.zone_region[zones ? (*zones)[z] : z]);
  grid->GetCellData()->AddArray(region);
  std::vector<double> sxx, syy;
  for (const auto& f : fields) {
    if (f.on_points || f.always) continue;
    const std::span<const double> values = zone_values(f.values);
    add_zone_field(grid, std::string(f.name).c_str(), values);
    if (f.role == Role::deviator_xx) sxx.assign(values.begin(), values.end());
    if (f.role == Role::deviator_yy) syy.assign(values.begin(), values.end());
    if (f.role == Role::deviator_xy && sxx.size() == values.size() && syy.size() == values.size())
      add_von_mises(grid, sxx, syy, values);
  }
  std::string active_vectors;
  for (const auto& fx : fields) {
    if (!fx.on_points || fx.role != Role::vector_x) continue;
    for (const auto& fy : fields) {
      if (!fy.on_points || fy.role != Role::vector_y || fy.name != fx.name) continue;
      const std::string name(fx.name);
      vtkNew<vtkDoubleArray> vector;
      vector->SetName(name.c_str());
      vector->SetNumberOfComponents(3);
      vector->SetNumberOfTuples(np);
      for (Index p = 0; p < np; ++p) {
        const Index q = points ? (*points)[p] : p;
        vector->SetTuple3(p, fx.values[q], fy.values[q], 0.0);
      }
      grid->GetPointData()->AddArray(vector);
      if (active_vectors.empty()) active_vectors = name;
    }
  }
  if (!active_vectors.empty()) grid->GetPointData()->SetActiveVectors(active_vectors.c_str());

  // ParaView reads the time of a single file from the TimeValue field.
  vtkNew<vtkDoubleArray> time;
  time->SetName("TimeValue");
  time->SetNumberOfValues(1);
  time->SetValue(0, simulation.time());
  grid->GetFieldData()->AddArray(time);
  vtkNew<vtkIntArray> cycle;
  cycle->SetName("cycle");
  cycle->SetNumberOfValues(1);
  cycle->SetValue(0, static_cast<int>(simulation.cycle()));
  grid->GetFieldData()->AddArray(cycle);
  // The rz convention (docs/output.md). Only rz runs carry it, so that planar .vtu files stay
  // byte for byte what they were; no `geometry` field means planar.
  if (simulation.problem().options.geometry == CoordinateSystem::rz) {
    vtkNew<vtkStringArray> geometry;
    geometry->SetName("geometry");
    geometry->InsertNextValue("rz");
    grid->GetFieldData()->AddArray(geometry);
    vtkNew<vtkStringArray> convention;
    convention->SetName("geometry_convention");
    convention->InsertNextValue("x = r, y = z, axis x = 0; masses, volumes, energies and momenta per radian");
    grid->GetFieldData()->AddArray(convention);
  }
}

void add_int_field(vtkDataSetAttributes* data, const char* name, Index count, const std::function<int(Index)>& value) {
  vtkNew<vtkIntArray> array;
  array->SetName(name);
  array->SetNumberOfValues(count);
  for (Index i = 0; i < count; ++i) array->SetValue(i, value(i));
  data->AddArray(array);
}

/// A distributed run's piece (docs/output.md, "Distributed runs"): the zones this rank
/// owns, the points of those zones (some owned by other ranks, so the pieces share their
/// boundary points), the state arrays of write_vtu, then `rank`, and the serial numbers
/// `zone_id` and `point_id`.
vtkNew<vtkUnstructuredGrid> make_piece(const Simulation& part) {
  const Mesh& mesh = part.mesh();
  const auto ghost = part.ghost_zones();
  std::vector<Index> zones, points, local(mesh.num_points(), -1);
  for (Index z = 0; z < mesh.num_zones(); ++z)
    if (ghost.empty() || !ghost[z]) zones.push_back(z);
  for (Index z : zones)
    for (Index c = mesh.zone_corner_begin[z]; c < mesh.zone_corner_begin[z + 1]; ++c) local[mesh.corner_point[c]] = 0;
  for (Index p = 0; p < mesh.num_points(); ++p)
    if (local[p] == 0) local[p] = static_cast<Index>(points.size()), points.push_back(p);

  auto grid = make_grid(mesh, part.x(), part.y(), &zones, &points, &local);
  add_state(grid, part, &zones, &points);
  const auto global_zone = part.global_zones();
  const auto global_point = part.global_points();
  const Index nz = static_cast<Index>(zones.size()), np = static_cast<Index>(points.size());
  const int rank = part.rank();
  add_int_field(grid->GetCellData(), "rank", nz, [&](Index) { return rank; });
  add_int_field(grid->GetCellData(), "zone_id", nz,
                [&](Index i) { return global_zone.empty() ? zones[i] : global_zone[zones[i]]; });
  add_int_field(grid->GetPointData(), "point_id", np,
                [&](Index i) { return global_point.empty() ? points[i] : global_point[points[i]]; });
  return grid;
}

/// The type name of a VTK XML data array.
std::string xml_type(vtkDataArray* array) {
  switch (array->GetDataType()) {
    case VTK_DOUBLE:
      return "Float64";
    case VTK_INT:
      return "Int32";
    default:
      throw Error(std::string("internal: no .pvtu type for the array '") + array->GetName() + "'");
  }
}

}  // namespace

void write_vtu(const std::string& path, const Simulation& simulation) {
  const Mesh& mesh = simulation.mesh();
  auto grid = make_grid(mesh, simulation.x(), simulation.y());
  add_state(grid, simulation, nullptr, nullptr);
  write_grid(grid, path);
}

std::string write_vtu_piece(const std::string& path, const Simulation& part, const std::vector<std::string>& pieces) {
  auto grid = make_piece(part);
  write_grid(grid, path);
  // The .pvtu lists the arrays of the pieces (the same on every rank: the whole problem's
  // configuration) and the piece files.
  std::string text =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      "  <PUnstructuredGrid GhostLevel=\"0\">\n";
  auto arrays = [&](vtkDataSetAttributes* data, const char* tag) {
    text += std::string("    <") + tag;
    if (vtkDataArray* vectors = data->GetVectors()) text += std::string(" Vectors=\"") + vectors->GetName() + "\"";
    text += ">\n";
    for (int i = 0; i < data->GetNumberOfArrays(); ++i) {
      vtkDataArray* array = data->GetArray(i);
      text += "      <PDataArray type=\"" + xml_type(array) + "\" Name=\"" + array->GetName() + "\"";
      if (array->GetNumberOfComponents() != 1)
        text += " NumberOfComponents=\"" + std::to_string(array->GetNumberOfComponents()) + "\"";
      text += "/>\n";
    }
    text += std::string("    </") + tag + ">\n";
  };
  arrays(grid->GetPointData(), "PPointData");
  arrays(grid->GetCellData(), "PCellData");
  text +=
      "    <PPoints>\n"
      "      <PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n"
      "    </PPoints>\n";
  for (const std::string& piece : pieces) text += "    <Piece Source=\"" + io_detail::xml_attribute(piece) + "\"/>\n";
  text += "  </PUnstructuredGrid>\n</VTKFile>\n";
  return text;
}

void write_mesh_vtu(const std::string& path, const Mesh& mesh) {
  auto grid = make_grid(mesh, mesh.x, mesh.y);
  add_region_field(grid, mesh);
  for (const BoundaryTag& tag : mesh.tags) {
    vtkNew<vtkIntArray> marker;
    marker->SetName(("tag_" + tag.name).c_str());
    marker->SetNumberOfValues(mesh.num_points());
    marker->FillValue(0);
    for (const Index p : tag.points) marker->SetValue(p, 1);
    grid->GetPointData()->AddArray(marker);
  }
  write_grid(grid, path);
}

}  // namespace stagger
