// rostest: load. A bounded loop publishes 100 000 small impulses on ~apply_impulse at 10 kHz
// (10 s, loopback; the node's subscriber asks for TCP_NODELAY). Measured and printed: what
// the node received, applied and dropped (~stats), its deepest queue, its RSS before and after
// (/proc/<pid>/status, pid from the node's XML-RPC getPid), sim time vs wall time over the
// burst (the node runs at real-time factor 1) and the steps it skipped for being late.
// Asserted (nothing about time): every received command is applied, rejected or dropped; none
// is rejected (all are valid); the queue never held more than its capacity; RSS grew by less
// than 64 MiB; no body fault; the node still answers and its ~link_states are finite.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>

#include <ragdoll_sim/ApplyImpulse.h>
#include <ragdoll_sim/LinkStates.h>
#include <ragdoll_sim/NodeStats.h>
#include <ros/master.h>
#include <ros/network.h>
#include <xmlrpcpp/XmlRpcClient.h>

#include "node_log.hpp"
#include "sim_client.hpp"

using namespace ragdoll_test;

namespace {

const std::string kNode = "/ragdoll_sim";
constexpr int kRateHz = 10000;
constexpr int kCount = 10 * kRateHz;  // 10 s

// The node's pid through its slave API (what `rosnode info` does); -1 on failure.
int nodePid(const std::string& node) {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  args[1] = node;
  if (!ros::master::execute("lookupNode", args, result, payload, true)) return -1;
  std::string host;
  uint32_t port = 0;
  if (!ros::network::splitURI(std::string(payload), host, port)) return -1;
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue pid_args, pid_result;
  pid_args[0] = ros::this_node::getName();
  if (!client.execute("getPid", pid_args, pid_result) || pid_result.size() < 3) return -1;
  return int(pid_result[2]);
}

// VmRSS in kB, -1 when unreadable.
long rssKb(int pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

struct Fixture {
  ros::NodeHandle nh;
  SimClient sim{kNode};
  ros::Publisher impulse_pub;
  ros::Subscriber stats_sub, link_states_sub;
  std::mutex mutex;
  ragdoll_sim::NodeStats stats;
  ragdoll_sim::LinkStates link_states;
  ros::WallTime stats_at;  // when `stats` arrived

  void init() {
    impulse_pub = nh.advertise<ragdoll_sim::ApplyImpulse>(kNode + "/apply_impulse", 1000);
    stats_sub = nh.subscribe<ragdoll_sim::NodeStats>(
        kNode + "/stats", 10, [this](const ragdoll_sim::NodeStats::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex);
          stats = *m;
          stats_at = ros::WallTime::now();
        });
    link_states_sub = nh.subscribe<ragdoll_sim::LinkStates>(
        kNode + "/link_states", 10, [this](const ragdoll_sim::LinkStates::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex);
          link_states = *m;
        });
  }

  // The first stats message that arrives after `after`.
  bool statsAfter(const ros::WallTime& after, ragdoll_sim::NodeStats* out, double timeout = 10.0) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < deadline) {
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (stats_at > after) {
          *out = stats;
          return true;
        }
      }
      ros::WallDuration(0.01).sleep();
    }
    return false;
  }
};

Fixture* fx = nullptr;

}  // namespace

TEST(Load, TenKiloHertzImpulsesForTenSeconds) {
  ASSERT_TRUE(fx->sim.waitUp()) << "node did not come up";
  ASSERT_TRUE(waitConnected(fx->impulse_pub));
  ASSERT_TRUE(waitConnected(fx->stats_sub));
  const int pid = nodePid(kNode);
  ASSERT_GT(pid, 0) << "no pid for " << kNode;
  ros::WallDuration(1.0).sleep();  // the ragdoll lands; start-up allocations are done

  ragdoll_sim::NodeStats s0, s1;
  ASSERT_TRUE(fx->statsAfter(ros::WallTime::now(), &s0));
  const long rss0 = rssKb(pid);
  ASSERT_GT(rss0, 0);
  const double sim0 = fx->sim.step(0).sim_time;  // running: refused, but it tells the sim time
  const auto wall0 = std::chrono::steady_clock::now();

  // The bounded loop: message i goes out at wall0 + i / rate (at once when already late).
  ragdoll_sim::ApplyImpulse m;
  m.link = "torso";
  m.frame = "link";
  for (int i = 0; i < kCount && ros::ok(); ++i) {
    const auto due = wall0 + std::chrono::nanoseconds(int64_t(i) * 1000000000 / kRateHz);
    if (std::chrono::steady_clock::now() < due) std::this_thread::sleep_until(due);
    m.impulse.x = i % 2 ? 1e-3 : -1e-3;  // 1 mN*s, alternating: the ragdoll stays put
    fx->impulse_pub.publish(m);
  }
  const auto wall1 = std::chrono::steady_clock::now();
  const double sim1 = fx->sim.step(0).sim_time;
  const double wall_s = std::chrono::duration<double>(wall1 - wall0).count();

  // Wait until the node has taken everything it will get: received steady for 1 s, queue empty.
  uint64_t last = ~0ull;
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(30.0);
  while (ros::ok() && ros::WallTime::now() < deadline) {
    ASSERT_TRUE(fx->statsAfter(ros::WallTime::now(), &s1));
    if (s1.received == last && s1.queued == 0) break;
    last = s1.received;
    ros::WallDuration(1.0).sleep();
  }
  const long rss1 = rssKb(pid);

  const uint64_t received = s1.received - s0.received, applied = s1.applied - s0.applied;
  const uint64_t rejected = s1.rejected - s0.rejected, dropped = s1.dropped - s0.dropped;
  const double ratio = (sim1 - sim0) / wall_s;
  std::ostringstream report;
  report << "sent " << kCount << " in " << wall_s << " s (" << kCount / wall_s
         << " Hz); node received " << received << " (" << 100.0 * double(received) / kCount
         << " %), applied " << applied << ", rejected " << rejected << ", dropped " << dropped
         << ", max queued " << s1.max_queued << " of " << s1.queue_capacity << "; RSS "
         << rss0 << " kB before, " << rss1 << " kB after (" << (rss1 - rss0)
         << " kB); sim/wall over the burst " << ratio << " at real-time factor 1; skipped steps "
         << (s1.skipped_steps - s0.skipped_steps);
  std::printf("[ load     ] %s\n", report.str().c_str());
  RecordProperty("load_report", report.str());

  EXPECT_EQ(s1.queued, 0u);
  EXPECT_EQ(received, applied + rejected + dropped) << "commands unaccounted for";
  EXPECT_EQ(rejected, 0u) << "valid impulses were rejected";
  EXPECT_GT(received, 0u);
  EXPECT_LE(received, uint64_t(kCount));
  EXPECT_LE(s1.max_queued, s1.queue_capacity);
  EXPECT_LT(rss1 - rss0, 64 * 1024) << "RSS grew by " << (rss1 - rss0) << " kB";
  EXPECT_EQ(s1.body_faults, s0.body_faults);

  // Alive and finite.
  const ros::WallTime now = ros::WallTime::now();
  ros::Time stamp;
  {
    std::lock_guard<std::mutex> lock(fx->mutex);
    stamp = fx->link_states.header.stamp;
  }
  ragdoll_sim::LinkStates ls;
  const ros::WallTime until = now + ros::WallDuration(10.0);
  while (ros::ok() && ros::WallTime::now() < until) {
    {
      std::lock_guard<std::mutex> lock(fx->mutex);
      ls = fx->link_states;
    }
    if (ls.header.stamp > stamp) break;
    ros::WallDuration(0.02).sleep();
  }
  ASSERT_GT(ls.header.stamp, stamp) << "~link_states stopped after the burst";
  ASSERT_FALSE(ls.link.empty());
  for (size_t i = 0; i < ls.link.size(); ++i) {
    const auto& p = ls.pose[i].position;
    const auto& v = ls.twist[i].linear;
    EXPECT_TRUE(std::isfinite(p.x + p.y + p.z + v.x + v.y + v.z)) << ls.link[i];
  }
  EXPECT_GT(fx->sim.step(0).sim_time, sim1) << "sim time stopped";
}

int main(int argc, char** argv) {
  return runFixtureTests(argc, argv, "load_test", 2, fx);
}
