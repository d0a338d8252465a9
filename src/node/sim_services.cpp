// SimNode: services and dynamic_reconfigure.
#include <cmath>
#include <fstream>
#include <sstream>

#include "ragdoll_sim/urdf_loader.hpp"
#include "msg_convert.hpp"
#include "sim_node.hpp"

namespace ragdoll_sim {
namespace node {

namespace {

// How far a quaternion's length may be from 1 and still be taken (normalized): hand-typed
// values rounded to 3 digits, e.g. (0.707, 0, 0, 0.707), pass; a rotation vector or a
// half-filled message does not.
constexpr double kUnitQuatTolerance = 0.01;

// A pose from a message, or "" and the error naming the problem (*problem: its throttle key):
// position finite and within max_position of the origin; orientation finite and a unit
// quaternion within kUnitQuatTolerance (normalized then), or all zeros, which means identity
// (an unset Pose, e.g. rosservice call without an orientation).
std::string poseFromMsg(const geometry_msgs::Pose& m, double max_position, Transform* t,
                        std::string* problem) {
  const Vec3 p(m.position.x, m.position.y, m.position.z);
  Quat q(m.orientation.w, m.orientation.x, m.orientation.y, m.orientation.z);
  std::ostringstream e;
  const double n = q.norm();
  if (!p.allFinite()) {
    *problem = "position not finite";
    e << "the position (" << p.x() << ", " << p.y() << ", " << p.z() << ") is not finite";
  } else if (p.norm() > max_position) {
    *problem = "position above cap";
    e << "the position (" << p.x() << ", " << p.y() << ", " << p.z() << ") is " << p.norm()
      << " m from the origin, more than ~max_position = " << max_position << " m";
  } else if (!q.coeffs().allFinite()) {
    *problem = "orientation not finite";
    e << "the orientation is not finite";
  } else if (n == 0.0) {
    q = Quat::Identity();
  } else if (std::abs(n - 1.0) > kUnitQuatTolerance) {
    *problem = "orientation not unit";
    e << "the orientation (w " << q.w() << ", x " << q.x() << ", y " << q.y() << ", z " << q.z()
      << ") has length " << n << ", not a unit quaternion (within " << kUnitQuatTolerance
      << "; all zeros = identity)";
  }
  if (!e.str().empty()) return e.str();
  *t = Transform(p, q.normalized());
  return "";
}

}  // namespace

template <class Res>
bool SimNode::refuse(Res& res, const std::string& kind, const std::string& message) {
  res.success = false;
  res.message = message;
  warn(kind, message);
  return true;  // the call itself worked; success says what happened
}

bool SimNode::onSetBalance(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res) {
  res.success = true;
  res.message = req.data ? "balance on" : "balance off";
  for (RagdollInstance& r : ragdolls_) {
    setBalance(r, req.data, /*log=*/true);
    if (r.balance && !r.balance->missing().empty()) {
      res.message += "; '" + r.name + "': joints hold the pose, but the balance law is off: missing";
      for (const std::string& m : r.balance->missing()) res.message += " " + m;
    }
  }
  ROS_INFO("%s at sim time %.3f s", res.message.c_str(), simTime());
  return true;
}

bool SimNode::onClearTargets(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  for (RagdollInstance& r : ragdolls_) {
    r.targets.assign(r.targets.size(), AxisTarget());
    r.moving_targets.clear();
    applyAllMotors(r);
  }
  ROS_INFO("joint targets cleared at sim time %.3f s", simTime());
  return true;
}

bool SimNode::onPause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  paused_ = true;
  ROS_INFO("paused at sim time %.3f s", simTime());
  return true;
}

bool SimNode::onUnpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  paused_ = false;
  ROS_INFO("unpaused at sim time %.3f s", simTime());
  return true;
}

bool SimNode::onReset(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  resetAll();
  ROS_INFO("%zu ragdoll(s) reset to their spawn poses at sim time %.3f s", ragdolls_.size(),
           simTime());
  return true;
}

bool SimNode::onClearForces(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  ROS_INFO("cleared %zu active force(s)", activeForceCount());
  for (RagdollInstance& r : ragdolls_) r.forces.clear();
  visualizer_->endForces(simTime());
  return true;
}

bool SimNode::onStep(ragdoll_sim::Step::Request& req, ragdoll_sim::Step::Response& res) {
  if (req.steps > static_cast<uint32_t>(config_.max_steps_per_call)) {
    refuse(res, "step/too many", "step rejected: " + std::to_string(req.steps) +
                                     " steps exceed ~max_steps_per_call = " +
                                     std::to_string(config_.max_steps_per_call));
  } else if (!paused_) {
    res.success = false;
    res.message = "the simulation is running; call ~pause first";
  } else {
    for (uint32_t i = 0; i < req.steps && ros::ok(); ++i) stepOnce();
    res.success = true;
    res.message = "stepped " + std::to_string(req.steps) + " step(s)";
  }
  res.sim_time = simTime();
  res.pending_commands = static_cast<uint32_t>(queue_.size());
  res.awake_bodies = static_cast<uint32_t>(world_->awakeBodyCount());
  res.resting_bodies = static_cast<uint32_t>(world_->islandCounters().resting_bodies);
  return true;
}

bool SimNode::onSpawn(ragdoll_sim::SpawnRagdoll::Request& req,
                      ragdoll_sim::SpawnRagdoll::Response& res) {
  const std::string what = "spawn '" + req.name + "' rejected: ";
  std::string e = ragdollNameError(req.name);
  if (!e.empty()) return refuse(res, "spawn/bad name", what + e);
  if (findRagdoll(req.name) >= 0)
    return refuse(res, "spawn/name in use", what + "a ragdoll of that name exists");
  const std::string prefix = req.tf_prefix.empty() ? req.name : req.tf_prefix;
  for (const RagdollInstance& r : ragdolls_)
    if (r.tf_prefix == prefix)
      return refuse(res, "spawn/prefix in use",
                    what + "ragdoll '" + r.name + "' already has TF prefix '" + prefix + "'");
  Transform pose;
  std::string problem;
  e = poseFromMsg(req.pose, config_.max_position, &pose, &problem);
  if (!e.empty()) return refuse(res, "spawn/" + problem, what + e);
  UrdfLoadResult loaded;
  std::string xml = req.urdf;
  if (!xml.empty()) {
    loaded = loadUrdfString(xml);
  } else if (!req.urdf_file.empty()) {
    loaded = loadUrdfFile(req.urdf_file);
    if (loaded.ok) {
      std::ifstream in(req.urdf_file);
      std::stringstream s;
      s << in.rdbuf();
      xml = s.str();
    }
  } else {
    return refuse(res, "spawn/no urdf", what + "neither urdf nor urdf_file is set");
  }
  if (!loaded.ok)
    return refuse(res, "spawn/bad urdf", what + "failed to load the URDF: " + loaded.error);

  RagdollInstance r;
  if (!makeInstance(std::move(loaded.def), req.name, prefix, pose, /*warn_unknown_joints=*/false,
                    &r, &e))
    return refuse(res, "spawn/bad model", what + e);
  r.balance_on = false;
  r.spawned = true;
  const std::string ns = nh_.resolveName(req.name);
  r.joint_states_pub = nh_.advertise<sensor_msgs::JointState>(req.name + "/joint_states", 10);
  ragdolls_.push_back(std::move(r));
  RagdollInstance& added = ragdolls_.back();
  if (!spawnInWorld(added, &e)) {
    // The bodies it did create stay in the World: rebuild it without them.
    ragdolls_.pop_back();
    std::string ignored;
    buildWorld(/*carry_state=*/true, &ignored);
    structureChanged();
    return refuse(res, "spawn/failed", what + e);
  }
  rebindControllers();  // the vector may have moved the instances
  applyAllMotors(added);
  nh_.setParam(req.name + "/robot_description", xml);
  structureChanged();
  res.success = true;
  std::ostringstream msg;
  msg << "spawned '" << req.name << "' (" << added.def.links.size() << " links, "
      << added.def.joints.size() << " joints, " << added.def.totalMass() << " kg) at ("
      << pose.p.x() << ", " << pose.p.y() << ", " << pose.p.z() << "), TF prefix '" << prefix
      << "', joint_states on " << ns << "/joint_states, at sim time " << simTime() << " s";
  res.message = msg.str();
  ROS_INFO("%s", res.message.c_str());
  return true;
}

bool SimNode::onDelete(ragdoll_sim::DeleteRagdoll::Request& req,
                       ragdoll_sim::DeleteRagdoll::Response& res) {
  const int k = req.name.empty() ? -1 : findRagdoll(req.name);
  if (k < 0)
    return refuse(res, "delete/unknown ragdoll",
                  "delete rejected: no ragdoll named '" + req.name + "'");
  const bool spawned = ragdolls_[static_cast<size_t>(k)].spawned;
  // The World has no destroy API: rebuild it from the others, carrying their state over.
  ragdolls_.erase(ragdolls_.begin() + k);
  std::string e;
  if (!buildWorld(/*carry_state=*/true, &e)) {
    res.success = false;
    res.message = "delete: rebuilding the world failed: " + e;
    ROS_ERROR("%s", res.message.c_str());
    return true;
  }
  if (spawned) nh_.deleteParam(req.name + "/robot_description");
  markers_delete_all_ = true;
  structureChanged();
  res.success = true;
  res.message = "deleted '" + req.name + "' at sim time " + std::to_string(simTime()) + " s; " +
                std::to_string(ragdolls_.size()) + " ragdoll(s) left";
  ROS_INFO("%s", res.message.c_str());
  return true;
}

bool SimNode::onSetState(ragdoll_sim::SetRagdollState::Request& req,
                         ragdoll_sim::SetRagdollState::Response& res) {
  const int k = findRagdoll(req.ragdoll);
  if (k < 0)
    return refuse(res, "set_ragdoll_state/unknown ragdoll",
                  "set_ragdoll_state rejected: no ragdoll named '" + req.ragdoll + "'");
  Transform target;
  std::string problem;
  const std::string e = poseFromMsg(req.pose, config_.max_position, &target, &problem);
  if (!e.empty())
    return refuse(res, "set_ragdoll_state/" + problem, "set_ragdoll_state rejected: " + e);
  const Vec3 v(req.twist.linear.x, req.twist.linear.y, req.twist.linear.z);
  const Vec3 w(req.twist.angular.x, req.twist.angular.y, req.twist.angular.z);
  if (!v.allFinite() || !w.allFinite())
    return refuse(res, "set_ragdoll_state/bad twist",
                  "set_ragdoll_state rejected: the twist is not finite");
  if (v.norm() > config_.max_linear_speed || w.norm() > config_.max_angular_speed) {
    std::ostringstream m;
    m << "set_ragdoll_state rejected: |linear| = " << v.norm() << " m/s or |angular| = "
      << w.norm() << " rad/s exceeds ~max_linear_speed = " << config_.max_linear_speed
      << " m/s / ~max_angular_speed = " << config_.max_angular_speed << " rad/s";
    return refuse(res, "set_ragdoll_state/twist above cap", m.str());
  }
  RagdollInstance& r = ragdolls_[static_cast<size_t>(k)];
  const BodyId root = r.ragdoll.bodies[static_cast<size_t>(r.def.root)];
  // Rigid move: every link keeps its pose relative to the root link.
  const Transform move = target * world_->bodyPose(root).inverse();
  std::vector<Transform> poses;
  for (BodyId b : r.ragdoll.bodies) poses.push_back(move * world_->bodyPose(b));
  for (size_t i = 0; i < r.ragdoll.bodies.size(); ++i) {
    const BodyId b = r.ragdoll.bodies[i];
    const Vec3 com = poses[i].apply(world_->bodyDef(b).com);
    world_->setBodyState(b, poses[i], v + w.cross(com - target.p), w);
  }
  res.success = true;
  res.message = "moved '" + r.name + "'";
  ROS_INFO("set_ragdoll_state: '%s' root at (%.3f, %.3f, %.3f), v (%.3f, %.3f, %.3f), "
           "w (%.3f, %.3f, %.3f) at sim time %.3f s", r.name.c_str(), target.p.x(), target.p.y(),
           target.p.z(), v.x(), v.y(), v.z(), w.x(), w.y(), w.z(), simTime());
  return true;
}

bool SimNode::onGetLinkState(ragdoll_sim::GetLinkState::Request& req,
                             ragdoll_sim::GetLinkState::Response& res) {
  res.sim_time = simTime();
  const int k = findRagdoll(req.ragdoll);
  if (k < 0)
    return refuse(res, "get_link_state/unknown ragdoll",
                  "get_link_state: no ragdoll named '" + req.ragdoll + "'");
  const RagdollInstance& r = ragdolls_[static_cast<size_t>(k)];
  const int link = r.links.find(req.link);
  if (link < 0)
    return refuse(res, "get_link_state/unknown link",
                  "get_link_state: ragdoll '" + r.name + "' has no simulated link '" + req.link +
                      "'");
  const BodyId b = r.ragdoll.bodies[static_cast<size_t>(link)];
  const BodyState s = world_->bodyState(b);
  toMsg(s.pose, &res.pose);
  toMsg(world_->pointVelocity(b, s.pose.p), &res.twist.linear);
  toMsg(s.angular_velocity, &res.twist.angular);
  res.com.x = s.com_position.x();
  res.com.y = s.com_position.y();
  res.com.z = s.com_position.z();
  res.success = true;
  return true;
}

// ------------------------------------------------------------------------------------------
// dynamic_reconfigure

ragdoll_sim::PhysicsConfig SimNode::currentPhysics() const {
  ragdoll_sim::PhysicsConfig c;
  c.gravity_x = config_.gravity.x();
  c.gravity_y = config_.gravity.y();
  c.gravity_z = config_.gravity.z();
  c.time_step = dt_;
  c.substeps = config_.substeps;
  c.position_iterations = config_.position_iterations;
  c.static_friction = config_.ragdoll_surface.static_friction;
  c.kinetic_friction = config_.ragdoll_surface.kinetic_friction;
  c.restitution = config_.ragdoll_surface.restitution;
  c.real_time_factor = std::isfinite(config_.real_time_factor) ? config_.real_time_factor : 0.0;
  c.sleep_enabled = config_.sleep.enabled;
  c.sleep_time = config_.sleep.time;
  c.sleep_speed = config_.sleep.speed;
  c.rest_time = config_.sleep.rest_time;
  c.rest_substeps = config_.sleep.rest_substeps;
  c.rest_relax_iterations = config_.sleep.rest_relax_iterations;
  return c;
}

void SimNode::startReconfigure() {
  reconfigure_ = std::make_unique<dynamic_reconfigure::Server<ragdoll_sim::PhysicsConfig>>(
      reconfigure_mutex_, pnh_);
  // The node's parameters are the start-up values, not the .cfg defaults.
  ragdoll_sim::PhysicsConfig c = currentPhysics();
  reconfigure_->updateConfig(c);
  reconfigure_->setCallback(
      [this](ragdoll_sim::PhysicsConfig& cfg, uint32_t level) { onReconfigure(cfg, level); });
  reconfigure_ready_ = true;
}

void SimNode::onReconfigure(ragdoll_sim::PhysicsConfig& cfg, uint32_t) {
  // Runs in spinOnce, between steps: changes take effect at the next step.
  const ragdoll_sim::PhysicsConfig old = currentPhysics();
  // The server clamps to the .cfg ranges, but NaN passes every comparison: refuse it whole
  // (the answer then holds the values in force).
  for (double v : {cfg.gravity_x, cfg.gravity_y, cfg.gravity_z, cfg.time_step,
                   cfg.static_friction, cfg.kinetic_friction, cfg.restitution,
                   cfg.real_time_factor, cfg.sleep_time, cfg.sleep_speed, cfg.rest_time}) {
    if (std::isfinite(v)) continue;
    warn("reconfigure/not finite", "reconfigure rejected: a value is not finite (NaN or inf); "
                                   "the physics parameters stay as they were");
    cfg = old;
    return;
  }
  std::ostringstream log;
  const Vec3 g(cfg.gravity_x, cfg.gravity_y, cfg.gravity_z);
  if (g != config_.gravity) {
    log << " gravity (" << g.x() << ", " << g.y() << ", " << g.z() << ")";
    config_.gravity = g;
    world_->setGravity(g);
  }
  const int64_t dt_ns = std::max<int64_t>(1, std::llround(cfg.time_step * 1e9));
  if (dt_ns != dt_ns_) {
    log << " time_step " << cfg.time_step << " s";
    dt_ns_ = dt_ns;
    dt_ = static_cast<double>(dt_ns_) * 1e-9;
    config_.physics_rate = 1.0 / dt_;
    restartPacing();
  }
  if (cfg.real_time_factor != old.real_time_factor) {
    log << " real_time_factor " << cfg.real_time_factor
        << (cfg.real_time_factor == 0.0 ? " (as fast as possible)" : "");
    config_.real_time_factor = cfg.real_time_factor;
    restartPacing();
  }
  // Sleep and rest settings change in place (World::setSleep: nothing wakes unless sleep goes
  // off). Solver settings and materials live in the World and its shapes: rebuild it, carrying
  // every body's state, broken joint and motor over (every body wakes).
  bool rebuild = false;
  if (cfg.substeps != config_.substeps || cfg.position_iterations != config_.position_iterations) {
    log << " substeps " << cfg.substeps << ", position_iterations " << cfg.position_iterations;
    config_.substeps = cfg.substeps;
    config_.position_iterations = cfg.position_iterations;
    rebuild = true;
  }
  if (cfg.static_friction != old.static_friction || cfg.kinetic_friction != old.kinetic_friction ||
      cfg.restitution != old.restitution) {
    log << " friction " << cfg.static_friction << " / " << cfg.kinetic_friction
        << ", restitution " << cfg.restitution << " (every shape and the ground; named "
        << "materials off)";
    config_.material = Material{cfg.static_friction, cfg.kinetic_friction, cfg.restitution,
                                config_.material.rolling_resistance};
    config_.ragdoll_surface = config_.material;
    config_.ground_surface = config_.material;
    config_.materials = MaterialTable();  // pair entries would override the new values
    rebuild = true;
  }
  if (cfg.sleep_enabled != old.sleep_enabled || cfg.sleep_time != old.sleep_time ||
      cfg.sleep_speed != old.sleep_speed) {
    log << " sleep " << (cfg.sleep_enabled ? "on" : "off") << ", after " << cfg.sleep_time
        << " s below " << cfg.sleep_speed << " m/s"
        << (!cfg.sleep_enabled && old.sleep_enabled ? " (sleeping bodies wake)" : "");
  }
  SleepDef& sleep = config_.sleep;  // a rebuild reads it
  sleep.enabled = cfg.sleep_enabled;
  sleep.time = cfg.sleep_time;
  sleep.speed = cfg.sleep_speed;
  sleep.rest_time = cfg.rest_time;
  sleep.rest_substeps = cfg.rest_substeps;
  sleep.rest_relax_iterations = cfg.rest_relax_iterations;
  if (cfg.rest_time != old.rest_time || cfg.rest_substeps != old.rest_substeps ||
      cfg.rest_relax_iterations != old.rest_relax_iterations) {
    log << " rest substeps " << cfg.rest_substeps << " of " << cfg.rest_relax_iterations
        << " relax sweeps after " << cfg.rest_time << " s slow"
        << (sleep.restOn(config_.substeps) ? "" : " (off)");
  }
  if (rebuild) {
    std::string e;
    if (!buildWorld(/*carry_state=*/true, &e)) ROS_ERROR("reconfigure: %s", e.c_str());
    structureChanged();
  } else {
    // The .cfg ranges keep every value >= 0, and NaN was refused above: it cannot throw.
    world_->setSleep(sleep);
  }
  const std::string changes = log.str();
  if (!changes.empty() && reconfigure_ready_)
    ROS_INFO("reconfigure at sim time %.3f s:%s", simTime(), changes.c_str());
}

}  // namespace node
}  // namespace ragdoll_sim
