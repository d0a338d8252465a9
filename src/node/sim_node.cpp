#include "sim_node.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include "names.hpp"
#include "ragdoll_sim/urdf_loader.hpp"
#include "world_startup.hpp"

namespace ragdoll_sim {
namespace node {

namespace {

// The start-up line's ground: the default plane, a world's plane, or none.
std::string groundText(const Scene& scene) {
  std::string objects;
  if (scene.staticObjectCount() > 0)
    objects = ", " + std::to_string(scene.staticObjectCount()) + " static object(s)";
  const BodyId g = scene.ground();
  if (!g.valid() || !scene.world().isValid(g)) return objects + ", no ground plane";
  return objects + ", ground plane";
}

}  // namespace

SimNode::SimNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh) : ctx_(nh, pnh) {}

SimNode::~SimNode() = default;

bool SimNode::loadLaunchRagdoll(SpawnDef* spawn, std::string* source, std::string* error) {
  const NodeConfig& c = ctx_.config;
  UrdfLoadResult loaded;
  if (!c.urdf_file.empty()) {
    *source = "file '" + c.urdf_file + "' (~urdf_file)";
    loaded = loadUrdfFile(c.urdf_file);
  } else {
    std::string xml;
    std::string param = ctx_.nh.resolveName("robot_description");
    if (!ctx_.nh.getParam("robot_description", xml)) {
      *error = "no URDF: parameter " + param + " is not set (or not a string) and ~urdf_file is empty";
      return false;
    }
    *source = "parameter " + param;
    loaded = loadUrdfString(xml);
  }
  if (!loaded.ok) {
    *error = "failed to load the URDF from " + *source + ": " + loaded.error;
    return false;
  }
  for (const std::string& note : loaded.def.notes) ROS_INFO("URDF: %s", note.c_str());
  for (const std::string& w : loaded.def.warnings) ROS_WARN("URDF: %s", w.c_str());
  spawn->name = c.ragdoll_name;
  if (spawn->name.empty()) {
    spawn->name = "ragdoll";
    const std::string e = scene::ragdollNameError(loaded.def.name);
    if (e.empty()) spawn->name = loaded.def.name;
    else if (!loaded.def.name.empty()) ROS_WARN("the URDF's robot name is no ragdoll name: %s; "
                                                "naming it 'ragdoll' (set ~ragdoll_name)", e.c_str());
  }
  spawn->def = std::move(loaded.def);
  spawn->pose = c.spawnTransform();
  spawn->balance = c.balance;
  spawn->warn_unknown_joints = true;
  return true;
}

bool SimNode::init(std::string* error) {
  NodeConfig& config = ctx_.config;
  if (!loadNodeConfig(ctx_.pnh, &config, error)) return false;
  logParameters();
  ctx_.spawned_params = std::make_unique<SpawnedParams>(ctx_.nh, ctx_.pnh);
  ctx_.spawned_params->deleteLeftovers();

  // --- the Scene and the launch-time ragdoll ---
  SpawnDef spawn;
  std::string source;
  if (!loadLaunchRagdoll(&spawn, &source, error)) return false;
  ctx_.scene = std::make_unique<Scene>(config.scene, &ctx_.log);
  RagdollTopics first;
  first.name = spawn.name;
  const std::string first_name = spawn.name;
  first.tf_prefix = config.tf_prefix;
  if (ctx_.scene->addRagdoll(std::move(spawn), error) != SpawnResult::Added) {
    *error = "the URDF from " + source + ": " + *error;
    return false;
  }
  first.joint_states_pub = ctx_.nh.advertise<sensor_msgs::JointState>("joint_states", 10);
  if (!loadStartupWorld(config, ctx_.scene.get(), error)) return false;
  ctx_.paused = config.paused;
  if (!ctx_.clock.init(ctx_.pnh, error)) return false;
  if (!ctx_.scene->start(error)) return false;
  const Vec3 v0 = config.spawnLinearVelocity(), w0 = config.spawnAngularVelocity();
  if (v0.squaredNorm() > 0 || w0.squaredNorm() > 0) {  // ~spawn/v*, ~spawn/w*: a push at start
    const int k = ctx_.scene->find(first.name);
    ctx_.scene->setRagdollState(k, ctx_.scene->spawnPose(k), v0, w0);
  }

  // --- ROS interface ---
  ctx_.publishers = std::make_unique<Publishers>(ctx_);
  ctx_.publishers->addRagdoll(std::move(first));
  ctx_.reports = std::make_unique<ReportTopics>(ctx_);
  ctx_.visualizer = std::make_unique<Visualizer>(config.markers, config.world_frame);
  ctx_.log.setVisualizer(ctx_.visualizer.get());
  ctx_.interaction = std::make_unique<Interaction>(
      ctx_.nh, ctx_.pnh,
      InteractionSettings{config.poke, config.drag, config.world_frame, config.scene.limits},
      ctx_.visualizer.get());
  ctx_.scene->setBeforeForces(
      [this](World&, double sim_time) { ctx_.interaction->beforeStep(sim_time); });
  ctx_.structureChanged();
  topics_ = std::make_unique<CommandTopics>(ctx_);
  ctx_.steps = std::make_unique<StepService>(ctx_);
  services_ = std::make_unique<Services>(ctx_);
  object_services_ = std::make_unique<ObjectServices>(ctx_);
  reconfigure_ = std::make_unique<Reconfigure>(ctx_);
  services_->advertiseStep();  // last: tests take it as "the node is up"

  const Scene& scene = *ctx_.scene;
  const int first_k = scene.find(first_name);
  const RagdollDef& def = scene.def(first_k);
  const std::string& own = ctx_.publishers->ragdolls().at(static_cast<size_t>(first_k)).tf_prefix;
  const std::string prefix = joinFrames(config.frame_prefix, own);
  const Vec3 at = config.spawnTransform().p;
  const Vec3& g = scene.def().world.gravity;
  const auto threadsText = [](int n) {
    if (n == 0) return std::string("all cores");
    return std::to_string(n) + (n == 1 ? " thread" : " threads");
  };
  const auto lanesText = [](const World& world) {
    const int width = world.laneWidth();
    if (width == 1) return std::string("rows in double");
    return "rows in float lanes, " + std::to_string(width) + " wide" +
           (world.lanesAutomatic()
                ? ", from " + std::to_string(World::kLanesMinBodies) + " awake bodies"
                : "");
  };
  ROS_INFO("ragdoll_sim: '%s' (%zu links, %zu joints, %.2f kg%s%s) at (%.2f, %.2f, %.2f), "
           "physics %.0f Hz x %d substeps on %s (%s), real-time factor %g%s, publish %.0f Hz, "
           "gravity (%.2f, %.2f, %.2f)%s%s%s%s",
           scene.name(first_k).c_str(), def.links.size(), def.joints.size(), def.totalMass(),
           prefix.empty() ? "" : ", TF prefix ", prefix.c_str(), at.x(), at.y(), at.z(),
           config.physics_rate, scene.def().world.solver.substeps,
           threadsText(scene.world().def().threads).c_str(),  // as the World took it
           lanesText(scene.world()).c_str(),
           config.real_time_factor, ctx_.pacer.asFastAsPossible() ? " (as fast as possible)" : "",
           config.publish_rate, g.x(), g.y(), g.z(), groundText(scene).c_str(),
           ctx_.paused ? ", PAUSED" : "", scene.balanceOn(first_k) ? ", balance ON" : "",
           ctx_.clock.simTime()
               ? (ctx_.clock.publishing() ? ", /use_sim_time: publishing /clock" : ", /use_sim_time")
               : "");
  return true;
}

void SimNode::logParameters() const {
  const std::vector<std::string>& d = ctx_.config.differing_from_defaults;
  if (d.empty()) return;
  std::string list;
  for (const std::string& p : d) list += (list.empty() ? "" : ", ") + p;
  // ~time_step is written only by the reconfigure server: an earlier node ran here, and what
  // it reconfigured under a start-up name (~substeps, ~real_time_factor, ...) is read now.
  if (ctx_.pnh.hasParam("time_step"))
    ROS_WARN("start-up parameters that differ from the defaults: %s (the parameter server holds "
             "an earlier node's reconfigured values; they are inherited where the names are "
             "start-up parameters)", list.c_str());
  else
    ROS_INFO("start-up parameters that differ from the defaults: %s", list.c_str());
}

int SimNode::run(const std::atomic<bool>& stop) {
  using Clock = scene::Pacer::Clock;
  NodeContext& c = ctx_;
  const Clock::duration publish_period =
      std::chrono::nanoseconds(std::llround(1e9 / c.config.publish_rate));
  c.restartPacing();
  Clock::time_point next_publish = Clock::now();
  int64_t reported_drops = 0;
  c.clock.publish(c.scene->timeNs(), /*force=*/true, c.config.clock_rate);

  while (ros::ok() && !stop) {
    ros::spinOnce();
    c.scene->applyDueCommands();  // what the callbacks queued (also while paused)
    Clock::time_point now = Clock::now();
    if (c.pacing_dirty || c.paused) {
      c.pacer.restart(now);  // real time counts from here (unpause, new dt or factor)
      c.pacing_dirty = false;
    }
    if (c.paused) {
      // ~step calls run here, a slice at a time, so callbacks are served in between.
      c.steps->serve(now + std::chrono::milliseconds(10));
      now = Clock::now();
    } else {
      c.steps->serve(now);  // a call arriving unpaused is refused
      if (c.pacer.asFastAsPossible()) {
        // Steps until the next publish (10 ms at most, so callbacks are served), at least one.
        const Clock::time_point until = std::min(next_publish, now + std::chrono::milliseconds(10));
        do {
          c.stepOnce();
        } while (!c.paused && Clock::now() < until);
      } else {
        for (int n = c.pacer.take(now); n > 0 && !c.paused; --n) c.stepOnce();
        if (c.pacer.droppedSteps() != reported_drops) {
          reported_drops = c.pacer.droppedSteps();
          ROS_WARN_THROTTLE(10.0,
                            "physics is slower than %g x real time: skipped %.3f s of wall clock "
                            "so far (sim time runs slower; stamps follow sim time)",
                            c.config.real_time_factor,
                            static_cast<double>(reported_drops) * c.scene->dt());
        }
      }
      now = Clock::now();
    }

    if (now >= next_publish) {
      c.publishers->publish();
      next_publish += publish_period;
      if (next_publish <= now) next_publish = now + publish_period;
    }

    const Clock::time_point wake = c.steps->busy() ? now
                                   : c.paused  ? next_publish
                                               : std::min(c.pacer.next(now), next_publish);
    if (wake > Clock::now()) c.wakeup.sleepUntil(wake);
  }
  c.steps->end("shutdown");
  c.spawned_params->removeAll();  // the master is still there (the signal only set `stop`)
  return 0;
}

}  // namespace node
}  // namespace ragdoll_sim
