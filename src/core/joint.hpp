// A joint: what every type has (joint_base.hpp) and its type's own parts, one struct per type
// (joint_ball.hpp, joint_hinge.hpp, joint_fixed.hpp, joint_prismatic.hpp) in a variant. Each
// type prepares, warm starts, solves, advances and projects its parts and resets and rescales
// their impulses; the functions here dispatch to it with a switch on the variant's index.
#pragma once

#include <cstddef>
#include <type_traits>
#include <variant>

#include "joint_ball.hpp"
#include "joint_base.hpp"
#include "joint_fixed.hpp"
#include "joint_hinge.hpp"
#include "joint_prismatic.hpp"

namespace ragdoll_sim {

// In the order of JointType.
using JointKind = std::variant<BallJoint, HingeJoint, FixedJoint, PrismaticJoint>;

struct Joint : JointBase {
  Joint() : Joint(BallJointDef()) {}  // between no bodies (a = b = -1)
  explicit Joint(const BallJointDef& def)
      : JointBase(def), kind(std::in_place_type<BallJoint>, def) {}
  explicit Joint(const HingeJointDef& def)
      : JointBase(def), kind(std::in_place_type<HingeJoint>, def) {}
  explicit Joint(const FixedJointDef& def)
      : JointBase(def), kind(std::in_place_type<FixedJoint>, def) {}
  explicit Joint(const PrismaticJointDef& def)
      : JointBase(def), kind(std::in_place_type<PrismaticJoint>, def) {}

  JointKind kind;

  JointType type() const { return JointType(kind.index()); }
  template <class T>
  const T* as() const {
    return std::get_if<T>(&kind);
  }

  // f(type struct): each case a direct call, no exception path.
  template <class F>
  decltype(auto) visit(F&& f) {
    switch (kind.index()) {
      case 0: return f(*std::get_if<0>(&kind));
      case 1: return f(*std::get_if<1>(&kind));
      case 2: return f(*std::get_if<2>(&kind));
      default: return f(*std::get_if<3>(&kind));
    }
  }

  // The anchor of a ball, hinge or fixed joint; nullptr for a slider, which has none.
  AnchorPart* anchor() {
    switch (kind.index()) {
      case 0: return &std::get_if<0>(&kind)->anchor;
      case 1: return &std::get_if<1>(&kind)->anchor;
      case 2: return &std::get_if<2>(&kind)->anchor;
      default: return nullptr;
    }
  }

  // Every part's accumulated impulse times s (warmStartScale, solver_context.hpp).
  void scaleImpulses(double s) {
    visit([&](auto& t) { t.scaleImpulses(s); });
  }
  // After a solver fault: the parts lose their impulses (prepareJoint rebuilds the rest).
  void clearWarmStart() {
    visit([&](auto& t) { t.clearWarmStart(); });
    force = 0.0;
    torque = 0.0;
    overloaded = false;
  }
  // The motor of one axis (hinge, prismatic: 0; ball: Euler axes 0..2); std::out_of_range
  // for an axis the type does not have.
  JointMotor& motorAt(int axis) {
    return visit([&](auto& t) -> JointMotor& { return t.motorAt(axis); });
  }
  // A motor turned off drops its accumulated impulse: its solve no longer updates it, and the
  // warm start would otherwise keep applying it while the joint's other rows are active.
  void clearMotorImpulse(int axis) {
    if (HingeJoint* h = std::get_if<HingeJoint>(&kind)) h->axes.motor_parts.at(axis).impulse = 0.0;
    else if (BallJoint* b = std::get_if<BallJoint>(&kind)) b->axes.motor_parts.at(axis).impulse = 0.0;
    else if (PrismaticJoint* p = std::get_if<PrismaticJoint>(&kind)) p->linear_motor.impulse = 0.0;
  }
};
static_assert(std::variant_size_v<JointKind> == 4, "Joint::visit has a case per type");
static_assert(std::is_same_v<std::variant_alternative_t<size_t(JointType::Prismatic), JointKind>,
                             PrismaticJoint>,
              "JointKind in the order of JointType");

// The step functions (joint.cpp) dispatch to the joint's type. They are not inline: the
// solver's loops stay small, and each dispatch ends in a jump to the type's function.
void prepareJoint(Joint& j, const StepContext& ctx);
// first_substep: the angles and rows are recomputed exactly, and the anchors and hinge axes
// refreshed; later substeps keep the advanced angles of joints whose limits stay open
// (AngleAxes::limitsOpen) and the anchors and axes advanceJoint refreshed.
void warmStartJoint(Joint& j, const StepContext& ctx, bool first_substep);
void solveJoint(Joint& j, const StepContext& ctx, bool use_bias);
// Before the first substep's warm starts of joints[0, count) (scalar sweeps): the exact angles
// those warm starts would compute one joint at a time, several joints at once in double lanes
// (joint_angles_lanes.hpp; the same bits), with their rows and masses.
void firstSubstepAngles(Joint* const* joints, int count, const StepContext& ctx);
// After a substep's last sweep: sets a rigid anchor's force (N, from its accumulated impulse)
// and says whether the joint breaks (break force or torque passed, or the anchor capped).
bool breaksAfterSubstep(Joint& j, const StepContext& ctx);
// After the position update of a substep, before the relax sweeps: angles advance by h rate,
// anchors and axes follow the moved bodies.
void advanceJoint(Joint& j, const StepContext& ctx);
// Position projection after the substeps (the error beyond the slops, no velocity added):
// projectJointLimits turns the bodies (rotation lock of fixed and prismatic joints, hinge axis,
// angle limits, swing-twist) and moves a prismatic joint back into its slide range;
// projectJointAnchor moves the rigid anchor (part_point.hpp) or a slider back onto its line. A
// sweep projects every joint's limits before any anchor: a limit turns its bodies about their
// centres, which moves the neighbours' anchors. Both return true when they moved a body.
bool projectJointLimits(Joint& j, const StepContext& ctx);
bool projectJointAnchor(Joint& j, const StepContext& ctx);

}  // namespace ragdoll_sim
