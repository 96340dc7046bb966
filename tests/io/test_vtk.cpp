// VTK round trip: what write_vtu / write_mesh_vtu write, VTK's own reader reads back.
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <cmath>

#include "io_test_support.hpp"
#include "stagger/error.hpp"
#include "stagger/output.hpp"
#include "stagger/simulation.hpp"

namespace stagger {
namespace {

using io_test::ScratchDirectory;

vtkSmartPointer<vtkUnstructuredGrid> read_vtu(const std::string& path) {
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkSmartPointer<vtkUnstructuredGrid> grid = reader->GetOutput();
  return grid;
}

void expect_zone_field(vtkUnstructuredGrid* grid, const char* name, std::span<const double> values) {
  vtkDataArray* array = grid->GetCellData()->GetArray(name);
  ASSERT_NE(array, nullptr) << name;
  EXPECT_EQ(array->GetDataType(), VTK_DOUBLE) << name;
  ASSERT_EQ(array->GetNumberOfTuples(), static_cast<vtkIdType>(values.size())) << name;
  for (std::size_t z = 0; z < values.size(); ++z) {
    ASSERT_EQ(array->GetComponent(static_cast<vtkIdType>(z), 0), values[z]) << name << " zone " << z;
  }
}

TEST(VtkOutput, StateRoundTripsThroughVtksReaderBitForBit) {
  ScratchDirectory scratch("vtu_round_trip");
  Simulation simulation(io_test::sod_problem(20, 0.2));
  for (int i = 0; i < 5; ++i) simulation.step();
  const std::string path = scratch.file("state.vtu");
  write_vtu(path, simulation);

  const auto grid = read_vtu(path);
  const Mesh& mesh = simulation.mesh();
  ASSERT_EQ(grid->GetNumberOfPoints(), mesh.num_points());
  ASSERT_EQ(grid->GetNumberOfCells(), mesh.num_zones());
  EXPECT_EQ(grid->GetPoints()->GetDataType(), VTK_DOUBLE);
  for (Index p = 0; p < mesh.num_points(); ++p) {
    double point[3];
    grid->GetPoint(p, point);
    ASSERT_EQ(point[0], simulation.x()[p]);
    ASSERT_EQ(point[1], simulation.y()[p]);
    ASSERT_EQ(point[2], 0.0);
  }
  for (Index z = 0; z < mesh.num_zones(); ++z) {
    ASSERT_EQ(grid->GetCellType(z), VTK_QUAD);
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    grid->GetCellPoints(z, n, ids);
    ASSERT_EQ(n, 4);
    for (vtkIdType k = 0; k < n; ++k) ASSERT_EQ(ids[k], mesh.corner_point[mesh.zone_corner_begin[z] + k]);
  }
  expect_zone_field(grid, "density", simulation.density());
  expect_zone_field(grid, "pressure", simulation.pressure());
  expect_zone_field(grid, "specific_internal_energy", simulation.specific_internal_energy());
  expect_zone_field(grid, "artificial_viscosity", simulation.artificial_viscosity());
  expect_zone_field(grid, "sound_speed", simulation.sound_speed());

  vtkDataArray* region = grid->GetCellData()->GetArray("region");
  ASSERT_NE(region, nullptr);
  EXPECT_EQ(region->GetDataType(), VTK_INT);
  // A gas-only scene writes no strength or burn fields.
  EXPECT_EQ(grid->GetCellData()->GetArray("von_mises"), nullptr);
  EXPECT_EQ(grid->GetCellData()->GetArray("burn_fraction"), nullptr);

  vtkDataArray* velocity = grid->GetPointData()->GetArray("velocity");
  ASSERT_NE(velocity, nullptr);
  ASSERT_EQ(velocity->GetNumberOfComponents(), 3);
  double largest_speed = 0;
  for (Index p = 0; p < mesh.num_points(); ++p) {
    ASSERT_EQ(velocity->GetComponent(p, 0), simulation.velocity_x()[p]);
    ASSERT_EQ(velocity->GetComponent(p, 1), simulation.velocity_y()[p]);
    ASSERT_EQ(velocity->GetComponent(p, 2), 0.0);
    largest_speed = std::max(largest_speed, std::abs(simulation.velocity_x()[p]));
  }
  EXPECT_GT(largest_speed, 0.0) << "after 5 cycles the gas near the diaphragm moves";

  vtkDataArray* time = grid->GetFieldData()->GetArray("TimeValue");
  ASSERT_NE(time, nullptr);
  EXPECT_EQ(time->GetComponent(0, 0), simulation.time());
}

TEST(VtkOutput, StrengthScenesWriteDeviatoricStressAndVonMises) {
  ScratchDirectory scratch("vtu_strength");
  Problem problem = io_test::sod_problem(6, 1e-3);
  problem.materials[0].name = "metal";
  problem.materials[0].eos = MieGruneisen{8930.0, 3940.0, 2.0, 1.49};
  problem.materials[0].strength = Strength{4.5e10, 9.0e7};
  problem.regions[0].material = "metal";
  problem.regions[0].density = constant_field(8930.0);
  problem.regions[0].pressure = constant_field(1e5);
  problem.regions[0].stress_xx = [](double x, double) { return 1e7 * (1 + x); };
  problem.regions[0].stress_yy = constant_field(-3e6);
  problem.regions[0].stress_xy = constant_field(2e6);
  Simulation simulation(std::move(problem));
  ASSERT_TRUE(simulation.has_strength());
  const std::string path = scratch.file("strength.vtu");
  write_vtu(path, simulation);

  const auto grid = read_vtu(path);
  expect_zone_field(grid, "deviatoric_stress_xx", simulation.stress_xx());
  expect_zone_field(grid, "deviatoric_stress_yy", simulation.stress_yy());
  expect_zone_field(grid, "deviatoric_stress_xy", simulation.stress_xy());
  expect_zone_field(grid, "plastic_strain", simulation.plastic_strain());
  vtkDataArray* von_mises = grid->GetCellData()->GetArray("von_mises");
  ASSERT_NE(von_mises, nullptr);
  for (Index z = 0; z < simulation.mesh().num_zones(); ++z) {
    const double sxx = simulation.stress_xx()[z], syy = simulation.stress_yy()[z], sxy = simulation.stress_xy()[z];
    const double szz = -(sxx + syy);
    // sqrt(3/2 S:S), out-of-plane S_zz included.
    const double expected = std::sqrt(1.5 * (sxx * sxx + syy * syy + szz * szz + 2 * sxy * sxy));
    EXPECT_NEAR(von_mises->GetComponent(z, 0), expected, 1e-12 * expected) << "zone " << z;
    EXPECT_GT(expected, 1e6);
  }
}

// The rz convention is written into the .vtu's field data and summary.json (docs/output.md);
// planar outputs carry neither key (they stay byte for byte what they were).
TEST(VtkOutput, RzRunsRecordTheirConventionInTheVtuAndTheSummaryPlanarRunsDoNot) {
  ScratchDirectory scratch("vtu_rz");
  for (const CoordinateSystem geometry : {CoordinateSystem::planar, CoordinateSystem::rz}) {
    Problem problem = io_test::sod_problem(6, 1e-3);
    problem.options.geometry = geometry;
    Simulation simulation(std::move(problem));
    simulation.step();
    const bool rz = geometry == CoordinateSystem::rz;
    const std::string vtu = scratch.file(rz ? "rz.vtu" : "planar.vtu");
    write_vtu(vtu, simulation);
    const auto grid = read_vtu(vtu);
    auto* name = vtkStringArray::SafeDownCast(grid->GetFieldData()->GetAbstractArray("geometry"));
    auto* convention = vtkStringArray::SafeDownCast(grid->GetFieldData()->GetAbstractArray("geometry_convention"));
    ASSERT_NE(grid->GetFieldData()->GetArray("TimeValue"), nullptr);
    const std::string summary_path = scratch.file(rz ? "rz.json" : "planar.json");
    RunSummary summary;
    summary.status = "completed";
    write_summary(summary_path, simulation, summary);
    const io_test::Json json = io_test::parse_json_file(summary_path);
    if (!rz) {
      EXPECT_EQ(name, nullptr);
      EXPECT_EQ(convention, nullptr);
      EXPECT_FALSE(json.has("geometry"));
      EXPECT_FALSE(json.has("geometry_convention"));
      continue;
    }
    ASSERT_NE(name, nullptr);
    ASSERT_EQ(name->GetNumberOfValues(), 1);
    EXPECT_EQ(name->GetValue(0), "rz");
    ASSERT_NE(convention, nullptr);
    EXPECT_NE(convention->GetValue(0).find("per radian"), std::string::npos);
    EXPECT_NE(convention->GetValue(0).find("x = r, y = z"), std::string::npos);
    ASSERT_TRUE(json.has("geometry"));
    EXPECT_EQ(json["geometry"].text, "rz");
    EXPECT_EQ(json["geometry_convention"].text, convention->GetValue(0));
  }
}

TEST(VtkOutput, MixedMeshKeepsTrianglesQuadsAndPolygonsAndTagMarkers) {
  ScratchDirectory scratch("vtu_mixed");
  PolygonSoup soup;
  soup.x = {0, 1, 1, 0, 0.5, 2, 2.5, 2};
  soup.y = {0, 0, 1, 1, 2, 0, 0.5, 1};
  soup.region_names = {"left", "right"};
  soup.add_polygon({0, 1, 2, 3}, 0);     // quad
  soup.add_polygon({3, 2, 4}, 0);        // triangle
  soup.add_polygon({1, 5, 6, 7, 2}, 1);  // pentagon
  soup.tag_names = {"bottom"};
  soup.tagged_edges = {{0, 1, 0}, {1, 5, 0}};
  const Mesh mesh = build_mesh(soup);
  const std::string path = scratch.file("mesh.vtu");
  write_mesh_vtu(path, mesh);

  const auto grid = read_vtu(path);
  ASSERT_EQ(grid->GetNumberOfCells(), 3);
  ASSERT_EQ(grid->GetNumberOfPoints(), 8);
  EXPECT_EQ(grid->GetPoints()->GetDataType(), VTK_DOUBLE);
  vtkDataArray* region = grid->GetCellData()->GetArray("region");
  ASSERT_NE(region, nullptr);
  int triangles = 0, quads = 0, polygons = 0;
  for (Index z = 0; z < 3; ++z) {
    const Index n = mesh.zone_corner_begin[z + 1] - mesh.zone_corner_begin[z];
    const int type = grid->GetCellType(z);
    EXPECT_EQ(type, n == 3 ? VTK_TRIANGLE : n == 4 ? VTK_QUAD : VTK_POLYGON);
    triangles += type == VTK_TRIANGLE;
    quads += type == VTK_QUAD;
    polygons += type == VTK_POLYGON;
    EXPECT_EQ(region->GetComponent(z, 0), mesh.zone_region[z]);
  }
  EXPECT_EQ(triangles, 1);
  EXPECT_EQ(quads, 1);
  EXPECT_EQ(polygons, 1);

  vtkDataArray* bottom = grid->GetPointData()->GetArray("tag_bottom");
  ASSERT_NE(bottom, nullptr);
  int marked = 0;
  for (Index p = 0; p < mesh.num_points(); ++p) {
    const bool on_bottom = mesh.y[p] == 0.0;
    EXPECT_EQ(bottom->GetComponent(p, 0), on_bottom ? 1.0 : 0.0) << "point " << p;
    marked += on_bottom;
  }
  EXPECT_EQ(marked, 3);
}

TEST(VtkOutput, MissingDirectoryIsAnErrorNamingThePath) {
  ScratchDirectory scratch("vtu_missing_dir");
  Simulation simulation(io_test::sod_problem(4, 0.1));
  const std::string path = scratch.file("no_such_dir/state.vtu");
  try {
    write_vtu(path, simulation);
    FAIL() << "expected stagger::Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
  }
  EXPECT_TRUE(io_test::temporary_files(scratch.path()).empty());
}

}  // namespace
}  // namespace stagger
