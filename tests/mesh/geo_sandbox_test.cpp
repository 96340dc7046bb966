// gmsh in a child process (limits, command scan, sandbox, OpenMP left alone) and honest mesh
// import (planarity, unassigned elements, partition interfaces, subdivision, overlaps).
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "mesh_checks.hpp"
#include "stagger/meshgen.hpp"
#include "stagger/scene.hpp"
#include "support/files.hpp"
#include "support/scene_toml.hpp"
#include "support/scratch_directory.hpp"
#include "support/stagger_binary.hpp"

namespace stagger {
namespace {

namespace fs = std::filesystem;
using testing::expect_consistent;
using testing::expect_error;
namespace toml = testing::toml;

const char* const kSquare = R"(Point(1) = {0, 0, 0, 0.25}; Point(2) = {1, 0, 0, 0.25};
Point(3) = {1, 1, 0, 0.25}; Point(4) = {0, 1, 0, 0.25};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Physical Surface("domain") = {1}; Physical Curve("wall") = {1, 2, 3, 4};
)";

class GeoSandbox : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& text) const { return scratch_.write(name, text); }
  // Under the build tree, one directory per test: parallel sessions never share it.
  const testing::ScratchDirectory scratch_{fs::path(STAGGER_BINARY_DIR) / "test_geo_sandbox" /
                                           testing::current_test_name()};
  const fs::path directory_ = scratch_.path();
};

// Whether gmsh's library is mapped into this process.
bool gmsh_mapped() {
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line))
    if (line.find("libgmsh") != std::string::npos) return true;
  return false;
}

// gmsh is loaded by the child that meshes, never by the process that asks (docs/mesh.md,
// "gmsh in a child process"): about 35 MiB of every process's resident set, and of every
// rank's in a distributed run (docs/parallel.md, "Memory").
TEST_F(GeoSandbox, OnlyTheChildLoadsGmsh) {
  ASSERT_FALSE(gmsh_mapped()) << "the test binary itself maps gmsh: a library links it";
  const std::string geo = write("square.geo", kSquare);
  EXPECT_EQ(build_mesh(meshgen::read_geo(geo)).num_zones(), 21);
  EXPECT_FALSE(gmsh_mapped());
}

// --- The command scan -------------------------------------------------------------------

TEST_F(GeoSandbox, ScanFindsCommandsAndNamesFileAndLine) {
  const std::string square = write("square.geo", kSquare);
  EXPECT_EQ(meshgen::find_outside_command(square), "");
  const std::string system = write("system.geo", "Include \"square.geo\";\n\nSystemCall \"touch x\";\n");
  EXPECT_EQ(meshgen::find_outside_command(system), system + ":3: 'SystemCall' runs a shell command");
  // Comments, strings and option names are not commands; Printf without '>' is harmless.
  const std::string harmless = write("harmless.geo", std::string(kSquare) +
                                                         "// SystemCall \"x\";\n/* Exit; \n Sleep 3; */\n"
                                                         "s = \"Exit; SystemCall\"; t = 'Merge \"a\"';\n"
                                                         "Print.Width = 100; Printf(\"%g\", 2);\nExits = 1;\n");
  EXPECT_EQ(meshgen::find_outside_command(harmless), "");
  // ... but a command in an included file is found, with that file's line.
  write("sub/inner.geo", "a = 1;\nSleep 100;\n");
  const std::string outer = write("outer.geo", "Include \"sub/inner.geo\";\n");
  EXPECT_EQ(meshgen::find_outside_command(outer), (directory_ / "sub/inner.geo").string() + ":2: 'Sleep' pauses gmsh");
  // Merge of a CAD or mesh file is allowed; a merged .geo is scanned like an Include.
  EXPECT_EQ(meshgen::find_outside_command(write("cad.geo", "Merge \"part.STEP\";\nMerge 'sub/mesh.msh';\n")), "");
  EXPECT_EQ(meshgen::find_outside_command(write("merge_geo.geo", "Merge \"sub/inner.geo\";\n")),
            (directory_ / "sub/inner.geo").string() + ":2: 'Sleep' pauses gmsh");
  // A number glued to a keyword is still the keyword (gmsh's lexer: "2" then "Exit").
  EXPECT_NE(meshgen::find_outside_command(write("glued.geo", "x = 2;2Exit;\n")).find(":1: 'Exit' ends the process"),
            std::string::npos);
  for (const std::string command :
       {"Printf(\"a\") >> \"f.txt\";", "Save \"out.msh\";", "Merge \"a.py\";", "Merge StrCat(\"a\", \".step\");",
        "Plugin(Smooth).Run;", "OnelabRun(\"client\");", "CreateDir \"d\";", "System \"ls\";",
        "NonBlockingSystemCall \"ls\";", "Include StrCat(\"a\", \".geo\");"})
    EXPECT_NE(meshgen::find_outside_command(write("c.geo", std::string(kSquare) + command + "\n")), "") << command;
}

TEST_F(GeoSandbox, RefusedCommandIsOneLocatedErrorAndRunsNothing) {
  write("square.geo", kSquare);
  const std::string geo =
      write("touch.geo", "Include \"square.geo\";\nSystemCall \"touch " + (directory_ / "ran").string() + "\";\n");
  expect_error([&] { meshgen::read_geo(geo); },
               {geo + ":2: 'SystemCall' runs a shell command", "mesh.allow_geo_commands = true", "arbitrary code"});
  EXPECT_FALSE(fs::exists(directory_ / "ran"));
  // Allowed, it runs (the option is documented as running arbitrary code).
  meshgen::GeoOptions options;
  options.allow_commands = true;
  EXPECT_EQ(build_mesh(meshgen::read_geo(geo, options)).num_zones(), 21);
  EXPECT_TRUE(fs::exists(directory_ / "ran"));
}

TEST_F(GeoSandbox, SandboxStopsWhatTheScanMisses) {
  // Second line of defence: with the scan off (a test hook), the child's seccomp filter
  // still refuses to start a shell or to create a file.
  write("square.geo", kSquare);
  const std::string shell =
      write("shell.geo", "Include \"square.geo\";\nSystemCall \"touch " + (directory_ / "ran").string() + "\";\n");
  const std::string printf = write(
      "printf.geo", "Include \"square.geo\";\nPrintf(\"x\") > \"" + (directory_ / "written.txt").string() + "\";\n");
  ::setenv("STAGGER_GEO_SCAN", "0", 1);
  expect_error([&] { meshgen::read_geo(shell); }, {"shell.geo", "system call"});
  expect_error([&] { meshgen::read_geo(printf); }, {"printf.geo", "line 2", "Unable to open file"});
  ::unsetenv("STAGGER_GEO_SCAN");
  EXPECT_FALSE(fs::exists(directory_ / "ran"));
  EXPECT_FALSE(fs::exists(directory_ / "written.txt"));
}

// --- Limits and crashes -----------------------------------------------------------------

TEST_F(GeoSandbox, EndlessLoopIsStoppedByTheTimeLimit) {
  write("square.geo", kSquare);
  const std::string geo = write("loop.geo", "Include \"square.geo\";\nFor i In {1:1e9}\n  a = i;\nEndFor\n");
  meshgen::GeoOptions options;
  options.time_limit_seconds = 1;
  const auto start = std::chrono::steady_clock::now();
  expect_error([&] { meshgen::read_geo(geo, options); },
               {"gmsh did not finish meshing " + geo + " within 1 s", "mesh.gmsh_time_limit"});
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
}

TEST_F(GeoSandbox, RunningOutOfMemoryIsAnError) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "no address-space limit under AddressSanitizer (its shadow memory)";
#endif
  // A limit just above what the (forked) process already maps: the fine mesh exceeds it.
  std::ifstream status("/proc/self/status");
  double vm_kib = 0;
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmSize:", 0) == 0) vm_kib = std::stod(line.substr(7));
  ASSERT_GT(vm_kib, 0);
  write("square.geo", kSquare);
  // A list of 3e8 numbers (2.4 GB): gmsh grows it with realloc, which it does not check, so
  // running out ends in a segfault that the error still calls by its name.
  const std::string geo = write("big_list.geo", "Include \"square.geo\";\na[] = {1:3e8};\n");
  meshgen::GeoOptions options;
  options.memory_limit_mib = vm_kib / 1024 + 256;
  expect_error([&] { meshgen::read_geo(geo, options); },
               {"meshing " + geo, "ran out of memory", "mesh.gmsh_memory_limit"});
  // Where the allocation is checked (operator new), the child says so itself.
  const std::string fine = write("fine.geo", "Include \"square.geo\";\nMesh.CharacteristicLengthMax = 3e-4;\n");
  options.memory_limit_mib = vm_kib / 1024 + 32;
  expect_error([&] { meshgen::read_geo(fine, options); },
               {"meshing " + fine, "ran out of memory", "mesh.gmsh_memory_limit"});
}

TEST_F(GeoSandbox, GmshCrashAndExitAreErrorsNamingTheFile) {
  const std::string crash = write("crash.geo", std::string(kSquare) + "MeshAlgorithm Surface{1} = 8;\n");
  expect_error([&] { meshgen::read_geo(crash); }, {"gmsh crashed (signal", "meshing " + crash, "= 8"});
  const std::string exit = write("exit.geo", std::string(kSquare) + "Exit;\n");
  meshgen::GeoOptions options;
  options.allow_commands = true;
  expect_error([&] { meshgen::read_geo(exit, options); }, {"gmsh ended before it finished meshing " + exit, "Exit"});
}

TEST_F(GeoSandbox, ControlCharactersInGmshMessagesAreEscaped) {
  // Found by scripts/fuzz_geo.py: gmsh quotes the bad token, here a vertical tab.
  const std::string geo = write("vtab.geo", "Point(1) = {0, 0, 0, 0.1};\nPoint(2) = {1, 0, 0, 0.1} \v;\n");
  try {
    meshgen::read_geo(geo);
    ADD_FAILURE() << "expected stagger::Error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("line 2"), std::string::npos) << what;
    EXPECT_NE(what.find("\\x0b"), std::string::npos) << what;
    for (const char ch : what) EXPECT_GE(static_cast<unsigned char>(ch), 0x20) << what;
  }
}

TEST_F(GeoSandbox, MeshingLeavesOpenMpAsTheUserSetIt) {
  const std::string geo = write("square.geo", kSquare);
  const int before = omp_get_max_threads();
  omp_set_num_threads(2);
  EXPECT_EQ(build_mesh(meshgen::read_geo(geo)).num_zones(), 21);
  EXPECT_EQ(omp_get_max_threads(), 2);
  // In-process (the debugging switch) the session restores it too.
  ::setenv("STAGGER_GMSH_IN_PROCESS", "1", 1);
  EXPECT_EQ(build_mesh(meshgen::read_geo(geo)).num_zones(), 21);
  ::unsetenv("STAGGER_GMSH_IN_PROCESS");
  EXPECT_EQ(omp_get_max_threads(), 2);
  omp_set_num_threads(before);
}

TEST_F(GeoSandbox, ThreadsTwoOnAGeoSceneRunsOnTwoThreads) {
  // The real command line: `stagger run --threads 2` on a .geo scene reports 2 threads.
  write("square.geo", kSquare);
  const std::string scene =
      write("scene.toml", toml::time("0.001") + "[mesh]\nfile = \"square.geo\"\n" + toml::ideal_gas() +
                              toml::gas_region() + toml::walls(R"(["wall"])"));
  const fs::path out = directory_ / "out";
  const std::string command = testing::stagger_binary() + " run " + scene + " --threads 2 --quiet --out " +
                              out.string() + " >" + (directory_ / "log.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const std::string text = testing::read_text(out / "summary.json");
  EXPECT_NE(text.find("\"threads\": 2"), std::string::npos) << text;
}

// --- The parameter wrapper --------------------------------------------------------------

TEST_F(GeoSandbox, ParametersWorkForPathsWithQuotes) {
  const std::string text = R"(DefineConstant[ h = 0.25 ];
Point(1) = {0, 0, 0, h}; Point(2) = {1, 0, 0, h}; Point(3) = {1, 1, 0, h}; Point(4) = {0, 1, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Physical Surface("domain") = {1}; Physical Curve("wall") = {1, 2, 3, 4};
)";
  meshgen::GeoOptions options;
  options.parameters = {{"h", 0.5}};
  const std::string quoted = write("a \"quoted\" dir/square.geo", text);
  EXPECT_EQ(build_mesh(meshgen::read_geo(quoted, options)).num_zones(), 6);
  const std::string single = write("it's/square.geo", text);
  EXPECT_EQ(build_mesh(meshgen::read_geo(single, options)).num_zones(), 6);
  const std::string both = write("it's \"both\"/square.geo", text);
  expect_error([&] { meshgen::read_geo(both, options); }, {"contains both \" and ' quotes", "rename"});
}

// --- Mesh import tells the truth --------------------------------------------------------

TEST_F(GeoSandbox, NonPlanarAnd3dMeshesSaySo) {
  const std::string tilted = write("tilted.geo", R"(Point(1) = {0, 0, 0, 0.5}; Point(2) = {1, 0, 0, 0.5};
Point(3) = {1, 1, 1, 0.5}; Point(4) = {0, 1, 1, 0.5};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
)");
  expect_error([&] { meshgen::read_geo(tilted); }, {tilted, "not flat in the x-y plane: z varies from 0 to 1"});
  const std::string yz = write("yz.geo", R"(Point(1) = {2, 0, 0, 0.5}; Point(2) = {2, 1, 0, 0.5};
Point(3) = {2, 1, 1, 0.5}; Point(4) = {2, 0, 1, 0.5};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
)");
  expect_error([&] { meshgen::read_geo(yz); }, {yz, "lies in the y-z plane (x = 2 everywhere"});
  // A plane z = const other than 0 is fine.
  const std::string raised = write("raised.geo", R"(Point(1) = {0, 0, 3, 0.5}; Point(2) = {1, 0, 3, 0.5};
Point(3) = {1, 1, 3, 0.5}; Point(4) = {0, 1, 3, 0.5};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
)");
  EXPECT_GT(build_mesh(meshgen::read_geo(raised)).num_zones(), 0);
  // A .msh with a tetrahedron.
  const std::string tet = write("tet.msh", R"($MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
4
1 0 0 0
2 1 0 0
3 0 1 0
4 0 0 1
$EndNodes
$Elements
2
1 2 2 1 1 1 2 3
2 4 2 2 2 1 2 3 4
$EndElements
)");
  expect_error([&] { meshgen::read_msh(tet); }, {tet, "a 3D model", "1 volume elements", "stagger is 2D"});
}

TEST_F(GeoSandbox, UnassignedElementsGetANoteAndAreAnErrorUnderQuadsOnly) {
  const std::string geo = write("two.geo", R"(Point(1) = {0, 0, 0, 0.5}; Point(2) = {1, 0, 0, 0.5};
Point(3) = {1, 1, 0, 0.5}; Point(4) = {0, 1, 0, 0.5}; Point(5) = {2, 0, 0, 0.5}; Point(6) = {2, 1, 0, 0.5};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {2, 5}; Line(6) = {5, 6}; Line(7) = {6, 3};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, -2}; Plane Surface(2) = {2};
Transfinite Surface{1, 2}; Transfinite Curve{1:7} = 3;
Physical Surface("left") = {1};
)");
  const PolygonSoup soup = meshgen::read_geo(geo);
  EXPECT_EQ(soup.unassigned_elements, 4);
  MeshBuildReport report;
  EXPECT_EQ(build_mesh(soup, {}, &report).num_zones(), 4);
  ASSERT_FALSE(report.notes.empty());
  EXPECT_NE(report.notes.front().find("4 of 8 2D elements belong to no physical surface"), std::string::npos);
  MeshBuildOptions quads_only;
  quads_only.quads_only = true;
  expect_error([&] { build_mesh(soup, quads_only); }, {"quads only: 4 2D elements", "no physical surface"});
}

TEST_F(GeoSandbox, TrianglesOnlyMshSubdividesIntoQuads) {
  // Two triangles making the unit square, a tag on the bottom edge.
  const std::string msh = write("triangles.msh", R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
2
1 1 "bottom"
2 2 "domain"
$EndPhysicalNames
$Nodes
4
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
$EndNodes
$Elements
3
1 2 2 2 1 1 2 3
2 2 2 2 1 1 3 4
3 1 2 1 1 1 2
$EndElements
)");
  const Mesh m = build_mesh(meshgen::read_msh(msh, meshgen::TrianglePolicy::subdivide));
  expect_consistent(m);
  EXPECT_EQ(m.num_zones(), 6);  // 3 quads per triangle
  EXPECT_TRUE(m.all_quads());
  EXPECT_EQ(m.num_points(), 4 + 5 + 2);  // corners, edge midpoints, centroids
  EXPECT_NEAR(testing::total_area(m), 1.0, 1e-15);
  const BoundaryTag& bottom = m.tags.at(static_cast<std::size_t>(m.tag_index("bottom")));
  EXPECT_EQ(bottom.edges.size(), 2U);
  for (Index p : bottom.points) EXPECT_EQ(m.y[p], 0.0);
}

TEST_F(GeoSandbox, PartitionInterfacesAreNoTags) {
  // `gmsh -2 -part 2` of a square (lc 0.5): the curve between the two partitions carries
  // an unnamed physical curve (tag 1), which read as a tag "curve_1".
  const std::string msh = std::string(STAGGER_SOURCE_DIR) + "/tests/mesh/data/partitioned_square.msh";
  MeshBuildReport report;
  const Mesh m = build_mesh(meshgen::read_msh(msh), {}, &report);
  EXPECT_EQ(m.num_zones(), 14);
  EXPECT_EQ(m.tag_index("curve_1"), -1) << "the partition interface became a tag";
  ASSERT_GE(m.tag_index("wall"), 0);
  EXPECT_EQ(m.tags.at(static_cast<std::size_t>(m.tag_index("wall"))).edges.size(), 8U);
  bool noted = false;
  for (const auto& note : report.notes) noted = noted || note.find("partition interface") != std::string::npos;
  EXPECT_TRUE(noted);
}

// --- Overlapping zones ------------------------------------------------------------------

PolygonSoup squares(const std::vector<std::array<double, 3>>& boxes) {  // x0, y0, side
  PolygonSoup soup;
  for (const auto& [x0, y0, side] : boxes) {
    const auto base = static_cast<std::int64_t>(soup.x.size());
    soup.x.insert(soup.x.end(), {x0, x0 + side, x0 + side, x0});
    soup.y.insert(soup.y.end(), {y0, y0, y0 + side, y0 + side});
    soup.add_polygon({base, base + 1, base + 2, base + 3}, 0);
  }
  return soup;
}

TEST(Overlaps, SeparatePiecesOnTopOfEachOtherAreRejected) {
  for (const bool topology : {true, false}) {
    MeshBuildOptions options;
    options.check_topology = topology;
    expect_error([&] { build_mesh(squares({{0, 0, 1}, {0.5, 0.5, 1}}), options); }, {"zones overlap", "crosses"});
    expect_error(
        [&] {
          build_mesh(squares({{0, 0, 3}, {1, 1, 1}}), options);
        },
        {"zones overlap", "lies inside zone 0"});
    // A corner on another zone's edge: the zones do not connect (a hanging node).
    expect_error(
        [&] {
          build_mesh(squares({{0, 0, 1}, {1, 0.5, 1}}), options);
        },
        {"lies on edge", "not a corner of that zone"});
    // Apart, or sharing an edge properly, is fine.
    EXPECT_EQ(build_mesh(squares({{0, 0, 1}, {2, 0, 1}}), options).num_zones(), 2);
  }
  EXPECT_EQ(build_mesh(meshgen::rectangle(0, 1, 0, 1, 7, 5)).num_zones(), 35);
}

TEST(Overlaps, AStripWoundOneAndAHalfTimesIsRejected) {
  // All zones turn the same way (no fold a zone's orientation shows), yet they overlap.
  PolygonSoup soup = meshgen::rectangle(0, 1, 0, 1, 24, 2);
  for (std::size_t p = 0; p < soup.x.size(); ++p) {
    const double angle = 3 * std::numbers::pi * soup.x[p], radius = 1 + 0.3 * soup.y[p] + 0.1 * soup.x[p];
    soup.x[p] = radius * std::cos(angle);
    soup.y[p] = radius * std::sin(angle);
  }
  for (const bool topology : {true, false}) {
    MeshBuildOptions options;
    options.check_topology = topology;
    expect_error([&] { build_mesh(soup, options); }, {"zones overlap"});
  }
}

TEST(Overlaps, ATransformThatFoldsAGeneratedMeshIsAnError) {
  // Generated meshes skipped the topology check: the folded half was "repaired" by
  // reorienting it, leaving overlapping zones.
  const fs::path dir = fs::path(STAGGER_BINARY_DIR) / "test_geo_sandbox" / "fold";
  fs::create_directories(dir);
  // Line 9: the transform.
  testing::write_text(dir / "fold.toml", toml::time("0.01") + toml::rectangle("[0, 1]", "[0, 1]", 4, 2) +
                                             "transform.x = \"x > 0.6 ? 1.2 - x : x\"\n" + toml::ideal_gas() +
                                             toml::gas_region() + toml::walls());
  expect_error([&] { load_scene((dir / "fold.toml").string()); },
               {"fold.toml:9: key 'mesh.transform'", "inverted", "folds"});
  // Without the check the trusted path still refuses a partial reversal.
  PolygonSoup soup = meshgen::rectangle(0, 1, 0, 1, 4, 2);
  for (double& x : soup.x) x = x > 0.6 ? 1.2 - x : x;
  MeshBuildOptions trusted;
  trusted.check_topology = false;
  expect_error([&] { build_mesh(soup, trusted); }, {"inverted relative to the other zones", "folds"});
  fs::remove_all(dir);
}

}  // namespace
}  // namespace stagger
