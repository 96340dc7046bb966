// `cmake --install` into a temporary prefix, then apps/examples/embed configured and built
// against it with find_package(Stagger), run, and its output checked (docs/api.md).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "support/files.hpp"

namespace {

namespace fs = std::filesystem;

std::string quote(const fs::path& path) {
  std::string quoted(1, '\'');  // (appending, not operator+: GCC 12 -Wrestrict false positive)
  quoted += path.string();
  quoted += '\'';
  return quoted;
}

using stagger::testing::read_text;

// Runs `command` with stdout and stderr going to `log`; returns the exit status.
int run(const std::string& command, const fs::path& log) {
  const int status = std::system((command + " > " + quote(log) + " 2>&1").c_str());
  return status;
}

#define ASSERT_RUNS(command, log) \
  ASSERT_EQ(run(command, log), 0) << "command failed: " << (command) << "\n" << read_text(log)

// Parses "name value" lines.
std::map<std::string, std::string> key_values(const std::string& text) {
  std::map<std::string, std::string> values;
  std::istringstream lines(text);
  std::string key, value;
  while (lines >> key && std::getline(lines >> std::ws, value)) values[key] = value;
  return values;
}

class Install : public ::testing::Test {
 protected:
  void SetUp() override {
    if (STAGGER_SANITIZED) GTEST_SKIP() << "sanitizer build: the example would need the sanitizer flags too";
    // One directory per test: ctest runs the tests of this file in parallel.
    root_ =
        fs::path(STAGGER_BINARY_DIR) / "install-test" / ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::error_code ignored;
    fs::remove_all(root_, ignored);
    fs::create_directories(root_);
    prefix_ = root_ / "prefix";
  }
  void install() {
    ASSERT_RUNS(
        std::string(STAGGER_CMAKE_COMMAND) + " --install " + quote(STAGGER_BINARY_DIR) + " --prefix " + quote(prefix_),
        root_ / "install.log");
  }
  fs::path root_, prefix_;
};

TEST_F(Install, EmbeddingExampleBuildsAgainstTheInstalledPackageAndSolvesSod) {
  ASSERT_NO_FATAL_FAILURE(install());
  const fs::path build = root_ / "embed-build", out = root_ / "embed-out";
  std::string configure =
      std::string(STAGGER_CMAKE_COMMAND) + " -S " + quote(fs::path(STAGGER_SOURCE_DIR) / "apps/examples/embed") +
      " -B " + quote(build) + " -G '" + STAGGER_CMAKE_GENERATOR + "' -DCMAKE_BUILD_TYPE=Release" +
      " -DCMAKE_PREFIX_PATH=" + quote(prefix_) + " -DCMAKE_CXX_COMPILER=" + quote(STAGGER_CXX_COMPILER);
  if (std::string(STAGGER_MAKE_PROGRAM).size() > 0) configure += " -DCMAKE_MAKE_PROGRAM=" + quote(STAGGER_MAKE_PROGRAM);
  ASSERT_RUNS(configure, root_ / "configure.log");
  // The package found is the installed one, not the build tree.
  const std::string cache = read_text(build / "CMakeCache.txt");
  EXPECT_NE(cache.find("Stagger_DIR:PATH=" + (prefix_ / STAGGER_INSTALL_LIBDIR).string()), std::string::npos)
      << "Stagger_DIR not under the prefix";
  ASSERT_RUNS(std::string(STAGGER_CMAKE_COMMAND) + " --build " + quote(build), root_ / "build.log");

  ASSERT_RUNS(quote(build / "embed_sod") + " " + quote(out), root_ / "run.log");
  const std::string output = read_text(root_ / "run.log");
  const auto values = key_values(output);
  ASSERT_TRUE(values.count("L1_density") && values.count("energy_audit")) << output;
  const double l1 = std::stod(values.at("L1_density"));
  const double audit = std::stod(values.at("energy_audit"));
  // 200 x 5 zones at t = 0.2 gives L1 ~ 2.9e-3 (docs/verification.md §1); the audit is round-off.
  EXPECT_GT(l1, 1e-4) << output;
  EXPECT_LT(l1, 5e-3) << output;
  EXPECT_LT(std::abs(audit), 1e-12) << output;
  EXPECT_TRUE(fs::exists(out / "sod.pvd")) << output;
  EXPECT_NE(read_text(out / "sod.pvd").find("sod_"), std::string::npos) << "the .pvd lists no dumps";
  EXPECT_TRUE(fs::exists(out / "summary.json"));
  std::printf("embed_sod via installed package: L1_density %.4e, audit %.2e\n", l1, audit);
}

TEST_F(Install, PackageHoldsOnlyPublicHeadersAndNoBuildTreeTargets) {
  ASSERT_NO_FATAL_FAILURE(install());
  // Headers: exactly the public ones.
  std::set<std::string> source_headers, installed_headers;
  for (const char* dir : {"lib/include/stagger", "meshgen/include/stagger"})
    for (const auto& entry : fs::directory_iterator(fs::path(STAGGER_SOURCE_DIR) / dir))
      source_headers.insert(entry.path().filename().string());
  for (const auto& entry : fs::recursive_directory_iterator(prefix_ / "include"))
    if (entry.is_regular_file())
      installed_headers.insert(fs::relative(entry.path(), prefix_ / "include/stagger").string());
  EXPECT_EQ(installed_headers, source_headers);

  // Package files, and exported targets that reference nothing of the build tree.
  const fs::path package = prefix_ / STAGGER_INSTALL_LIBDIR / "cmake/Stagger";
  for (const char* file : {"StaggerConfig.cmake", "StaggerConfigVersion.cmake", "StaggerTargets.cmake"})
    EXPECT_TRUE(fs::exists(package / file)) << file;
  std::string exported;
  for (const auto& entry : fs::directory_iterator(package)) exported += read_text(entry.path());
  for (const char* target : {"Stagger::stagger", "Stagger::meshgen", "Stagger::scene"})
    EXPECT_NE(exported.find(std::string("add_library(") + target + " SHARED IMPORTED)"), std::string::npos) << target;
  for (const char* forbidden : {"stagger_warnings", "stagger_gmsh", STAGGER_BINARY_DIR, STAGGER_SOURCE_DIR})
    EXPECT_EQ(exported.find(forbidden), std::string::npos) << "exported package mentions " << forbidden;
  // What consumers compile and link with: the private dependencies stay private. (CMake may
  // still list VTK in IMPORTED_LINK_DEPENDENT_LIBRARIES, a linker search hint it ignores
  // when the consumer has no such target.)
  std::istringstream lines(exported);
  for (std::string line; std::getline(lines, line);) {
    if (line.find("INTERFACE_") == std::string::npos) continue;
    for (const char* forbidden : {"CGAL", "VTK", "PkgConfig::", "OpenMP", "gmsh", "Eigen", "toml", "muparser"})
      EXPECT_EQ(line.find(forbidden), std::string::npos) << "exported interface mentions " << forbidden << ": " << line;
  }
}

TEST_F(Install, InstalledCommandLineRunsFromItsOwnLibraries) {
  ASSERT_NO_FATAL_FAILURE(install());
  // Not on any library path: it must find libstagger* through its RPATH ($ORIGIN/../<libdir>),
  // and the libraries find each other through theirs ($ORIGIN).
  const fs::path log = root_ / "cli.log";
  ASSERT_RUNS("env -u LD_LIBRARY_PATH " + quote(prefix_ / "bin/stagger") + " --help", log);
  EXPECT_NE(read_text(log).find("usage: stagger"), std::string::npos) << read_text(log);
  ASSERT_RUNS("ldd " + quote(prefix_ / "bin/stagger"), log);
  const std::string libraries = read_text(log);
  for (const char* library : {"libstagger.so", "libstagger_meshgen.so", "libstagger_scene.so"}) {
    const auto at = libraries.find(library);
    ASSERT_NE(at, std::string::npos) << library << "\n" << libraries;
    const std::string line = libraries.substr(at, libraries.find('\n', at) - at);
    EXPECT_NE(line.find((prefix_ / "bin/.." / STAGGER_INSTALL_LIBDIR).string()), std::string::npos) << line;
  }
  // Each installed library finds its siblings next to itself, whoever loads it.
  for (const char* library : {"libstagger_scene.so", "libstagger_meshgen.so"}) {
    ASSERT_RUNS("readelf -d " + quote(prefix_ / STAGGER_INSTALL_LIBDIR / library), log);
    EXPECT_NE(read_text(log).find("[$ORIGIN]"), std::string::npos) << library << "\n" << read_text(log);
  }
  // gmsh is loaded at run time, by the child that meshes, from the installed bridge module
  // (docs/mesh.md): the installed command meshes a .geo file.
  const fs::path vtu = root_ / "box.vtu";
  ASSERT_RUNS("env -u LD_LIBRARY_PATH " + quote(prefix_ / "bin/stagger") + " mesh " +
                  quote(fs::path(STAGGER_SOURCE_DIR) / "geometries/blast_box.geo") + " -o " + quote(vtu),
              log);
  EXPECT_GT(fs::file_size(vtu), 1000u) << read_text(log);
}

// Every installed scene is checked by the installed command (`stagger check` loads it and
// meshes it): the scenes whose meshes are .geo files find them in share/stagger/geometries.
TEST_F(Install, EveryInstalledSceneChecks) {
  ASSERT_NO_FATAL_FAILURE(install());
  int scenes = 0, with_geo = 0;
  for (const auto& entry : fs::directory_iterator(prefix_ / "share/stagger/scenes")) {
    if (entry.path().extension() != ".toml") continue;
    ++scenes;
    with_geo += read_text(entry.path()).find("../geometries/") != std::string::npos;
    const fs::path log = root_ / (entry.path().stem().string() + ".log");
    ASSERT_RUNS("cd " + quote(root_) + " && env -u LD_LIBRARY_PATH " + quote(prefix_ / "bin/stagger") + " check " +
                    quote(entry.path()),
                log);
  }
  EXPECT_GE(scenes, 23);
  EXPECT_GE(with_geo, 8);
}

}  // namespace
