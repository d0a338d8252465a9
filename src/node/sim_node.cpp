#include "sim_node.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include "ragdoll_sim/urdf_loader.hpp"

namespace ragdoll_sim {
namespace node {

namespace {

void toMsg(const Transform& t, geometry_msgs::Transform* m) {
  m->translation.x = t.p.x();
  m->translation.y = t.p.y();
  m->translation.z = t.p.z();
  m->rotation.x = t.q.x();
  m->rotation.y = t.q.y();
  m->rotation.z = t.q.z();
  m->rotation.w = t.q.w();
}

void toMsg(const Transform& t, geometry_msgs::Pose* m) {
  m->position.x = t.p.x();
  m->position.y = t.p.y();
  m->position.z = t.p.z();
  m->orientation.x = t.q.x();
  m->orientation.y = t.q.y();
  m->orientation.z = t.q.z();
  m->orientation.w = t.q.w();
}

Vec3 toVec(const geometry_msgs::Vector3& v) { return Vec3(v.x, v.y, v.z); }
Vec3 toVec(const geometry_msgs::Point& v) { return Vec3(v.x, v.y, v.z); }

std_msgs::ColorRGBA color(float r, float g, float b, float a = 1.0f) {
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

// A few distinguishable colours for the links.
std_msgs::ColorRGBA linkColor(size_t i) {
  static const float kPalette[][3] = {{0.90f, 0.60f, 0.30f}, {0.35f, 0.60f, 0.90f},
                                      {0.45f, 0.80f, 0.45f}, {0.85f, 0.45f, 0.55f},
                                      {0.75f, 0.70f, 0.35f}, {0.60f, 0.50f, 0.85f}};
  const float* p = kPalette[i % (sizeof(kPalette) / sizeof(kPalette[0]))];
  return color(p[0], p[1], p[2], 0.9f);
}

}  // namespace

SimNode::SimNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh) : nh_(nh), pnh_(pnh) {}

SimNode::~SimNode() = default;

bool SimNode::init(std::string* error) {
  if (!loadNodeConfig(pnh_, &config_, error)) return false;

  // --- model ---
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
  def_ = std::move(loaded.def);
  if (def_.links.empty()) {
    *error = "the URDF from " + source + " has no links";
    return false;
  }
  for (const std::string& note : def_.notes) ROS_INFO("URDF: %s", note.c_str());
  for (const std::string& w : def_.warnings) ROS_WARN("URDF: %s", w.c_str());

  // --- joints: springs, break forces and motor gains (~joint_defaults, ~joints) ---
  axes_ = AxisTable(def_);
  JointSettingsResult settings =
      applyJointSettings(&def_, axes_, config_.joint_defaults, config_.joints, config_.motor);
  for (const std::string& w : settings.warnings) ROS_WARN("%s", w.c_str());
  if (!settings.error.empty()) {
    *error = settings.error;
    return false;
  }
  gains_ = std::move(settings.gains);
  targets_.assign(static_cast<size_t>(axes_.size()), AxisTarget());
  moving_targets_.clear();
  for (const RagdollJointDef& j : def_.joints) {
    if (j.spring.stiffness > 0.0 || std::isfinite(j.spring.break_force))
      ROS_INFO("joint '%s': anchor stiffness %g N/m, damping %g N*s/m, break_force %g N",
               j.name.c_str(), j.spring.stiffness, j.spring.damping, j.spring.break_force);
  }

  // --- world ---
  balance_on_ = config_.balance.enabled;
  if (!buildWorld(error)) return false;

  links_ = LinkTable(def_);
  limits_.max_impulse = config_.max_impulse;
  limits_.max_force = config_.max_force;
  limits_.max_torque = config_.max_torque;
  limits_.max_lever_arm = config_.max_lever_arm;

  dt_ns_ = std::max<int64_t>(1, std::llround(1e9 / config_.physics_rate));
  dt_ = static_cast<double>(dt_ns_) * 1e-9;
  paused_ = config_.paused;
  forces_.reserve(kMaxActiveForces);

  // --- publishing buffers ---
  buildTfMessages();
  buildMarkers();
  buildJointState();

  // --- ROS interface ---
  tf_broadcaster_ = std::make_unique<tf2_ros::TransformBroadcaster>();
  broken_pub_ = pnh_.advertise<ragdoll_sim::JointBroken>("joint_broken", 20);
  target_sub_ = pnh_.subscribe("target_pose", 10, &SimNode::onTargetPose, this);
  balance_srv_ = pnh_.advertiseService("set_balance", &SimNode::onSetBalance, this);
  clear_targets_srv_ = pnh_.advertiseService("clear_targets", &SimNode::onClearTargets, this);
  markers_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("markers", 1, /*latch=*/true);
  joints_pub_ = nh_.advertise<sensor_msgs::JointState>("joint_states", 10);
  impulse_sub_ = pnh_.subscribe("apply_impulse", 20, &SimNode::onImpulse, this);
  force_sub_ = pnh_.subscribe("apply_force", 20, &SimNode::onForce, this);
  pause_srv_ = pnh_.advertiseService("pause", &SimNode::onPause, this);
  unpause_srv_ = pnh_.advertiseService("unpause", &SimNode::onUnpause, this);
  reset_srv_ = pnh_.advertiseService("reset", &SimNode::onReset, this);
  clear_srv_ = pnh_.advertiseService("clear_forces", &SimNode::onClearForces, this);
  step_srv_ = pnh_.advertiseService("step", &SimNode::onStep, this);

  start_stamp_ = ros::Time::now();
  const Transform spawn = config_.spawnTransform();
  ROS_INFO("ragdoll_sim: '%s' (%zu links, %zu joints, %.2f kg) at (%.2f, %.2f, %.2f), "
           "physics %.0f Hz x %d substeps, publish %.0f Hz, gravity (%.2f, %.2f, %.2f)%s%s%s",
           def_.name.c_str(), def_.links.size(), def_.joints.size(), def_.totalMass(),
           spawn.p.x(), spawn.p.y(), spawn.p.z(), config_.physics_rate, config_.substeps,
           config_.publish_rate, config_.gravity.x(), config_.gravity.y(), config_.gravity.z(),
           config_.ground ? ", ground plane z=0" : "", paused_ ? ", PAUSED" : "",
           balance_ ? ", balance ON" : "");
  return true;
}

bool SimNode::buildWorld(std::string* error) {
  balance_.reset();  // it drives the joints of the old world
  WorldDef wd;
  wd.gravity = config_.gravity;
  wd.substeps = config_.substeps;
  wd.materials = config_.materials;
  world_ = std::make_unique<World>(wd);
  ground_ = BodyId();
  if (config_.ground) {
    BodyDef gd;
    gd.type = BodyType::Static;
    gd.name = "ground";
    ground_ = world_->createBody(gd);
    ShapeDef sd;
    sd.geometry = Geometry::plane(Vec3::UnitZ(), 0.0);
    sd.material = config_.ground_surface;
    world_->addShape(ground_, sd);
  }
  ragdoll_ = spawnRagdoll(*world_, def_, config_.spawnTransform(), &config_.ragdoll_surface);
  if (ragdoll_.bodies.size() != def_.links.size() || ragdoll_.joints.size() != def_.joints.size()) {
    *error = "spawnRagdoll returned " + std::to_string(ragdoll_.bodies.size()) + " bodies / " +
             std::to_string(ragdoll_.joints.size()) + " joints for a model with " +
             std::to_string(def_.links.size()) + " links / " + std::to_string(def_.joints.size()) +
             " joints";
    return false;
  }
  setBalance(balance_on_);
  return true;
}

void SimNode::setBalance(bool on) {
  balance_on_ = on;
  balance_.reset();
  if (on) {
    BalanceDef bd;
    bd.hold = holdMotor(0.0, config_.motor, JointMotor());
    bd.kp = config_.balance.kp;
    bd.kd = config_.balance.kd;
    bd.ankles = config_.balance.ankles;
    bd.feet = config_.balance.feet;
    balance_ = std::make_unique<BalanceController>(*world_, ragdoll_, def_, bd);
    for (const std::string& m : balance_->missing())
      ROS_WARN("balance: %s not in the model; the joints hold their pose but the balance law "
               "on the ankles is off (~balance/ankles, ~balance/feet)", m.c_str());
  }
  // Per-joint gains, URDF damping and the targets on top of what the controller set.
  for (int i = 0; i < axes_.size(); ++i) applyAxisMotor(i);
}

void SimNode::applyAxisMotor(int i) {
  const AxisInfo& a = axes_[i];
  const JointMotor passive = passiveMotor(def_.joints[static_cast<size_t>(a.joint)], a.axis);
  const AxisTarget& t = targets_[static_cast<size_t>(i)];
  JointMotor m = passive;
  if (t.active) {
    m = targetMotor(t, a, gains_[static_cast<size_t>(i)], passive, simTime());
    // The controller keeps its own ankle targets (its balance law adds to them).
    if (balance_ && t.has_position) balance_->setTarget(*world_, a.name, m.target);
  } else if (balance_) {
    m = holdMotor(0.0, gains_[static_cast<size_t>(i)], passive);
    balance_->setTarget(*world_, a.name, 0.0);
  }
  world_->setJointMotor(ragdoll_.joints[static_cast<size_t>(a.joint)], a.axis, m);
}

void SimNode::publishBrokenJoints() {
  for (JointId id : world_->takeBrokenJoints()) {
    const auto it = std::find(ragdoll_.joints.begin(), ragdoll_.joints.end(), id);
    if (it == ragdoll_.joints.end()) continue;
    const RagdollJointDef& j = def_.joints[static_cast<size_t>(it - ragdoll_.joints.begin())];
    ragdoll_sim::JointBroken msg;
    msg.header.stamp = simStamp();
    msg.header.frame_id = config_.world_frame;
    msg.ragdoll = def_.name;
    msg.joint = j.name;
    msg.parent_link = def_.links[static_cast<size_t>(j.parent)].name;
    msg.child_link = def_.links[static_cast<size_t>(j.child)].name;
    msg.force = world_->jointForce(id);
    broken_pub_.publish(msg);
    ROS_INFO("joint '%s' broke at sim time %.3f s: '%s' came off '%s' (anchor force %.1f N, "
             "break_force %g N)",
             j.name.c_str(), simTime(), msg.child_link.c_str(), msg.parent_link.c_str(), msg.force,
             j.spring.break_force);
  }
}

// ------------------------------------------------------------------------------------------
// Simulation

Transform SimNode::linkPose(int link) const { return world_->bodyPose(ragdoll_.bodies[link]); }

ros::Time SimNode::simStamp() const {
  ros::Time t;
  t.fromNSec(start_stamp_.toNSec() + static_cast<uint64_t>(steps_ * dt_ns_));
  return t;
}

double SimNode::simTime() const { return static_cast<double>(steps_ * dt_ns_) * 1e-9; }

void SimNode::stepOnce() {
  for (const ActiveForce& f : forces_) {
    BodyId body = ragdoll_.bodies[f.link];
    world_->applyForce(body, f.force, world_->bodyPose(body).apply(f.local_point));
    if (!f.torque.isZero(0.0)) world_->applyTorque(body, f.torque);
  }
  for (int i : moving_targets_) applyAxisMotor(i);  // targets that move with their velocity
  if (balance_) balance_->update(*world_);
  world_->step(dt_);
  ++steps_;
  if (!forces_.empty()) {
    for (ActiveForce& f : forces_)
      if (f.steps_left > 0) --f.steps_left;
    forces_.erase(std::remove_if(forces_.begin(), forces_.end(),
                                 [](const ActiveForce& f) { return f.steps_left == 0; }),
                  forces_.end());
  }
  publishBrokenJoints();
}

void SimNode::resetRagdoll() {
  // A fresh world rejoins broken joints; bodies and joints get the same ids as before.
  std::string error;
  if (!buildWorld(&error)) ROS_ERROR("reset: %s", error.c_str());
  forces_.clear();
  prev_joint_step_ = -1;
}

int SimNode::run() {
  using Clock = std::chrono::steady_clock;
  const Clock::duration step_period = std::chrono::nanoseconds(dt_ns_);
  const Clock::duration publish_period =
      std::chrono::nanoseconds(std::llround(1e9 / config_.publish_rate));
  const int max_catchup_steps =
      std::max(1, static_cast<int>(std::ceil(config_.max_catchup * config_.physics_rate)));

  Clock::time_point next_step = Clock::now();
  Clock::time_point next_publish = next_step;
  int64_t dropped_steps = 0;

  while (ros::ok()) {
    ros::spinOnce();
    Clock::time_point now = Clock::now();

    if (paused_) {
      next_step = now;  // on unpause, real time restarts from here
    } else {
      int n = 0;
      while (next_step <= now && n < max_catchup_steps) {
        stepOnce();
        next_step += step_period;
        ++n;
      }
      now = Clock::now();
      if (next_step + step_period * max_catchup_steps <= now) {
        // More than max_catchup behind wall clock: drop the backlog instead of spiralling.
        int64_t behind = (now - next_step) / step_period;
        dropped_steps += behind;
        next_step += step_period * behind;
        ROS_WARN_THROTTLE(10.0,
                          "physics is slower than real time: skipped %.3f s of wall clock so far "
                          "(sim time runs slower; stamps follow sim time)",
                          static_cast<double>(dropped_steps) * dt_);
      }
    }

    if (now >= next_publish) {
      publish();
      next_publish += publish_period;
      if (next_publish <= now) next_publish = now + publish_period;
    }

    Clock::time_point wake = paused_ ? next_publish : std::min(next_step, next_publish);
    if (wake > Clock::now()) std::this_thread::sleep_until(wake);
  }
  return 0;
}

// ------------------------------------------------------------------------------------------
// Publishing

void SimNode::buildTfMessages() {
  tf_msgs_.clear();
  for (const LinkDef& l : def_.links) {
    geometry_msgs::TransformStamped t;
    t.header.frame_id = config_.world_frame;
    t.child_frame_id = l.name;
    tf_msgs_.push_back(t);
  }
  ball_joints_.clear();
  ball_tf_offset_.clear();
  for (size_t j = 0; j < def_.joints.size(); ++j) {
    const RagdollJointDef& jd = def_.joints[j];
    if (jd.kind != RagdollJointKind::Ball || jd.chain_links.empty()) continue;
    ball_joints_.push_back(static_cast<int>(j));
    ball_tf_offset_.push_back(static_cast<int>(tf_msgs_.size()));
    for (const std::string& c : jd.chain_links) {
      geometry_msgs::TransformStamped t;
      t.header.frame_id = config_.world_frame;
      t.child_frame_id = c;
      tf_msgs_.push_back(t);
    }
  }
}

void SimNode::publishTf(const ros::Time& stamp) {
  for (size_t i = 0; i < ragdoll_.bodies.size(); ++i) {
    tf_msgs_[i].header.stamp = stamp;
    toMsg(world_->bodyPose(ragdoll_.bodies[i]), &tf_msgs_[i].transform);
  }
  for (size_t k = 0; k < ball_joints_.size(); ++k) {
    const int j = ball_joints_[k];
    std::vector<Transform> poses = ballChainLinkPoses(*world_, ragdoll_, def_, j);
    const size_t n = std::min(poses.size(), def_.joints[j].chain_links.size());
    for (size_t c = 0; c < n; ++c) {
      geometry_msgs::TransformStamped& t = tf_msgs_[ball_tf_offset_[k] + c];
      t.header.stamp = stamp;
      toMsg(poses[c], &t.transform);
    }
  }
  tf_broadcaster_->sendTransform(tf_msgs_);
}

void SimNode::buildMarkers() {
  markers_.markers.clear();
  marker_sources_.clear();
  auto add = [&](const std::string& ns, int id, BodyId body, const Transform& local, int type,
                 const Vec3& scale, const std_msgs::ColorRGBA& c) -> visualization_msgs::Marker& {
    visualization_msgs::Marker m;
    m.header.frame_id = config_.world_frame;
    m.ns = ns;
    m.id = id;
    m.type = type;
    m.action = visualization_msgs::Marker::ADD;
    m.scale.x = scale.x();
    m.scale.y = scale.y();
    m.scale.z = scale.z();
    m.color = c;
    m.pose.orientation.w = 1.0;
    markers_.markers.push_back(m);
    marker_sources_.push_back({body, local});
    return markers_.markers.back();
  };

  using visualization_msgs::Marker;
  for (size_t i = 0; i < ragdoll_.bodies.size(); ++i) {
    const BodyId body = ragdoll_.bodies[i];
    const std::string& ns = def_.links[i].name;
    const std_msgs::ColorRGBA c = linkColor(i);
    int id = 0;
    for (const ShapeDef& s : world_->bodyShapes(body)) {
      const Geometry& g = s.geometry;
      switch (g.type) {
        case ShapeType::Sphere:
          add(ns, id++, body, s.local, Marker::SPHERE, Vec3::Constant(2 * g.radius), c);
          break;
        case ShapeType::Box:
          add(ns, id++, body, s.local, Marker::CUBE, 2 * g.half_extents, c);
          break;
        case ShapeType::Cylinder:
          add(ns, id++, body, s.local, Marker::CYLINDER,
              Vec3(2 * g.radius, 2 * g.radius, 2 * g.half_height), c);
          break;
        case ShapeType::Capsule: {
          add(ns, id++, body, s.local, Marker::CYLINDER,
              Vec3(2 * g.radius, 2 * g.radius, 2 * g.half_height), c);
          for (double sign : {1.0, -1.0}) {
            Transform cap = s.local * Transform(Vec3(0, 0, sign * g.half_height), Quat::Identity());
            add(ns, id++, body, cap, Marker::SPHERE, Vec3::Constant(2 * g.radius), c);
          }
          break;
        }
        case ShapeType::ConvexHull: {
          if (!g.hull) break;
          Marker& m = add(ns, id++, body, s.local, Marker::TRIANGLE_LIST, Vec3::Ones(), c);
          for (const HullData::Face& f : g.hull->faces) {
            for (size_t k = 1; k + 1 < f.verts.size(); ++k) {
              for (int v : {f.verts[0], f.verts[k], f.verts[k + 1]}) {
                geometry_msgs::Point p;
                p.x = g.hull->vertices[v].x();
                p.y = g.hull->vertices[v].y();
                p.z = g.hull->vertices[v].z();
                m.points.push_back(p);
              }
            }
          }
          break;
        }
        case ShapeType::Plane:
          break;  // planes on ragdoll links make no sense to draw
      }
    }
  }

  if (ground_.valid()) {
    // The plane as a thin 20 m x 20 m slab whose top face is the plane.
    for (const ShapeDef& s : world_->bodyShapes(ground_)) {
      if (s.geometry.type != ShapeType::Plane) continue;
      const double thickness = 0.02;
      const Vec3 n = s.geometry.normal.normalized();
      Transform slab(n * (s.geometry.offset - 0.5 * thickness),
                     Quat::FromTwoVectors(Vec3::UnitZ(), n));
      add("ground", 0, ground_, s.local * slab, Marker::CUBE, Vec3(20.0, 20.0, thickness),
          color(0.55f, 0.55f, 0.55f, 0.6f));
      break;
    }
  }
}

void SimNode::publishMarkers(const ros::Time& stamp) {
  for (size_t k = 0; k < markers_.markers.size(); ++k) {
    visualization_msgs::Marker& m = markers_.markers[k];
    m.header.stamp = stamp;
    toMsg(world_->bodyPose(marker_sources_[k].body) * marker_sources_[k].local, &m.pose);
  }
  markers_pub_.publish(markers_);
}

void SimNode::buildJointState() {
  // Names as in axes_ (the names ~target_pose takes).
  joint_state_.name.clear();
  for (const AxisInfo& a : axes_.axes()) joint_state_.name.push_back(a.name);
  joint_sources_.clear();
  for (size_t j = 0; j < def_.joints.size(); ++j) {
    JointSource src;
    src.id = ragdoll_.joints[j];
    src.kind = def_.joints[j].kind;
    src.first = axes_.first(static_cast<int>(j));
    joint_sources_.push_back(src);
  }
  joint_state_.position.assign(joint_state_.name.size(), 0.0);
  joint_state_.velocity.assign(joint_state_.name.size(), 0.0);
  prev_positions_.assign(joint_state_.name.size(), 0.0);
}

void SimNode::publishJointState(const ros::Time& stamp) {
  std::vector<double>& q = joint_state_.position;
  for (const JointSource& s : joint_sources_) {
    if (s.kind == RagdollJointKind::Ball) {
      const std::array<double, 3> a = world_->ballAngles(s.id);
      q[s.first] = a[0];
      q[s.first + 1] = a[1];
      q[s.first + 2] = a[2];
    } else if (s.kind == RagdollJointKind::Prismatic) {
      q[s.first] = world_->prismaticPosition(s.id);
    } else if (s.kind == RagdollJointKind::Hinge) {
      q[s.first] = world_->hingeAngle(s.id);
    }  // fixed: no position
  }
  // Velocities: finite differences over the sim time since the last message.
  if (prev_joint_step_ >= 0 && steps_ > prev_joint_step_) {
    const double h = static_cast<double>((steps_ - prev_joint_step_) * dt_ns_) * 1e-9;
    for (size_t i = 0; i < q.size(); ++i) joint_state_.velocity[i] = (q[i] - prev_positions_[i]) / h;
  } else {
    std::fill(joint_state_.velocity.begin(), joint_state_.velocity.end(), 0.0);
  }
  prev_positions_ = q;
  prev_joint_step_ = steps_;
  joint_state_.header.stamp = stamp;
  joints_pub_.publish(joint_state_);
}

void SimNode::publish() {
  const ros::Time stamp = simStamp();
  // TF and joint_states only when sim time advanced: a repeated stamp would make every tf2
  // listener complain (TF_REPEATED_DATA) while paused.
  if (steps_ != last_tf_step_) {
    publishTf(stamp);
    publishJointState(stamp);
    last_tf_step_ = steps_;
  }
  if (config_.publish_markers && markers_pub_.getNumSubscribers() > 0) publishMarkers(stamp);
}

// ------------------------------------------------------------------------------------------
// Commands

void SimNode::onImpulse(const ragdoll_sim::ApplyImpulse::ConstPtr& msg) {
  ImpulseCommand cmd;
  cmd.link = msg->link;
  cmd.frame = msg->frame;
  cmd.point = toVec(msg->point);
  cmd.impulse = toVec(msg->impulse);
  CommandCheck check =
      checkImpulse(cmd, links_, limits_, [this](int link) { return linkPose(link); });
  if (!check.ok) {
    ROS_WARN_THROTTLE(1.0, "%s; command dropped", check.error.c_str());
    return;
  }
  WorldImpulse w = toWorldImpulse(cmd, check, linkPose(check.link));
  world_->applyLinearImpulse(ragdoll_.bodies[w.link], w.impulse, w.point);
  ROS_DEBUG("impulse (%g, %g, %g) N*s on '%s' at (%g, %g, %g)", w.impulse.x(), w.impulse.y(),
            w.impulse.z(), cmd.link.c_str(), w.point.x(), w.point.y(), w.point.z());
}

void SimNode::onForce(const ragdoll_sim::ApplyForce::ConstPtr& msg) {
  ForceCommand cmd;
  cmd.link = msg->link;
  cmd.frame = msg->frame;
  cmd.point = toVec(msg->point);
  cmd.force = toVec(msg->force);
  cmd.torque = toVec(msg->torque);
  cmd.duration = msg->duration;
  CommandCheck check =
      checkForce(cmd, links_, limits_, [this](int link) { return linkPose(link); });
  if (!check.ok) {
    ROS_WARN_THROTTLE(1.0, "%s; command dropped", check.error.c_str());
    return;
  }
  if (forces_.size() >= kMaxActiveForces) {
    ROS_WARN_THROTTLE(1.0, "force on '%s' rejected: %zu forces are already active (call ~clear_forces)",
                      cmd.link.c_str(), forces_.size());
    return;
  }
  forces_.push_back(toActiveForce(cmd, check, linkPose(check.link), dt_));
  ROS_DEBUG("force on '%s' for %lld steps", cmd.link.c_str(),
            static_cast<long long>(forces_.back().steps_left));
}

void SimNode::onTargetPose(const sensor_msgs::JointState::ConstPtr& msg) {
  TargetPoseCommand cmd;
  cmd.names = msg->name;
  cmd.position = msg->position;
  cmd.velocity = msg->velocity;
  const TargetPoseCheck check = checkTargetPose(cmd, axes_);
  if (!check.ok) {
    ROS_WARN_THROTTLE(1.0, "%s; target pose dropped", check.error.c_str());
    return;
  }
  if (!check.clamped.empty()) {
    std::string names;
    for (const std::string& n : check.clamped) names += (names.empty() ? "'" : ", '") + n + "'";
    ROS_WARN_THROTTLE(1.0, "target pose: %s outside the joint limits, clamped to them", names.c_str());
  }
  for (const auto& [axis, target] : toAxisTargets(cmd, check, simTime())) {
    targets_[static_cast<size_t>(axis)] = target;
    applyAxisMotor(axis);
  }
  moving_targets_.clear();
  for (int i = 0; i < axes_.size(); ++i) {
    const AxisTarget& t = targets_[static_cast<size_t>(i)];
    if (t.active && t.has_position && t.velocity != 0.0) moving_targets_.push_back(i);
  }
  ROS_DEBUG("target pose for %zu joint(s)", check.axes.size());
}

bool SimNode::onSetBalance(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res) {
  setBalance(req.data);
  res.success = true;
  if (!req.data) {
    res.message = "balance off";
  } else if (balance_ && balance_->missing().empty()) {
    res.message = "balance on";
  } else {
    res.message = "joints hold the pose, but the balance law is off: missing";
    for (const std::string& m : balance_->missing()) res.message += " " + m;
  }
  ROS_INFO("%s at sim time %.3f s", res.message.c_str(), simTime());
  return true;
}

bool SimNode::onClearTargets(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  targets_.assign(targets_.size(), AxisTarget());
  moving_targets_.clear();
  for (int i = 0; i < axes_.size(); ++i) applyAxisMotor(i);
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
  resetRagdoll();
  ROS_INFO("ragdoll reset to its spawn pose at sim time %.3f s", simTime());
  return true;
}

bool SimNode::onClearForces(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  ROS_INFO("cleared %zu active force(s)", forces_.size());
  forces_.clear();
  return true;
}

bool SimNode::onStep(ragdoll_sim::Step::Request& req, ragdoll_sim::Step::Response& res) {
  if (!paused_) {
    res.success = false;
    res.message = "the simulation is running; call ~pause first";
  } else {
    for (uint32_t i = 0; i < req.steps && ros::ok(); ++i) stepOnce();
    res.success = true;
    res.message = "stepped " + std::to_string(req.steps) + " step(s)";
  }
  res.sim_time = simTime();
  return true;
}

}  // namespace node
}  // namespace ragdoll_sim
