// rostest: ~spawn with a urdf_file that is no regular file or too large is refused at once
// (a reply naming the path and the rule within 1 s), a regular file is still spawned (its
// robot_description the text read), and the node keeps simulating and publishing. A call that
// has not answered after 2 s fails the test; for the named pipe the test then opens the pipe
// for writing itself, so that a node blocked on it is released.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <ragdoll_sim/LinkStates.h>
#include <ragdoll_sim/SpawnRagdoll.h>
#include <ros/ros.h>

#include "node_log.hpp"

namespace fs = std::filesystem;

namespace {

const std::string kNode = "/ragdoll_sim";
constexpr double kDeadline = 1.0;  // s
const std::string kRule = "only regular files up to 64 MiB";

struct Fixture {
  ros::NodeHandle nh;
  ros::Subscriber link_states_sub;
  std::mutex mutex;
  ros::Time last_stamp;
  int received = 0;
  fs::path dir;

  void init() {
    link_states_sub = nh.subscribe<ragdoll_sim::LinkStates>(
        kNode + "/link_states", 10, [this](const ragdoll_sim::LinkStates::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex);
          last_stamp = m->header.stamp;
          ++received;
        });
    dir = fs::temp_directory_path() / ("ragdoll_bad_files_" + std::to_string(getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir / "folder.urdf");
  }
  ~Fixture() { fs::remove_all(dir); }

  // Sim stamp of the latest ~link_states and how many have arrived.
  std::pair<ros::Time, int> latest() {
    std::lock_guard<std::mutex> lock(mutex);
    return {last_stamp, received};
  }
};

Fixture* fx = nullptr;

// The spawn call's answer, filled by a thread that may stay blocked in the call.
struct Call {
  std::atomic<bool> done{false};
  bool called = false;
  ragdoll_sim::SpawnRagdoll srv;
};

}  // namespace

TEST(BadFiles, SpawnRefusesAtOnceAndTheNodeRuns) {
  ASSERT_TRUE(ros::service::waitForService(kNode + "/spawn", ros::Duration(30)));
  ASSERT_TRUE(ragdoll_test::waitConnected(fx->link_states_sub));
  const std::string fifo = (fx->dir / "pipe.urdf").string();
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string huge = (fx->dir / "huge.urdf").string();
  {
    const int fd = open(huge.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(ftruncate(fd, off_t(1) << 40), 0);  // 1 TiB, sparse
    close(fd);
  }
  const struct {
    std::string path, why;
  } cases[] = {
      // The pipe first: a node that reads it blocks, which this test can undo.
      {fifo, "is not a regular file (a named pipe)"},
      {(fx->dir / "folder.urdf").string(), "is not a regular file (a directory)"},
      {huge, "is too large (1099511627776 bytes)"},
      {"/dev/zero", "is not a regular file (a character device)"},
  };
  int k = 0;
  for (const auto& c : cases) {
    auto call = std::make_shared<Call>();
    call->srv.request.name = "hostile_" + std::to_string(k++);
    call->srv.request.urdf_file = c.path;
    call->srv.request.pose.orientation.w = 1.0;
    call->srv.request.pose.position.y = 3.0 * k;
    const ros::WallTime t0 = ros::WallTime::now();
    std::thread([call] {
      call->called = ros::service::call(kNode + "/spawn", call->srv);
      call->done = true;
    }).detach();
    while (!call->done && (ros::WallTime::now() - t0).toSec() < 2 * kDeadline)
      ros::WallDuration(0.005).sleep();
    const double seconds = (ros::WallTime::now() - t0).toSec();
    if (!call->done && c.path == fifo) {  // release the node: a writer that closes at once
      const int w = open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
      if (w >= 0) close(w);
    }
    ASSERT_TRUE(call->done) << c.path << ": no reply within " << 2 * kDeadline << " s";
    EXPECT_LT(seconds, kDeadline) << c.path;
    ::testing::Test::RecordProperty(call->srv.request.name + "_ms", std::to_string(seconds * 1e3));
    ASSERT_TRUE(call->called) << c.path;
    const std::string& m = call->srv.response.message;
    EXPECT_FALSE(call->srv.response.success) << m;
    for (const std::string& w : {"'" + c.path + "'", c.why, kRule})
      EXPECT_NE(m.find(w), std::string::npos) << w << " not in: " << m;
  }
  // A regular file is still spawned, its robot_description the text read for the model.
  ragdoll_sim::SpawnRagdoll good;
  good.request.name = "regular";
  good.request.urdf_file = RAGDOLL_SIM_SOURCE_DIR "/urdf/ragdoll.urdf";
  good.request.pose.position.y = -3.0;
  good.request.pose.position.z = 1.1;
  good.request.pose.orientation.w = 1.0;
  ASSERT_TRUE(ros::service::call(kNode + "/spawn", good));
  EXPECT_TRUE(good.response.success) << good.response.message;
  std::ifstream in(good.request.urdf_file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string description;
  EXPECT_TRUE(ros::param::get("/regular/robot_description", description));
  EXPECT_EQ(description, text);
  // Still simulating: ~link_states keeps coming, its sim stamp moving on.
  const auto [stamp0, count0] = fx->latest();
  ros::WallDuration(1.0).sleep();
  const auto [stamp1, count1] = fx->latest();
  EXPECT_GT(count1, count0 + 5);
  EXPECT_GT(stamp1, stamp0);
}

int main(int argc, char** argv) {
  return ragdoll_test::runFixtureTests(argc, argv, "bad_files_test", 1, fx);
}
