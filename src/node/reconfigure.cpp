#include "reconfigure.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "node_context.hpp"
#include "physics_ranges.hpp"

namespace ragdoll_sim {
namespace node {

Reconfigure::Reconfigure(NodeContext& ctx) : ctx_(ctx) {
  // Latched, as dynamic_reconfigure::Server does: clients (dynparam, rqt_reconfigure) read
  // the description and the values in force when they connect.
  descriptions_pub_ =
      ctx_.pnh.advertise<dynamic_reconfigure::ConfigDescription>("parameter_descriptions", 1, true);
  descriptions_pub_.publish(ragdoll_sim::PhysicsConfig::__getDescriptionMessage__());
  updates_pub_ = ctx_.pnh.advertise<dynamic_reconfigure::Config>("parameter_updates", 1, true);
  publish();
  set_srv_ = ctx_.pnh.advertiseService("set_parameters", &Reconfigure::onSetParameters, this);
}

void Reconfigure::publish() {
  const ragdoll_sim::PhysicsConfig c = current();
  c.__toServer__(ctx_.pnh);
  dynamic_reconfigure::Config msg;
  c.__toMessage__(msg);
  updates_pub_.publish(msg);
}

bool Reconfigure::onSetParameters(dynamic_reconfigure::Reconfigure::Request& req,
                                  dynamic_reconfigure::Reconfigure::Response& res) {
  // Runs in spinOnce, between steps: changes take effect at the next step. The request names
  // some fields; the others keep the values in force.
  const ragdoll_sim::PhysicsConfig in_force = current();
  ragdoll_sim::PhysicsConfig cfg = in_force;
  cfg.__fromMessage__(req.config);
  const RangeProblem p = physicsRangeProblem(cfg, &in_force);
  if (!p.ok()) {
    std::ostringstream m;
    m << "reconfigure refused: " << p.field << " = " << p.value << " is outside its range "
      << p.rule << "; no parameter changed";
    ctx_.warn("reconfigure/" + p.field + " out of range", m.str());
  } else {
    apply(cfg);
    publish();
  }
  current().__toMessage__(res.config);  // the values in force
  return true;
}

ragdoll_sim::PhysicsConfig Reconfigure::current() const {
  const Scene& scene = *ctx_.scene;
  const double rtf = ctx_.config.real_time_factor;  // .inf at start-up means 0 here
  return physicsConfigOf(scene.def(), scene.dt(), scene.def().ragdoll_surface,
                         std::isfinite(rtf) ? rtf : 0.0);
}

void Reconfigure::apply(const ragdoll_sim::PhysicsConfig& cfg) {
  Scene& scene = *ctx_.scene;
  const ragdoll_sim::PhysicsConfig old = current();
  std::ostringstream log;
  const Vec3 g(cfg.gravity_x, cfg.gravity_y, cfg.gravity_z);
  if (g != scene.def().world.gravity) {
    log << " gravity (" << g.x() << ", " << g.y() << ", " << g.z() << ")";
    scene.setGravity(g);
  }
  const int64_t dt_ns = std::max<int64_t>(1, std::llround(cfg.time_step * 1e9));
  if (dt_ns != scene.dtNs()) {
    log << " time_step " << cfg.time_step << " s";
    scene.setTimeStep(dt_ns);
    ctx_.config.physics_rate = 1.0 / scene.dt();
    ctx_.restartPacing();
  }
  // +inf is taken as 0, the one spelling of "as fast as possible" in the answer.
  const double rtf = std::isinf(cfg.real_time_factor) ? 0.0 : cfg.real_time_factor;
  if (rtf != old.real_time_factor) {
    log << " real_time_factor " << rtf << (rtf == 0.0 ? " (as fast as possible)" : "");
    ctx_.config.real_time_factor = rtf;
    ctx_.restartPacing();
  }
  // Sleep and rest settings change in place (nothing wakes unless sleep goes off); solver
  // settings and friction go through the Scene's setSolverSettings / setMaterials.
  const bool solver = cfg.substeps != old.substeps ||
                      cfg.position_iterations != old.position_iterations;
  if (solver)
    log << " substeps " << cfg.substeps << ", position_iterations " << cfg.position_iterations;
  const bool friction = cfg.static_friction != old.static_friction ||
                        cfg.kinetic_friction != old.kinetic_friction ||
                        cfg.restitution != old.restitution;
  if (friction)
    log << " friction " << cfg.static_friction << " / " << cfg.kinetic_friction
        << ", restitution " << cfg.restitution << " (every shape and the ground; named "
        << "materials off)";
  if (cfg.sleep_enabled != old.sleep_enabled || cfg.sleep_time != old.sleep_time ||
      cfg.sleep_speed != old.sleep_speed) {
    log << " sleep " << (cfg.sleep_enabled ? "on" : "off") << ", after " << cfg.sleep_time
        << " s below " << cfg.sleep_speed << " m/s"
        << (!cfg.sleep_enabled && old.sleep_enabled ? " (sleeping bodies wake)" : "");
  }
  SleepDef sleep = scene.def().world.sleep;
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
        << (sleep.restOn(cfg.substeps) ? "" : " (off)");
  }
  // The ranges were checked (physics_ranges.hpp): every value >= 0 and finite; it cannot throw.
  scene.setSleep(sleep);
  if (solver) {
    SolverSettings settings = scene.def().world.solver;
    settings.substeps = cfg.substeps;
    settings.position_iterations = cfg.position_iterations;
    std::string e;  // the node checked the ranges first: a guard
    if (!scene.setSolverSettings(settings, &e)) ROS_ERROR("reconfigure: %s", e.c_str());
  }
  if (friction) {
    const Material m{cfg.static_friction, cfg.kinetic_friction, cfg.restitution,
                     scene.def().material.rolling_resistance};
    scene.setMaterials(m, MaterialTable());  // pair entries would override the new values
  }
  if (solver || friction) ctx_.structureChanged();
  const std::string changes = log.str();
  if (!changes.empty())
    ROS_INFO("reconfigure at sim time %.3f s:%s", scene.time(), changes.c_str());
}

}  // namespace node
}  // namespace ragdoll_sim
