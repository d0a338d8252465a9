// RagdollDef: a tree of links and joints independent of any file format (the URDF loader
// produces one); spawnRagdoll instantiates it in a World.
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ragdoll_sim/world.hpp"

namespace ragdoll_sim {

struct LinkDef {
  std::string name;
  double mass = 1.0;
  Vec3 com = Vec3::Zero();                 // link frame
  Mat3 inertia = Mat3::Identity() * 0.01;  // about com, link-frame axes
  std::vector<ShapeDef> shapes;            // in the link frame
  // Per shape (parallel to `shapes`, may be shorter): where the loader got it, e.g. "box",
  // "capsule", "mesh hull of foo.stl (24 vertices)", "box fitted to the inertia (mesh ...
  // unresolved)"; approximated shapes say so. For reports (ragdoll_check) only.
  std::vector<std::string> shape_sources;
  // URDF <gazebo reference> mu1 / mu2 of the link (mean of the two), applied to its own shapes'
  // friction by spawnRagdoll even over a material override; < 0: not given.
  std::vector<double> shape_friction;      // per shape, parallel to `shapes` (may be shorter)
  // Surface material by its name in the material table (WorldDef::materials): the link's, and
  // per shape (parallel to `shapes`, may be shorter; "" = the link's). "" = the Scene's default
  // surface for the model's kind. From SDF <surface><ragdoll_sim:material>, URDF <gazebo
  // reference> <ragdoll_sim:material>, a visual material script name as written ("Gazebo/Wood":
  // the Scene takes it as "wood" when the table has that, else silently as ""), or the Scene's
  // per-link map (SceneDef::link_materials). An unknown name that is not "Gazebo/..." is WARNed.
  std::string material;
  std::vector<std::string> shape_materials;
  bool has_color = false;                  // a visual colour (URDF / SDF <material>)
  std::array<double, 4> color = {0.5, 0.5, 0.5, 1.0};  // rgba
  Transform rest_pose;                     // link frame relative to the root link, zero angles
  // Velocity damping of the body, 1/s (BodyDef: dv/dt = -c v): from URDF <gazebo reference>
  // <dampingFactor> (urdf_loader.hpp: the mapping) or the Scene's per-link map.
  double linear_damping = 0.0;
  double angular_damping = 0.0;
};

// Swing-twist limits of a ball joint (BallJointDef, limit_mode SwingTwist): twist about the
// joint's axes[0] within [twist_lower, twist_upper], swing within the cone of half-angle cone_1
// about axes[1] and cone_2 about axes[2] (an ellipse; equal: circular). Defaults: free.
struct SwingTwistLimits {
  double cone_1 = M_PI, cone_2 = M_PI;  // rad, in (0, pi]
  double twist_lower = -M_PI, twist_upper = M_PI;  // rad, in [-pi, pi], lower <= upper
};

// "" when valid, else "<name> must be ..., got <v>" for the first bad field, named by `names`
// (cone_1, cone_2, twist_lower, twist_upper in the caller's words).
std::string swingTwistLimitsError(const SwingTwistLimits& l, const std::array<const char*, 4>& names);

// Ball: a URDF revolute chain folded into one joint, or URDF `spherical`. Hinge: revolute /
// continuous. Prismatic: URDF prismatic (axes[0], limits in m). Fixed: a URDF fixed joint kept
// as a weld (gazebo <preserveFixedJoint>); other fixed joints are lumped by the loader.
enum class RagdollJointKind { Ball, Hinge, Prismatic, Fixed };

const char* jointKindName(RagdollJointKind kind);
// Angles (or positions) the joint has: Ball 3, Hinge 1, Prismatic 1, Fixed 0.
int jointAxisCount(RagdollJointKind kind);

struct RagdollJointDef {
  std::string name;                        // ball: "<first>+<second>+<third>" revolute names
  RagdollJointKind kind = RagdollJointKind::Hinge;
  int parent = -1, child = -1;             // link indices
  Transform frame_parent;                  // joint frame in the parent link frame
  Transform frame_child;                   // joint frame in the child link frame
  // Hinge, Prismatic: axes[0]. Ball: the three chain axes in order (joint frame). Fixed: none.
  std::vector<Vec3> axes;
  bool limited = false;
  std::vector<double> lower, upper;        // one per axis
  std::vector<std::string> source_joints;  // URDF joint names, one per axis
  std::vector<std::string> chain_links;    // URDF links inside a ball chain (massless dummies)
  // Pose of chain link k relative to the joint frame rotated by the first k+1 axis angles:
  // link_k = parent * frame_parent * R(a0,t0)..R(ak,tk) * chain_offsets[k] (O_{k+2}... folded).
  std::vector<Transform> chain_offsets;
  // URDF <dynamics>, one value per axis (a ball chain: each source joint's on its axis; empty
  // or short = 0): viscous damping (N m s/rad) -> JointMotor::damping, and Coulomb friction
  // torque (N m) -> a velocity motor with target 0 capped at the friction (see passiveMotor).
  std::vector<double> damping, friction;
  // Elasticity and break force of the anchor (not in URDF; default rigid and unbreakable).
  JointSpring spring;
  // Ball: swing-twist limits in place of the Euler limits lower / upper (URDF spherical
  // <limit cone_y ...>, the Scene's ~joints cone / twist); unset: the Euler limits.
  std::optional<SwingTwistLimits> swing_twist;
};

// A URDF link the loader lumped into a body through fixed joints (a sensor frame, a hand's
// palm link): it has no body of its own but a fixed pose in the body's link frame (for TF).
struct FixedFrameDef {
  std::string name;
  int link = -1;        // RagdollDef::links index of the body that carries it
  Transform offset;     // its frame in that link's frame
};

struct RagdollDef {
  std::string name;
  int root = 0;
  // The root link is pinned where it is spawned (a static body): a URDF whose root is a link
  // named "world" fixed-jointed to the robot (Gazebo's convention), an SDF joint to the world.
  bool fixed_base = false;
  std::vector<LinkDef> links;
  std::vector<FixedFrameDef> fixed_frames;
  std::vector<RagdollJointDef> joints;
  std::vector<std::pair<int, int>> no_collide;  // link index pairs that never collide
  std::vector<std::string> notes;                // what the loader merged or mapped
  std::vector<std::string> warnings;             // what it approximated, repaired or ignored

  int findLink(const std::string& name) const;   // -1 if absent
  double totalMass() const;
};

struct Ragdoll {
  std::vector<BodyId> bodies;   // one per RagdollDef::links entry
  std::vector<JointId> joints;  // one per RagdollDef::joints entry
};

// The motor spawnRagdoll puts on one axis of a joint: viscous damping damping[axis], and for
// friction[axis] > 0 a velocity motor (hertz 0, target_velocity 0, max_torque = friction).
JointMotor passiveMotor(const RagdollJointDef& joint, int axis);

// Creates bodies (root link at root_pose, the rest at their rest poses; a fixed_base root is a
// static body there), shapes, joints and collision filters. Optional material overrides every
// shape's material. Joints get passiveMotor on every axis and their `spring`.
Ragdoll spawnRagdoll(World& world, const RagdollDef& def, const Transform& root_pose,
                     const Material* material = nullptr);

// World poses of the chain links of a ball joint (for publishing them as TF).
std::vector<Transform> ballChainLinkPoses(const World& world, const Ragdoll& ragdoll,
                                          const RagdollDef& def, int joint_index);

}  // namespace ragdoll_sim
