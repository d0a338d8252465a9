// rostest: objects at run time on one paused node that the tests step (in order):
// A a dynamic box falls (get_link_state, TF, ~link_states) and a ball keeps its initial twist,
// B a static box does not move, carries a ball and has no TF, C ~delete of dynamic and static
// objects (gone from ~link_states and ~markers; what stood on them falls), D ~spawn_model from SDF
// text, E from a URDF file with and without fixed_base, F ~spawn fixed_base, G bad input refused
// with a message naming it, nothing added, sim time still advancing; H a material name takes
// effect; I an SDF model welded to the world is pinned.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <set>

#include <ragdoll_sim/DeleteRagdoll.h>
#include <ragdoll_sim/LinkStates.h>
#include <ragdoll_sim/SpawnModel.h>
#include <ragdoll_sim/SpawnObject.h>
#include <ragdoll_sim/SpawnRagdoll.h>
#include <tf2_msgs/TFMessage.h>

#include "marker_log.hpp"
#include "node_log.hpp"
#include "sim_client.hpp"

using namespace ragdoll_test;

namespace {

const std::string kNode = "/ragdoll_sim";
constexpr double kG = 9.81;  // config/sim.yaml
constexpr double kDt = 0.001;

struct Fixture {
  ros::NodeHandle nh;
  SimClient sim{kNode};
  std::unique_ptr<MarkerLog> markers;
  ros::Subscriber link_states_sub, tf_sub;
  std::mutex mutex;
  ragdoll_sim::LinkStates link_states;
  size_t link_states_count = 0;
  std::map<std::string, Vec3> tf;  // child frame -> latest position

  void init() {
    markers = std::make_unique<MarkerLog>(nh, kNode + "/markers");
    link_states_sub = nh.subscribe<ragdoll_sim::LinkStates>(
        kNode + "/link_states", 10, [this](const ragdoll_sim::LinkStates::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex);
          link_states = *m;
          ++link_states_count;
        });
    tf_sub = nh.subscribe<tf2_msgs::TFMessage>("/tf", 100, [this](const tf2_msgs::TFMessage::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex);
      for (const auto& t : m->transforms)
        tf[t.child_frame_id] = Vec3(t.transform.translation.x, t.transform.translation.y,
                                    t.transform.translation.z);
    });
  }

  template <class Pred>
  bool waitFor(Pred pred, double timeout = 10.0) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < deadline) {
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (pred()) return true;
      }
      ros::WallDuration(0.02).sleep();
    }
    return false;
  }

  // Index of (ragdoll, link) in the latest ~link_states, or -1. Call with `mutex` held.
  int linkStateIndex(const std::string& ragdoll, const std::string& link) const {
    for (size_t i = 0; i < link_states.ragdoll.size(); ++i)
      if (link_states.ragdoll[i] == ragdoll && link_states.link[i] == link) return int(i);
    return -1;
  }
  bool hasObjectInLinkStates(const std::string& name) const {
    for (const std::string& r : link_states.ragdoll)
      if (r == name) return true;
    return false;
  }
};

Fixture* fx = nullptr;

geometry_msgs::Pose poseAt(const Vec3& p) {
  geometry_msgs::Pose m;
  m.position.x = p.x();
  m.position.y = p.y();
  m.position.z = p.z();
  m.orientation.w = 1.0;
  return m;
}

ragdoll_sim::SpawnObject::Request box(const std::string& name, const Vec3& p, double size = 0.2) {
  ragdoll_sim::SpawnObject::Request r;
  r.name = name;
  r.shape = "box";
  r.dimensions = {size, size, size};
  r.pose = poseAt(p);
  r.mass = 4.0;
  return r;
}

ragdoll_sim::SpawnObject::Response spawnObject(const ragdoll_sim::SpawnObject::Request& req) {
  ragdoll_sim::SpawnObject s;
  s.request = req;
  if (!ros::service::call(kNode + "/spawn_object", s)) {
    s.response.success = false;
    s.response.message = "call failed";
  }
  return s.response;
}

ragdoll_sim::SpawnModel::Response spawnModel(const ragdoll_sim::SpawnModel::Request& req) {
  ragdoll_sim::SpawnModel s;
  s.request = req;
  if (!ros::service::call(kNode + "/spawn_model", s)) {
    s.response.success = false;
    s.response.message = "call failed";
  }
  return s.response;
}

ragdoll_sim::DeleteRagdoll::Response del(const std::string& name) {
  ragdoll_sim::DeleteRagdoll s;
  s.request.name = name;
  if (!ros::service::call(kNode + "/delete", s)) {
    s.response.success = false;
    s.response.message = "call failed";
  }
  return s.response;
}

bool hasNs(const visualization_msgs::MarkerArray& a, const std::string& ns) {
  for (const auto& m : a.markers)
    if (m.ns == ns && m.action == visualization_msgs::Marker::ADD) return true;
  return false;
}

std::string pendulumUrdf() {
  std::string p;
  ros::param::get("~pendulum_urdf", p);
  return p;
}

const char* kSdfBox = R"(<model name="sdf_box">
  <link name="l">
    <inertial><mass>2</mass>
      <inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia>
    </inertial>
    <collision name="c"><geometry><box><size>0.3 0.3 0.3</size></box></geometry></collision>
    <visual name="v"><geometry><box><size>0.3 0.3 0.3</size></box></geometry>
      <material><diffuse>1 0 0 1</diffuse></material></visual>
  </link>
</model>)";

}  // namespace

TEST(Objects, A_DynamicBoxFalls) {
  ASSERT_TRUE(fx->sim.waitUp()) << "node did not come up";
  // TF and link states go out once per step count while paused: be there for them.
  ASSERT_TRUE(waitConnected(fx->link_states_sub));
  ASSERT_TRUE(waitConnected(fx->tf_sub));
  const auto r = spawnObject(box("crate", Vec3(2, 0, 3)));
  ASSERT_TRUE(r.success) << r.message;
  auto ball = box("ball", Vec3(4, 0, 3));
  ball.shape = "sphere";
  ball.dimensions = {0.1};
  ball.mass = 0.0;
  ball.density = 500.0;
  ball.twist.linear.x = 1.0;
  const auto rb = spawnObject(ball);
  ASSERT_TRUE(rb.success) << rb.message;

  const double t0 = fx->sim.step(0).sim_time;
  ASSERT_TRUE(fx->sim.step(300).success);
  const double t = fx->sim.step(0).sim_time - t0;
  EXPECT_NEAR(t, 0.3, 1e-9);
  const auto s = fx->sim.link("crate", "link");
  ASSERT_TRUE(s.success) << s.message;
  // Free fall from rest: z = 3 - g t^2 / 2 (the solver's semi-implicit steps: within 1 cm).
  const double z = 3.0 - 0.5 * kG * t * t;
  EXPECT_NEAR(position(s).z(), z, 0.01);
  EXPECT_NEAR(linear(s).z(), -kG * t, 0.02);
  const auto sb = fx->sim.link("ball", "link");
  ASSERT_TRUE(sb.success) << sb.message;
  EXPECT_NEAR(position(sb).x(), 4.0 + 1.0 * t, 1e-3);  // the initial twist
  // TF crate/link and ~link_states follow it down.
  EXPECT_TRUE(fx->waitFor([&] {
    auto it = fx->tf.find("crate/link");
    return it != fx->tf.end() && std::abs(it->second.z() - position(s).z()) < 1e-6;
  })) << "no TF crate/link at z " << position(s).z();
  EXPECT_TRUE(fx->waitFor([&] {
    const int i = fx->linkStateIndex("crate", "link");
    return i >= 0 && std::abs(fx->link_states.pose[size_t(i)].position.z - position(s).z()) < 1e-6 &&
           fx->link_states.twist[size_t(i)].linear.z < -2.0;
  })) << "~link_states has no falling crate";
}

TEST(Objects, B_StaticBoxHolds) {
  auto req = box("pedestal", Vec3(6, 0, 0.5), 1.0);
  req.is_static = true;
  req.mass = 0.0;
  const auto r = spawnObject(req);
  ASSERT_TRUE(r.success) << r.message;
  auto ball = box("ball2", Vec3(6, 0, 1.5));
  ball.shape = "sphere";
  ball.dimensions = {0.1};
  ASSERT_TRUE(spawnObject(ball).success);
  EXPECT_FALSE(fx->sim.link("pedestal", "link").success) << "a static object has no link state";
  ASSERT_TRUE(fx->sim.step(1500).success);
  // The ball rests on the static box's top (z = 1.0 + r), not on the ground (z = r).
  const auto s = fx->sim.link("ball2", "link");
  ASSERT_TRUE(s.success) << s.message;
  EXPECT_NEAR(position(s).z(), 1.1, 0.01);
  // Drawn, darker than neutral grey, where it was put; no TF.
  visualization_msgs::MarkerArray a;
  ASSERT_TRUE(fx->markers->waitFor([](const auto& m) { return hasNs(m, "pedestal"); }, &a,
                                   fx->markers->count()));
  const auto ms = MarkerLog::inNs(a, "pedestal");
  ASSERT_EQ(ms.size(), 1u);
  EXPECT_EQ(ms[0]->type, visualization_msgs::Marker::CUBE);
  EXPECT_NEAR(ms[0]->pose.position.z, 0.5, 1e-9);
  EXPECT_NEAR(ms[0]->scale.x, 1.0, 1e-9);
  EXPECT_LT(ms[0]->color.r, 0.5);
  EXPECT_NEAR(ms[0]->color.r, ms[0]->color.g, 1e-6);
  {
    std::lock_guard<std::mutex> lock(fx->mutex);
    EXPECT_EQ(fx->tf.count("pedestal/link"), 0u);
    EXPECT_FALSE(fx->hasObjectInLinkStates("pedestal"));
  }
  // The dynamic objects are neutral grey (no colour given), lighter than the static one.
  const auto crate = MarkerLog::inNs(a, "crate");
  ASSERT_EQ(crate.size(), 1u);
  EXPECT_GT(crate[0]->color.r, ms[0]->color.r);
}

TEST(Objects, C_Delete) {
  auto r = del("crate");
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_FALSE(fx->sim.link("crate", "link").success);
  ASSERT_TRUE(fx->sim.step(1).success);
  EXPECT_TRUE(fx->waitFor([&] {
    return !fx->link_states.ragdoll.empty() && !fx->hasObjectInLinkStates("crate") &&
           fx->hasObjectInLinkStates("ball");
  })) << "crate still in ~link_states";
  EXPECT_TRUE(fx->markers->waitFor(
      [](const auto& m) { return !hasNs(m, "crate") && hasNs(m, "ball"); }, nullptr,
      fx->markers->count()))
      << "crate still in ~markers";

  // A static object: its markers go, and the ball on it falls to the ground.
  r = del("pedestal");
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_TRUE(fx->markers->waitFor([](const auto& m) { return !hasNs(m, "pedestal") && hasNs(m, "ball2"); },
                                   nullptr, fx->markers->count()))
      << "pedestal still in ~markers";
  ASSERT_TRUE(fx->sim.step(1500).success);
  const auto s = fx->sim.link("ball2", "link");
  ASSERT_TRUE(s.success) << s.message;
  EXPECT_NEAR(position(s).z(), 0.1, 0.01);
  EXPECT_FALSE(del("pedestal").success);  // gone
  EXPECT_TRUE(del("ball2").success);
}

TEST(Objects, D_SpawnModelSdf) {
  ragdoll_sim::SpawnModel::Request req;
  req.name = "sdfbox";
  req.model_xml = kSdfBox;
  req.pose = poseAt(Vec3(8, 0, 3));
  const auto r = spawnModel(req);
  ASSERT_TRUE(r.success) << r.message;
  // <sdf><model> with the model's own name and <pose>, composed with the request's pose.
  req.name = "";
  req.model_xml = std::string("<sdf version='1.6'>") + kSdfBox + "</sdf>";
  req.model_xml.replace(req.model_xml.find("<link"), 0, "<pose>0 0 1 0 0 0</pose>");
  req.pose = poseAt(Vec3(8, 2, 2));
  const auto r2 = spawnModel(req);
  ASSERT_TRUE(r2.success) << r2.message;
  const auto s0 = fx->sim.link("sdf_box", "l");
  ASSERT_TRUE(s0.success) << s0.message;
  EXPECT_NEAR(position(s0).z(), 3.0, 1e-9);
  ASSERT_TRUE(fx->sim.step(300).success);
  const auto s = fx->sim.link("sdfbox", "l");
  ASSERT_TRUE(s.success) << s.message;
  EXPECT_NEAR(position(s).z(), 3.0 - 0.5 * kG * 0.09, 0.01);
  EXPECT_TRUE(fx->waitFor([&] { return fx->linkStateIndex("sdfbox", "l") >= 0; }));
  // Its SDF colour in rviz.
  visualization_msgs::MarkerArray a;
  ASSERT_TRUE(fx->markers->waitFor([](const auto& m) { return hasNs(m, "sdfbox"); }, &a,
                                   fx->markers->count()));
  const auto ms = MarkerLog::inNs(a, "sdfbox");
  ASSERT_EQ(ms.size(), 1u);
  EXPECT_NEAR(ms[0]->color.r, 1.0, 1e-6);
  EXPECT_NEAR(ms[0]->color.g, 0.0, 1e-6);
  EXPECT_TRUE(del("sdfbox").success);
  EXPECT_TRUE(del("sdf_box").success);
}

TEST(Objects, E_SpawnModelUrdfFile) {
  ragdoll_sim::SpawnModel::Request req;
  req.name = "pinned";
  req.model_file = pendulumUrdf();
  req.pose = poseAt(Vec3(10, 0, 2));
  req.fixed_base = true;
  auto r = spawnModel(req);
  ASSERT_TRUE(r.success) << r.message;
  req.name = "loose";
  req.pose = poseAt(Vec3(10, 3, 2));
  req.fixed_base = false;
  r = spawnModel(req);
  ASSERT_TRUE(r.success) << r.message;
  ASSERT_TRUE(fx->sim.step(300).success);
  const auto pinned = fx->sim.link("pinned", "base"), loose = fx->sim.link("loose", "base");
  ASSERT_TRUE(pinned.success) << pinned.message;
  ASSERT_TRUE(loose.success) << loose.message;
  EXPECT_LT((position(pinned) - Vec3(10, 0, 2)).norm(), 1e-6);
  EXPECT_NEAR(position(loose).z(), 2.0 - 0.5 * kG * 0.09, 0.01);
  EXPECT_TRUE(fx->waitFor([&] { return fx->tf.count("pinned/bar") > 0 && fx->tf.count("loose/base") > 0; }));
  EXPECT_TRUE(del("pinned").success);
  EXPECT_TRUE(del("loose").success);
}

TEST(Objects, F_SpawnFixedBaseRagdoll) {
  std::string root;
  const auto links = urdfLinks(&root);
  ASSERT_FALSE(root.empty());
  std::string urdf;
  ASSERT_TRUE(ros::param::get("/robot_description", urdf));
  ragdoll_sim::SpawnRagdoll s;
  s.request.name = "hung";
  s.request.urdf = urdf;
  s.request.pose = poseAt(Vec3(14, 0, 3));
  s.request.fixed_base = true;
  ASSERT_TRUE(ros::service::call(kNode + "/spawn", s));
  ASSERT_TRUE(s.response.success) << s.response.message;
  ASSERT_TRUE(fx->sim.step(500).success);
  const auto p = fx->sim.link("hung", root);
  ASSERT_TRUE(p.success) << p.message;
  EXPECT_LT((position(p) - Vec3(14, 0, 3)).norm(), 1e-6) << "the pinned root moved";
  EXPECT_TRUE(del("hung").success);
}

TEST(Objects, G_BadInputRefused) {
  ASSERT_TRUE(fx->sim.step(1).success);
  size_t entries = 0;
  // F's deleted "hung" may still be in a message sent before its deletion.
  ASSERT_TRUE(fx->waitFor([&] {
    return !fx->link_states.ragdoll.empty() && !fx->hasObjectInLinkStates("hung");
  }));
  {
    std::lock_guard<std::mutex> lock(fx->mutex);
    entries = fx->link_states.ragdoll.size();
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    std::string what;
    ragdoll_sim::SpawnObject::Request req;
    std::vector<std::string> words;
  };
  std::vector<Case> cases;
  const auto add = [&](const std::string& what, auto edit, std::vector<std::string> words) {
    Case c{what, box("bad", Vec3(0, 5, 1)), std::move(words)};
    edit(c.req);
    cases.push_back(std::move(c));
  };
  add("unknown shape", [](auto& r) { r.shape = "cone"; }, {"shape 'cone'", "box, sphere"});
  add("negative size", [](auto& r) { r.dimensions = {0.2, -1.0, 0.2}; }, {"dimensions[1]", "> 0", "-1"});
  add("zero radius", [](auto& r) { r.shape = "sphere"; r.dimensions = {0.0}; }, {"dimensions[0]", "radius"});
  add("wrong count", [](auto& r) { r.dimensions = {0.2, 0.2}; }, {"box takes 3"});
  add("negative mass", [](auto& r) { r.mass = -2.0; }, {"mass", "got -2"});
  add("no mass", [](auto& r) { r.mass = 0.0; }, {"mass > 0", "density > 0"});
  add("NaN mass", [&](auto& r) { r.mass = nan; }, {"mass", "nan"});
  add("NaN position", [&](auto& r) { r.pose.position.y = nan; }, {"position", "not finite"});
  add("NaN orientation", [&](auto& r) { r.pose.orientation.x = nan; }, {"orientation", "not finite"});
  add("NaN twist", [&](auto& r) { r.twist.angular.z = nan; }, {"twist is not finite"});
  add("static twist", [](auto& r) { r.is_static = true; r.twist.linear.x = 1; }, {"static", "twist"});
  add("duplicate name", [](auto& r) { r.name = "ball"; }, {"'ball'", "exists"});
  add("ragdoll's name", [](auto& r) { r.name = "ragdoll"; }, {"exists"});
  add("bad name", [](auto& r) { r.name = "bad/name"; }, {"bad/name"});
  add("bad material", [](auto& r) { r.material = "unobtainium"; }, {"material 'unobtainium'", "~materials"});
  for (const Case& c : cases) {
    const double t0 = fx->sim.step(0).sim_time;
    const auto r = spawnObject(c.req);
    EXPECT_FALSE(r.success) << c.what;
    for (const std::string& w : c.words)
      EXPECT_NE(r.message.find(w), std::string::npos) << c.what << ": " << r.message;
    EXPECT_NEAR(fx->sim.step(10).sim_time - t0, 10 * kDt, 1e-9) << c.what;
  }

  struct ModelCase {
    std::string what, xml, file;
    std::vector<std::string> words;
  };
  const std::vector<ModelCase> models = {
      {"not XML", "<model name='x'><link", "", {"not well-formed XML"}},
      {"not a model", "<world name='w'/>", "", {"<world>", "expected <robot>"}},
      {"SDF error", "<model name='m'><link name='l'><collision name='c'><geometry><box><size>1 -2 1"
                    "</size></box></geometry></collision></link></model>", "", {"SDF"}},
      {"SDF world", "<sdf version='1.7'><world name='w'/></sdf>", "", {"<world>", "~world_file"}},
      {"URDF error", "<robot name='r'><link name='a'/><joint name='j' type='fixed'><parent link='a'/>"
                     "<child link='nope'/></joint></robot>", "", {"URDF"}},
      {"missing file", "", "/nonexistent/model.sdf", {"/nonexistent/model.sdf"}},
      {"device file", "", "/dev/zero", {"/dev/zero", "not a regular file"}},
      {"nothing given", "", "", {"neither model_xml nor model_file"}},
      {"duplicate name", kSdfBox, "", {"'ball'", "exists"}},
  };
  for (const ModelCase& c : models) {
    ragdoll_sim::SpawnModel::Request req;
    req.name = c.what == "duplicate name" ? "ball" : "";
    req.model_xml = c.xml;
    req.model_file = c.file;
    req.pose = poseAt(Vec3(0, 5, 1));
    const double t0 = fx->sim.step(0).sim_time;
    const ros::WallTime w0 = ros::WallTime::now();
    const auto r = spawnModel(req);
    EXPECT_LT((ros::WallTime::now() - w0).toSec(), 5.0) << c.what;
    EXPECT_FALSE(r.success) << c.what;
    for (const std::string& w : c.words)
      EXPECT_NE(r.message.find(w), std::string::npos) << c.what << ": " << r.message;
    EXPECT_NEAR(fx->sim.step(10).sim_time - t0, 10 * kDt, 1e-9) << c.what;
  }
  const auto d = del("nobody");
  EXPECT_FALSE(d.success);
  EXPECT_NE(d.message.find("no ragdoll named 'nobody'"), std::string::npos) << d.message;

  // Nothing was added.
  ASSERT_TRUE(fx->sim.step(1).success);
  const size_t seen = fx->link_states_count;
  EXPECT_TRUE(fx->waitFor([&] { return fx->link_states_count > seen; }));
  std::lock_guard<std::mutex> lock(fx->mutex);
  EXPECT_EQ(fx->link_states.ragdoll.size(), entries);
  EXPECT_FALSE(fx->hasObjectInLinkStates("bad"));
}

TEST(Objects, I_SpawnModelSdfWeldedToWorld) {
  // A fixed joint to the world pins the welded link (the root) where the model puts it.
  std::string xml = kSdfBox;
  xml.replace(xml.rfind("</model>"), 0,
              "<joint name='weld' type='fixed'><parent>world</parent><child>l</child></joint>");
  ragdoll_sim::SpawnModel::Request req;
  req.name = "welded";
  req.model_xml = xml;
  req.pose = poseAt(Vec3(16, 0, 2));
  const auto r = spawnModel(req);
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_NE(r.message.find("fixed-base"), std::string::npos) << r.message;
  ASSERT_TRUE(fx->sim.step(300).success);
  const auto s = fx->sim.link("welded", "l");
  ASSERT_TRUE(s.success) << s.message;
  EXPECT_LT((position(s) - Vec3(16, 0, 2)).norm(), 1e-6);
  EXPECT_TRUE(del("welded").success);
}

TEST(Objects, H_MaterialTakesEffect) {
  // Two boxes sliding on the ground at 2 m/s: teflon goes far, rubber stops soon.
  std::map<std::string, double> slid;
  for (const std::string material : {"teflon", "rubber"}) {
    auto req = box("slider_" + material, Vec3(0, material == "teflon" ? -3 : -5, 0.1));
    req.material = material;
    req.twist.linear.x = 2.0;
    const auto r = spawnObject(req);
    ASSERT_TRUE(r.success) << r.message;
  }
  ASSERT_TRUE(fx->sim.step(2000).success);
  for (const std::string material : {"teflon", "rubber"}) {
    const auto s = fx->sim.link("slider_" + material, "link");
    ASSERT_TRUE(s.success) << s.message;
    slid[material] = position(s).x();
    EXPECT_TRUE(del("slider_" + material).success);
  }
  std::printf("[figure] 2 m/s slide on the ground: teflon %.3f m, rubber %.3f m\n", slid["teflon"],
              slid["rubber"]);
  EXPECT_GT(slid["teflon"], 1.0);
  EXPECT_LT(slid["rubber"], 0.6);
}

int main(int argc, char** argv) {
  return ragdoll_test::runFixtureTests(argc, argv, "objects_test", 2, fx);
}
