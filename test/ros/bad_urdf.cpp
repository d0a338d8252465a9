// rostest: the node binary, started with ~urdf_file set to each malformed fixture
// (test/urdf/fixtures/bad_*.urdf), exits with code 1 and a FATAL message naming the element;
// with ~urdf_file naming a named pipe, a directory or /dev/zero, likewise (naming the rule).
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "../urdf/malformed_cases.hpp"
#include "node_binary.hpp"
#include "node_log.hpp"

TEST(BadUrdf, NodeExitsNonZeroNamingTheElement) {
  int k = 0;
  for (const auto& [file, words] : malformed::badCases()) {
    std::string out;
    const std::string args = "_urdf_file:=" + malformed::kFixtures + file;
    const std::string name = "bad_urdf_node_" + std::to_string(k++);
    const int rc = ragdoll_test::runNodeBinary(name, args, 60, &out);
    EXPECT_EQ(rc, 1) << file << ":\n" << out;
    EXPECT_NE(out.find("FATAL"), std::string::npos) << file << ":\n" << out;
    EXPECT_NE(out.find(file), std::string::npos) << out;
    for (const std::string& w : words) EXPECT_NE(out.find(w), std::string::npos) << file << ": " << out;
  }
}

TEST(BadUrdf, NodeExitsNonZeroOnAFileItMustNotRead) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("ragdoll_bad_urdf_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "folder.urdf");
  const std::string fifo = (dir / "pipe.urdf").string();
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::vector<std::pair<std::string, std::string>> cases = {
      // The pipe first: a node blocked on it is killed (-k) and the test stops there.
      {fifo, "is not a regular file (a named pipe)"},
      {(dir / "folder.urdf").string(), "is not a regular file (a directory)"},
      {"/dev/zero", "is not a regular file (a character device)"},
  };
  const std::string kRule = "only regular files up to 64 MiB";
  int k = 0;
  for (const auto& [path, why] : cases) {
    std::string out;
    // SIGINT after 20 s, SIGKILL 2 s later: a node blocked in open() ignores SIGINT.
    const int rc = malformed::run("timeout -k 2 -s INT 20 " + std::string(RAGDOLL_SIM_NODE_BIN) +
                                      " __name:=hostile_file_node_" + std::to_string(k++) +
                                      " _urdf_file:=" + path,
                                  &out);
    ASSERT_EQ(rc, 1) << path << ":\n" << out;
    EXPECT_NE(out.find("FATAL"), std::string::npos) << path << ":\n" << out;
    for (const std::string& w : {"'" + path + "'", why, kRule})
      EXPECT_NE(out.find(w), std::string::npos) << w << " not in: " << out;
  }
  std::filesystem::remove_all(dir);
}

int main(int argc, char** argv) {
  return ragdoll_test::runRosTests(argc, argv, "bad_urdf_test", 1, [] {}, [] {});
}
