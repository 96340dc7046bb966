// Hostile mesh and scene inputs through the `stagger` executable (docs/robustness.md,
// "Hostile input, round three"): mesh paths that are not regular files, includes of a FIFO
// or of an oversized file, keys nested 50 000 deep, and a meshing child that must die with
// its parent.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "support/files.hpp"
#include "support/scene_toml.hpp"
#include "support/scratch_directory.hpp"
#include "support/stagger_binary.hpp"

namespace fs = std::filesystem;

namespace {

using Result = stagger::testing::CommandResult;
using stagger::testing::read_text;
namespace toml = stagger::testing::toml;

class HostileMeshInputs : public ::testing::Test {
 protected:
  Result stagger(const std::string& args) const { return stagger::testing::run_stagger(args, directory_); }
  std::string write(const std::string& name, const std::string& text) const { return scratch_.write(name, text); }
  // Exit 1 and exactly one line, `stagger: error:`, holding every part of `parts`.
  static void expect_error(const Result& result, const std::vector<std::string>& parts) {
    EXPECT_EQ(result.status, 1) << result.err;
    EXPECT_EQ(result.err.rfind("stagger: error: ", 0), 0u) << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    for (const std::string& part : parts)
      EXPECT_NE(result.err.find(part), std::string::npos) << part << "\n" << result.err;
  }

  const stagger::testing::ScratchDirectory scratch_{"hostile_mesh_" + stagger::testing::current_test_name()};
  const fs::path directory_ = scratch_.path();
};

// A mesh path that is a directory, a FIFO, a device or a link loop says what it is.
TEST_F(HostileMeshInputs, MeshPathsThatAreNotRegularFilesSayWhatTheyAre) {
  const fs::path dir = directory_ / "dir.msh", fifo = directory_ / "fifo.msh", loop = directory_ / "loop.msh";
  fs::create_directory(dir);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  fs::create_symlink(loop.filename(), loop);
  const fs::path device = directory_ / "zero.geo";
  fs::create_symlink("/dev/zero", device);
  const std::vector<std::pair<fs::path, std::string>> cases = {{dir, "is a directory"},
                                                               {fifo, "is a FIFO (named pipe)"},
                                                               {loop, "is a symbolic link loop"},
                                                               {device, "is a character device"}};
  for (const auto& [path, what] : cases) {
    const std::string name = path.string();
    expect_error(stagger("mesh " + name),
                 {std::string(1, '\'').append(name).append("' ").append(what), "not a regular file"});
    // From a scene: the key and the same words.
    const std::string scene = write("scene_" + path.stem().string() + ".toml",
                                    toml::time("0.01") + "[mesh]\nfile = \"" + path.filename().string() + "\"\n" +
                                        toml::ideal_gas() + toml::gas_region("1.0", "1.0"));
    expect_error(stagger("check " + scene),
                 {std::string("key 'mesh.file': '").append(path.filename().string()).append("' ").append(what)});
  }
  expect_error(stagger("mesh " + (directory_ / "absent.msh").string()), {"absent.msh' not found"});
}

// The .geo scan reads regular files only, and opens none that could block it: an Include of
// a FIFO (which used to block for ever) or a file over 16 MiB is an error naming the line.
TEST_F(HostileMeshInputs, GeoScanRefusesFifosAndHugeIncludesWithoutBlocking) {
  const fs::path fifo = directory_ / "pipe.geo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string geo = write("includes_fifo.geo", "// a FIFO\nInclude \"pipe.geo\";\n");
  const auto start = std::chrono::steady_clock::now();
  expect_error(stagger("mesh " + geo), {geo + ":2: 'Include' of '" + fifo.string() + "': it is a FIFO (named pipe)"});
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
  {
    std::ofstream big(directory_ / "big.geo");
    const std::string comment = "// " + std::string(1000, 'x') + "\n";
    for (int i = 0; i < 17 * 1024; ++i) big << comment;
  }
  const std::string includes_big = write("includes_big.geo", "Include \"big.geo\";\n");
  expect_error(stagger("mesh " + includes_big), {"big.geo", "exceed stagger's limit of 16 MiB a file"});
  // Includes 25 files deep (no cycle): one error at the 21st, also with allowed commands.
  for (int i = 0; i < 25; ++i)
    write("chain" + std::to_string(i) + ".geo", "Include \"chain" + std::to_string(i + 1) + ".geo\";\n");
  write("chain25.geo", "x = 1;\n");
  for (const char* allow : {"", " --allow-geo-commands"})
    expect_error(stagger("mesh " + (directory_ / "chain0.geo").string() + allow),
                 {"chain20.geo:1: 'Include' nests more than 20 files deep"});
}

// Keys nested 50 000 deep (a dotted key in the file, a --set path, an inline table in a --set
// value) used to overflow the parser's stack: one error line now, naming the file and line.
TEST_F(HostileMeshInputs, KeysNested50000DeepAreErrorsNotStackOverflows) {
  std::string deep = "a";
  for (int i = 0; i < 50000; ++i) deep += ".a";
  const std::string base = toml::time("0.01") + toml::rectangle("[0.0, 1.0]", "[0.0, 1.0]", 2, 2) + toml::ideal_gas() +
                           toml::gas_region("1.0", "1.0") + toml::walls();
  const std::string file = write("deep.toml", base + "[numerics]\n" + deep + " = 1\n");
  expect_error(stagger("check " + file), {"deep.toml:", "a key nests more than 64 levels deep"});
  const std::string header = write("deep_header.toml", base + "[" + deep + "]\nx = 1\n");
  expect_error(stagger("check " + header), {"deep_header.toml:", "a key nests more than 64 levels deep"});
  const std::string plain = write("plain.toml", base);
  expect_error(stagger("check " + plain + " --set " + deep + "=1"), {"--set a.a.a", "nests more than 64 levels"});
  std::string inline_table = "1";
  for (int i = 0; i < 20000; ++i) inline_table = "{a=" + inline_table + "}";
  expect_error(stagger("check " + plain + " --set numerics.x='" + inline_table + "'"),
               {"--set numerics.x=", "nests more than 64 levels"});
  // 64 levels are fine for the parser; the reader then names the unknown key.
  std::string ok = "a";
  for (int i = 0; i < 62; ++i) ok += ".a";
  const Result shallow = stagger("check " + plain + " --set numerics." + ok + "=1");
  EXPECT_EQ(shallow.status, 1);
  EXPECT_NE(shallow.err.find("unknown key"), std::string::npos) << shallow.err;
}

// Mesh sizes asking for about 1e9 points used to mesh for minutes with no word: the curves'
// mesh gives a lower bound at once, refused above mesh.max_points (--max-points; 0: none).
TEST_F(HostileMeshInputs, MeshSizesAskingForTooManyPointsAreRefusedAtOnce) {
  const std::string square =
      "Point(1) = {0, 0, 0, lc}; Point(2) = {1, 0, 0, lc};\n"
      "Point(3) = {1, 1, 0, lc}; Point(4) = {0, 1, 0, lc};\n"
      "Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};\n"
      "Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};\n"
      "Physical Surface(\"domain\") = {1};\n";
  const std::string huge = write("huge.geo", "lc = 1e-8;\n" + square);  // 1e16 points, 4e8 on the curves
  const auto start = std::chrono::steady_clock::now();
  expect_error(stagger("mesh " + huge),
               {huge + ": its mesh would have at least about", "the sizes asked for are smaller still",
                "more than the limit of 5e+06 (scene key mesh.max_points, stagger mesh --max-points; 0: no limit)"});
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 20.0);
  // A small mesh (lc 0.1: 140 points) against a limit of 50; without a limit it meshes.
  const std::string small = write("small.geo", "lc = 0.1;\n" + square);
  expect_error(
      stagger("mesh " + small + " --max-points 50"),
      {"at least about 100 points (surface 1: area 1, boundary segments up to 0.1 long", "more than the limit of 50"});
  const Result meshed = stagger("mesh " + small + " --max-points 0");
  EXPECT_EQ(meshed.status, 0) << meshed.err;
  EXPECT_NE(meshed.out.find("140 points"), std::string::npos) << meshed.out;
  expect_error(stagger("mesh " + small + " --max-points -1"), {"--max-points '-1': give a number >= 0"});
}

// The pids of the children of `parent` (from /proc/PID/task/*/children).
std::vector<pid_t> children_of(pid_t parent) {
  std::vector<pid_t> children;
  std::error_code error;
  for (const auto& task : fs::directory_iterator(fs::path("/proc") / std::to_string(parent) / "task", error)) {
    std::ifstream in(task.path() / "children");
    for (long pid; in >> pid;) children.push_back(static_cast<pid_t>(pid));
  }
  return children;
}

// Whether `pid` is alive (a zombie, which a container's init may never reap, is not).
bool alive(pid_t pid) {
  std::ifstream stat(fs::path("/proc") / std::to_string(pid) / "stat");
  std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
  const std::size_t close = text.rfind(')');
  return close != std::string::npos && close + 2 < text.size() && text[close + 2] != 'Z' && text[close + 2] != 'X';
}

// `kill -9` of `stagger mesh -o` used to leave its gmsh child meshing: the child dies with
// its parent (PR_SET_PDEATHSIG, and a check of getppid() against the parent it was forked
// from for a parent that died before that).
TEST_F(HostileMeshInputs, KilledMeshCommandTakesItsGmshChildAlong) {
  const std::string geo = write("slow.geo", "x = 0;\nFor i In {1:2000000000}\n  x = x + 1;\nEndFor\n");
  const std::string out = (directory_ / "slow.msh").string();
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::freopen("/dev/null", "w", stdout);
    std::freopen("/dev/null", "w", stderr);
    const std::string binary = stagger::testing::stagger_binary();
    ::execl(binary.c_str(), binary.c_str(), "mesh", geo.c_str(), "-o", out.c_str(), "--gmsh-time-limit", "120",
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ASSERT_GT(pid, 0);
  std::vector<pid_t> children;
  for (int i = 0; i < 3000 && children.empty(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    children = children_of(pid);
  }
  ASSERT_EQ(children.size(), 1u) << "no gmsh child started";
  const pid_t child = children.front();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the child is in gmsh's loop
  ASSERT_TRUE(alive(child));
  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  const auto killed = std::chrono::steady_clock::now();
  while (alive(child) && std::chrono::steady_clock::now() - killed < std::chrono::seconds(5))
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_FALSE(alive(child)) << "the gmsh child " << child << " outlived its parent by 5 s";
  if (alive(child)) ::kill(child, SIGKILL);
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
