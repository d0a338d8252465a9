// Static shapes in their own tree (static_tree.hpp, collide.hpp): a query gives exactly the
// brute-force overlaps; a world's pairs are exactly the brute-force pairs of its boxes while
// bodies move, sleep and static shapes come, go and move, and the same pairs and states as
// with every shape in the broadphase (WorldTuning::static_tree off); stepping neither rebuilds
// the tree nor computes a static box again.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "scene_util.hpp"
#include "static_tree.hpp"
#include "world_tuning.hpp"

using namespace ragdoll_sim;

namespace {

using Pairs = std::vector<std::pair<int, int>>;

TEST(StaticTree, QueryEqualsBruteForce) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> pos(-10.0, 10.0), size(0.0, 1.0), u(0.0, 1.0);
  const double inf = std::numeric_limits<double>::infinity();
  for (const int n : {0, 1, 3, 4, 5, 37, 500}) {
    std::vector<Aabb> boxes(n + 10);  // ids 0..9 are not in the tree
    std::vector<int> ids;
    for (int k = 0; k < n; ++k) {
      const int id = k + 10;
      const Vec3 c(pos(rng), pos(rng), pos(rng)), h(size(rng), size(rng), size(rng));
      boxes[id] = {c - h, c + h};
      const double kind = u(rng);
      if (kind < 0.03) boxes[id].lo.x() = std::nan("");   // overlaps nothing
      else if (kind < 0.06) boxes[id].hi.y() = inf;       // reaches out forever
      else if (kind < 0.08) boxes[id] = {Vec3::Constant(-inf), Vec3::Constant(inf)};
      else if (kind < 0.12) boxes[id].hi = boxes[id].lo;  // a point
      else if (kind < 0.2 && k > 0) boxes[id].lo.x() = boxes[id - 1].hi.x();  // may touch
      ids.push_back(id);
    }
    StaticTree tree;
    tree.build(ids, boxes);
    EXPECT_EQ(tree.builds(), 1);
    EXPECT_EQ(tree.size(), n);
    for (int q = 0; q < 200; ++q) {
      const Vec3 c(pos(rng), pos(rng), pos(rng)), h = 2.0 * Vec3(size(rng), size(rng), size(rng));
      Aabb box{c - h, c + h};
      if (q % 50 == 0 && n > 0) box = boxes[ids[q % n]];  // exactly a tree box (faces touch)
      std::vector<int> expected, found;
      for (int id : ids)
        if (boxes[id].overlaps(box)) expected.push_back(id);
      tree.query(box, [&](int id) { found.push_back(id); });
      std::sort(found.begin(), found.end());
      EXPECT_EQ(found, expected) << "n=" << n << " query " << q;
    }
  }
}

// A random world: ground plane, static bodies of 1-3 shapes (boxes, spheres, capsules), and
// dynamic boxes and spheres dropped onto them with random velocities; two bodies never collide.
struct RandomWorld {
  std::vector<BodyId> statics, dynamics;
};

Geometry randomGeometry(std::mt19937& rng) {
  std::uniform_real_distribution<double> s(0.05, 0.4);
  switch (rng() % 3) {
    case 0: return Geometry::box(Vec3(s(rng), s(rng), s(rng)));
    case 1: return Geometry::sphere(s(rng));
    default: return Geometry::capsule(s(rng), s(rng));
  }
}

void addStaticBody(World& w, std::mt19937& rng, RandomWorld& rw) {
  std::uniform_real_distribution<double> xy(-3.0, 3.0), z(0.0, 1.5), a(-1.0, 1.0);
  BodyDef d;
  d.type = BodyType::Static;
  d.pose.p = Vec3(xy(rng), xy(rng), z(rng));
  d.pose.q = Quat(a(rng), a(rng), a(rng), 1.0).normalized();
  const BodyId b = w.createBody(d);
  const int shapes = 1 + int(rng() % 3);
  for (int k = 0; k < shapes; ++k)
    w.addShape(b, {randomGeometry(rng), Transform(Vec3(a(rng), a(rng), 0.3 * a(rng)), Quat::Identity()),
                   Material()});
  rw.statics.push_back(b);
}

RandomWorld buildRandom(World& w, uint32_t seed) {
  std::mt19937 rng(seed);
  RandomWorld rw;
  test::addGround(w);
  for (int k = 0; k < 25; ++k) addStaticBody(w, rng, rw);
  std::uniform_real_distribution<double> xy(-3.0, 3.0), z(0.5, 3.0), v(-2.0, 2.0);
  for (int k = 0; k < 30; ++k) {
    const Vec3 p(xy(rng), xy(rng), z(rng));
    const BodyId b = k % 2 ? test::addBox(w, Vec3(0.15, 0.1, 0.2), 1.0, p)
                           : test::addBody(w, Geometry::sphere(0.15), 1.0,
                                           Mat3::Identity() * 0.009, Transform(p, Quat::Identity()),
                                           Material(), Vec3(v(rng), v(rng), v(rng)));
    rw.dynamics.push_back(b);
  }
  w.disableCollision(rw.dynamics[0], rw.statics[0]);
  return rw;
}

// The pairs the world must have: different bodies, one of them dynamic, not disabled, boxes
// overlapping (planes left out: the broadphase's own test covers them).
Pairs bruteForce(const World& w, const std::vector<std::pair<BodyId, int>>& owner,
                 const RandomWorld& rw) {
  const std::vector<Aabb>& boxes = WorldInternals::shapeBoxes(w);
  const std::vector<char> bounded = WorldInternals::boundedShapes(w);
  Pairs out;
  for (size_t i = 0; i < bounded.size(); ++i)
    for (size_t j = i + 1; j < bounded.size(); ++j) {
      if (!bounded[i] || !bounded[j]) continue;
      const BodyId a = owner[i].first, b = owner[j].first;
      const bool dyn = w.bodyDef(a).type == BodyType::Dynamic || w.bodyDef(b).type == BodyType::Dynamic;
      const bool disabled = (a == rw.dynamics[0] && b == rw.statics[0]) ||
                            (b == rw.dynamics[0] && a == rw.statics[0]);
      if (a != b && dyn && !disabled && boxes[i].overlaps(boxes[j])) out.emplace_back(int(i), int(j));
    }
  return out;
}

Pairs boundedPairs(const World& w) {
  const std::vector<char> bounded = WorldInternals::boundedShapes(w);
  Pairs out;
  for (const auto& p : WorldInternals::pairs(w))
    if (bounded[p.first] && bounded[p.second]) out.push_back(p);
  return out;
}

bool sameStates(const World& a, const World& b) {
  for (int i = 0; i < a.bodyCount(); ++i) {
    if (!a.isValid(BodyId{i})) continue;
    const BodyState sa = a.bodyState(BodyId{i}), sb = b.bodyState(BodyId{i});
    if (sa.pose.p != sb.pose.p || sa.pose.q.coeffs() != sb.pose.q.coeffs() ||
        sa.linear_velocity != sb.linear_velocity || sa.angular_velocity != sb.angular_velocity)
      return false;
  }
  return true;
}

}  // namespace

// Shapes are numbered in the order they are added; owner[s] is (body, index at creation).
TEST(StaticTreeWorld, PairsEqualBruteForceWhileStaticShapesChange) {
  for (const uint32_t seed : {1u, 2u, 3u}) {
    World with, without;
    WorldTuning off;
    off.static_tree = false;
    WorldInternals::setTuning(without, off);
    const RandomWorld rw = buildRandom(with, seed);
    buildRandom(without, seed);
    std::vector<std::pair<BodyId, int>> owner;  // per shape id
    for (int b = 0; b < with.bodyCount(); ++b)
      for (size_t k = 0; k < with.bodyShapes(BodyId{b}).size(); ++k) owner.emplace_back(BodyId{b}, int(k));
    std::mt19937 rng(100 + seed);
    RandomWorld extra_with, extra_without;
    size_t checked = 0;
    bool slept_into = false;
    for (int step = 1; step <= 900; ++step) {
      // Static shapes come, go and move while dynamic bodies sleep on them or fall past.
      if (step == 120 || step == 260) {
        std::mt19937 r2 = rng;
        addStaticBody(with, rng, extra_with);
        addStaticBody(without, r2, extra_without);
        const BodyId b = extra_with.statics.back();
        for (size_t k = 0; k < with.bodyShapes(b).size(); ++k) owner.emplace_back(b, int(k));
        const ShapeDef more{Geometry::box(Vec3(0.3, 0.3, 0.05)), Transform(), Material()};
        with.addShape(rw.statics[3], more);  // a shape added to an old static body
        without.addShape(rw.statics[3], more);
        owner.emplace_back(rw.statics[3], int(with.bodyShapes(rw.statics[3]).size()) - 1);
      }
      if (step == 180) {
        with.removeShape(rw.statics[4], 0);
        without.removeShape(rw.statics[4], 0);
        with.destroyBody(rw.statics[5]);
        without.destroyBody(rw.statics[5]);
        const Transform moved(Vec3(0.5, -0.5, 0.2), Quat::Identity());
        with.setBodyState(rw.statics[6], moved, Vec3::Zero(), Vec3::Zero());
        without.setBodyState(rw.statics[6], moved, Vec3::Zero(), Vec3::Zero());
      }
      if (step == 850) {
        // A static box appears around a sleeping body: their pair must be found although the
        // sleeping body's other pairs are carried over.
        for (const BodyId b : rw.dynamics) {
          if (with.isAwake(b)) continue;
          BodyDef d;
          d.type = BodyType::Static;
          d.pose.p = with.bodyPose(b).p;
          const ShapeDef cage{Geometry::box(Vec3(0.05, 0.05, 0.05)), Transform(), Material()};
          with.addShape(with.createBody(d), cage);
          without.addShape(without.createBody(d), cage);
          owner.emplace_back(BodyId{with.bodyCount() - 1}, 0);
          slept_into = true;
          break;
        }
      }
      with.step(1.0 / 240.0);
      without.step(1.0 / 240.0);
      const Pairs got = boundedPairs(with);
      ASSERT_EQ(got, bruteForce(with, owner, rw)) << "seed " << seed << " step " << step;
      ASSERT_EQ(WorldInternals::pairs(with), WorldInternals::pairs(without))
          << "seed " << seed << " step " << step;
      ASSERT_TRUE(sameStates(with, without)) << "seed " << seed << " step " << step;
      checked += got.size();
    }
    EXPECT_GT(checked, 1000u);  // the scenes have pairs to compare
    EXPECT_TRUE(slept_into) << "seed " << seed << ": no dynamic body asleep at step 850";
  }
}

// Stepping a world of 2 000 static bodies and a static body of 1 000 shapes computes their
// boxes and builds their tree once; only adding or moving a static shape does it again.
TEST(StaticTreeWorld, SteppingDoesNotTouchStaticShapes) {
  World w;
  test::addGround(w);
  BodyDef d;
  d.type = BodyType::Static;
  for (int k = 0; k < 2000; ++k) {
    d.pose.p = Vec3((k % 50) * 1.0 - 25.0, (k / 50) * 1.0 - 20.0, 0.1);
    w.addShape(w.createBody(d), {Geometry::box(Vec3::Constant(0.1)), Transform(), Material()});
  }
  d.pose.p = Vec3(0, 0, -1.0);
  const BodyId many = w.createBody(d);
  for (int k = 0; k < 1000; ++k)
    w.addShape(many, {Geometry::sphere(0.1), Transform(Vec3(k * 0.3, 40.0, 1.1), Quat::Identity()),
                      Material()});
  test::addBox(w, Vec3::Constant(0.1), 1.0, Vec3(0.0, 0.0, 0.35));  // lands on a static box
  for (int k = 0; k < 100; ++k) w.step(1.0 / 240.0);
  EXPECT_EQ(WorldInternals::staticTreeBuilds(w), 1);
  EXPECT_EQ(WorldInternals::staticBoxesComputed(w), 3000);
  EXPECT_FALSE(WorldInternals::pairs(w).empty());  // the box met a static one

  w.addShape(many, {Geometry::sphere(0.1), Transform(Vec3(0, 45.0, 1.1), Quat::Identity()), Material()});
  for (int k = 0; k < 100; ++k) w.step(1.0 / 240.0);
  EXPECT_EQ(WorldInternals::staticTreeBuilds(w), 2);
  EXPECT_EQ(WorldInternals::staticBoxesComputed(w), 6001);

  w.setBodyState(BodyId{1}, Transform(Vec3(30, 30, 0.1), Quat::Identity()), Vec3::Zero(), Vec3::Zero());
  for (int k = 0; k < 100; ++k) w.step(1.0 / 240.0);
  EXPECT_EQ(WorldInternals::staticTreeBuilds(w), 3);
}
