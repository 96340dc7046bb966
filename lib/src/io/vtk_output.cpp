// VTK .vtu output (the only translation units that include VTK are in lib/src/io).
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
#include <span>
#include <string>

#include "io/atomic_file.hpp"
#include "stagger/error.hpp"
#include "stagger/output.hpp"
#include "stagger/simulation.hpp"

namespace stagger {

namespace {

/// Points (double precision, z = 0) and cells (quads, triangles, polygons) of the mesh
/// with the given point positions.
vtkNew<vtkUnstructuredGrid> make_grid(const Mesh& mesh, std::span<const double> x, std::span<const double> y) {
  vtkNew<vtkUnstructuredGrid> grid;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  const Index npoints = mesh.num_points();
  points->SetNumberOfPoints(npoints);
  for (Index p = 0; p < npoints; ++p) points->SetPoint(p, x[p], y[p], 0.0);
  grid->SetPoints(points);

  const Index nzones = mesh.num_zones();
  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfValues(nzones + 1);
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfValues(mesh.num_corners());
  vtkNew<vtkUnsignedCharArray> types;
  types->SetNumberOfValues(nzones);
  for (Index z = 0; z <= nzones; ++z) offsets->SetValue(z, mesh.zone_corner_begin[z]);
  for (Index c = 0; c < mesh.num_corners(); ++c) connectivity->SetValue(c, mesh.corner_point[c]);
  for (Index z = 0; z < nzones; ++z) {
    const Index n = mesh.zone_corner_begin[z + 1] - mesh.zone_corner_begin[z];
    // Zones are counter-clockwise, which is VTK's ordering for 2D cells.
    types->SetValue(z, n == 4 ? VTK_QUAD : (n == 3 ? VTK_TRIANGLE : VTK_POLYGON));
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
  const std::filesystem::path temporary = io_detail::temporary_path(target);
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetFileName(temporary.string().c_str());
  writer->SetInputData(grid);
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();  // raw binary
  writer->SetCompressorTypeToZLib();
  writer->SetHeaderTypeToUInt64();  // large meshes
  if (writer->Write() != 1 || writer->GetErrorCode() != 0) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw Error("cannot write '" + path +
                "': the VTK writer failed; check that the output directory is writable "
                "and the disk is not full");
  }
  io_detail::replace_file(temporary, target);
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

}  // namespace

void write_vtu(const std::string& path, const Simulation& simulation) {
  const Mesh& mesh = simulation.mesh();
  auto grid = make_grid(mesh, simulation.x(), simulation.y());
  using Role = Simulation::OutputRole;

  // The state table's dumped arrays (Simulation::output_fields): the zone arrays of every
  // run, the region (from the mesh), then those of the material models, the deviatoric
  // stress followed by its von Mises invariant; then the point vectors.
  const auto fields = simulation.output_fields();
  for (const auto& f : fields)
    if (!f.on_points && f.always) add_zone_field(grid, std::string(f.name).c_str(), f.values);
  add_region_field(grid, mesh);
  std::span<const double> sxx, syy;
  for (const auto& f : fields) {
    if (f.on_points || f.always) continue;
    add_zone_field(grid, std::string(f.name).c_str(), f.values);
    if (f.role == Role::deviator_xx) sxx = f.values;
    if (f.role == Role::deviator_yy) syy = f.values;
    if (f.role == Role::deviator_xy && sxx.size() == f.values.size() && syy.size() == f.values.size())
      add_von_mises(grid, sxx, syy, f.values);
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
      vector->SetNumberOfTuples(mesh.num_points());
      for (Index p = 0; p < mesh.num_points(); ++p) vector->SetTuple3(p, fx.values[p], fy.values[p], 0.0);
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

  write_grid(grid, path);
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
