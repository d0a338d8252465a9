// modelRagdollDef: a loaded model spawned in a World starts where the world file puts it and
// steps finitely on the world's ground.
#include "world_test_util.hpp"

using namespace ragdoll_sim;
using namespace world_test;

TEST(WorldRagdoll, ArticulatedModelSpawnsWhereTheFileHasIt) {
  const WorldLoadResult r = load("articulated.world");
  ASSERT_TRUE(r.ok) << r.error;
  const WorldModelDef* ground = model(r.def, "ground");
  const WorldModelDef* chain = model(r.def, "chain");
  ASSERT_TRUE(ground && chain);
  const RagdollDef def = modelRagdollDef(*chain);
  ASSERT_EQ(def.links.size(), 3u);
  ASSERT_EQ(def.joints.size(), 2u);
  EXPECT_EQ(def.no_collide.size(), 2u);

  World world;
  BodyDef g;
  g.type = BodyType::Static;
  g.pose = ground->links[0].pose;
  const BodyId gid = world.createBody(g);
  for (const WorldCollisionDef& c : ground->links[0].collisions) world.addShape(gid, c.shape);
  const Ragdoll rd = spawnRagdoll(world, def, chain->links[0].pose);
  for (size_t k = 0; k < 3; ++k) {
    const Transform p = world.bodyState(rd.bodies[k]).pose;
    EXPECT_TRUE(p.p.isApprox(chain->links[k].pose.p, 1e-9)) << k;
    EXPECT_NEAR(std::abs(p.q.dot(chain->links[k].pose.q)), 1.0, 1e-9) << k;
  }
  for (JointId j : rd.joints) EXPECT_LT(world.jointAnchorError(j).norm(), 1e-9);
  for (int i = 0; i < 1000; ++i) world.step(1e-3);
  for (BodyId b : rd.bodies) {
    const BodyState s = world.bodyState(b);
    EXPECT_TRUE(s.pose.p.allFinite());
    EXPECT_GT(s.pose.p.z(), -0.01);  // on the ground, not through it
    EXPECT_LT(s.pose.p.z(), 0.5);    // it fell
  }
  for (JointId j : rd.joints) EXPECT_LT(world.jointAnchorError(j).norm(), 5e-3);
}

TEST(WorldRagdoll, JointToTheWorldIsLeftOutWithANote) {
  const WorldLoadResult r = load("joints.world");
  ASSERT_TRUE(r.ok) << r.error;
  const RagdollDef def = modelRagdollDef(r.def.models[0]);
  EXPECT_EQ(def.joints.size(), 4u);
  EXPECT_TRUE(contains(def.notes, "joint 'hinge' to the world pins link 'bar'"));
}
