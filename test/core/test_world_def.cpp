// WorldDef's ranges (src/core/world_def.cpp): every field out of range is refused by
// worldDefError with its name, World's constructor throws with that message, a shape with a bad
// material, geometry or pose is refused without being added, and so is a joint def out of range
// (src/core/joint_def.cpp) or a bad motor at run time; the defaults and the ends of each range
// pass.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "ragdoll_sim/range_check.hpp"
#include "ragdoll_sim/world.hpp"

using namespace ragdoll_sim;

namespace {
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

struct BadCase {
  std::string name;  // the field the message must name
  std::function<void(WorldDef&)> spoil;
};

bool contains(const std::string& text, const std::string& word) {
  return text.find(word) != std::string::npos;
}
}  // namespace

TEST(RangeCheck, Boundaries) {
  EXPECT_EQ(positiveError("x", 1e-300), "");
  EXPECT_EQ(positiveError("x", 0.0), "x must be a finite number > 0, got 0");
  EXPECT_NE(positiveError("x", kInf), "");
  EXPECT_NE(positiveError("x", kNaN), "");
  EXPECT_EQ(nonNegativeError("x", 0.0), "");
  EXPECT_EQ(nonNegativeError("x", -0.5), "x must be a finite number >= 0, got -0.5");
  EXPECT_NE(nonNegativeError("x", kNaN), "");
  EXPECT_EQ(rangeError("x", 1.0, 0.0, 1.0), "");
  EXPECT_EQ(rangeError("x", 0.0, 0.0, 1.0), "");
  EXPECT_EQ(rangeError("x", 1.5, 0.0, 1.0), "x must be a finite number in [0, 1], got 1.5");
  EXPECT_NE(rangeError("x", kNaN, 0.0, 1.0), "");
  EXPECT_EQ(intRangeError("n", 0, 0), "");
  EXPECT_EQ(intRangeError("n", -1, 0, INT_MAX, " (0 = off)"), "n must be >= 0 (0 = off), got -1");
  EXPECT_EQ(intRangeError("n", 9, 1, 8), "n must be >= 1 and <= 8, got 9");
  EXPECT_EQ(intRangeError("n", 8, 1, 8), "");
  EXPECT_EQ(finiteError("t", -1e300), "");
  EXPECT_EQ(finiteError("t", kInf), "t must be finite, got inf");
  EXPECT_EQ(positiveOrInfError("f", kInf), "");
  EXPECT_EQ(positiveOrInfError("f", 0.0), "f must be > 0 (or inf), got 0");
  EXPECT_EQ(nonNegativeOrInfError("c", 0.0), "");
  EXPECT_EQ(nonNegativeOrInfError("c", kInf), "");
  EXPECT_NE(nonNegativeOrInfError("c", kNaN), "");
  EXPECT_EQ(orderError("lo", -kInf, "hi", kInf), "");
  EXPECT_EQ(orderError("lo", 1.0, "hi", 1.0), "");
  EXPECT_EQ(orderError("lo", 2.0, "hi", 1.0), "lo must be <= hi, got 2 > 1");
  EXPECT_NE(orderError("lo", kNaN, "hi", 1.0), "");
  EXPECT_EQ(firstError({"", "b", "c"}), "b");
  EXPECT_EQ(firstError({"", ""}), "");
}

TEST(WorldDefRanges, DefaultsPass) {
  EXPECT_EQ(worldDefError(WorldDef()), "");
  EXPECT_EQ(sleepDefError(SleepDef()), "");
  WorldDef edge;  // the ends of each range are allowed
  edge.solver.contact_relax_iterations = edge.solver.joint_relax_iterations = edge.solver.position_iterations = 0;
  edge.solver.anchor_iterations = 0;
  edge.solver.position_factor = 1.0;
  edge.solver.contact_hertz = edge.solver.joint_hertz = 0.0;  // rigid rows
  edge.solver.contact_damping_ratio = edge.solver.joint_damping_ratio = 0.0;
  edge.solver.joint_slop = edge.solver.angular_slop = edge.solver.linear_slop = 0.0;
  edge.solver.speculative_distance = 0.0;
  edge.threads = WorldDef::kMaxThreads;
  edge.sleep.rest_substeps = 0;
  EXPECT_EQ(worldDefError(edge), "");
  edge.threads = 0;
  EXPECT_NO_THROW(World w(edge));
}

TEST(WorldDefRanges, EveryFieldOutOfRangeIsNamedAndRefused) {
  const std::vector<BadCase> cases = {
      {"gravity", [](WorldDef& d) { d.gravity.y() = kNaN; }},
      {"substeps", [](WorldDef& d) { d.solver.substeps = 0; }},
      {"contact_relax_iterations", [](WorldDef& d) { d.solver.contact_relax_iterations = -1; }},
      {"joint_relax_iterations", [](WorldDef& d) { d.solver.joint_relax_iterations = -1; }},
      {"position_iterations", [](WorldDef& d) { d.solver.position_iterations = -1; }},
      {"anchor_iterations", [](WorldDef& d) { d.solver.anchor_iterations = -2; }},
      {"position_factor", [](WorldDef& d) { d.solver.position_factor = 1.5; }},
      {"position_factor", [](WorldDef& d) { d.solver.position_factor = -0.1; }},
      {"max_position_correction", [](WorldDef& d) { d.solver.max_position_correction = kInf; }},
      {"joint_slop", [](WorldDef& d) { d.solver.joint_slop = -1e-4; }},
      {"angular_slop", [](WorldDef& d) { d.solver.angular_slop = kNaN; }},
      {"max_angular_correction", [](WorldDef& d) { d.solver.max_angular_correction = -0.2; }},
      {"contact_hertz", [](WorldDef& d) { d.solver.contact_hertz = -360.0; }},
      {"contact_damping_ratio", [](WorldDef& d) { d.solver.contact_damping_ratio = -1.0; }},
      {"joint_hertz", [](WorldDef& d) { d.solver.joint_hertz = kNaN; }},
      {"joint_damping_ratio", [](WorldDef& d) { d.solver.joint_damping_ratio = -2.0; }},
      {"max_push_velocity", [](WorldDef& d) { d.solver.max_push_velocity = -3.0; }},
      {"restitution_threshold", [](WorldDef& d) { d.solver.restitution_threshold = kNaN; }},
      {"static_friction_speed", [](WorldDef& d) { d.solver.static_friction_speed = -0.02; }},
      {"speculative_distance", [](WorldDef& d) { d.solver.speculative_distance = -0.02; }},
      {"linear_slop", [](WorldDef& d) { d.solver.linear_slop = -5e-4; }},
      {"max_linear_speed", [](WorldDef& d) { d.solver.max_linear_speed = 0.0; }},
      {"max_angular_speed", [](WorldDef& d) { d.solver.max_angular_speed = kInf; }},
      {"threads", [](WorldDef& d) { d.threads = -1; }},
      {"threads", [](WorldDef& d) { d.threads = WorldDef::kMaxThreads + 1; }},
      {"sleep.time", [](WorldDef& d) { d.sleep.time = -0.5; }},
      {"sleep.speed", [](WorldDef& d) { d.sleep.speed = kNaN; }},
      {"sleep.rest_time", [](WorldDef& d) { d.sleep.rest_time = kInf; }},
      {"sleep.rest_substeps", [](WorldDef& d) { d.sleep.rest_substeps = -1; }},
      {"sleep.rest_relax_iterations", [](WorldDef& d) { d.sleep.rest_relax_iterations = -1; }},
      {"materials 'ice': kinetic_friction",
       [](WorldDef& d) { d.materials.add("ice", {0.1, -0.03, 0.1}); }},
      {"materials 'ice': restitution",
       [](WorldDef& d) { d.materials.add("ice", {0.1, 0.03, 1.5}); }},
      {"materials pair 'ice'/'steel': static_friction",
       [](WorldDef& d) {
         const int ice = d.materials.add("ice", {0.1, 0.03, 0.1});
         const int steel = d.materials.add("steel", {0.74, 0.57, 0.6});
         d.materials.setPair(steel, ice, {kNaN, 0.02, 0.2});
       }},
  };
  for (const BadCase& c : cases) {
    WorldDef d;
    c.spoil(d);
    const std::string e = worldDefError(d);
    EXPECT_EQ(e.rfind(c.name, 0), 0u) << c.name << ": " << e;  // named first
    try {
      World w(d);
      ADD_FAILURE() << c.name << ": the World took it";
    } catch (const std::invalid_argument& ex) {
      EXPECT_TRUE(contains(ex.what(), c.name)) << ex.what();
    }
  }
}

TEST(WorldDefRanges, SetSleepNamesTheField) {
  World w;
  SleepDef s;
  s.rest_relax_iterations = -3;
  try {
    w.setSleep(s);
    ADD_FAILURE() << "setSleep took rest_relax_iterations -3";
  } catch (const std::invalid_argument& ex) {
    EXPECT_TRUE(contains(ex.what(), "rest_relax_iterations must be >= 0, got -3")) << ex.what();
  }
  EXPECT_EQ(w.def().sleep.rest_relax_iterations, SleepDef().rest_relax_iterations);
}

TEST(WorldDefRanges, ShapeWithBadMaterialIsRefusedAndNotAdded) {
  World w;
  BodyDef bd;
  bd.name = "box";
  const BodyId b = w.createBody(bd);
  ShapeDef sd;
  sd.geometry = Geometry::box(Vec3(0.1, 0.1, 0.1));
  for (double mu : {-0.1, kNaN}) {
    sd.material.kinetic_friction = mu;
    try {
      w.addShape(b, sd);
      ADD_FAILURE() << "addShape took kinetic_friction " << mu;
    } catch (const std::invalid_argument& ex) {
      EXPECT_TRUE(contains(ex.what(), "'box'")) << ex.what();
      EXPECT_TRUE(contains(ex.what(), "kinetic_friction")) << ex.what();
    }
  }
  EXPECT_TRUE(w.bodyShapes(b).empty());
  sd.material.kinetic_friction = 0.5;
  w.addShape(b, sd);
  EXPECT_EQ(w.bodyShapes(b).size(), 1u);
  w.step(1e-3);  // the world goes on
  EXPECT_TRUE(w.bodyState(b).pose.p.allFinite());
}

TEST(GeometryRanges, BadGeometryOrPoseIsRefusedAndNotAdded) {
  EXPECT_EQ(geometryError(Geometry()), "");
  EXPECT_EQ(geometryError(Geometry::capsule(0.05, 0.0)), "");  // a sphere
  EXPECT_EQ(geometryError(Geometry::sphere(0.0)), "");          // a contact point
  EXPECT_EQ(geometryError(Geometry::plane(Vec3(0, 0, 2), 1.0)), "");  // normalised
  // the ends of the World's range (kWorldRange, 2^20 m)
  EXPECT_EQ(geometryError(Geometry::box(Vec3(kWorldRange, 1e-9, kWorldRange))), "");
  EXPECT_EQ(geometryError(Geometry::plane(Vec3::UnitZ(), -kWorldRange)), "");
  Transform far;
  far.p = Vec3(-kWorldRange, 0, kWorldRange);
  EXPECT_EQ(poseError("local", far), "");
  const std::vector<std::pair<Geometry, std::string>> bad = {
      {Geometry::sphere(-0.01), "sphere radius must be a finite number >= 0 and <= 1048576"},
      {Geometry::sphere(kNaN), "sphere radius"},
      {Geometry::capsule(-0.05, 0.1), "capsule radius"},
      {Geometry::capsule(0.05, -0.1), "capsule half_height must be a finite number >= 0 and"},
      {Geometry::cylinder(-0.05, 0.15), "cylinder radius must be a finite number > 0 and"},
      {Geometry::cylinder(0.05, 1048576.5), "cylinder half_height must be a finite number > 0 "
                                            "and <= 1048576 (m, kWorldRange), got 1048576.5"},
      {Geometry::sphere(1e100), "sphere radius"},  // loaded from a URDF and dropped from 5e99 m
      {Geometry::cylinder(0.05, 0.0), "cylinder half_height"},
      {Geometry::box(Vec3(-0.1, -0.1, 0.1)), "box half_extents.x"},
      {Geometry::box(Vec3(0.1, 0.1, kInf)), "box half_extents.z"},
      {Geometry::box(Vec3(0.1, 2e6, 0.1)), "box half_extents.y"},
      {Geometry::plane(Vec3(0, 0, 1), kNaN), "plane offset"},
      {Geometry::plane(Vec3(0, 0, 1), -2e6),
       "plane offset must be a finite number in [-1048576, 1048576], got -2000000"},
      {[] {  // the factory normalises; a normal set by hand is checked
         Geometry g = Geometry::plane(Vec3::UnitZ(), 0.0);
         g.normal = Vec3(0, 0, 2);
         return g;
       }(),
       "plane normal"},
      // four points in a plane: no hull data for the narrowphase to read
      {Geometry::convexHull({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)}),
       "convex_hull has no hull"},
      {Geometry::convexHull({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 3e6)}),
       "convex_hull vertices must be finite and within 1048576 m"},
  };
  World w;
  BodyDef bd;
  bd.name = "link";
  const BodyId b = w.createBody(bd);
  for (const auto& [g, words] : bad) {
    EXPECT_TRUE(contains(geometryError(g), words)) << geometryError(g);
    ShapeDef sd;
    sd.geometry = g;
    try {
      w.addShape(b, sd);
      ADD_FAILURE() << words << ": addShape took it";
    } catch (const std::invalid_argument& ex) {
      EXPECT_TRUE(contains(ex.what(), "'link'")) << ex.what();
      EXPECT_TRUE(contains(ex.what(), words)) << ex.what();
    }
  }
  ShapeDef sd;
  sd.local.p.y() = kNaN;
  EXPECT_THROW(w.addShape(b, sd), std::invalid_argument);
  sd.local = Transform(Vec3::Zero(), Quat(0, 0, 0, 0));
  EXPECT_THROW(w.addShape(b, sd), std::invalid_argument);
  sd.local = Transform(Vec3(0, 1048577.0, 0), Quat::Identity());  // beyond kWorldRange
  try {
    w.addShape(b, sd);
    ADD_FAILURE() << "addShape took a shape 1048577 m from its body";
  } catch (const std::invalid_argument& ex) {
    EXPECT_TRUE(contains(ex.what(), "local must be a finite pose within 1048576 m")) << ex.what();
  }
  EXPECT_TRUE(w.bodyShapes(b).empty());
  w.addShape(b, ShapeDef());
  for (int i = 0; i < 10; ++i) w.step(1e-3);  // the world goes on with the good shape
  EXPECT_EQ(w.bodyShapes(b).size(), 1u);
  EXPECT_TRUE(w.bodyState(b).pose.p.allFinite());
}

namespace {
using MakeJoint = std::function<void(World&, BodyId, BodyId)>;

struct JointCase {
  std::string words;  // the message must hold these
  MakeJoint create;   // creates the bad joint
};

// `base` between bodies a and b, with `spoil` applied, passed to `create`.
template <class Def>
MakeJoint spoiled(JointId (World::*create)(const Def&), const Def& base,
                  std::function<void(Def&)> spoil) {
  return [=](World& w, BodyId a, BodyId b) {
    Def d = base;
    d.body_a = a, d.body_b = b;
    spoil(d);
    (w.*create)(d);
  };
}
}  // namespace

TEST(JointDefRanges, BadDefsAreRefusedAndNothingIsCreated) {
  // Each maker creates a valid def spoiled by one field.
  BallJointDef euler;
  euler.enable_limits = true;
  euler.lower = {-1, -1, -1};
  euler.upper = {1, 1, 1};
  BallJointDef swing = euler;
  swing.limit_mode = BallLimitMode::SwingTwist;
  swing.swing_cone_angle = 0.5;
  swing.twist_lower = -0.5, swing.twist_upper = 0.5;
  const auto ball = [&](std::function<void(BallJointDef&)> f) {
    return spoiled(&World::createBallJoint, euler, f);
  };
  const auto twist = [&](std::function<void(BallJointDef&)> f) {
    return spoiled(&World::createBallJoint, swing, f);
  };
  const auto hinge = [](std::function<void(HingeJointDef&)> f) {
    return spoiled(&World::createHingeJoint, HingeJointDef(), f);
  };
  const auto fixed = [](std::function<void(FixedJointDef&)> f) {
    return spoiled(&World::createFixedJoint, FixedJointDef(), f);
  };
  const auto prismatic = [](std::function<void(PrismaticJointDef&)> f) {
    return spoiled(&World::createPrismaticJoint, PrismaticJointDef(), f);
  };
  const std::vector<JointCase> cases = {
      {"ball joint between 'a' and 'b': frame_a", ball([](auto& d) { d.frame_a.p.x() = kNaN; })},
      {"axes[1] must be a finite, non-zero vector", ball([](auto& d) { d.axes[1].setZero(); })},
      {"lower[2] must be <= upper[2], got 0.5 > 0.25",
       ball([](auto& d) { d.lower[2] = 0.5, d.upper[2] = 0.25; })},
      {"lower[0] must be <= upper[0], got nan", ball([](auto& d) { d.lower[0] = kNaN; })},
      {"swing_cone_angle must be > 0", twist([](auto& d) { d.swing_cone_angle = 0; })},
      {"twist_lower must be <= twist_upper", twist([](auto& d) { d.twist_lower = 0.6; })},
      {"motors[1].target must be finite, got nan",
       ball([](auto& d) { d.motors[1].target = kNaN; })},
      {"spring.break_force must be > 0 (or inf), got nan",
       ball([](auto& d) { d.spring.break_force = kNaN; })},
      {"spring.stiffness must be a finite number >= 0, got -1",
       ball([](auto& d) { d.spring.stiffness = -1; })},
      {"hinge joint between 'a' and 'b': axis", hinge([](auto& d) { d.axis = Vec3(kInf, 0, 0); })},
      {"lower must be <= upper, got 1 > -1",
       hinge([](auto& d) { d.enable_limit = true, d.lower = 1, d.upper = -1; })},
      {"motor.hertz must be a finite number >= 0, got -1",
       hinge([](auto& d) { d.motor.hertz = -1; })},
      {"motor.max_torque must be >= 0 (or inf), got nan",
       hinge([](auto& d) { d.motor.max_torque = kNaN; })},
      {"frame_a must be a finite pose within 1048576 m",
       hinge([](auto& d) { d.frame_a.p.z() = 1e7; })},
      {"fixed joint between 'a' and 'b': frame_b must be a finite pose",
       fixed([](auto& d) { d.frame_b.q = Quat(0, 0, 0, 0); })},
      {"spring.break_torque must be > 0 (or inf), got 0",
       fixed([](auto& d) { d.spring.break_torque = 0; })},
      {"prismatic joint between 'a' and 'b': spring.stiffness must be 0",
       prismatic([](auto& d) { d.spring.stiffness = 100; })},
      {"prismatic joint between 'a' and 'b': axis", prismatic([](auto& d) { d.axis.setZero(); })},
  };
  WorldDef wd;
  wd.gravity.setZero();
  World w(wd);
  BodyDef bd;
  bd.name = "a";
  const BodyId a = w.createBody(bd);
  bd.name = "b";
  bd.pose.p = Vec3(0, 0, -0.5);
  const BodyId b = w.createBody(bd);
  for (const JointCase& c : cases) {
    try {
      c.create(w, a, b);
      ADD_FAILURE() << c.words << ": the joint was created";
    } catch (const std::invalid_argument& ex) {
      EXPECT_TRUE(contains(ex.what(), c.words)) << c.words << "\n  got: " << ex.what();
    }
  }
  EXPECT_EQ(w.jointCount(), 0);
  // The ends that are allowed: infinite limits and motor torque, a reversed but unused limit.
  BallJointDef open;
  open.body_a = a, open.body_b = b;
  open.enable_limits = true;
  open.lower = {-kInf, -1, -1};
  open.upper = {kInf, 1, 1};
  open.motors[0].max_torque = kInf;
  const JointId j = w.createBallJoint(open);
  HingeJointDef unused;
  unused.body_a = a, unused.body_b = b;
  unused.lower = 1, unused.upper = -1;  // enable_limit false
  w.createHingeJoint(unused);
  EXPECT_EQ(w.jointCount(), 2);
  // A NaN motor target at run time is refused; the joint keeps its motor and nothing faults.
  JointMotor m;
  m.enabled = true;
  m.hertz = 5;
  m.max_torque = 10;
  m.target = kNaN;
  try {
    w.setJointMotor(j, 1, m);
    ADD_FAILURE() << "setJointMotor took a NaN target";
  } catch (const std::invalid_argument& ex) {
    EXPECT_TRUE(contains(ex.what(), "axis 1 of the joint between 'a' and 'b': motor.target"))
        << ex.what();
  }
  m.target = 0.3;
  w.setJointMotor(j, 1, m);
  for (int i = 0; i < 100; ++i) w.step(1e-3);
  EXPECT_EQ(w.bodyFaultCount(), 0);
  EXPECT_TRUE(std::isfinite(w.ballAngles(j)[1]));
}

TEST(BodyDefRanges, BadDampingOrGravityScaleIsRefused) {
  World w;
  for (const auto& [field, spoil] :
       std::vector<std::pair<std::string, std::function<void(BodyDef&)>>>{
           {"linear_damping", [](BodyDef& d) { d.linear_damping = -0.1; }},
           {"angular_damping", [](BodyDef& d) { d.angular_damping = kNaN; }},
           {"gravity_scale", [](BodyDef& d) { d.gravity_scale = kInf; }}}) {
    BodyDef d;
    d.name = "limb";
    spoil(d);
    try {
      w.createBody(d);
      ADD_FAILURE() << field << ": the body was created";
    } catch (const std::invalid_argument& ex) {
      EXPECT_TRUE(contains(ex.what(), "body 'limb': " + field)) << ex.what();
    }
  }
  EXPECT_EQ(w.bodyCount(), 0);
  BodyDef d;
  d.gravity_scale = -1.0;  // allowed: a body that falls up
  w.createBody(d);
  EXPECT_EQ(w.bodyCount(), 1);
}
