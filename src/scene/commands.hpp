// Validation and conversion of the node's impulse / force commands. ROS-free: the node copies
// the message fields into these plain structs, so the rules here can be unit-tested without ROS.
//
// Rules (both commands):
//   - `link` must name a real (simulated) link of the ragdoll; the massless dummy links inside a
//     ball-joint chain are rejected with a message naming the joint.
//   - `frame` is "" or "world" (point and vectors in world coordinates) or "link" (point relative
//     to the link origin, vectors in link axes).
//   - every number must be finite; |impulse| <= max_impulse, |force| <= max_force,
//     |torque| <= max_torque; the application point must lie within max_lever_arm of the link
//     origin (a far-away point would turn a small push into a huge spin).
// Conversion happens once, when the command arrives: the application point becomes a point fixed
// in the link (so a long force keeps acting on the same material point), vectors become world
// vectors (fixed in world axes for the whole duration, like gazebo_ros apply_body_wrench).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

#include "names.hpp"
#include "ragdoll_sim/math.hpp"
#include "ragdoll_sim/scene.hpp"

namespace ragdoll_sim {

struct RagdollDef;

namespace scene {

enum class CommandFrame { World, Link };

// Name -> link index of a RagdollDef, built once at start-up.
class LinkTable {
 public:
  LinkTable() = default;
  explicit LinkTable(const RagdollDef& def);
  // Index into RagdollDef::links, or -1.
  int find(const std::string& name) const;
  // For a dummy chain link: the name of its ball joint; nullptr otherwise.
  const std::string* chainJointOf(const std::string& name) const;
  const std::vector<std::string>& names() const { return names_; }

 private:
  std::vector<std::string> names_;
  std::unordered_map<std::string, int> index_;
  std::unordered_map<std::string, std::string> chain_joint_;
};

// Outcome of validation: ok, or an error message that names the problem.
struct CommandCheck {
  bool ok = false;
  std::string error;
  // The rule that failed, from a fixed set of short names ("unknown link", "force not
  // finite", "above max_torque", "lever arm", ...): the key of the node's per-kind warning
  // throttle (never message contents).
  std::string problem;
  int link = -1;
  CommandFrame frame = CommandFrame::World;
};

// Parses "", "world" -> World, "link" -> Link.
bool parseFrame(const std::string& frame, CommandFrame* out);

// Current pose of a link by index (called at most once, after the link name was resolved).
using LinkPoseFn = std::function<Transform(int link)>;

CommandCheck checkImpulse(const ImpulseCommand& cmd, const LinkTable& links,
                          const CommandLimits& limits, const LinkPoseFn& link_pose);
CommandCheck checkForce(const ForceCommand& cmd, const LinkTable& links,
                        const CommandLimits& limits, const LinkPoseFn& link_pose);

// The same checks in two parts: the link and frame, resolved once when the command arrives
// (ok with link and frame set, or the error), then the rest when it is applied.
CommandCheck resolveImpulseLink(const ImpulseCommand& cmd, const LinkTable& links);
CommandCheck resolveForceLink(const ForceCommand& cmd, const LinkTable& links);
CommandCheck checkImpulse(const ImpulseCommand& cmd, const CommandCheck& resolved,
                          const CommandLimits& limits, const LinkPoseFn& link_pose);
CommandCheck checkForce(const ForceCommand& cmd, const CommandCheck& resolved,
                        const CommandLimits& limits, const LinkPoseFn& link_pose);

// A validated impulse in world coordinates.
struct WorldImpulse {
  int link = -1;
  Vec3 point = Vec3::Zero();    // world
  Vec3 impulse = Vec3::Zero();  // world
};

WorldImpulse toWorldImpulse(const ImpulseCommand& cmd, const CommandCheck& check,
                            const Transform& link_pose);

// A force being applied, re-applied every physics step until steps_left reaches 0.
struct ActiveForce {
  int link = -1;
  Vec3 local_point = Vec3::Zero();  // fixed in the link frame
  Vec3 force = Vec3::Zero();        // world
  Vec3 torque = Vec3::Zero();       // world
  int64_t steps_left = 1;           // < 0: until cleared
};

// Number of physics steps of length dt a force of `duration` acts for: -1 for a negative
// duration (until cleared), at least 1 otherwise (0 -> one step), round(duration / dt) else.
int64_t forceStepCount(double duration, double dt);

ActiveForce toActiveForce(const ForceCommand& cmd, const CommandCheck& check,
                          const Transform& link_pose, double dt);

// Splits "<ragdoll>/<rest>" when the part before the first '/' is the name of a ragdoll
// (is_ragdoll); otherwise ragdoll = "" and rest = qualified.
template <class IsRagdoll>
void splitQualifiedName(const std::string& qualified, IsRagdoll is_ragdoll, std::string* ragdoll,
                        std::string* rest) {
  const size_t slash = qualified.find('/');
  if (slash != std::string::npos && slash > 0 && is_ragdoll(qualified.substr(0, slash))) {
    *ragdoll = qualified.substr(0, slash);
    *rest = qualified.substr(slash + 1);
  } else {
    ragdoll->clear();
    *rest = qualified;
  }
}

}  // namespace scene
}  // namespace ragdoll_sim
