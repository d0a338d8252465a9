// <include>: model:// through the search path, overrides, what cannot be resolved, cycles;
// renamed duplicates; poses through frames and nested models; joints.
#include <cmath>

#include "world_test_util.hpp"

using namespace ragdoll_sim;
using namespace world_test;

TEST(WorldIncludes, OverridesAndUnresolved) {
  const WorldLoadResult r = load("includes.world");
  ASSERT_TRUE(r.ok) << r.error;
  const WorldFileDef& d = r.def;
  // crate, 'pinned crate' -> pinned_crate, a second 'crate' -> crate_2, placed.
  ASSERT_EQ(d.models.size(), 4u);
  const WorldModelDef* first = model(d, "crate");
  ASSERT_NE(first, nullptr);
  EXPECT_FALSE(first->is_static);
  EXPECT_TRUE(first->pose.p.isApprox(Vec3(0, 0, 5)));  // the model file's own pose
  EXPECT_TRUE(first->links[0].pose.p.isApprox(Vec3(0, 0, 5.25)));
  EXPECT_EQ(first->links[0].mass, 2);  // model.config's 1.6 file, not the 1.5 or the 1.11 one
  EXPECT_EQ(first->links[0].visual_material, "Gazebo/Wood");
  EXPECT_FALSE(first->links[0].has_color);
  const WorldModelDef* pinned = model(d, "pinned_crate");
  ASSERT_NE(pinned, nullptr);
  EXPECT_EQ(pinned->file_name, "pinned crate");
  EXPECT_TRUE(pinned->is_static);
  EXPECT_TRUE(pinned->pose.p.isApprox(Vec3(1, 2, 0)));
  EXPECT_TRUE(pinned->links[0].pose.p.isApprox(Vec3(1, 2, 0.25)));
  EXPECT_NEAR(pinned->pose.q.z(), std::sin(0.25), 1e-12);
  const WorldModelDef* second = model(d, "crate_2");
  ASSERT_NE(second, nullptr);
  EXPECT_EQ(second->file_name, "crate");
  EXPECT_TRUE(second->links[0].pose.p.isApprox(Vec3(3, 0, 0.25)));
  EXPECT_TRUE(contains(d.warnings, "renamed to 'crate_2' (the name is taken)"));
  EXPECT_TRUE(contains(d.warnings, "renamed to 'pinned_crate' (spaces in the name)"));
  // <placement_frame>: the <pose> places the link 'body', not the model frame.
  const WorldModelDef* placed = model(d, "placed");
  ASSERT_NE(placed, nullptr);
  EXPECT_TRUE(placed->links[0].pose.p.isApprox(Vec3(5, 5, 1))) << placed->links[0].pose.p.transpose();
  EXPECT_TRUE(placed->pose.p.isApprox(Vec3(5, 5, 0.75)));
  // The light in model://lamp is a note, not an unresolved include.
  EXPECT_TRUE(contains(d.notes, "1 <light> not simulated"));
  EXPECT_TRUE(contains(d.warnings, "https://fuel.gazebosim.org/1.0/OpenRobotics/models/Sun: online URI"));
  EXPECT_TRUE(contains(d.warnings, "model://no_such_model: model 'no_such_model' not found in the model search path"));
  EXPECT_TRUE(contains(d.warnings, "model 'wrapper': nothing to simulate left in it"));
  EXPECT_TRUE(contains(d.warnings, "model://broken: "));
  EXPECT_TRUE(contains(d.warnings, "broken/model.sdf is not well-formed XML"));
  EXPECT_EQ(d.counts.unresolved, 4);
  EXPECT_EQ(d.counts.skipped, 1);
  EXPECT_EQ(d.counts.dynamic_bodies, 3);
  EXPECT_EQ(d.counts.static_shapes, 1);
}

TEST(WorldIncludes, StrictRefusesAnUnresolvedInclude) {
  const WorldLoadResult r = load("includes.world", true);
  ASSERT_FALSE(r.ok);
  EXPECT_NE(r.error.find("<include> world 'includes' <include> https://fuel.gazebosim.org"), std::string::npos)
      << r.error;
  EXPECT_NE(r.error.find("strict"), std::string::npos) << r.error;
}

// SDFormat 12 would expand the cycle until it runs out of memory.
TEST(WorldIncludes, CycleIsRefused) {
  const WorldLoadResult r = load("cycle.world");
  ASSERT_FALSE(r.ok);
  EXPECT_NE(r.error.find("a cycle of includes"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("model://cycle_a"), std::string::npos) << r.error;
}

TEST(WorldIncludes, DepthIsBounded) {
  WorldLoadOptions o = options();
  o.max_include_depth = 1;
  // crate itself is one level; a wrapper model including it stays within one level as well.
  EXPECT_TRUE(loadWorldFile(fixture("includes.world"), o).ok);
  o.max_include_depth = 0;
  const WorldLoadResult r = loadWorldFile(fixture("includes.world"), o);
  ASSERT_FALSE(r.ok);
  EXPECT_NE(r.error.find("includes nested deeper than 0"), std::string::npos) << r.error;
}

TEST(WorldIncludes, ExpansionIsBounded) {
  const WorldLoadResult r = load("fan_out.world");
  ASSERT_FALSE(r.ok);
  EXPECT_NE(r.error.find("the world's includes expand to more than 20000 models or 64 MiB"), std::string::npos)
      << r.error;
}

// What SDFormat would hold is bounded before it runs (it copies its description per element).
TEST(WorldIncludes, SdfMemoryIsBounded) {
  WorldLoadOptions o = options();
  o.max_sdf_megabytes = 10;
  const WorldLoadResult r = loadWorldFile(fixture("all_shapes.world"), o);
  ASSERT_FALSE(r.ok);
  EXPECT_NE(r.error.find("the world needs SDFormat 12 to hold about 14 MB (3 distinct models, 3 links, "
                         "11 collisions), more than max_sdf_megabytes 10"),
            std::string::npos)
      << r.error;
  o.max_sdf_megabytes = 15;
  EXPECT_TRUE(loadWorldFile(fixture("all_shapes.world"), o).ok);
}

TEST(WorldIncludes, DuplicateNamesAndSpacesAreRenamed) {
  const WorldLoadResult r = load("duplicates.world");
  ASSERT_TRUE(r.ok) << r.error;
  std::vector<std::string> names;
  for (const auto& m : r.def.models) names.push_back(m.name);
  EXPECT_EQ(names, (std::vector<std::string>{"wall", "wall_3", "wall_2", "Construction_Cone"}));
  EXPECT_EQ(r.def.models[1].file_name, "wall");
  EXPECT_TRUE(r.def.models[1].links[0].pose.p.isApprox(Vec3(2, 0, 0)));
  EXPECT_EQ(r.def.counts.static_shapes, 4);
}

TEST(WorldPoses, FramesNestedModelsAndRelativeTo) {
  const WorldLoadResult r = load("frames.world");
  ASSERT_TRUE(r.ok) << r.error;
  const WorldModelDef& table = r.def.models[0];
  // table_corner at (10,0,0) turned 90 deg; the table 1 m along its x: (10,1,0).
  EXPECT_TRUE(table.pose.p.isApprox(Vec3(10, 1, 0), 1e-9)) << table.pose.p.transpose();
  ASSERT_EQ(table.links.size(), 2u);
  EXPECT_EQ(table.links[0].name, "board");
  EXPECT_TRUE(table.links[0].pose.p.isApprox(Vec3(10, 1, 0.7), 1e-9));
  const Vec3 board_box = table.links[0].pose.apply(table.links[0].collisions[0].shape.local.p);
  EXPECT_TRUE(board_box.isApprox(Vec3(10, 1.5, 0.7), 1e-9)) << board_box.transpose();
  EXPECT_EQ(table.links[1].name, "drawer::front");
  // drawer 1 m along the table's y (world -x) at the top; its box 0.2 m below the drawer frame.
  EXPECT_TRUE(table.links[1].pose.p.isApprox(Vec3(9, 1, 0.7), 1e-9)) << table.links[1].pose.p.transpose();
  const Vec3 front = table.links[1].pose.apply(table.links[1].collisions[0].shape.local.p);
  EXPECT_TRUE(front.isApprox(Vec3(9, 1, 0.5), 1e-9)) << front.transpose();
  EXPECT_TRUE(table.links[1].is_static);
}

TEST(WorldJoints, MappedAsTheUrdfLoaderDoes) {
  const WorldLoadResult r = load("joints.world");
  ASSERT_TRUE(r.ok) << r.error;
  const WorldModelDef& m = r.def.models[0];
  ASSERT_EQ(m.joints.size(), 5u);
  const RagdollJointDef& hinge = m.joints[0];
  EXPECT_EQ(hinge.kind, RagdollJointKind::Hinge);
  EXPECT_EQ(hinge.parent, -1);  // the world: a fixed base
  EXPECT_EQ(hinge.child, 0);
  EXPECT_TRUE(hinge.frame_parent.p.isApprox(Vec3(0, 0, 2), 1e-12));  // in the world
  EXPECT_TRUE(hinge.frame_child.p.isApprox(Vec3(0, 0, 0.5), 1e-12));
  EXPECT_TRUE(hinge.axes[0].isApprox(Vec3::UnitY()));
  EXPECT_TRUE(hinge.limited);
  EXPECT_EQ(hinge.lower[0], -1);
  EXPECT_EQ(hinge.damping[0], 0.2);
  EXPECT_EQ(m.joints[1].kind, RagdollJointKind::Fixed);
  const RagdollJointDef& slide = m.joints[2];
  EXPECT_EQ(slide.kind, RagdollJointKind::Prismatic);
  EXPECT_TRUE(slide.axes[0].isApprox(Vec3::UnitX()));
  EXPECT_EQ(slide.upper[0], 0.3);
  EXPECT_EQ(m.joints[3].kind, RagdollJointKind::Ball);
  const RagdollJointDef& renamed = m.joints[4];
  EXPECT_EQ(renamed.name, "world_joint");
  EXPECT_FALSE(renamed.limited);  // continuous
  EXPECT_TRUE(contains(r.def.warnings, "joint 'world': the name is reserved in SDF; renamed to 'world_joint'"));
}
