// rostest: the reports of the last step on their topics. The bundled ragdoll lies at rest on
// the ground: ~contacts' normal forces on it sum to its weight within 0.5 %, its pairs are
// named "ragdoll/<link>" and "ground", and messages come at ~contacts/rate (100 Hz of sim
// time: stamps 0.01 s apart); ~link_loads carries every link and joint and the same weight;
// joint_states has one finite effort per joint. Dropped onto the ground it makes ~impacts
// events; ~injury/reset answers with the record of the drop and publishes it on ~injury.
// A spawned model without that head link gets a WARN naming it. Tests run in order and
// share one node.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <set>

#include <ragdoll_sim/ContactsState.h>
#include <ragdoll_sim/Impact.h>
#include <ragdoll_sim/Injury.h>
#include <ragdoll_sim/LinkLoads.h>
#include <ragdoll_sim/ResetInjury.h>
#include <ragdoll_sim/SetRagdollState.h>
#include <ragdoll_sim/SpawnRagdoll.h>
#include <sensor_msgs/JointState.h>

#include "node_log.hpp"
#include "sim_client.hpp"

using namespace ragdoll_test;

namespace {

const std::string kNode = "/ragdoll_sim";
const std::string kRagdoll = "ragdoll";

// Everything received on one topic, under a lock.
template <class M>
struct Inbox {
  std::mutex mutex;
  std::vector<M> msgs;
  ros::Subscriber sub;
  void start(ros::NodeHandle& nh, const std::string& topic) {
    sub = nh.subscribe<M>(topic, 1000, [this](const typename M::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex);
      msgs.push_back(*m);
    });
  }
  std::vector<M> take() {
    std::lock_guard<std::mutex> lock(mutex);
    std::vector<M> out;
    out.swap(msgs);
    return out;
  }
  // Waits (wall clock) until at least `count` messages arrived; returns them all.
  std::vector<M> wait(double timeout = 10.0, size_t count = 1) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < deadline) {
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (msgs.size() >= count) break;
      }
      ros::WallDuration(0.01).sleep();
    }
    return take();
  }
};

struct Fixture {
  ros::NodeHandle nh;
  SimClient sim{kNode};
  Inbox<ragdoll_sim::ContactsState> contacts;
  Inbox<ragdoll_sim::LinkLoads> loads;
  Inbox<ragdoll_sim::Impact> impacts;
  Inbox<ragdoll_sim::Injury> injury;
  Inbox<sensor_msgs::JointState> joints;
  double mass = 0.0;
  std::set<std::string> links;

  void init() {
    for (const LinkMass& l : urdfLinks()) {
      mass += l.mass;
      links.insert(l.name);
    }
  }
};

Fixture* fx = nullptr;
constexpr double kG = 9.81;  // config/sim.yaml

bool isRagdoll(const std::string& body) { return body.rfind(kRagdoll + "/", 0) == 0; }

// Vertical force of the ground and other bodies on the ragdoll, from one ~contacts message.
double liftOnRagdoll(const ragdoll_sim::ContactsState& m, std::string* bad_name) {
  double fz = 0.0;
  for (const ragdoll_sim::ContactState& s : m.states) {
    const bool r1 = isRagdoll(s.collision1_name), r2 = isRagdoll(s.collision2_name);
    for (const std::string& n : {s.collision1_name, s.collision2_name})
      if (!(n == "ground" || (isRagdoll(n) && fx->links.count(n.substr(kRagdoll.size() + 1)))))
        *bad_name = n;
    if (r1 == r2) continue;  // a pair within the ragdoll carries nothing from outside
    EXPECT_EQ(s.normal_forces.size(), s.contact_positions.size());
    EXPECT_EQ(s.depths.size(), s.contact_positions.size());
    EXPECT_EQ(s.wrenches.size(), s.contact_positions.size());
    double on2 = 0.0;  // z of the force on body 2
    for (size_t i = 0; i < s.normal_forces.size(); ++i)
      on2 += s.normal_forces[i] * s.contact_normals[i].z + s.friction_forces[i].z;
    fz += r2 ? on2 : -on2;
    // wrench1 and wrench2 are equal and opposite
    EXPECT_NEAR(s.wrench1.force.z, -s.wrench2.force.z, 1e-6 * m.states.size() + 1e-9);
  }
  return fz;
}

}  // namespace

TEST(Reports, A_RestingRagdollCarriesItsWeightOnContacts) {
  ASSERT_TRUE(fx->sim.waitUp()) << "node did not come up";
  ASSERT_GT(fx->mass, 10.0);
  fx->contacts.start(fx->nh, kNode + "/contacts");
  fx->loads.start(fx->nh, kNode + "/link_loads");
  fx->impacts.start(fx->nh, kNode + "/impacts");
  fx->injury.start(fx->nh, kNode + "/injury");
  fx->joints.start(fx->nh, "/joint_states");
  ASSERT_TRUE(waitConnected(fx->contacts.sub));
  ASSERT_TRUE(waitConnected(fx->impacts.sub));
  ros::WallDuration(0.3).sleep();  // a publish cycle counts the subscribers
  ASSERT_TRUE(fx->sim.step(2000).success);  // 2 s: settled
  ros::WallDuration(0.5).sleep();  // the messages of those steps arrived
  fx->contacts.take();
  fx->loads.take();
  const double t0 = fx->sim.step(0).sim_time;
  const ragdoll_sim::Step::Response r = fx->sim.step(200);
  ASSERT_TRUE(r.success);
  // ~contacts/rate 100 Hz over 0.2 s of sim time: 20 messages 0.01 s apart (a loaded machine
  // delivers them late, not fewer), then a moment for any beyond them; one of the steps before
  // that arrived late is not counted.
  std::vector<ragdoll_sim::ContactsState> msgs = fx->contacts.wait(10.0, 20);
  ros::WallDuration(0.3).sleep();
  for (ragdoll_sim::ContactsState& m : fx->contacts.take()) msgs.push_back(std::move(m));
  msgs.erase(std::remove_if(msgs.begin(), msgs.end(),
                            [&](const auto& m) { return m.header.stamp.toSec() <= t0; }),
             msgs.end());
  ASSERT_GE(msgs.size(), 19u);
  EXPECT_LE(msgs.size(), 21u);
  for (size_t i = 1; i < msgs.size(); ++i)
    EXPECT_NEAR((msgs[i].header.stamp - msgs[i - 1].header.stamp).toSec(), 0.01, 1e-6) << i;
  // Each message holds the last substep's forces, which a body settling on several points
  // shares out a little differently from substep to substep; their mean over the 0.2 s is
  // the weight.
  double worst = 0.0, last = 0.0, sum = 0.0;
  for (const ragdoll_sim::ContactsState& m : msgs) {
    ASSERT_FALSE(m.states.empty());
    std::string bad;
    last = liftOnRagdoll(m, &bad);
    sum += last;
    EXPECT_TRUE(bad.empty()) << "unknown body name '" << bad << "'";
    worst = std::max(worst, std::abs(last / (fx->mass * kG) - 1.0));
  }
  const double mean = sum / msgs.size();
  EXPECT_LT(std::abs(mean / (fx->mass * kG) - 1.0), 0.005)
      << "mean summed normal force " << mean << " N, weight " << fx->mass * kG << " N";
  EXPECT_LT(worst, 0.01) << "summed normal force " << last << " N, weight " << fx->mass * kG << " N";
  std::printf("[ contacts ] %zu messages in 0.2 s of sim time; mean lift %.3f N, last %.3f N for "
              "weight %.3f N (worst %.3f %%), %zu pairs\n", msgs.size(), mean, last,
              fx->mass * kG, 100 * worst, msgs.back().states.size());
}

TEST(Reports, B_LinkLoadsAndJointEfforts) {
  const std::vector<ragdoll_sim::LinkLoads> loads = fx->loads.wait();
  ASSERT_FALSE(loads.empty()) << "no ~link_loads";
  const ragdoll_sim::LinkLoads& m = loads.back();
  ASSERT_EQ(m.link.size(), m.link_ragdoll.size());
  ASSERT_EQ(m.link.size(), m.contact_wrench.size());
  ASSERT_EQ(m.joint.size(), m.joint_wrench.size());
  ASSERT_EQ(m.joint.size(), m.joint_child.size());
  EXPECT_GE(m.link.size(), 10u);
  EXPECT_GE(m.joint.size(), 9u);
  double fz = 0.0;
  for (size_t i = 0; i < m.link.size(); ++i) {
    EXPECT_EQ(m.link_ragdoll[i], kRagdoll);
    EXPECT_TRUE(fx->links.count(m.link[i])) << m.link[i];
    fz += m.contact_wrench[i].force.z;
  }
  EXPECT_NEAR(fz, fx->mass * kG, 0.005 * fx->mass * kG);
  double neck = 0.0;
  for (size_t j = 0; j < m.joint.size(); ++j) {
    const geometry_msgs::Vector3& f = m.joint_wrench[j].force;
    EXPECT_TRUE(std::isfinite(f.x) && std::isfinite(f.y) && std::isfinite(f.z)) << m.joint[j];
    if (m.joint_child[j] == "head") neck = std::hypot(f.x, f.y, f.z);
  }
  EXPECT_GT(neck, 0.0) << "the neck holds nothing";

  fx->joints.take();
  ASSERT_TRUE(fx->sim.step(5).success);  // joint_states go out when the sim advanced
  const std::vector<sensor_msgs::JointState> js = fx->joints.wait();
  ASSERT_FALSE(js.empty()) << "no /joint_states";
  const sensor_msgs::JointState& s = js.back();
  ASSERT_EQ(s.effort.size(), s.name.size());
  double sum = 0.0;
  for (size_t i = 0; i < s.effort.size(); ++i) {
    EXPECT_TRUE(std::isfinite(s.effort[i])) << s.name[i];
    sum += std::abs(s.effort[i]);
  }
  std::printf("[ loads    ] %zu links carry %.3f N up; %zu joints, neck %.3f N; %zu efforts, "
              "sum |effort| %.3f\n", m.link.size(), fz, m.joint.size(), neck, s.effort.size(), sum);
}

TEST(Reports, C_DropMakesImpactsAndInjuryRecord) {
  fx->impacts.take();
  // Lying, 0.5 m up, falling at 3 m/s.
  ragdoll_sim::SetRagdollState set;
  set.request.ragdoll = kRagdoll;
  const ragdoll_sim::GetLinkState::Response pelvis = fx->sim.link(kRagdoll, "pelvis");
  ASSERT_TRUE(pelvis.success) << pelvis.message;
  set.request.pose = pelvis.pose;
  set.request.pose.position.z += 0.5;
  set.request.twist.linear.z = -3.0;
  ASSERT_TRUE(ros::service::call(kNode + "/set_ragdoll_state", set));
  ASSERT_TRUE(set.response.success) << set.response.message;
  ASSERT_TRUE(fx->sim.step(500).success);
  const std::vector<ragdoll_sim::Impact> events = fx->impacts.wait();
  ASSERT_FALSE(events.empty()) << "no ~impacts event for a drop at 3 m/s";
  const ragdoll_sim::Impact* hardest = &events.front();
  for (const ragdoll_sim::Impact& e : events) {
    EXPECT_EQ(e.ragdoll, kRagdoll);
    EXPECT_TRUE(fx->links.count(e.link)) << e.link;
    EXPECT_TRUE(std::isfinite(e.impulse) && std::isfinite(e.closing_speed) &&
                std::isfinite(e.peak_force) && std::isfinite(e.separating_speed));
    if (e.closing_speed > hardest->closing_speed) hardest = &e;
  }
  EXPECT_EQ(hardest->other, "ground");
  // sqrt(3^2 + 2 g 0.5) = 4.4 m/s at most (a link's speed, not the ragdoll's)
  EXPECT_GT(hardest->closing_speed, 2.5);
  EXPECT_LT(hardest->closing_speed, 5.0);
  EXPECT_NEAR(hardest->normal.z, 1.0, 0.05);
  std::printf("[ impacts  ] %zu events; hardest '%s' on '%s' at %.3f m/s, %.3f N s, peak %.0f N\n",
              events.size(), hardest->link.c_str(), hardest->other.c_str(),
              hardest->closing_speed, hardest->impulse, hardest->peak_force);

  fx->injury.take();
  ragdoll_sim::ResetInjury reset;
  reset.request.ragdoll = kRagdoll;
  ASSERT_TRUE(ros::service::call(kNode + "/injury/reset", reset));
  ASSERT_TRUE(reset.response.success) << reset.response.message;
  const ragdoll_sim::Injury& a = reset.response.injury;
  EXPECT_EQ(a.ragdoll, kRagdoll);
  EXPECT_EQ(a.head_link, "head");
  EXPECT_EQ(a.reason, "reset");
  for (double v : {a.start_time, a.end_time, a.peak_g, a.peak_time, a.hic15, a.hic15_t1,
                   a.hic15_t2, a.hic36, a.hic36_t1, a.hic36_t2, a.peak_angular_acceleration,
                   a.peak_neck_force, a.peak_neck_torque})
    EXPECT_TRUE(std::isfinite(v) && v >= 0.0) << v;
  EXPECT_GT(a.peak_g, 1.5) << "the head hit the ground at about 4 m/s";
  EXPECT_GE(a.hic36, a.hic15);
  const std::vector<ragdoll_sim::Injury> published = fx->injury.wait();
  ASSERT_FALSE(published.empty()) << "~injury/reset published nothing on ~injury";
  EXPECT_EQ(published.back().reason, "reset");
  EXPECT_DOUBLE_EQ(published.back().hic15, a.hic15);
  std::printf("[ injury   ] %s\n", reset.response.message.c_str());

  ragdoll_sim::ResetInjury unknown;
  unknown.request.ragdoll = "nobody";
  ASSERT_TRUE(ros::service::call(kNode + "/injury/reset", unknown));
  EXPECT_FALSE(unknown.response.success);
  EXPECT_NE(unknown.response.message.find("nobody"), std::string::npos);
}

TEST(Reports, D_HeadLinkAModelLacksIsNamed) {
  // ~injury/head_link 'head' does not fit the pendulum: a WARN names both.
  NodeWarnings warnings(fx->nh, kNode);
  ros::WallDuration(0.5).sleep();  // connected to /rosout
  ragdoll_sim::SpawnRagdoll spawn;
  spawn.request.name = "pend";
  spawn.request.urdf_file = std::string(RAGDOLL_SIM_SOURCE_DIR) + "/urdf/pendulum.urdf";
  spawn.request.pose.position.x = 3.0;
  spawn.request.pose.position.z = 2.0;
  spawn.request.fixed_base = true;
  ASSERT_TRUE(ros::service::call(kNode + "/spawn", spawn));
  ASSERT_TRUE(spawn.response.success) << spawn.response.message;
  EXPECT_TRUE(warnings.wait({"~injury/head_link", "'head'", "'pend'"}, 5.0))
      << "no WARN naming the head link the pendulum lacks";
  ASSERT_TRUE(fx->sim.step(10).success);
}

int main(int argc, char** argv) { return runFixtureTests(argc, argv, "reports_test", 2, fx); }
