// rostest: names (src/scene/names.hpp). A: ~spawn with a 1,000,000-character name is refused at
// once with the rule, in a short answer, and nothing of it appears (no parameter, no topic);
// other services asked about a huge name answer briefly too. B: bad tf_prefixes are refused with
// the rule, a valid nested one is taken. C: the node binary with a bad ~ragdoll_name or
// ~tf_prefix or ~frame_prefix exits 1 with a FATAL message stating the rule.
#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <vector>

#include <ragdoll_sim/DeleteRagdoll.h>
#include <ragdoll_sim/SpawnRagdoll.h>
#include <ros/master.h>

#include "node_binary.hpp"
#include "node_log.hpp"
#include "sim_client.hpp"

using namespace ragdoll_test;

namespace {

const std::string kNode = "/ragdoll_sim";
const char* kModel = RAGDOLL_SIM_SOURCE_DIR "/urdf/ragdoll.urdf";
const char* kNameRule = "a letter first, then letters, digits or '_'";
const char* kPrefixRule = "joined by single '/'";

struct Fixture {
  ros::NodeHandle nh;
  SimClient sim{kNode};
  std::unique_ptr<NodeWarnings> warnings;
  std::atomic<int> rosout_messages{0};
  ros::Subscriber rosout;  // shares the process's /rosout connections with `warnings`
  void init() {
    warnings = std::make_unique<NodeWarnings>(nh, kNode);
    rosout = nh.subscribe<rosgraph_msgs::Log>(
        "/rosout", 1, [this](const rosgraph_msgs::Log::ConstPtr&) { ++rosout_messages; });
  }
  // The node's first WARN must not go out before /rosout connects to it.
  bool waitRosoutFromNode(double timeout = 20.0) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && rosout.getNumPublishers() < 2 && ros::WallTime::now() < deadline)
      ros::WallDuration(0.02).sleep();
    return rosout.getNumPublishers() >= 2;
  }
};

Fixture* fx = nullptr;

ragdoll_sim::SpawnRagdoll spawnRequest(const std::string& name, const std::string& prefix = "") {
  ragdoll_sim::SpawnRagdoll s;
  s.request.name = name;
  s.request.tf_prefix = prefix;
  s.request.urdf_file = kModel;
  s.request.pose.position.x = 3.0;
  s.request.pose.position.z = 5.0;
  s.request.pose.orientation.w = 1.0;
  return s;
}

bool anyTopicLongerThan(size_t n) {
  ros::master::V_TopicInfo topics;
  ros::master::getTopics(topics);
  for (const auto& t : topics)
    if (t.name.size() > n) return true;
  return false;
}

}  // namespace

TEST(Names, A_HugeNameIsRefusedBriefly) {
  ASSERT_TRUE(fx->sim.waitUp()) << "node not up";
  EXPECT_TRUE(fx->waitRosoutFromNode()) << "/rosout not connected to the node";
  const std::string huge(1000000, 'a');
  ragdoll_sim::SpawnRagdoll s = spawnRequest(huge);
  const ros::WallTime t0 = ros::WallTime::now();
  ASSERT_TRUE(ros::service::call(kNode + "/spawn", s));
  const double took = (ros::WallTime::now() - t0).toSec();
  EXPECT_FALSE(s.response.success) << "a 1,000,000-character name was accepted";
  EXPECT_LT(s.response.message.size(), 500u) << s.response.message.substr(0, 500);
  for (const char* w : {"too long", "1000000 characters", kNameRule, "128"})
    EXPECT_NE(s.response.message.find(w), std::string::npos)
        << "'" << s.response.message.substr(0, 500) << "' lacks \"" << w << "\"";
  EXPECT_LT(took, 2.0) << "the refusal took " << took << " s";
  RecordProperty("refusal_s", std::to_string(took));
  EXPECT_TRUE(fx->warnings->wait({"spawn", "too long", kNameRule}, 5.0));
  EXPECT_FALSE(anyTopicLongerThan(200)) << "a topic carries the huge name";
  EXPECT_FALSE(fx->nh.hasParam("/" + huge.substr(0, 200) + "/robot_description"));

  ragdoll_sim::DeleteRagdoll del;
  del.request.name = huge;
  ASSERT_TRUE(ros::service::call(kNode + "/delete", del));
  EXPECT_FALSE(del.response.success);
  EXPECT_LT(del.response.message.size(), 500u) << "the delete answer echoes the huge name";

  for (const std::string& bad : {std::string("2bad"), std::string("a-b"), std::string(129, 'b')}) {
    ragdoll_sim::SpawnRagdoll b = spawnRequest(bad);
    ASSERT_TRUE(ros::service::call(kNode + "/spawn", b));
    EXPECT_FALSE(b.response.success) << bad;
    EXPECT_NE(b.response.message.find(kNameRule), std::string::npos) << b.response.message;
  }
}

TEST(Names, B_TfPrefixesAreChecked) {
  for (const std::string& bad : {std::string("/bob"), std::string("bob/"), std::string("a//b"),
                                 std::string("bob-1"), std::string(200, 'p')}) {
    ragdoll_sim::SpawnRagdoll s = spawnRequest("bob", bad);
    ASSERT_TRUE(ros::service::call(kNode + "/spawn", s));
    EXPECT_FALSE(s.response.success) << "tf_prefix '" << bad << "' accepted";
    EXPECT_NE(s.response.message.find("tf_prefix"), std::string::npos) << s.response.message;
    EXPECT_NE(s.response.message.find(kPrefixRule), std::string::npos) << s.response.message;
    EXPECT_LT(s.response.message.size(), 500u);
  }
  EXPECT_TRUE(fx->warnings->wait({"spawn 'bob' rejected", "tf_prefix", kPrefixRule}, 5.0));
  ragdoll_sim::SpawnRagdoll ok = spawnRequest("bob", "robots/bob");
  ASSERT_TRUE(ros::service::call(kNode + "/spawn", ok));
  EXPECT_TRUE(ok.response.success) << ok.response.message;
  EXPECT_NE(ok.response.message.find("TF prefix 'robots/bob'"), std::string::npos)
      << ok.response.message;
}

TEST(Names, C_BadNameParametersStopTheNode) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"_ragdoll_name:=" + std::string(300, 'r'), {"~ragdoll_name", "too long", kNameRule}},
      {"_ragdoll_name:=robot-1", {"~ragdoll_name", "'-'", kNameRule}},
      {"_tf_prefix:=/sim", {"~tf_prefix", kPrefixRule}},
      {"_tf_prefix:=" + std::string(300, 't'), {"~tf_prefix", "too long", kPrefixRule}},
      {"_frame_prefix:=sim_a/", {"~frame_prefix", kPrefixRule}},
  };
  int k = 0;
  for (const auto& [args, words] : cases) {
    std::string out;
    const int rc = runNodeBinary("names_node_" + std::to_string(k++),
                                 std::string("_urdf_file:=") + kModel + " " + args, 60, &out);
    EXPECT_EQ(rc, 1) << args.substr(0, 60) << ":\n" << out;
    EXPECT_NE(out.find("FATAL"), std::string::npos) << out;
    for (const std::string& w : words) EXPECT_NE(out.find(w), std::string::npos) << w << ": " << out;
    EXPECT_EQ(out.find(std::string(100, args.back())), std::string::npos)
        << "the message echoes the whole name";
  }
}

int main(int argc, char** argv) { return runFixtureTests(argc, argv, "names_test", 2, fx); }
