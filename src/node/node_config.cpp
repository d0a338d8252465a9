#include "node_config.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <vector>

#include <ros/node_handle.h>
#include <xmlrpcpp/XmlRpcException.h>

#include "anatomy_config.hpp"
#include "material_yaml.hpp"
#include "ragdoll_sim/range_check.hpp"
#include "pacing.hpp"
#include "commands.hpp"
#include "physics_ranges.hpp"

namespace ragdoll_sim {
namespace node {

Transform NodeConfig::spawnTransform() const {
  return Transform(Vec3(spawn.x, spawn.y, spawn.z), quatFromRpy(spawn.roll, spawn.pitch, spawn.yaw));
}

namespace {

// Where the parameters come from, and what of them differs from the defaults.
struct Source {
  const ros::NodeHandle& pnh;
  std::vector<std::string>* differing;
};

template <class T>
void show(std::ostream& s, const T& v) { s << v; }
void show(std::ostream& s, bool v) { s << (v ? "true" : "false"); }
void show(std::ostream& s, const std::string& v) { s << "'" << v << "'"; }
template <class T>
void show(std::ostream& s, const std::vector<T>& v) {
  s << "[";
  for (size_t i = 0; i < v.size(); ++i) {
    if (i) s << ", ";
    show(s, v[i]);
  }
  s << "]";
}

// A parameter that is absent keeps its default; one that is present with the wrong type is an
// error (ros::NodeHandle::param would silently fall back to the default).
template <class T>
bool read(Source& src, const std::string& name, const char* type, T* value, std::string* error) {
  if (!src.pnh.hasParam(name)) return true;
  const T before = *value;
  if (!src.pnh.getParam(name, *value)) {
    *error = "parameter " + src.pnh.resolveName(name) + " must be " + type;
    return false;
  }
  if (!(*value == before)) {
    std::ostringstream s;
    s << "~" << name << " ";
    show(s, *value);
    s << " (default ";
    show(s, before);
    s << ")";
    src.differing->push_back(s.str());
  }
  return true;
}

double number(XmlRpc::XmlRpcValue& v) {
  if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) return double(int(v));
  if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) return double(v);
  return std::nan("");
}

// A parameter as the YAML node a material file would hold, for the shared conversion.
YAML::Node toYaml(XmlRpc::XmlRpcValue& v) {
  switch (v.getType()) {
    case XmlRpc::XmlRpcValue::TypeStruct: {
      YAML::Node n(YAML::NodeType::Map);
      for (auto& [key, value] : v) n[key] = toYaml(value);
      return n;
    }
    case XmlRpc::XmlRpcValue::TypeArray: {
      YAML::Node n(YAML::NodeType::Sequence);
      for (int i = 0; i < v.size(); ++i) n.push_back(toYaml(v[i]));
      return n;
    }
    case XmlRpc::XmlRpcValue::TypeString: return YAML::Node(std::string(v));
    case XmlRpc::XmlRpcValue::TypeInt: return YAML::Node(int(v));
    case XmlRpc::XmlRpcValue::TypeDouble: return YAML::Node(double(v));
    case XmlRpc::XmlRpcValue::TypeBoolean: return YAML::Node(bool(v));
    default: return YAML::Node(YAML::NodeType::Null);
  }
}

// ~materials and ~link_materials (config/materials.yaml) through the conversion that
// loadMaterialFile uses (material_yaml.hpp): the same table and the same rules.
bool loadMaterials(const ros::NodeHandle& pnh, SceneDef* scene, std::string* error) {
  const std::string where = "parameter " + pnh.resolveName("materials");
  try {
    XmlRpc::XmlRpcValue root, links;
    if (pnh.getParam("materials", root) &&
        !material_yaml::readTable(toYaml(root), where, &scene->world.materials, error))
      return false;
    if (pnh.getParam("link_materials", links) &&
        !material_yaml::readLinkMaterials(toYaml(links), "parameter " + pnh.resolveName("link_materials"),
                                          scene->world.materials, &scene->link_materials, error))
      return false;
  } catch (const XmlRpc::XmlRpcException& e) {
    *error = where + ": " + e.getMessage();
    return false;
  }
  return true;
}

// One ~joints entry (or ~joint_defaults): {stiffness, damping, break_force, break_torque,
// motor: {hertz, damping_ratio, max_torque}}, every key optional, no other keys.
bool jointSettings(XmlRpc::XmlRpcValue& v, const std::string& where, JointSettings* s,
                   std::string* error) {
  if (v.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
    *error = where + " must be a dictionary {stiffness, damping, break_force, break_torque, "
                     "motor: {hertz, damping_ratio, max_torque}}";
    return false;
  }
  auto field = [&](XmlRpc::XmlRpcValue& value, const std::string& name,
                   std::optional<double>* out) {
    const double x = number(value);
    if (std::isnan(x)) {
      *error = where + "/" + name + " must be a number";
      return false;
    }
    *out = x;
    return true;
  };
  for (auto& [key, value] : v) {
    bool ok = true;
    if (key == "stiffness") ok = field(value, key, &s->stiffness);
    else if (key == "damping") ok = field(value, key, &s->damping);
    else if (key == "break_force") ok = field(value, key, &s->break_force);
    else if (key == "break_torque") ok = field(value, key, &s->break_torque);
    else if (key == "cone" || key == "twist") ok = readSwingTwistKey(key, value, where, s, error);
    else if (key == "motor") {
      if (value.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
        *error = where + "/motor must be a dictionary {hertz, damping_ratio, max_torque}";
        return false;
      }
      for (auto& [mkey, mvalue] : value) {
        if (mkey == "hertz") ok = field(mvalue, "motor/hertz", &s->hertz);
        else if (mkey == "damping_ratio") ok = field(mvalue, "motor/damping_ratio", &s->damping_ratio);
        else if (mkey == "max_torque") ok = field(mvalue, "motor/max_torque", &s->max_torque);
        else {
          *error = where + "/motor has an unknown key '" + mkey +
                   "' (known: hertz, damping_ratio, max_torque)";
          return false;
        }
        if (!ok) return false;
      }
    } else {
      *error = where + " has an unknown key '" + key +
               "' (known: stiffness, damping, break_force, break_torque, motor, cone, twist)";
      return false;
    }
    if (!ok) return false;
  }
  *error = scene::validateJointSettings(*s, where);
  return error->empty();
}

// ~joint_defaults and ~joints (config/joints.yaml).
bool loadJointSettings(const ros::NodeHandle& pnh, NodeConfig* c, std::string* error) {
  try {
    XmlRpc::XmlRpcValue defaults;
    if (pnh.getParam("joint_defaults", defaults) &&
        !jointSettings(defaults, "parameter " + pnh.resolveName("joint_defaults"),
                       &c->scene.joint_defaults, error))
      return false;
    if (c->scene.joint_defaults.cone || c->scene.joint_defaults.twist) {
      *error = "parameter " + pnh.resolveName("joint_defaults") +
               ": cone and twist are set per ball joint (under ~joints), not for every joint";
      return false;
    }
    XmlRpc::XmlRpcValue joints;
    if (!pnh.getParam("joints", joints)) return true;
    const std::string where = "parameter " + pnh.resolveName("joints");
    if (joints.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
      *error = where + " must be a dictionary: joint name -> {stiffness, damping, break_force, "
                       "break_torque, motor}";
      return false;
    }
    for (auto& [name, value] : joints) {
      JointSettings s;
      if (!jointSettings(value, where + "/" + name, &s, error)) return false;
      c->scene.joints.emplace_back(name, s);
    }
  } catch (const XmlRpc::XmlRpcException& e) {
    *error = "parameter " + pnh.resolveName("joints") + ": " + e.getMessage();
    return false;
  }
  return true;
}

// ~markers, ~poke, ~drag (rviz_settings.hpp).
bool loadRvizSettings(Source& pnh, NodeConfig* c, std::string* error) {
  return read(pnh, "markers/contacts", "a bool", &c->markers.contacts, error) &&
         read(pnh, "markers/arrow_fade", "a number (s)", &c->markers.arrow_fade, error) &&
         read(pnh, "markers/impulse_scale", "a number (m/(N*s))", &c->markers.impulse_scale, error) &&
         read(pnh, "markers/force_scale", "a number (m/N)", &c->markers.force_scale, error) &&
         read(pnh, "markers/max_arrow", "a number (m)", &c->markers.max_arrow, error) &&
         read(pnh, "markers/max_arrows", "an integer", &c->markers.max_arrows, error) &&
         read(pnh, "markers/impact_flash", "a number (s)", &c->markers.impact_flash, error) &&
         read(pnh, "poke/enabled", "a bool", &c->poke.enabled, error) &&
         read(pnh, "poke/impulse", "a number (N*s)", &c->poke.impulse, error) &&
         read(pnh, "poke/max_distance", "a number (m)", &c->poke.max_distance, error) &&
         read(pnh, "drag/enabled", "a bool", &c->drag.enabled, error) &&
         read(pnh, "drag/link", "a string", &c->drag.link, error) &&
         read(pnh, "drag/stiffness", "a number (N/m)", &c->drag.stiffness, error) &&
         read(pnh, "drag/damping", "a number (N*s/m)", &c->drag.damping, error) &&
         read(pnh, "drag/max_force", "a number (N)", &c->drag.max_force, error) &&
         read(pnh, "drag/handle_height", "a number (m)", &c->drag.handle_height, error);
}

// ~injury/ragdolls: {<ragdoll>: {head_link: <link>, neck_joint: <joint>}}, both keys optional.
bool loadInjuryRagdolls(const ros::NodeHandle& pnh, NodeConfig* c, std::string* error) {
  XmlRpc::XmlRpcValue v;
  if (!pnh.getParam("injury/ragdolls", v)) return true;
  const std::string where = "parameter " + pnh.resolveName("injury/ragdolls");
  const std::string shape = " must be a dictionary: ragdoll name -> {head_link, neck_joint}";
  if (v.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
    *error = where + shape;
    return false;
  }
  for (auto& [name, entry] : v) {
    if (entry.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
      *error = where + "/" + name + " must be a dictionary {head_link, neck_joint}";
      return false;
    }
    NodeConfig::HeadAndNeck& h = c->injury_ragdolls[name];
    for (auto& [key, value] : entry) {
      if ((key != "head_link" && key != "neck_joint") ||
          value.getType() != XmlRpc::XmlRpcValue::TypeString) {
        *error = where + "/" + name + "/" + key +
                 (key == "head_link" || key == "neck_joint"
                      ? " must be a string"
                      : " is an unknown key (known: head_link, neck_joint)");
        return false;
      }
      (key == "head_link" ? h.head_link : h.neck_joint) = std::string(value);
    }
  }
  return true;
}

// ~contacts, ~impacts, ~injury, ~joint_effort (report_topics.hpp, command_topics.hpp).
bool loadReportSettings(Source& pnh, NodeConfig* c, std::string* error) {
  InjuryDef& injury = c->scene.injury;
  return read(pnh, "contacts/rate", "a number (Hz)", &c->contacts_rate, error) &&
         read(pnh, "impacts/min_impulse", "a number (N*s)", &c->scene.impacts.min_impulse, error) &&
         read(pnh, "impacts/min_speed", "a number (m/s)", &c->scene.impacts.min_speed, error) &&
         read(pnh, "injury/enabled", "a bool", &injury.enabled, error) &&
         read(pnh, "injury/head_link", "a string", &c->injury_head_link, error) &&
         read(pnh, "injury/neck_joint", "a string", &c->injury_neck_joint, error) &&
         read(pnh, "injury/fall_speed", "a number (m/s)", &injury.fall_speed, error) &&
         read(pnh, "injury/rest_speed", "a number (m/s)", &injury.rest_speed, error) &&
         read(pnh, "injury/rest_time", "a number (s)", &injury.rest_time, error) &&
         read(pnh, "joint_effort/duration", "a number (s)", &c->joint_effort_duration, error);
}

// The named surface of the table, or the fallback when the name is empty.
bool surface(const MaterialTable& t, const std::string& name, const char* param,
             const Material& fallback, Material* out, std::string* error) {
  if (name.empty()) {
    *out = fallback;
    return true;
  }
  const int id = t.find(name);
  if (id < 0) {
    *error = std::string("parameter ~") + param + " names '" + name + "', not in ~materials/surfaces";
    return false;
  }
  *out = t.material(id);
  return true;
}

// The physics settings dynamic_reconfigure also sets, checked against the same ranges; the
// message names the start-up parameter.
std::string physicsRangeError(const NodeConfig& c) {
  const ragdoll_sim::PhysicsConfig p =
      physicsConfigOf(c.scene, 1.0 / c.physics_rate, c.scene.material, c.real_time_factor);
  const RangeProblem r = physicsRangeProblem(p);
  if (r.ok()) return "";
  std::ostringstream e;
  if (r.field == "time_step") {
    e << "parameter ~physics_rate " << c.physics_rate << " Hz gives a step of " << r.value
      << " s, outside the range of time_step " << r.rule << " s; got " << c.physics_rate;
    return e.str();
  }
  const std::map<std::string, std::string> names = {
      {"gravity_x", "gravity[0]"},  {"gravity_y", "gravity[1]"},
      {"gravity_z", "gravity[2]"},  {"sleep_time", "sleep/time"},
      {"sleep_speed", "sleep/speed"}, {"rest_time", "sleep/rest_time"},
      {"rest_substeps", "sleep/rest_substeps"},
      {"rest_relax_iterations", "sleep/rest_relax_iterations"}};
  const auto it = names.find(r.field);
  e << "parameter ~" << (it == names.end() ? r.field : it->second) << " must be in " << r.rule
    << " (the range of dynamic_reconfigure's " << r.field << "), got " << r.value;
  return e.str();
}

// The reports' thresholds and rates; a fall must start above the speed it ends below.
std::string reportSettingsError(const NodeConfig& c) {
  std::string e;
  for (const auto& [name, v] :
       {std::pair<const char*, double>{"contacts/rate", c.contacts_rate},
        {"impacts/min_impulse", c.scene.impacts.min_impulse},
        {"impacts/min_speed", c.scene.impacts.min_speed},
        {"injury/rest_speed", c.scene.injury.rest_speed},
        {"injury/rest_time", c.scene.injury.rest_time}})
    if (!(e = nonNegativeError(name, v)).empty()) return "parameter ~" + e;
  if (!(e = positiveError("injury/fall_speed", c.scene.injury.fall_speed)).empty())
    return "parameter ~" + e;
  if (!(c.scene.injury.fall_speed > c.scene.injury.rest_speed))
    return "parameter ~injury/fall_speed must be above ~injury/rest_speed, got " +
           std::to_string(c.scene.injury.fall_speed) + " <= " +
           std::to_string(c.scene.injury.rest_speed);
  if (!(e = finiteError("joint_effort/duration", c.joint_effort_duration)).empty())
    return "parameter ~" + e + " (s; < 0 = until replaced)";
  return "";
}

}  // namespace

bool loadNodeConfig(const ros::NodeHandle& node, NodeConfig* c, std::string* error) {
  const Vec3& g = c->scene.world.gravity;
  std::vector<double> gravity{g.x(), g.y(), g.z()};
  Source pnh{node, &c->differing_from_defaults};
  for (const char* dict : {"materials", "link_materials", "joint_defaults", "joints", "link_damping",
                           "injury/ragdolls"})
    if (node.hasParam(dict)) c->differing_from_defaults.push_back(std::string("~") + dict + " (set)");
  bool ok = read(pnh, "physics_rate", "a number (Hz)", &c->physics_rate, error) &&
            read(pnh, "real_time_factor", "a number", &c->real_time_factor, error) &&
            read(pnh, "clock_rate", "a number (Hz)", &c->clock_rate, error) &&
            read(pnh, "position_iterations", "an integer", &c->scene.world.solver.position_iterations, error) &&
            read(pnh, "ragdoll_name", "a string", &c->ragdoll_name, error) &&
            read(pnh, "tf_prefix", "a string", &c->tf_prefix, error) &&
            read(pnh, "frame_prefix", "a string", &c->frame_prefix, error) &&
            read(pnh, "publish_rate", "a number (Hz)", &c->publish_rate, error) &&
            read(pnh, "substeps", "an integer", &c->scene.world.solver.substeps, error) &&
            read(pnh, "threads", "an integer", &c->scene.world.threads, error) &&
            read(pnh, "lanes", "an integer", &c->scene.world.solver.lanes, error) &&
            read(pnh, "gravity", "a list of 3 numbers (m/s^2)", &gravity, error) &&
            read(pnh, "spawn/x", "a number (m)", &c->spawn.x, error) &&
            read(pnh, "spawn/y", "a number (m)", &c->spawn.y, error) &&
            read(pnh, "spawn/z", "a number (m)", &c->spawn.z, error) &&
            read(pnh, "spawn/roll", "a number (rad)", &c->spawn.roll, error) &&
            read(pnh, "spawn/pitch", "a number (rad)", &c->spawn.pitch, error) &&
            read(pnh, "spawn/yaw", "a number (rad)", &c->spawn.yaw, error) &&
            read(pnh, "spawn/vx", "a number (m/s)", &c->spawn.vx, error) &&
            read(pnh, "spawn/vy", "a number (m/s)", &c->spawn.vy, error) &&
            read(pnh, "spawn/vz", "a number (m/s)", &c->spawn.vz, error) &&
            read(pnh, "spawn/wx", "a number (rad/s)", &c->spawn.wx, error) &&
            read(pnh, "spawn/wy", "a number (rad/s)", &c->spawn.wy, error) &&
            read(pnh, "spawn/wz", "a number (rad/s)", &c->spawn.wz, error) &&
            read(pnh, "world_file", "a string (path)", &c->world_file, error) &&
            read(pnh, "world_strict", "a bool", &c->world_strict, error) &&
            read(pnh, "static_friction", "a number", &c->scene.material.static_friction, error) &&
            read(pnh, "kinetic_friction", "a number", &c->scene.material.kinetic_friction, error) &&
            read(pnh, "restitution", "a number", &c->scene.material.restitution, error) &&
            read(pnh, "rolling_resistance", "a number", &c->scene.material.rolling_resistance, error) &&
            read(pnh, "paused", "a bool", &c->paused, error) &&
            read(pnh, "urdf_file", "a string", &c->urdf_file, error) &&
            read(pnh, "world_frame", "a string", &c->world_frame, error) &&
            read(pnh, "ground", "a bool", &c->scene.ground, error) &&
            read(pnh, "max_impulse", "a number (N*s)", &c->scene.limits.max_impulse, error) &&
            read(pnh, "max_force", "a number (N)", &c->scene.limits.max_force, error) &&
            read(pnh, "max_torque", "a number (N*m)", &c->scene.limits.max_torque, error) &&
            read(pnh, "max_lever_arm", "a number (m)", &c->scene.limits.max_lever_arm, error) &&
            read(pnh, "max_body_force", "a number (N)", &c->scene.limits.max_body_force, error) &&
            read(pnh, "max_body_torque", "a number (N*m)", &c->scene.limits.max_body_torque, error) &&
            read(pnh, "max_forces_per_ragdoll", "an integer", &c->scene.max_forces_per_ragdoll, error) &&
            read(pnh, "max_active_forces", "an integer", &c->scene.max_active_forces, error) &&
            read(pnh, "max_catchup", "a number (s)", &c->max_catchup, error) &&
            read(pnh, "max_linear_speed", "a number (m/s)", &c->scene.world.solver.max_linear_speed, error) &&
            read(pnh, "max_angular_speed", "a number (rad/s)", &c->scene.world.solver.max_angular_speed, error) &&
            read(pnh, "max_steps_per_call", "an integer", &c->max_steps_per_call, error) &&
            read(pnh, "max_position", "a number (m)", &c->max_position, error) &&
            read(pnh, "max_queued_commands", "an integer", &c->scene.max_queued_commands, error) &&
            read(pnh, "publish_markers", "a bool", &c->publish_markers, error) &&
            read(pnh, "ragdoll_material", "a string", &c->ragdoll_material, error) &&
            read(pnh, "ground_material", "a string", &c->ground_material, error) &&
            read(pnh, "motor/hertz", "a number (Hz)", &c->scene.motor.hertz, error) &&
            read(pnh, "motor/damping_ratio", "a number", &c->scene.motor.damping_ratio, error) &&
            read(pnh, "motor/max_torque", "a number (N*m)", &c->scene.motor.max_torque, error) &&
            read(pnh, "balance/enabled", "a bool", &c->balance, error) &&
            read(pnh, "balance/kp", "a number (rad/m)", &c->scene.balance.kp, error) &&
            read(pnh, "balance/kd", "a number (rad s/m)", &c->scene.balance.kd, error) &&
            read(pnh, "balance/ankles", "a list of joint names", &c->scene.balance.ankles, error) &&
            read(pnh, "balance/feet", "a list of link names", &c->scene.balance.feet, error) &&
            read(pnh, "sleep/enabled", "a bool", &c->scene.world.sleep.enabled, error) &&
            read(pnh, "sleep/time", "a number (s)", &c->scene.world.sleep.time, error) &&
            read(pnh, "sleep/speed", "a number (m/s)", &c->scene.world.sleep.speed, error) &&
            read(pnh, "sleep/rest_time", "a number (s)", &c->scene.world.sleep.rest_time, error) &&
            read(pnh, "sleep/rest_substeps", "an integer", &c->scene.world.sleep.rest_substeps, error) &&
            read(pnh, "sleep/rest_relax_iterations", "an integer",
                 &c->scene.world.sleep.rest_relax_iterations, error) &&
            loadMaterials(node, &c->scene, error) && loadJointSettings(node, c, error) &&
            loadLinkDamping(node, &c->scene, error) &&
            loadRvizSettings(pnh, c, error) && loadReportSettings(pnh, c, error) &&
            loadInjuryRagdolls(node, c, error);
  if (!ok) return false;
  if (gravity.size() != 3) {
    *error = "parameter " + node.resolveName("gravity") + " must be a list of 3 numbers, got " +
             std::to_string(gravity.size());
    return false;
  }
  c->scene.world.gravity = Vec3(gravity[0], gravity[1], gravity[2]);
  *error = validateNodeConfig(*c);
  if (!error->empty()) return false;
  c->scene.dt_ns = std::max<int64_t>(1, std::llround(1e9 / c->physics_rate));
  if (!(*error = physicsRangeError(*c)).empty()) return false;
  return
         surface(c->scene.world.materials, c->ragdoll_material, "ragdoll_material",
                 c->scene.material, &c->scene.ragdoll_surface, error) &&
         surface(c->scene.world.materials, c->ground_material, "ground_material",
                 c->scene.material, &c->scene.ground_surface, error);
}

std::string validateNodeConfig(const NodeConfig& c) {
  // The core's messages name the field ("sleep.speed must be ..."); the parameter is
  // ~sleep/speed.
  const auto param = [](std::string e) {
    if (e.empty()) return e;
    const size_t dot = e.find('.');
    if (dot < e.find(' ')) e[dot] = '/';
    return "parameter ~" + e;
  };
  std::string e;
  if (!(e = param(positiveError("physics_rate", c.physics_rate))).empty()) return e;
  if (!(e = param(positiveError("publish_rate", c.publish_rate))).empty()) return e;
  if (!(e = param(worldDefError(c.scene.world))).empty()) return e;
  if (!(e = param(nonNegativeError("clock_rate", c.clock_rate))).empty()) return e;
  if (!c.ragdoll_name.empty() && !scene::ragdollNameError(c.ragdoll_name).empty())
    return "parameter ~ragdoll_name: " + scene::ragdollNameError(c.ragdoll_name);
  if (!scene::tfPrefixError(c.tf_prefix).empty())
    return "parameter ~tf_prefix: " + scene::tfPrefixError(c.tf_prefix);
  if (!scene::tfPrefixError(c.frame_prefix).empty())
    return "parameter ~frame_prefix: " + scene::tfPrefixError(c.frame_prefix);
  const SpawnPose& s = c.spawn;
  for (double v : {s.x, s.y, s.z, s.roll, s.pitch, s.yaw})
    if (!std::isfinite(v)) return "parameters ~spawn/{x,y,z,roll,pitch,yaw} must be finite";
  const Vec3 v = c.spawnLinearVelocity(), w = c.spawnAngularVelocity();
  const SolverSettings& solver = c.scene.world.solver;
  if (!v.allFinite() || v.norm() > solver.max_linear_speed)
    return "parameters ~spawn/{vx,vy,vz} must be finite with |v| <= ~max_linear_speed = " +
           std::to_string(solver.max_linear_speed) + " m/s, got |v| = " + std::to_string(v.norm());
  if (!w.allFinite() || w.norm() > solver.max_angular_speed)
    return "parameters ~spawn/{wx,wy,wz} must be finite with |w| <= ~max_angular_speed = " +
           std::to_string(solver.max_angular_speed) + " rad/s, got |w| = " + std::to_string(w.norm());
  if (!(e = param(materialError(c.scene.material))).empty()) return e;
  if (c.world_frame.empty()) return "parameter ~world_frame must not be empty";
  for (const auto& [name, v] :
       {std::pair<const char*, double>{"max_impulse", c.scene.limits.max_impulse},
        {"max_force", c.scene.limits.max_force},
        {"max_torque", c.scene.limits.max_torque},
        {"max_lever_arm", c.scene.limits.max_lever_arm},
        {"max_body_force", c.scene.limits.max_body_force},
        {"max_body_torque", c.scene.limits.max_body_torque},
        {"max_catchup", c.max_catchup},
        {"max_position", c.max_position}})
    if (!(e = param(positiveError(name, v))).empty()) return e;
  if (!(e = param(intRangeError("max_steps_per_call", c.max_steps_per_call, 1))).empty())
    return e;
  if (!(e = param(intRangeError("max_queued_commands", c.scene.max_queued_commands, 1))).empty())
    return e;
  for (const auto& [name, v] :
       {std::pair<const char*, int>{"max_forces_per_ragdoll", c.scene.max_forces_per_ragdoll},
        {"max_active_forces", c.scene.max_active_forces}})
    if (!(e = param(intRangeError(name, v, 1))).empty()) return e;
  if (!(e = scene::validateMotorGains(c.scene.motor, "parameter ~motor")).empty()) return e;
  if (!std::isfinite(c.scene.balance.kp) || !std::isfinite(c.scene.balance.kd))
    return "parameters ~balance/kp and ~balance/kd must be finite";
  if (!(e = reportSettingsError(c)).empty()) return e;
  if (!(e = scene::validateMarkerSettings(c.markers)).empty()) return e;
  if (!(e = scene::validatePokeSettings(c.poke)).empty()) return e;
  return scene::validateDragSettings(c.drag);
}

}  // namespace node
}  // namespace ragdoll_sim
