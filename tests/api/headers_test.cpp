// The public headers are the library's whole front door: each compiles alone (the generated
// translation units of tests/api/area.cmake) and none pulls in a third-party header.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> public_headers() {
  std::vector<fs::path> headers;
  for (const char* dir : {"lib/include/stagger", "meshgen/include/stagger"})
    for (const auto& entry : fs::directory_iterator(fs::path(STAGGER_SOURCE_DIR) / dir))
      if (entry.path().extension() == ".hpp") headers.push_back(entry.path());
  return headers;
}

TEST(PublicHeaders, IncludeOnlyTheStandardLibraryAndEachOther) {
  const auto headers = public_headers();
  ASSERT_GE(headers.size(), 11u);
  // <name> without a path or extension is a standard header; "stagger/x.hpp" is ours.
  const std::regex include_line(R"(^\s*#\s*include\s*([<"])([^>"]+)[>"])");
  const std::regex standard(R"([a-z_]+)");
  const std::regex ours(R"(stagger/[a-z_]+\.hpp)");
  for (const auto& header : headers) {
    std::ifstream in(header);
    int line_number = 0, includes = 0;
    for (std::string line; std::getline(in, line);) {
      ++line_number;
      std::smatch match;
      if (!std::regex_search(line, match, include_line)) continue;
      ++includes;
      const std::string name = match[2];
      const bool allowed = (match[1] == "<" && std::regex_match(name, standard)) ||
                           (match[1] == "\"" && std::regex_match(name, ours) &&
                            (fs::exists(fs::path(STAGGER_SOURCE_DIR) / "lib/include" / name) ||
                             fs::exists(fs::path(STAGGER_SOURCE_DIR) / "meshgen/include" / name))) ||
                           // The distributed runs take an MPI communicator: MPI is that header's
                           // one public dependency (docs/parallel.md).
                           (header.filename() == "parallel.hpp" && match[1] == "<" && name == "mpi.h");
      EXPECT_TRUE(allowed) << header.string() << ":" << line_number << " includes " << name
                           << " (public headers may include only the standard library and stagger/*.hpp)";
    }
    EXPECT_GT(includes, 0) << header;
  }
}

TEST(PublicHeaders, NameNoThirdPartyLibrary) {
  // Belt and braces for the check above: not even a forward declaration or a comment-free
  // mention of the private dependencies' namespaces.
  for (const auto& header : public_headers()) {
    std::ifstream in(header);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const char* word : {"CGAL::", "gmsh::", "vtk", "toml::", "mu::", "Eigen::", "omp.h"})
      EXPECT_EQ(text.find(word), std::string::npos) << header.string() << " mentions " << word;
  }
}

}  // namespace
