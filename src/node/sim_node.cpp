#include "sim_node.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <thread>

#include <rosgraph_msgs/Clock.h>

#include "ragdoll_sim/urdf_loader.hpp"

namespace ragdoll_sim {
namespace node {

SimNode::SimNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh) : nh_(nh), pnh_(pnh) {}

SimNode::~SimNode() = default;

bool SimNode::init(std::string* error) {
  if (!loadNodeConfig(pnh_, &config_, error)) return false;

  // --- the launch-time ragdoll ---
  UrdfLoadResult loaded;
  std::string source;
  if (!config_.urdf_file.empty()) {
    source = "file '" + config_.urdf_file + "' (~urdf_file)";
    loaded = loadUrdfFile(config_.urdf_file);
  } else {
    std::string xml;
    std::string param = nh_.resolveName("robot_description");
    if (!nh_.getParam("robot_description", xml)) {
      *error = "no URDF: parameter " + param + " is not set (or not a string) and ~urdf_file is empty";
      return false;
    }
    source = "parameter " + param;
    loaded = loadUrdfString(xml);
  }
  if (!loaded.ok) {
    *error = "failed to load the URDF from " + source + ": " + loaded.error;
    return false;
  }
  for (const std::string& note : loaded.def.notes) ROS_INFO("URDF: %s", note.c_str());
  for (const std::string& w : loaded.def.warnings) ROS_WARN("URDF: %s", w.c_str());
  std::string name = config_.ragdoll_name;
  if (name.empty()) name = loaded.def.name.empty() ? "ragdoll" : loaded.def.name;
  RagdollInstance first;
  if (!makeInstance(std::move(loaded.def), name, config_.tf_prefix, config_.spawnTransform(),
                    /*warn_unknown_joints=*/true, &first, error)) {
    *error = "the URDF from " + source + ": " + *error;
    return false;
  }
  first.balance_on = config_.balance.enabled;
  first.joint_states_pub = nh_.advertise<sensor_msgs::JointState>("joint_states", 10);
  ragdolls_.push_back(std::move(first));

  limits_.max_impulse = config_.max_impulse;
  limits_.max_force = config_.max_force;
  limits_.max_torque = config_.max_torque;
  limits_.max_lever_arm = config_.max_lever_arm;
  queue_ = CommandQueue(static_cast<size_t>(config_.max_queued_commands));
  dt_ns_ = std::max<int64_t>(1, std::llround(1e9 / config_.physics_rate));
  dt_ = static_cast<double>(dt_ns_) * 1e-9;
  paused_ = config_.paused;

  // --- time: on /use_sim_time the node is the clock and stamps are sim time ---
  ros::param::param("/use_sim_time", sim_time_, false);
  publish_clock_ = sim_time_;
  if (pnh_.hasParam("publish_clock") && !pnh_.getParam("publish_clock", publish_clock_)) {
    *error = "parameter " + pnh_.resolveName("publish_clock") + " must be a bool";
    return false;
  }
  // Without sim time: the wall time now (ros::Time::now() is the wall clock then).
  stamp_origin_ = sim_time_ ? ros::Time(0, 0) : ros::Time::now();

  // --- world ---
  if (!buildWorld(/*carry_state=*/false, error)) return false;
  for (RagdollInstance& r : ragdolls_) setBalance(r, r.balance_on, /*log=*/true);

  // --- ROS interface ---
  tf_broadcaster_ = std::make_unique<tf2_ros::TransformBroadcaster>();
  // /clock ticks every step (1 kHz): a queue of 1 s of ticks, so that a subscriber stalled by
  // a busy machine loses no tick (with 10, a 10 ms stall dropped some).
  if (publish_clock_) clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 1000);
  broken_pub_ = pnh_.advertise<ragdoll_sim::JointBroken>("joint_broken", 20);
  markers_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("markers", 1, /*latch=*/true);
  link_states_pub_ = pnh_.advertise<ragdoll_sim::LinkStates>("link_states", 10);
  stats_pub_ = pnh_.advertise<ragdoll_sim::NodeStats>("stats", 10);
  visualizer_ = std::make_unique<Visualizer>(config_.markers, config_.world_frame);
  interaction_ = std::make_unique<Interaction>(
      nh_, pnh_, InteractionSettings{config_.poke, config_.drag, config_.world_frame, limits_},
      visualizer_.get());
  structureChanged();
  const ros::TransportHints no_delay = ros::TransportHints().tcpNoDelay();
  target_sub_ = pnh_.subscribe("target_pose", kCommandTopicQueue, &SimNode::onTargetPose, this,
                               no_delay);
  impulse_sub_ = pnh_.subscribe("apply_impulse", kCommandTopicQueue, &SimNode::onImpulse, this,
                                no_delay);
  force_sub_ = pnh_.subscribe("apply_force", kCommandTopicQueue, &SimNode::onForce, this,
                              no_delay);
  balance_srv_ = pnh_.advertiseService("set_balance", &SimNode::onSetBalance, this);
  clear_targets_srv_ = pnh_.advertiseService("clear_targets", &SimNode::onClearTargets, this);
  spawn_srv_ = pnh_.advertiseService("spawn", &SimNode::onSpawn, this);
  delete_srv_ = pnh_.advertiseService("delete", &SimNode::onDelete, this);
  set_state_srv_ = pnh_.advertiseService("set_ragdoll_state", &SimNode::onSetState, this);
  get_link_srv_ = pnh_.advertiseService("get_link_state", &SimNode::onGetLinkState, this);
  pause_srv_ = pnh_.advertiseService("pause", &SimNode::onPause, this);
  unpause_srv_ = pnh_.advertiseService("unpause", &SimNode::onUnpause, this);
  reset_srv_ = pnh_.advertiseService("reset", &SimNode::onReset, this);
  clear_srv_ = pnh_.advertiseService("clear_forces", &SimNode::onClearForces, this);
  startReconfigure();
  // Advertised last: tests take it as "the node is up".
  step_srv_ = pnh_.advertiseService("step", &SimNode::onStep, this);

  const RagdollInstance& r = ragdolls_.front();
  const Transform& spawn = r.spawn_pose;
  const auto threadsText = [](int n) {
    if (n == 0) return std::string("all cores");
    return std::to_string(n) + (n == 1 ? " thread" : " threads");
  };
  ROS_INFO("ragdoll_sim: '%s' (%zu links, %zu joints, %.2f kg%s%s) at (%.2f, %.2f, %.2f), "
           "physics %.0f Hz x %d substeps on %s, real-time factor %g%s, publish %.0f Hz, "
           "gravity (%.2f, %.2f, %.2f)%s%s%s%s",
           r.name.c_str(), r.def.links.size(), r.def.joints.size(), r.def.totalMass(),
           r.tf_prefix.empty() ? "" : ", TF prefix ", r.tf_prefix.c_str(), spawn.p.x(),
           spawn.p.y(), spawn.p.z(), config_.physics_rate, config_.substeps,
           threadsText(world_->def().threads).c_str(),  // as the World took it
           config_.real_time_factor, pacer_.asFastAsPossible() ? " (as fast as possible)" : "",
           config_.publish_rate, config_.gravity.x(), config_.gravity.y(), config_.gravity.z(),
           config_.ground ? ", ground plane z=0" : "", paused_ ? ", PAUSED" : "",
           r.balance ? ", balance ON" : "",
           sim_time_ ? (publish_clock_ ? ", /use_sim_time: publishing /clock" : ", /use_sim_time")
                     : "");
  return true;
}

// ------------------------------------------------------------------------------------------
// Time

ros::Time SimNode::simStamp() const {
  ros::Time t;
  t.fromNSec(stamp_origin_.toNSec() + static_cast<uint64_t>(sim_ns_));
  return t;
}

void SimNode::restartPacing() {
  const int max_catchup_steps = std::max(
      1, static_cast<int>(std::ceil(config_.max_catchup / dt_)));
  pacer_.configure(dt_ns_, config_.real_time_factor, max_catchup_steps);
  pacing_dirty_ = true;
}

void SimNode::warn(const std::string& kind, const std::string& text) {
  const double now = std::chrono::duration<double>(
                         std::chrono::steady_clock::now().time_since_epoch()).count();
  uint64_t held = 0;
  if (!warn_throttle_.allow(kind, now, &held)) return;
  if (held == 0) ROS_WARN("%s", text.c_str());
  else ROS_WARN("%s (%llu more like it in the last second not shown)", text.c_str(),
                static_cast<unsigned long long>(held));
}

void SimNode::reportBodyFaults() {
  const std::vector<BodyFault> faults = world_->takeBodyFaults();
  if (faults.empty()) return;
  body_faults_ += faults.size();
  std::string input, solver;
  for (const BodyFault& f : faults) {
    std::string where = "body " + std::to_string(f.body.index);
    for (const RagdollInstance& r : ragdolls_)
      for (size_t l = 0; l < r.ragdoll.bodies.size(); ++l)
        if (r.ragdoll.bodies[l] == f.body) where = "'" + r.name + "/" + r.def.links[l].name + "'";
    std::string& list = f.cause == BodyFaultCause::Input ? input : solver;
    list += (list.empty() ? "" : ", ") + where;
  }
  std::ostringstream at;
  at << "solver fault at sim time " << simTime() << " s: ";
  if (!input.empty())
    warn("body fault/input", at.str() + "link(s) " + input + " had a non-finite state, force or "
         "torque before the step; reset to the last finite pose with zero velocity");
  if (!solver.empty())
    warn("body fault/solver", at.str() + "link(s) " + solver + " went non-finite in the step; "
         "reset to the last finite pose with zero velocity");
}

void SimNode::stepOnce() {
  applyDueCommands();
  if (interaction_) interaction_->beforeStep(simTime());
  for (RagdollInstance& r : ragdolls_) {
    for (const ActiveForce& f : r.forces) {
      BodyId body = r.ragdoll.bodies[static_cast<size_t>(f.link)];
      world_->applyForce(body, f.force, world_->bodyPose(body).apply(f.local_point));
      if (!f.torque.isZero(0.0)) world_->applyTorque(body, f.torque);
    }
    for (int i : r.moving_targets) applyAxisMotor(r, i);  // targets that move with their velocity
    // applyAxisMotor drops a target that overflowed: it moves no more.
    r.moving_targets.erase(std::remove_if(r.moving_targets.begin(), r.moving_targets.end(),
                                          [&](int i) { return !r.targets[size_t(i)].active; }),
                           r.moving_targets.end());
    if (r.balance) r.balance->update(*world_);
  }
  world_->step(dt_);
  sim_ns_ += dt_ns_;
  ++steps_;
  reportBodyFaults();
  for (RagdollInstance& r : ragdolls_) {
    if (r.forces.empty()) continue;
    for (ActiveForce& f : r.forces)
      if (f.steps_left > 0) --f.steps_left;
    r.forces.erase(std::remove_if(r.forces.begin(), r.forces.end(),
                                  [](const ActiveForce& f) { return f.steps_left == 0; }),
                   r.forces.end());
  }
  publishClock(/*force=*/false);
  publishBrokenJoints();
}

int SimNode::run() {
  using Clock = Pacer::Clock;
  const Clock::duration publish_period =
      std::chrono::nanoseconds(std::llround(1e9 / config_.publish_rate));
  restartPacing();
  Clock::time_point next_publish = Clock::now();
  int64_t reported_drops = 0;
  publishClock(/*force=*/true);

  while (ros::ok()) {
    ros::spinOnce();
    applyDueCommands();  // what the callbacks queued (also while paused: impulses act at once)
    Clock::time_point now = Clock::now();
    if (pacing_dirty_ || paused_) {
      pacer_.restart(now);  // real time counts from here (unpause, new dt or factor)
      pacing_dirty_ = false;
    }
    if (!paused_) {
      if (pacer_.asFastAsPossible()) {
        // Steps until the next publish (10 ms at most, so callbacks are served), at least one.
        const Clock::time_point until = std::min(next_publish, now + std::chrono::milliseconds(10));
        do {
          stepOnce();
        } while (!paused_ && Clock::now() < until);
      } else {
        for (int n = pacer_.take(now); n > 0 && !paused_; --n) stepOnce();
        if (pacer_.droppedSteps() != reported_drops) {
          reported_drops = pacer_.droppedSteps();
          ROS_WARN_THROTTLE(10.0,
                            "physics is slower than %g x real time: skipped %.3f s of wall clock "
                            "so far (sim time runs slower; stamps follow sim time)",
                            config_.real_time_factor, static_cast<double>(reported_drops) * dt_);
        }
      }
      now = Clock::now();
    }

    if (now >= next_publish) {
      publish();
      next_publish += publish_period;
      if (next_publish <= now) next_publish = now + publish_period;
    }

    const Clock::time_point wake = paused_ ? next_publish : std::min(pacer_.next(now), next_publish);
    if (wake > Clock::now()) std::this_thread::sleep_until(wake);
  }
  return 0;
}

}  // namespace node
}  // namespace ragdoll_sim
