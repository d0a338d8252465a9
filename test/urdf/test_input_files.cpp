// Hostile file paths: a URDF or mesh path naming a device, a named pipe, a directory or an
// oversized file is refused at once with the path and the rule (kMaxInputFileBytes), by the
// loader and by ragdoll_check. Each hostile load runs in a child process killed at a deadline,
// so that a loader that blocks or reads forever fails the test instead of hanging it.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "ragdoll_sim/urdf_loader.hpp"

using namespace ragdoll_sim;
namespace fs = std::filesystem;

namespace {

constexpr double kDeadline = 1.0;  // s: the bound for a refusal
const std::string kRule = "only regular files up to 64 MiB";
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

struct Outcome {
  bool finished = false;  // within the deadline
  double seconds = 0;
  bool ok = false;
  std::string text;  // the error, or the warnings when ok
};

// `load` in a forked child; the child is killed when it has not answered after 2 deadlines.
template <class F>
Outcome inChild(F load) {
  int fds[2];
  if (pipe(fds) != 0) return {};
  const Clock::time_point t0 = Clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    const UrdfLoadResult r = load();
    std::string msg = (r.ok ? "1" : "0") + r.error;
    for (const std::string& w : r.def.warnings) msg += w + "\n";
    (void)!write(fds[1], msg.data(), msg.size());
    _exit(0);
  }
  close(fds[1]);
  Outcome o;
  std::string msg;
  for (;;) {
    pollfd p{fds[0], POLLIN, 0};
    const int left_ms = int((2 * kDeadline - since(t0)) * 1000);
    if (left_ms <= 0 || poll(&p, 1, left_ms) <= 0) break;
    std::array<char, 4096> buf;
    const ssize_t n = read(fds[0], buf.data(), buf.size());
    if (n <= 0) {
      o.finished = n == 0 && !msg.empty();
      break;
    }
    msg.append(buf.data(), size_t(n));
  }
  o.seconds = since(t0);
  close(fds[0]);
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  if (o.finished) {
    o.ok = msg[0] == '1';
    o.text = msg.substr(1);
  }
  return o;
}

Outcome loadFile(const std::string& path) {
  return inChild([&] { return loadUrdfFile(path); });
}

std::string oneMeshRobot(const std::string& filename) {
  return "<robot name='m'><link name='a'><inertial><mass value='1'/><inertia ixx='0.01' iyy='0.01' "
         "izz='0.01' ixy='0' ixz='0' iyz='0'/></inertial><collision><geometry><mesh filename='" +
         filename + "'/></geometry></collision></link></robot>";
}

// A fresh temporary folder holding a named pipe, a sparse file and a directory.
class HostileFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("ragdoll_hostile_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "folder.urdf");
    ASSERT_EQ(mkfifo(fifo().c_str(), 0600), 0);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string fifo() const { return (dir_ / "pipe.urdf").string(); }
  std::string folder() const { return (dir_ / "folder.urdf").string(); }
  // A sparse file of `size` bytes (nothing written but its length).
  std::string sparse(const std::string& name, off_t size) const {
    const std::string p = (dir_ / name).string();
    const int fd = open(p.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    EXPECT_GE(fd, 0);
    EXPECT_EQ(ftruncate(fd, size), 0);
    close(fd);
    return p;
  }
  fs::path dir_;
};

void expectRefused(const Outcome& o, const std::string& path, const std::string& why) {
  ASSERT_TRUE(o.finished) << path << ": no answer within " << 2 * kDeadline << " s";
  EXPECT_LT(o.seconds, kDeadline) << path;
  EXPECT_FALSE(o.ok) << path;
  for (const std::string& w : {"'" + path + "'", why, kRule})
    EXPECT_NE(o.text.find(w), std::string::npos) << w << " not in: " << o.text;
  EXPECT_EQ(o.text.find('\n'), std::string::npos) << o.text;
}

}  // namespace

TEST_F(HostileFiles, LoaderRefusesDeviceAtOnce) {
  expectRefused(loadFile("/dev/zero"), "/dev/zero", "is not a regular file (a character device)");
}

TEST_F(HostileFiles, LoaderRefusesNamedPipeWithoutWriter) {
  expectRefused(loadFile(fifo()), fifo(), "is not a regular file (a named pipe)");
}

TEST_F(HostileFiles, LoaderRefusesDirectory) {
  expectRefused(loadFile(folder()), folder(), "is not a regular file (a directory)");
}

TEST_F(HostileFiles, LoaderRefusesOversizedFileBeforeReading) {
  const std::string huge = sparse("huge.urdf", off_t(1) << 40);  // 1 TiB, sparse
  expectRefused(loadFile(huge), huge, "is too large (1099511627776 bytes)");
  const std::string over = sparse("over.urdf", off_t(kMaxInputFileBytes) + 1);
  expectRefused(loadFile(over), over, "is too large (67108865 bytes)");
}

TEST_F(HostileFiles, FileAtTheLimitIsRead) {
  // 64 MiB of NULs: read, then refused by the parser, not by the size rule.
  const std::string at = sparse("at.urdf", off_t(kMaxInputFileBytes));
  const UrdfLoadResult r = loadUrdfFile(at);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error.find("too large"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find(at), std::string::npos) << r.error;
}

TEST_F(HostileFiles, FileLongerThanItsStatSizeIsReadWhole) {
  // /proc files are regular with st_size 0: the reader goes on until end of file.
  const UrdfLoadResult r = loadUrdfFile("/proc/self/status");
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error.find("empty"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("not well-formed XML"), std::string::npos) << r.error;
}

TEST_F(HostileFiles, TheTextReadIsReturnedOnce) {
  const std::string p = (dir_ / "robot.urdf").string();
  const std::string xml = oneMeshRobot("missing.stl");
  std::ofstream(p) << xml;
  std::string text;
  const UrdfLoadResult r = loadUrdfFile(p, {}, &text);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(text, xml);
}

TEST_F(HostileFiles, MeshPathsAreCheckedBeforeAssimpOpensThem) {
  const std::string big = sparse("big.stl", off_t(kMaxInputFileBytes) + 1);
  const struct {
    std::string filename, why;
  } cases[] = {
      {fifo(), "is not a regular file (a named pipe)"},
      {"file://" + fifo(), "is not a regular file (a named pipe)"},
      {"/dev/zero", "is not a regular file (a character device)"},
      {folder(), "is not a regular file (a directory)"},
      {big, "is too large (67108865 bytes)"},
  };
  for (const auto& c : cases) {
    const std::string xml = oneMeshRobot(c.filename);
    const Outcome o = inChild([&] { return loadUrdfString(xml); });
    ASSERT_TRUE(o.finished) << c.filename << ": no answer within " << 2 * kDeadline << " s";
    EXPECT_LT(o.seconds, kDeadline) << c.filename;
    // The mesh is skipped with a warning naming the rule; the link keeps a fallback shape.
    EXPECT_TRUE(o.ok) << o.text;
    EXPECT_NE(o.text.find("mesh file '"), std::string::npos) << o.text;
    EXPECT_NE(o.text.find(c.why), std::string::npos) << c.why << " not in: " << o.text;
  }
}

TEST_F(HostileFiles, RagdollCheckExitsOneAtOnce) {
  const std::string big = sparse("huge.urdf", off_t(1) << 40);
  for (const std::string& path : {std::string("/dev/zero"), fifo(), folder(), big}) {
    // The shell's timeout kills a ragdoll_check that blocks or reads forever.
    const std::string cmd = "timeout -s KILL " + std::to_string(2 * kDeadline) +
                            " " RAGDOLL_CHECK_BIN " " + path + " 2>&1";
    const Clock::time_point t0 = Clock::now();
    FILE* p = popen(cmd.c_str(), "r");
    ASSERT_NE(p, nullptr);
    std::string out;
    std::array<char, 512> buf;
    while (fgets(buf.data(), buf.size(), p)) out += buf.data();
    const int status = pclose(p);
    const double seconds = since(t0);
    ASSERT_TRUE(WIFEXITED(status)) << path;
    EXPECT_EQ(WEXITSTATUS(status), 1) << path << "\n" << out;
    EXPECT_LT(seconds, kDeadline) << path;
    EXPECT_NE(out.find("status=refused"), std::string::npos) << out;
    EXPECT_NE(out.find(kRule), std::string::npos) << out;
  }
}
