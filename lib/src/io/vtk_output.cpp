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
    throw Error("cannot write '" + path + "': the VTK writer failed; check that the output directory is writable "
                "and the disk is not full");
  }
  io_detail::replace_file(temporary, target);
}

}  // namespace

void write_vtu(const std::string& path, const Simulation& simulation) {
  const Mesh& mesh = simulation.mesh();
  auto grid = make_grid(mesh, simulation.x(), simulation.y());
  const auto nzones = static_cast<std::size_t>(mesh.num_zones());

  add_zone_field(grid, "density", simulation.density());
  add_zone_field(grid, "pressure", simulation.pressure());
  add_zone_field(grid, "specific_internal_energy", simulation.specific_internal_energy());
  add_zone_field(grid, "artificial_viscosity", simulation.artificial_viscosity());
  add_zone_field(grid, "sound_speed", simulation.sound_speed());
  add_region_field(grid, mesh);

  if (simulation.has_strength()) {
    const auto sxx = simulation.stress_xx();
    const auto syy = simulation.stress_yy();
    const auto sxy = simulation.stress_xy();
    if (sxx.size() == nzones && syy.size() == nzones && sxy.size() == nzones) {
      add_zone_field(grid, "deviatoric_stress_xx", sxx);
      add_zone_field(grid, "deviatoric_stress_yy", syy);
      add_zone_field(grid, "deviatoric_stress_xy", sxy);
      vtkNew<vtkDoubleArray> von_mises;
      von_mises->SetName("von_mises");
      von_mises->SetNumberOfValues(static_cast<vtkIdType>(nzones));
      for (std::size_t z = 0; z < nzones; ++z) {
        // sigma_vm = sqrt(3/2 S:S) with the out-of-plane S_zz = -(S_xx + S_yy) (trace-free S).
        const double szz = -(sxx[z] + syy[z]);
        const double contraction = sxx[z] * sxx[z] + syy[z] * syy[z] + szz * szz + 2.0 * sxy[z] * sxy[z];
        von_mises->SetValue(static_cast<vtkIdType>(z), std::sqrt(1.5 * contraction));
      }
      grid->GetCellData()->AddArray(von_mises);
    }
    const auto plastic = simulation.plastic_strain();
    if (plastic.size() == nzones) add_zone_field(grid, "plastic_strain", plastic);
  }
  if (simulation.has_burn()) {
    const auto burn = simulation.burn_fraction();
    if (burn.size() == nzones) add_zone_field(grid, "burn_fraction", burn);
  }

  const auto vx = simulation.velocity_x();
  const auto vy = simulation.velocity_y();
  vtkNew<vtkDoubleArray> velocity;
  velocity->SetName("velocity");
  velocity->SetNumberOfComponents(3);
  velocity->SetNumberOfTuples(mesh.num_points());
  for (Index p = 0; p < mesh.num_points(); ++p) velocity->SetTuple3(p, vx[p], vy[p], 0.0);
  grid->GetPointData()->AddArray(velocity);
  grid->GetPointData()->SetActiveVectors("velocity");

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
