#include "commands.hpp"

#include <cctype>
#include <cmath>
#include <sstream>

#include "ragdoll_sim/ragdoll.hpp"

namespace ragdoll_sim {
namespace scene {

LinkTable::LinkTable(const RagdollDef& def) {
  names_.reserve(def.links.size());
  for (size_t i = 0; i < def.links.size(); ++i) {
    names_.push_back(def.links[i].name);
    index_.emplace(def.links[i].name, static_cast<int>(i));
  }
  for (const RagdollJointDef& j : def.joints)
    for (const std::string& c : j.chain_links) chain_joint_.emplace(c, j.name);
}

int LinkTable::find(const std::string& name) const {
  auto it = index_.find(name);
  return it == index_.end() ? -1 : it->second;
}

const std::string* LinkTable::chainJointOf(const std::string& name) const {
  auto it = chain_joint_.find(name);
  return it == chain_joint_.end() ? nullptr : &it->second;
}

bool parseFrame(const std::string& frame, CommandFrame* out) {
  if (frame.empty() || frame == "world") {
    *out = CommandFrame::World;
    return true;
  }
  if (frame == "link") {
    *out = CommandFrame::Link;
    return true;
  }
  return false;
}

namespace {

std::string fmt(const Vec3& v) {
  std::ostringstream s;
  s << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return s.str();
}

CommandCheck fail(const std::string& problem, const std::string& msg) {
  CommandCheck c;
  c.ok = false;
  c.error = msg;
  c.problem = problem;
  return c;
}

// Link and frame; fills check.link / check.frame or returns an error.
bool resolveLinkAndFrame(const std::string& kind, const std::string& link,
                         const std::string& frame, const LinkTable& links, CommandCheck* check) {
  if (link.empty()) {
    *check = fail("empty link", kind + " rejected: empty link name");
    return false;
  }
  int index = links.find(link);
  if (index < 0) {
    if (const std::string* joint = links.chainJointOf(link)) {
      *check = fail("dummy link", kind + " rejected: link " + quoted(link) +
                    " is a massless dummy link inside ball joint '" + *joint +
                    "'; use one of the links it connects");
      return false;
    }
    std::string known;
    for (const std::string& n : links.names()) known += (known.empty() ? "" : ", ") + n;
    *check = fail("unknown link",
                  kind + " rejected: unknown link " + quoted(link) + " (links: " + known + ")");
    return false;
  }
  CommandFrame f;
  if (!parseFrame(frame, &f)) {
    *check = fail("unknown frame", kind + " rejected: unknown frame '" + frame +
                  "' (use \"world\", \"\" = world, or \"link\")");
    return false;
  }
  check->link = index;
  check->frame = f;
  return true;
}

bool checkVector(const std::string& kind, const char* what, const Vec3& v, double cap,
                 const char* unit, const char* cap_param, CommandCheck* check) {
  if (!v.allFinite()) {
    *check = fail(std::string(what) + " not finite",
                  kind + " rejected: " + what + " " + fmt(v) + " is not finite");
    return false;
  }
  double n = v.norm();
  if (n > cap) {
    std::ostringstream s;
    s << kind << " rejected: |" << what << "| = " << n << " " << unit << " exceeds "
      << cap_param << " = " << cap << " " << unit;
    *check = fail(std::string("above ") + cap_param, s.str());
    return false;
  }
  return true;
}

bool checkPoint(const std::string& kind, const Vec3& point, const CommandCheck& resolved,
                const CommandLimits& limits, const LinkPoseFn& link_pose, CommandCheck* check) {
  if (!point.allFinite()) {
    *check = fail("point not finite", kind + " rejected: point " + fmt(point) + " is not finite");
    return false;
  }
  double lever = resolved.frame == CommandFrame::Link
                     ? point.norm()
                     : (point - link_pose(resolved.link).p).norm();
  if (lever > limits.max_lever_arm) {
    std::ostringstream s;
    s << kind << " rejected: point " << fmt(point) << " is " << lever
      << " m from the link origin, more than max_lever_arm = " << limits.max_lever_arm
      << " m (in frame \"world\" the point is in world coordinates; use frame \"link\" for a "
         "point relative to the link)";
    *check = fail("lever arm", s.str());
    return false;
  }
  return true;
}

}  // namespace

CommandCheck resolveImpulseLink(const ImpulseCommand& cmd, const LinkTable& links) {
  CommandCheck c;
  c.ok = resolveLinkAndFrame("impulse on " + quoted(cmd.link), cmd.link, cmd.frame, links, &c);
  return c;
}

CommandCheck resolveForceLink(const ForceCommand& cmd, const LinkTable& links) {
  CommandCheck c;
  c.ok = resolveLinkAndFrame("force on " + quoted(cmd.link), cmd.link, cmd.frame, links, &c);
  return c;
}

CommandCheck checkImpulse(const ImpulseCommand& cmd, const LinkTable& links,
                          const CommandLimits& limits, const LinkPoseFn& link_pose) {
  return checkImpulse(cmd, resolveImpulseLink(cmd, links), limits, link_pose);
}

CommandCheck checkForce(const ForceCommand& cmd, const LinkTable& links,
                        const CommandLimits& limits, const LinkPoseFn& link_pose) {
  return checkForce(cmd, resolveForceLink(cmd, links), limits, link_pose);
}

CommandCheck checkImpulse(const ImpulseCommand& cmd, const CommandCheck& resolved,
                          const CommandLimits& limits, const LinkPoseFn& link_pose) {
  if (!resolved.ok) return resolved;
  const std::string kind = "impulse on " + quoted(cmd.link);
  CommandCheck c = resolved;
  if (!checkVector(kind, "impulse", cmd.impulse, limits.max_impulse, "N*s", "max_impulse", &c))
    return c;
  if (!checkPoint(kind, cmd.point, resolved, limits, link_pose, &c)) return c;
  c.ok = true;
  return c;
}

CommandCheck checkForce(const ForceCommand& cmd, const CommandCheck& resolved,
                        const CommandLimits& limits, const LinkPoseFn& link_pose) {
  if (!resolved.ok) return resolved;
  const std::string kind = "force on " + quoted(cmd.link);
  CommandCheck c = resolved;
  if (!checkVector(kind, "force", cmd.force, limits.max_force, "N", "max_force", &c)) return c;
  if (!checkVector(kind, "torque", cmd.torque, limits.max_torque, "N*m", "max_torque", &c))
    return c;
  if (!std::isfinite(cmd.duration)) {
    std::ostringstream s;
    s << kind << " rejected: duration " << cmd.duration
      << " is not finite (use a negative duration for 'until cleared')";
    return fail("duration not finite", s.str());
  }
  if (!checkPoint(kind, cmd.point, resolved, limits, link_pose, &c)) return c;
  c.ok = true;
  return c;
}

WorldImpulse toWorldImpulse(const ImpulseCommand& cmd, const CommandCheck& check,
                            const Transform& link_pose) {
  WorldImpulse w;
  w.link = check.link;
  if (check.frame == CommandFrame::Link) {
    w.point = link_pose.apply(cmd.point);
    w.impulse = link_pose.q * cmd.impulse;
  } else {
    w.point = cmd.point;
    w.impulse = cmd.impulse;
  }
  return w;
}

int64_t forceStepCount(double duration, double dt) {
  if (duration < 0.0) return -1;
  double n = std::round(duration / dt);
  if (n < 1.0) return 1;
  if (n > 1e18) return -1;  // longer than any run: the same as "until cleared"
  return static_cast<int64_t>(n);
}

ActiveForce toActiveForce(const ForceCommand& cmd, const CommandCheck& check,
                          const Transform& link_pose, double dt) {
  ActiveForce f;
  f.link = check.link;
  if (check.frame == CommandFrame::Link) {
    f.local_point = cmd.point;
    f.force = link_pose.q * cmd.force;
    f.torque = link_pose.q * cmd.torque;
  } else {
    f.local_point = link_pose.applyInverse(cmd.point);
    f.force = cmd.force;
    f.torque = cmd.torque;
  }
  f.steps_left = forceStepCount(cmd.duration, dt);
  return f;
}

}  // namespace scene
}  // namespace ragdoll_sim
