// Graph colouring and lane packing (constraint_graph.hpp): no colour shares a dynamic body,
// every constraint is coloured once, static bodies do not count, the result depends only on the
// input order, and the wide records hold each colour in groups of 4 or 8 with a padding mask.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "constraint_graph.hpp"

namespace ragdoll_sim {
namespace {

using Edges = std::vector<GraphEdge>;

GraphEdge dyn(int a, int b) { return {a, b, true, true}; }
GraphEdge onStatic(int a) { return {a, -1, true, false}; }  // the static index is never read

// Every constraint once in order(), colourOf() matching its range, no dynamic body twice in a
// colour, and an overflow constraint only where each of the max_colours holds one of its bodies.
void expectValid(const ConstraintGraph& g, const Edges& e, int body_count, int max_colours) {
  const int n = int(e.size());
  ASSERT_EQ(g.size(), n);
  ASSERT_EQ(int(g.order().size()), n);
  std::vector<int> seen(n, 0);
  for (int c = 0; c <= g.colourCount(); ++c) {
    std::vector<char> body(body_count, 0);
    const int end = c < g.colourCount() ? g.colourBegin(c + 1) : n;
    for (int k = g.colourBegin(c); k < end; ++k) {
      const int i = g.order()[k];
      ++seen[i];
      EXPECT_EQ(g.colourOf(i), c < g.colourCount() ? c : ConstraintGraph::kOverflow);
      if (c == g.colourCount()) continue;
      if (e[i].dynamic_a) {
        EXPECT_FALSE(body[e[i].body_a]++) << "colour " << c << " body " << e[i].body_a;
      }
      if (e[i].dynamic_b) {
        EXPECT_FALSE(body[e[i].body_b]++) << "colour " << c << " body " << e[i].body_b;
      }
    }
    if (c < g.colourCount()) {
      EXPECT_GT(g.colourSize(c), 0) << "empty colour " << c;
    }
  }
  for (int i = 0; i < n; ++i) EXPECT_EQ(seen[i], 1) << "constraint " << i;
  EXPECT_LE(g.colourCount(), max_colours);
  // An overflow constraint found every colour taken by one of its bodies.
  for (int k = n - g.overflowSize(); k < n; ++k) {
    const GraphEdge& o = e[g.order()[k]];
    for (int c = 0; c < max_colours; ++c) {
      bool taken = false;
      for (int q = g.colourBegin(c); c < g.colourCount() && q < g.colourBegin(c + 1); ++q) {
        const GraphEdge& x = e[g.order()[q]];
        const auto shares = [&](int b) {
          return (x.dynamic_a && x.body_a == b) || (x.dynamic_b && x.body_b == b);
        };
        taken |= (o.dynamic_a && shares(o.body_a)) || (o.dynamic_b && shares(o.body_b));
      }
      EXPECT_TRUE(taken) << "overflow constraint " << g.order()[k] << " fits colour " << c;
    }
  }
}

Edges randomGraph(std::mt19937& rng, int bodies, int n) {
  std::uniform_int_distribution<int> body(0, bodies - 1), coin(0, 4);
  Edges e;
  for (int i = 0; i < n; ++i) {
    GraphEdge x = dyn(body(rng), body(rng));
    while (x.body_b == x.body_a) x.body_b = body(rng);
    x.dynamic_a = coin(rng) != 0;  // one in five ends static or asleep
    x.dynamic_b = coin(rng) != 0 || !x.dynamic_a;
    e.push_back(x);
  }
  return e;
}

// The bundled ragdoll's joint tree (urdf/ragdoll.urdf as the loader builds it: the revolute
// triples are ball joints), in the URDF's order. Degrees: torso 4, pelvis 3.
enum Link { pelvis, torso, head, uarm_l, larm_l, hand_l, uarm_r, larm_r, hand_r,
            thigh_l, shin_l, foot_l, thigh_r, shin_r, foot_r, kLinks };
Edges ragdollJoints() {
  return {dyn(pelvis, torso),  dyn(torso, head),     dyn(torso, uarm_l),   dyn(uarm_l, larm_l),
          dyn(larm_l, hand_l), dyn(torso, uarm_r),   dyn(uarm_r, larm_r),  dyn(larm_r, hand_r),
          dyn(pelvis, thigh_l), dyn(thigh_l, shin_l), dyn(shin_l, foot_l), dyn(pelvis, thigh_r),
          dyn(thigh_r, shin_r), dyn(shin_r, foot_r)};
}

std::vector<int> coloursOf(const ConstraintGraph& g) {
  std::vector<int> c(g.size());
  for (int i = 0; i < g.size(); ++i) c[i] = g.colourOf(i);
  return c;
}

TEST(ConstraintGraph, RandomGraphsColourValidly) {
  std::mt19937 rng(60);
  ConstraintGraph g;  // reused: its bits must be clear again after every call
  for (int round = 0; round < 200; ++round) {
    const int bodies = 2 + int(rng() % 60), n = int(rng() % 200);
    const Edges e = randomGraph(rng, bodies, n);
    for (const int max_colours : {ConstraintGraph::kMaxColours, 3, 1})
      for (const ColourPolicy p : {ColourPolicy::FirstFit, ColourPolicy::Balanced}) {
        g.colour(e, bodies, max_colours, p);
        expectValid(g, e, bodies, max_colours);
        // greedy: at most deg(a) + deg(b) - 1 colours, so 2 max degree - 1
        std::vector<int> degree(bodies, 0);
        for (const GraphEdge& x : e) {
          if (x.dynamic_a) ++degree[x.body_a];
          if (x.dynamic_b) ++degree[x.body_b];
        }
        const int max_degree = n ? *std::max_element(degree.begin(), degree.end()) : 0;
        EXPECT_LE(g.colourCount(), std::max(1, 2 * max_degree - 1));
        if (max_colours == ConstraintGraph::kMaxColours && 2 * max_degree - 1 <= max_colours) {
          EXPECT_EQ(g.overflowSize(), 0);
        }
      }
  }
}

TEST(ConstraintGraph, StaticBodiesDoNotCount) {
  // Ten bodies on one static body: one colour; with the static end counted they would need ten.
  Edges e;
  for (int b = 0; b < 10; ++b) e.push_back({b, 10, true, false});
  ConstraintGraph g;
  g.colour(e, 11);
  EXPECT_EQ(g.colourCount(), 1);
  for (GraphEdge& x : e) x.dynamic_b = true;
  g.colour(e, 11);
  EXPECT_EQ(g.colourCount(), 10);
  // A static end's index is not read, not even checked.
  g.colour({onStatic(0), onStatic(1), {-1, 5, false, true}}, 6);
  EXPECT_EQ(g.colourCount(), 1);
  EXPECT_THROW(g.colour({dyn(0, 6)}, 6), std::invalid_argument);
  EXPECT_THROW(g.colour({dyn(0, 1)}, 6, 0), std::invalid_argument);
}

// A refusal names the constraint and the body, and leaves no bits behind.
TEST(ConstraintGraph, RefusesABodyOutOfRangeAndStaysClean) {
  Edges e = ragdollJoints();
  e.push_back(dyn(0, kLinks));
  ConstraintGraph g;
  try {
    g.colour(e, kLinks);
    FAIL() << "no refusal";
  } catch (const std::invalid_argument& x) {
    EXPECT_NE(std::string(x.what()).find("constraint 14 has dynamic body 15"), std::string::npos) << x.what();
  }
  e.pop_back();
  g.colour(e, kLinks);
  ConstraintGraph fresh;
  fresh.colour(e, kLinks);
  EXPECT_EQ(coloursOf(g), coloursOf(fresh));
}

TEST(ConstraintGraph, RagdollJointTreeTakesFourColours) {
  const Edges e = ragdollJoints();
  ASSERT_EQ(e.size(), 14u);
  ConstraintGraph g;
  for (const ColourPolicy p : {ColourPolicy::FirstFit, ColourPolicy::Balanced}) {
    g.colour(e, kLinks, ConstraintGraph::kMaxColours, p);
    expectValid(g, e, kLinks, ConstraintGraph::kMaxColours);
    EXPECT_EQ(g.colourCount(), 4);  // the torso's degree: no fewer can do
    EXPECT_EQ(g.overflowSize(), 0);
  }
  // First fit fills the first colours: 5, 6, 2, 1.
  g.colour(e, kLinks);
  EXPECT_EQ(g.colourSize(0), 5);
  EXPECT_EQ(g.colourSize(1), 6);
  EXPECT_EQ(g.colourSize(2), 2);
  EXPECT_EQ(g.colourSize(3), 1);
}

TEST(ConstraintGraph, GroundContactsTakeTheBusiestBodysDegree) {
  // A ragdoll lying on the ground: every contact with the static ground; the torso and pelvis
  // touch it with three shapes, the limbs with one or two.
  const int per_body[kLinks] = {3, 3, 1, 1, 1, 1, 1, 1, 1, 2, 2, 2, 2, 2, 2};
  Edges e;
  for (int round = 0; round < 3; ++round)
    for (int b = 0; b < kLinks; ++b)
      if (round < per_body[b]) e.push_back(onStatic(b));
  for (const ColourPolicy p : {ColourPolicy::FirstFit, ColourPolicy::Balanced}) {
    ConstraintGraph g;
    g.colour(e, kLinks, ConstraintGraph::kMaxColours, p);
    expectValid(g, e, kLinks, ConstraintGraph::kMaxColours);
    EXPECT_EQ(g.colourCount(), 3);
  }
}

TEST(ConstraintGraph, DependsOnlyOnTheInputOrder) {
  std::mt19937 rng(7);
  const int bodies = 40;
  const Edges e = randomGraph(rng, bodies, 120);
  for (const ColourPolicy p : {ColourPolicy::FirstFit, ColourPolicy::Balanced}) {
    ConstraintGraph g1, g2;
    g1.colour(e, bodies, ConstraintGraph::kMaxColours, p);
    g2.colour(randomGraph(rng, bodies, 300), bodies, ConstraintGraph::kMaxColours, p);  // other history
    g2.colour(e, bodies, ConstraintGraph::kMaxColours, p);
    EXPECT_EQ(coloursOf(g1), coloursOf(g2));
    EXPECT_EQ(g1.order(), g2.order());
    // Renumbering the bodies changes nothing.
    std::vector<int> rename(bodies);
    std::iota(rename.begin(), rename.end(), 0);
    std::shuffle(rename.begin(), rename.end(), rng);
    Edges renamed = e;
    for (GraphEdge& x : renamed) x.body_a = rename[x.body_a], x.body_b = rename[x.body_b];
    g2.colour(renamed, bodies, ConstraintGraph::kMaxColours, p);
    EXPECT_EQ(coloursOf(g1), coloursOf(g2));
    // A permuted input is coloured in its own order: valid, and each constraint's colour is
    // what the greedy gives that order (here: the joint tree reversed takes 4 colours too, in
    // other sizes).
    Edges reversed = ragdollJoints();
    std::reverse(reversed.begin(), reversed.end());
    g1.colour(ragdollJoints(), kLinks, ConstraintGraph::kMaxColours, p);
    g2.colour(reversed, kLinks, ConstraintGraph::kMaxColours, p);
    expectValid(g2, reversed, kLinks, ConstraintGraph::kMaxColours);
    EXPECT_EQ(g2.colourCount(), 4);
  }
  ConstraintGraph g1, g2;
  Edges reversed = ragdollJoints();
  std::reverse(reversed.begin(), reversed.end());
  g1.colour(ragdollJoints(), kLinks);
  g2.colour(reversed, kLinks);
  std::vector<int> sizes1, sizes2;
  for (int c = 0; c < 4; ++c) sizes1.push_back(g1.colourSize(c)), sizes2.push_back(g2.colourSize(c));
  EXPECT_EQ(sizes1, (std::vector<int>{5, 6, 2, 1}));
  EXPECT_EQ(sizes2, (std::vector<int>{6, 5, 2, 1}));
}

// Islands share no dynamic body, so first fit gives each island's constraints the colours
// they take alone, however the islands are merged into one graph (a thread's run of islands):
// the colours do not depend on how the islands are spread over the threads.
TEST(ConstraintGraph, FirstFitColoursIslandsAsAlone) {
  std::mt19937 rng(11);
  const Edges a = randomGraph(rng, 30, 90), b = ragdollJoints();
  ConstraintGraph ga, gb, g;
  ga.colour(a, 30);
  gb.colour(b, kLinks);
  for (int round = 0; round < 20; ++round) {
    // b's bodies after a's; the two lists interleaved at random, each in its own order
    Edges merged;
    std::vector<int> from;  // per merged constraint: index in a, or -1 - index in b
    size_t ia = 0, ib = 0;
    while (ia < a.size() || ib < b.size()) {
      if (ib == b.size() || (ia < a.size() && rng() % 2)) {
        from.push_back(int(ia));
        merged.push_back(a[ia++]);
      } else {
        GraphEdge e = b[ib];
        e.body_a += 30, e.body_b += 30;
        from.push_back(-1 - int(ib++));
        merged.push_back(e);
      }
    }
    g.colour(merged, 30 + kLinks);
    for (size_t i = 0; i < merged.size(); ++i)
      EXPECT_EQ(g.colourOf(int(i)), from[i] >= 0 ? ga.colourOf(from[i]) : gb.colourOf(-1 - from[i]));
  }
}

TEST(ConstraintGraph, ReusesItsStorage) {
  std::mt19937 rng(3);
  const Edges big = randomGraph(rng, 50, 150), small = randomGraph(rng, 50, 100);
  ConstraintGraph g;
  g.colour(big, 50);
  const int* order = g.order().data();
  g.colour(small, 50);
  g.colour(big, 50);
  EXPECT_EQ(g.order().data(), order);
}

TEST(LanePacking, GroupsEachColourInRecordsOfWidthLanes) {
  ConstraintGraph g;
  g.colour(ragdollJoints(), kLinks);  // colours of 5, 6, 2, 1
  LanePacking pack;
  pack.pack(g, 4);
  ASSERT_EQ(pack.recordCount(), 6);
  const std::vector<int> begin4 = {0, 2, 4, 5, 6};
  for (int c = 0; c <= 4; ++c) EXPECT_EQ(pack.recordBegin(c), begin4[c]);
  const std::vector<int> masks4 = {0xF, 0x1, 0xF, 0x3, 0x3, 0x1};
  for (int r = 0; r < 6; ++r) EXPECT_EQ(pack.mask(r), masks4[r]) << "record " << r;
  EXPECT_EQ(pack.usedLanes(), 14);
  EXPECT_DOUBLE_EQ(pack.fill(), 14.0 / 24.0);
  pack.pack(g, 8);
  ASSERT_EQ(pack.recordCount(), 4);
  const std::vector<int> masks8 = {0x1F, 0x3F, 0x3, 0x1};
  for (int r = 0; r < 4; ++r) EXPECT_EQ(pack.mask(r), masks8[r]) << "record " << r;
  EXPECT_DOUBLE_EQ(pack.fill(), 14.0 / 32.0);
  // Lanes hold each colour's constraints in order, then -1 where the mask is clear.
  for (const int w : {4, 8}) {
    pack.pack(g, w);
    for (int c = 0; c < g.colourCount(); ++c) {
      int k = 0;
      for (int r = pack.recordBegin(c); r < pack.recordBegin(c + 1); ++r)
        for (int lane = 0; lane < w; ++lane, ++k) {
          const bool used = pack.mask(r) >> lane & 1;
          EXPECT_EQ(used, k < g.colourSize(c));
          EXPECT_EQ(pack.lane(r, lane), used ? g.order()[g.colourBegin(c) + k] : -1);
        }
    }
  }
  EXPECT_THROW(pack.pack(g, 5), std::invalid_argument);
}

// With a kind per constraint each colour's lanes hold its constraints ordered by kind, in the
// colour's order within a kind; the records and masks stay as without.
TEST(LanePacking, OrdersEachColourByKind) {
  std::mt19937 rng(5);
  const Edges e = randomGraph(rng, 40, 120);
  ConstraintGraph g;
  g.colour(e, 40);
  std::vector<int> kind(e.size());
  for (size_t i = 0; i < e.size(); ++i) kind[i] = int(rng() % 3);
  for (const int w : {4, 8}) {
    LanePacking plain, sorted;
    plain.pack(g, w);
    sorted.pack(g, w, &kind);
    ASSERT_EQ(sorted.recordCount(), plain.recordCount());
    for (int r = 0; r < plain.recordCount(); ++r) EXPECT_EQ(sorted.mask(r), plain.mask(r));
    for (int c = 0; c < g.colourCount(); ++c) {
      std::vector<int> expected(g.order().begin() + g.colourBegin(c),
                                g.order().begin() + g.colourBegin(c + 1));
      std::stable_sort(expected.begin(), expected.end(),
                       [&](int x, int y) { return kind[x] < kind[y]; });
      std::vector<int> got;
      for (int r = sorted.recordBegin(c); r < sorted.recordBegin(c + 1); ++r)
        for (int lane = 0; lane < w; ++lane)
          if (sorted.mask(r) >> lane & 1) got.push_back(sorted.lane(r, lane));
      EXPECT_EQ(got, expected) << "width " << w << ", colour " << c;
    }
  }
}

TEST(LanePacking, LeavesTheOverflowOut) {
  Edges e;
  for (int b = 1; b <= 5; ++b) e.push_back(dyn(0, b));  // a star: each its own colour
  ConstraintGraph g;
  g.colour(e, 6, 2);
  EXPECT_EQ(g.colourCount(), 2);
  EXPECT_EQ(g.overflowSize(), 3);
  LanePacking pack;
  pack.pack(g, 4);
  EXPECT_EQ(pack.recordCount(), 2);
  EXPECT_EQ(pack.usedLanes(), 2);
}

}  // namespace
}  // namespace ragdoll_sim
