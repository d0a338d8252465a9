// The SDF world loader on authored fixtures: every geometry kind, surfaces, colours, what is not
// simulated, the world's physics.
#include <cmath>

#include "world_test_util.hpp"

using namespace ragdoll_sim;
using namespace world_test;

namespace {

const WorldCollisionDef* collision(const WorldModelDef& m, const std::string& name) {
  for (const auto& l : m.links)
    for (const auto& c : l.collisions)
      if (c.name == name) return &c;
  return nullptr;
}

}  // namespace

TEST(WorldGeometry, EveryKindMapsToItsShape) {
  const WorldLoadResult r = load("all_shapes.world");
  ASSERT_TRUE(r.ok) << r.error;
  const WorldFileDef& d = r.def;
  EXPECT_EQ(d.name, "all_shapes");
  const WorldModelDef* shapes = model(d, "shapes");
  ASSERT_NE(shapes, nullptr);
  EXPECT_TRUE(shapes->is_static);
  const auto* box = collision(*shapes, "box");
  ASSERT_NE(box, nullptr);
  EXPECT_EQ(box->shape.geometry.type, ShapeType::Box);
  EXPECT_TRUE(box->shape.geometry.half_extents.isApprox(Vec3(0.5, 1, 1.5)));
  EXPECT_NEAR(collision(*shapes, "sphere")->shape.geometry.radius, 0.5, 1e-12);
  const auto* cyl = collision(*shapes, "cylinder");
  EXPECT_EQ(cyl->shape.geometry.type, ShapeType::Cylinder);
  EXPECT_NEAR(cyl->shape.geometry.half_height, 1.0, 1e-12);
  const auto* cap = collision(*shapes, "capsule");
  EXPECT_EQ(cap->shape.geometry.type, ShapeType::Capsule);
  EXPECT_NEAR(cap->shape.geometry.half_height, 0.3, 1e-12);
  const auto* ell = collision(*shapes, "ellipsoid");
  ASSERT_EQ(ell->shape.geometry.type, ShapeType::ConvexHull);
  ASSERT_TRUE(ell->shape.geometry.hull);
  double xmax = 0;
  for (const Vec3& v : ell->shape.geometry.hull->vertices) xmax = std::max(xmax, v.x());
  EXPECT_NEAR(xmax, 0.3, 1e-9);
  const auto* mesh = collision(*shapes, "mesh");
  ASSERT_EQ(mesh->shape.geometry.type, ShapeType::ConvexHull);
  EXPECT_EQ(mesh->shape.geometry.hull->vertices.size(), 8u);
  EXPECT_NE(mesh->source.find("convex hull of model://bar_mesh/meshes/cube.obj"), std::string::npos);
  EXPECT_FALSE(contains(d.warnings, "cube.obj is clearly concave"));
  const auto* concave = collision(*shapes, "concave");
  ASSERT_NE(concave, nullptr);
  EXPECT_NEAR(concave->shape.geometry.volume(), 5.08, 1e-6);  // the L's hull, not the L (1.16)
  EXPECT_TRUE(contains(d.warnings, "collision 'concave': mesh model://bar_mesh/meshes/ell.obj is clearly "
                                   "concave (it encloses 23 % of its convex hull); collisions use the hull"));
  // Static: a missing mesh and a heightmap are skipped with a warning, <empty> silently.
  EXPECT_EQ(collision(*shapes, "missing_mesh"), nullptr);
  EXPECT_EQ(collision(*shapes, "terrain"), nullptr);
  EXPECT_EQ(collision(*shapes, "nothing"), nullptr);
  EXPECT_TRUE(contains(d.warnings, "collision 'missing_mesh': mesh model://bar_mesh/meshes/absent.dae unusable"));
  EXPECT_TRUE(contains(d.warnings, "collision 'terrain': <heightmap> geometry is not simulated; skipped"));
  EXPECT_EQ(shapes->links[0].pose.p, Vec3(1, 2, 3));
}

TEST(WorldGeometry, PlaneSurfaceAndColour) {
  const WorldLoadResult r = load("all_shapes.world");
  ASSERT_TRUE(r.ok) << r.error;
  const WorldModelDef* ground = model(r.def, "ground");
  ASSERT_NE(ground, nullptr);
  const WorldCollisionDef& p = ground->links[0].collisions[0];
  EXPECT_EQ(p.shape.geometry.type, ShapeType::Plane);
  EXPECT_TRUE(p.shape.geometry.normal.isApprox(Vec3(0, 1, 1).normalized()));
  EXPECT_EQ(p.plane_size[0], 20);
  EXPECT_EQ(p.plane_size[1], 10);
  EXPECT_TRUE(p.has_friction);
  EXPECT_DOUBLE_EQ(p.mu, 0.6);
  EXPECT_DOUBLE_EQ(p.mu2, 0.4);
  EXPECT_DOUBLE_EQ(p.shape.material.kinetic_friction, 0.5);
  EXPECT_TRUE(p.has_restitution);
  EXPECT_DOUBLE_EQ(p.shape.material.restitution, 0.25);
  ASSERT_TRUE(ground->links[0].has_color);
  EXPECT_EQ(ground->links[0].color[0], 0.4);  // diffuse over ambient
  EXPECT_EQ(ground->links[0].color[3], 0.7);
}

TEST(WorldGeometry, DynamicLinkInertiaAndMeshStandIn) {
  const WorldLoadResult r = load("all_shapes.world");
  ASSERT_TRUE(r.ok) << r.error;
  const WorldModelDef* crate = model(r.def, "crate");
  ASSERT_NE(crate, nullptr);
  EXPECT_FALSE(crate->is_static);
  const WorldLinkDef& body = crate->links[0];
  EXPECT_TRUE(body.has_inertial);
  EXPECT_EQ(body.mass, 4);
  EXPECT_TRUE(body.com.isApprox(Vec3(0, 0, 0.1)));
  EXPECT_NEAR(body.inertia(1, 1), 0.0666667, 1e-12);
  EXPECT_TRUE(body.pose.p.isApprox(Vec3(0, 0, 1)));
  EXPECT_NEAR(std::abs(body.pose.q.z()), std::sqrt(0.5), 1e-9);
  // The missing meshes of a dynamic link: one box with the link's mass and principal moments
  // (a 0.2 x 0.3 x 0.4 m box of 4 kg); the second mesh is skipped.
  ASSERT_EQ(body.collisions.size(), 1u);
  EXPECT_TRUE(contains(r.def.warnings, "collision 'shell': mesh model://bar_mesh/meshes/absent.dae unusable"));
  EXPECT_TRUE(contains(r.def.warnings, "replaced by a 0.4 x 0.3 x 0.2 m box fitted to the link's inertia"));
  EXPECT_TRUE(contains(r.def.warnings, "collision 'handle': mesh model://bar_mesh/meshes/absent.stl unusable"));
  const Geometry& g = body.collisions[0].shape.geometry;
  ASSERT_EQ(g.type, ShapeType::Box);
  const Mat3 I = 4 * g.unitInertia() / g.volume();
  const Vec3 moments = I.diagonal();
  std::vector<double> got{moments.x(), moments.y(), moments.z()}, want{0.0433333, 0.0666667, 0.0833333};
  std::sort(got.begin(), got.end());
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], 1e-9);
  EXPECT_NEAR(8 * g.half_extents.prod(), 0.024, 1e-6);
  EXPECT_TRUE(body.has_color);
  EXPECT_EQ(body.color[0], 1.0);  // ambient when no diffuse
}

TEST(WorldGeometry, PhysicsNotesAndCounts) {
  const WorldLoadResult r = load("all_shapes.world");
  ASSERT_TRUE(r.ok) << r.error;
  const WorldFileDef& d = r.def;
  EXPECT_TRUE(d.gravity.isApprox(Vec3(0, 0, -9.81)));
  EXPECT_TRUE(d.has_max_step_size);
  EXPECT_EQ(d.max_step_size, 0.002);
  EXPECT_TRUE(contains(d.notes, "3 <plugin> not simulated"));
  EXPECT_TRUE(contains(d.notes, "1 <light> not simulated"));
  EXPECT_TRUE(contains(d.notes, "1 <sensor> not simulated"));
  EXPECT_TRUE(contains(d.notes, "1 <gui> not simulated"));
  EXPECT_TRUE(contains(d.notes, "max_step_size> 0.002 s is reported, not obeyed"));
  EXPECT_EQ(worldSummaryLine(d),
            "world=all_shapes status=ok models=3 static_shapes=8 dynamic_bodies=1 skipped=3 unresolved=0");
}

TEST(WorldGeometry, SdfOnePointFourIdioms) {
  const WorldLoadResult r = load("old14.world");
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(r.def.gravity.isApprox(Vec3(0, -1, -1)));  // <physics><gravity> before 1.6
  const WorldModelDef& door = r.def.models[0];
  ASSERT_EQ(door.joints.size(), 1u);
  // 1.4: the axis is in the model frame: model z, in the joint (leaf, pitched 90 deg) frame -x.
  const RagdollJointDef& j = door.joints[0];
  const Vec3 in_model = door.links[1].pose.q * (j.frame_child.q * j.axes[0]);
  EXPECT_TRUE((door.pose.q.conjugate() * in_model).isApprox(Vec3::UnitZ(), 1e-9))
      << (door.pose.q.conjugate() * in_model).transpose();
}
