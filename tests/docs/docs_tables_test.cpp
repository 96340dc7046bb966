// The cheap verification tables in docs/ (between BEGIN/END GENERATED comments) are what the
// code produces today: scripts/verification/check_tables.py reruns the scenes (Sod, Saltzman,
// Taylor-Green; about 20 s on one core) with stagger-profile and fails on any difference, so
// a change of results cannot leave docs/verification.md stale.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

namespace {

// The first python3 that has numpy and matplotlib (the table code is shared with
// make_figures.py, which draws the figures).
std::string python_with_matplotlib() {
  for (const std::string python : {"python3", "/usr/bin/python3"})
    if (std::system((python + " -c 'import matplotlib, numpy' > /dev/null 2>&1").c_str()) == 0) return python;
  return "";
}

TEST(DocsTables, CheapVerificationTablesMatchTheCode) {
  const std::string python = python_with_matplotlib();
  if (python.empty()) GTEST_SKIP() << "no python3 with matplotlib and numpy (apt-get install python3-matplotlib)";
  const std::string log = STAGGER_BINARY_DIR "/tests/check_tables.log";
  const std::string command = "OMP_NUM_THREADS=1 " + python +
                              " '" STAGGER_SOURCE_DIR
                              "/scripts/verification/check_tables.py' --build '" STAGGER_BINARY_DIR
                              "' --work '" STAGGER_BINARY_DIR "/tests/verification-check' > '" +
                              log + "' 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream in(log);
  const std::string output((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_TRUE(WIFEXITED(status)) << output;
  EXPECT_EQ(WEXITSTATUS(status), 0) << output
                                    << "\nIf the change of results is intended: python3 "
                                       "scripts/verification/check_tables.py --update, and review the diff.";
}

}  // namespace
