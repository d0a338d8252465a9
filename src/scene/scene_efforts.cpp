// Scene: joint loads and axis efforts of the last step, and joint effort commands
// (scene_reports.hpp).
//   - Signs: spawnRagdoll makes every RagdollDef joint's parent link the World joint's body A
//     and its child body B, so the World's wrench on B and its efforts (on B about +axis) are
//     the child's as they stand: what robot_state_publisher and ros_control read in
//     joint_states.effort.
//   - A commanded effort tau on an axis is a pair of torques tau a and -tau a on the child and
//     the parent about the axis's current world direction a (a ball's Euler axis: that revolute
//     joint of its chain at the current angles), or, on a prismatic axis, forces along it at
//     the child's anchor. It changes neither momentum nor angular momentum.
//   - Checked when applied, as target poses are; a bad command is rejected whole.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "names.hpp"
#include "scene_impl.hpp"

namespace ragdoll_sim {

using scene::ActiveEffort;
using scene::RagdollInstance;

namespace {

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

struct EffortCheck {
  std::string problem;  // "" when the command may be applied
  std::string error;
  std::vector<int> axes;  // per name: AxisTable index
};

// Rules: at least one name, one effort per name, every name an axis of the ragdoll and none
// twice, every effort finite and within max_torque (max_force on a prismatic axis), a duration
// that is finite or negative (until replaced or cleared).
EffortCheck checkJointEffort(const JointEffortCommand& cmd, const RagdollInstance& r,
                             const CommandLimits& limits) {
  EffortCheck c;
  auto fail = [&](const char* problem, const std::string& error) {
    c.problem = problem;
    c.error = error;
    return c;
  };
  const size_t n = cmd.names.size();
  if (n == 0) return fail("no names", "joint effort with no joint names");
  if (cmd.efforts.size() != n)
    return fail("efforts length", "joint effort has " + std::to_string(n) + " names but " +
                                      std::to_string(cmd.efforts.size()) +
                                      " efforts (one effort per name)");
  if (std::isnan(cmd.duration) || (std::isinf(cmd.duration) && cmd.duration > 0.0))
    return fail("duration not finite",
                "joint effort duration " + num(cmd.duration) +
                    " is not finite (use a negative duration for 'until replaced or cleared')");
  std::vector<bool> seen(static_cast<size_t>(r.axes.size()), false);
  for (size_t i = 0; i < n; ++i) {
    const std::string& name = cmd.names[i];
    const int a = r.axes.find(name);
    if (a < 0)
      return fail("unknown joint", "joint effort names " + scene::quoted(name) +
                                       ", not a joint of the ragdoll (names as in joint_states)");
    if (seen[static_cast<size_t>(a)])
      return fail("repeated joint", "joint effort names joint " + scene::quoted(name) + " twice");
    seen[static_cast<size_t>(a)] = true;
    const double e = cmd.efforts[i];
    if (!std::isfinite(e))
      return fail("effort not finite",
                  "joint effort of " + scene::quoted(name) + " is " + num(e) + ", not finite");
    const bool linear =
        r.def.joints[static_cast<size_t>(r.axes[a].joint)].kind == RagdollJointKind::Prismatic;
    const double cap = linear ? limits.max_force : limits.max_torque;
    if (std::abs(e) > cap)
      return fail(linear ? "above max_force" : "above max_torque",
                  "joint effort of " + scene::quoted(name) + " is " + num(e) +
                      (linear ? " N: |effort| exceeds max_force = " + num(cap) + " N"
                              : " N*m: |effort| exceeds max_torque = " + num(cap) + " N*m"));
    c.axes.push_back(a);
  }
  return c;
}

// World direction of axis k of RagdollDef joint `j` at the current pose (ball: the chain
// joint's axis, R = R(a0,t0) R(a1,t1) R(a2,t2) in the parent's joint frame).
Vec3 worldAxis(const World& world, const RagdollInstance& r, int j, int k) {
  const RagdollJointDef& jd = r.def.joints[static_cast<size_t>(j)];
  const size_t kk = static_cast<size_t>(k);
  Quat q = world.bodyPose(r.ragdoll.bodies[static_cast<size_t>(jd.parent)]).q * jd.frame_parent.q;
  if (jd.kind == RagdollJointKind::Ball) {
    const std::array<double, 3> t = world.ballAngles(r.ragdoll.joints[static_cast<size_t>(j)]);
    for (size_t i = 0; i < kk && i < jd.axes.size(); ++i)
      q = q * Quat(Eigen::AngleAxisd(t[i], jd.axes[i].normalized()));
  }
  const Vec3 fallback = jd.kind == RagdollJointKind::Prismatic ? Vec3::UnitX() : Vec3::UnitZ();
  return q * (kk < jd.axes.size() ? jd.axes[kk].normalized() : fallback);
}

bool spawned(const World* world, const RagdollInstance& r) {
  return world && r.ragdoll.joints.size() == r.def.joints.size() &&
         r.ragdoll.bodies.size() == r.def.links.size();
}

// RagdollDef joint j's axis efforts in the last step into e (motor + limit from the World,
// plus the commanded efforts, which acted in it); returns its axis count.
int axisEfforts(const World& world, const RagdollInstance& r, int j, double e[3]) {
  const JointId id = r.ragdoll.joints[static_cast<size_t>(j)];
  const int count = std::min(r.axes.count(j), 3);
  const int n = std::min(world.jointAxisEfforts(id, e), count);
  for (int i = n; i < count; ++i) e[i] = 0.0;
  if (world.isJointBroken(id)) return count;
  const int first = r.axes.first(j);
  for (const ActiveEffort& a : r.efforts)
    if (a.axis >= first && a.axis < first + count) e[a.axis - first] += a.effort;
  return count;
}

}  // namespace

bool Scene::Impl::applyJointEffort(RagdollInstance& r, const JointEffortCommand& cmd) {
  const EffortCheck check = checkJointEffort(cmd, r, def.limits);
  if (!check.problem.empty()) {
    warn("joint effort/" + check.problem,
         check.error + " (ragdoll '" + r.name + "'); joint effort dropped");
    return false;
  }
  const int64_t steps = scene::forceStepCount(cmd.duration, dt);
  for (size_t i = 0; i < check.axes.size(); ++i) {
    const ActiveEffort e{check.axes[i], cmd.efforts[i], steps};
    auto it = std::find_if(r.efforts.begin(), r.efforts.end(),
                           [&](const ActiveEffort& a) { return a.axis == e.axis; });
    if (it != r.efforts.end()) *it = e;
    else r.efforts.push_back(e);
  }
  debug(scene::format("joint effort on %zu axis(es) of '%s' for %lld steps", check.axes.size(),
                      r.name.c_str(), static_cast<long long>(steps)));
  return true;
}

void Scene::Impl::applyActiveEfforts(RagdollInstance& r) {
  if (r.efforts.empty()) return;
  // Those that acted for the last time in the previous step end now.
  r.efforts.erase(std::remove_if(r.efforts.begin(), r.efforts.end(),
                                 [](const ActiveEffort& e) { return e.steps_left == 0; }),
                  r.efforts.end());
  if (!spawned(world.get(), r)) return;
  for (ActiveEffort& e : r.efforts) {
    if (e.steps_left > 0) --e.steps_left;
    const scene::AxisInfo& info = r.axes[e.axis];
    const RagdollJointDef& jd = r.def.joints[static_cast<size_t>(info.joint)];
    if (world->isJointBroken(r.ragdoll.joints[static_cast<size_t>(info.joint)])) continue;
    const BodyId parent = r.ragdoll.bodies[static_cast<size_t>(jd.parent)];
    const BodyId child = r.ragdoll.bodies[static_cast<size_t>(jd.child)];
    const Vec3 a = worldAxis(*world, r, info.joint, info.axis);
    if (jd.kind == RagdollJointKind::Prismatic) {
      const Vec3 at = world->bodyPose(child).apply(jd.frame_child.p);
      world->applyForce(child, e.effort * a, at);
      world->applyForce(parent, -e.effort * a, at);
    } else {
      world->applyTorque(child, e.effort * a);
      world->applyTorque(parent, -e.effort * a);
    }
  }
}

size_t Scene::Impl::activeEffortCount() const {
  size_t n = 0;
  for (const RagdollInstance& r : ragdolls)
    n += static_cast<size_t>(std::count_if(r.efforts.begin(), r.efforts.end(),
                                           [](const ActiveEffort& e) { return e.steps_left != 0; }));
  return n;
}

size_t Scene::activeEffortCount() const { return impl_->activeEffortCount(); }

void Scene::jointEfforts(int k, std::vector<double>& out) const {
  const RagdollInstance& r = impl_->ragdolls.at(static_cast<size_t>(k));
  out.assign(r.axis_names.size(), 0.0);
  const World* world = impl_->world.get();
  if (!spawned(world, r)) return;
  for (size_t j = 0; j < r.def.joints.size(); ++j) {
    double e[3];
    const int n = axisEfforts(*world, r, static_cast<int>(j), e);
    const int first = r.axes.first(static_cast<int>(j));
    for (int i = 0; i < n; ++i) out[static_cast<size_t>(first + i)] = e[i];
  }
}

void Scene::linkLoads(int k, std::vector<LinkLoad>& links) const {
  const RagdollInstance& r = impl_->ragdolls.at(static_cast<size_t>(k));
  links.assign(r.def.links.size(), LinkLoad());
  const World* world = impl_->world.get();
  if (!spawned(world, r)) return;
  std::vector<ContactReport>& reports = impl_->contact_scratch;
  world->contactReports(reports);
  auto linkOf = [&](BodyId b) {
    for (size_t l = 0; l < r.ragdoll.bodies.size(); ++l)
      if (r.ragdoll.bodies[l] == b) return static_cast<int>(l);
    return -1;
  };
  for (const ContactReport& c : reports) {
    const int la = linkOf(c.body_a), lb = linkOf(c.body_b);
    if (la >= 0) {
      links[static_cast<size_t>(la)].contact_force += c.force_a;
      links[static_cast<size_t>(la)].contact_torque += c.torque_a;
    }
    if (lb >= 0) {
      links[static_cast<size_t>(lb)].contact_force += c.force_b;
      links[static_cast<size_t>(lb)].contact_torque += c.torque_b;
    }
  }
}

void Scene::loads(int k, std::vector<LinkLoad>& links, std::vector<JointLoad>& joints) const {
  linkLoads(k, links);
  const RagdollInstance& r = impl_->ragdolls.at(static_cast<size_t>(k));
  joints.assign(r.def.joints.size(), JointLoad());
  const World* world = impl_->world.get();
  if (!spawned(world, r)) return;
  for (size_t j = 0; j < r.def.joints.size(); ++j) {
    JointLoad& load = joints[j];
    load.wrench = world->jointWrench(r.ragdoll.joints[j]);
    load.axes = axisEfforts(*world, r, static_cast<int>(j), load.effort);
  }
}

}  // namespace ragdoll_sim
