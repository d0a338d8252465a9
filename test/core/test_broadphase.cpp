// The broadphase's pairs are exactly the brute-force overlaps, for both of its methods (sweep
// and prune below Broadphase::kGridMin bounded shapes, hash grid from it), over steps in which
// the boxes move (the sweep keeps its order between calls) and shapes come and go; a filter
// drops exactly the pairs it rejects; the kept candidates (of the sweep and of the grid) give the
// same pairs as a fresh broadphase; its loops split over threads give the same pairs in the
// same order.
// The world's sort of the pairs' keys (group_by.hpp) gives std::sort's order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "broadphase.hpp"
#include "contact.hpp"
#include "group_by.hpp"

using namespace ragdoll_sim;

namespace {
using Pairs = std::vector<std::pair<int, int>>;

Pairs bruteForce(const std::vector<Aabb>& boxes, const std::vector<char>& unbounded,
                 const std::vector<PlaneProxy>& planes, double margin) {
  Pairs out;
  for (size_t i = 0; i < boxes.size(); ++i)
    for (size_t j = i + 1; j < boxes.size(); ++j)
      if (!unbounded[i] && !unbounded[j] && boxes[i].overlaps(boxes[j])) out.emplace_back(i, j);
  for (const PlaneProxy& p : planes)
    for (size_t i = 0; i < boxes.size(); ++i) {
      if (unbounded[i]) continue;
      const Vec3 c = 0.5 * (boxes[i].lo + boxes[i].hi), e = 0.5 * (boxes[i].hi - boxes[i].lo);
      if (p.normal.dot(c) - p.normal.cwiseAbs().dot(e) <= p.offset + margin)
        out.emplace_back(std::min(p.shape, int(i)), std::max(p.shape, int(i)));
    }
  std::sort(out.begin(), out.end());
  return out;
}

// n boxes scattered over a field whose size keeps the density of a ragdoll scene; some share
// a face exactly (touching counts as overlapping), some have zero size, some are long (walls).
std::vector<Aabb> scatter(std::mt19937& rng, int n) {
  const double field = 2.0 * std::cbrt(double(n));
  std::uniform_real_distribution<double> pos(-field, field), size(0.0, 0.3), u(0.0, 1.0);
  std::vector<Aabb> boxes(n);
  for (int i = 0; i < n; ++i) {
    const Vec3 c(pos(rng), pos(rng), 0.25 * pos(rng));
    Vec3 h(size(rng), size(rng), size(rng));
    const double kind = u(rng);
    if (kind < 0.05) h.setZero();                       // a point
    else if (kind < 0.08) h.x() = 6.0 * field;          // longer than the grid's kMaxSpan cells
    boxes[i] = {c - h, c + h};
    if (kind > 0.9 && i > 0) {  // touches box i-1's +x face exactly
      const Aabb& o = boxes[i - 1];
      boxes[i].lo.x() = o.hi.x();
      boxes[i].hi.x() = o.hi.x() + 2.0 * h.x();
      boxes[i].lo.y() = o.lo.y();
      boxes[i].hi.y() = o.hi.y();
      boxes[i].lo.z() = o.lo.z();
      boxes[i].hi.z() = o.hi.z();
    }
  }
  return boxes;
}
}  // namespace

class BroadphaseExact : public ::testing::TestWithParam<int> {};
TEST_P(BroadphaseExact, PairsEqualBruteForceWhileBoxesMove) {
  const int n = GetParam();
  std::mt19937 rng(11 + n);
  std::vector<Aabb> boxes = scatter(rng, n);
  std::vector<char> unbounded(n, 0);
  unbounded[3] = 1;  // a plane's slot: its box is ignored
  const std::vector<PlaneProxy> planes = {{3, Vec3::UnitZ(), -0.2}};
  std::normal_distribution<double> step(0.0, 0.05);
  // bp unfiltered; filtered with a filter that drops a third of the pairs.
  Broadphase bp, filtered;
  const auto keep = [](int i, int j) { return (i + j) % 3 != 0; };
  Pairs pairs, filtered_pairs;
  size_t total = 0;
  int grid_calls = 0;
  for (int call = 0; call < 6; ++call) {
    if (call == 3) boxes.resize(n - 7);  // shapes removed: the kept order drops stale ids
    std::vector<char> ub(unbounded.begin(), unbounded.begin() + boxes.size());
    grid_calls += int(std::count(ub.begin(), ub.end(), 0)) >= Broadphase::kGridMin;
    bp.findPairs(boxes, ub, planes, 0.01, pairs);
    filtered.findPairs(boxes, ub, planes, 0.01, filtered_pairs, keep);
    for (const auto& [i, j] : pairs) ASSERT_LT(i, j);
    std::sort(pairs.begin(), pairs.end());
    std::sort(filtered_pairs.begin(), filtered_pairs.end());
    const Pairs truth = bruteForce(boxes, ub, planes, 0.01);
    ASSERT_EQ(pairs, truth) << "call " << call;
    Pairs kept;
    for (const auto& [i, j] : truth)
      if (keep(i, j)) kept.emplace_back(i, j);
    ASSERT_EQ(filtered_pairs, kept) << "call " << call;
    total += truth.size();
    for (Aabb& b : boxes) {  // every box moves a few cm, as bodies do between steps
      const Vec3 d(step(rng), step(rng), step(rng));
      b.lo += d;
      b.hi += d;
    }
  }
  EXPECT_GT(total, size_t(n));  // the scenes do have overlaps to find
  std::printf("[ broad    ] %d boxes: %zu pairs over 6 calls (%d by the grid, %d by the sweep), "
              "equal to brute force\n", n, total, grid_calls, 6 - grid_calls);
}
INSTANTIATE_TEST_SUITE_P(SweepAndGrid, BroadphaseExact,
                         // kGridMin + 4: the grid, then the sweep once 7 shapes are gone.
                         ::testing::Values(40, 500, Broadphase::kGridMin + 4, 3000));

// The sweep and the grid keep their candidates between calls (fat boxes): over many calls in
// which most boxes barely move or change size (kept candidates), a few jump (their candidates
// found again) and now and then all of them move (the whole sweep or grid again), the pairs stay
// the brute-force ones, and with a filter and frozen shapes the same as a fresh broadphase's,
// also after the filter changed (filterChanged).
class BroadphaseKept : public ::testing::TestWithParam<int> {};
TEST_P(BroadphaseKept, CandidatesEqualBruteForce) {
  const int n = GetParam();
  std::mt19937 rng(23);
  std::vector<Aabb> boxes = scatter(rng, n);
  const std::vector<char> unbounded(n, 0);
  std::normal_distribution<double> jitter(0.0, 0.001), jump(0.0, 0.4), drift(0.0, 0.05);
  std::uniform_int_distribution<int> pick(0, n - 1);
  std::vector<char> frozen(n, 0);
  for (int i = 0; i < n; i += 3) frozen[i] = 1;
  int modulus = 5;  // the filter changes now and then
  const auto keep = [&](int i, int j) { return (i + j) % modulus != 0; };
  Broadphase bp, filtered;
  Pairs pairs, filtered_pairs, fresh_pairs;
  size_t total = 0;
  for (int call = 0; call < 80; ++call) {
    if (call % 10 == 9) {
      modulus = modulus == 5 ? 7 : 5;
      filtered.filterChanged();
    }
    bp.findPairs(boxes, unbounded, {}, 0.0, pairs);
    filtered.findPairs(boxes, unbounded, {}, 0.0, filtered_pairs, keep, &frozen);
    Broadphase fresh;
    fresh.findPairs(boxes, unbounded, {}, 0.0, fresh_pairs, keep, &frozen);
    std::sort(pairs.begin(), pairs.end());
    ASSERT_EQ(pairs, bruteForce(boxes, unbounded, {}, 0.0)) << "call " << call;
    std::sort(filtered_pairs.begin(), filtered_pairs.end());
    std::sort(fresh_pairs.begin(), fresh_pairs.end());
    ASSERT_EQ(filtered_pairs, fresh_pairs) << "call " << call;
    total += pairs.size();
    if (call % 20 == 19) {  // everything moves
      for (Aabb& b : boxes) {
        const Vec3 d(drift(rng), drift(rng), drift(rng));
        b.lo += d;
        b.hi += d;
      }
      continue;
    }
    for (Aabb& b : boxes) {  // bodies at rest: a little motion, the boxes grow and shrink
      if ((b.hi - b.lo).minCoeff() < 0.05) continue;  // a point or thin box keeps no margin
      const Vec3 d(jitter(rng), jitter(rng), jitter(rng));
      const double g = 0.5 * std::abs(jitter(rng));
      b.lo += d - Vec3::Constant(call % 2 ? g : -g).cwiseMin(b.hi - b.lo);
      b.hi += d;
    }
    for (int k = 0; k < 4; ++k) {  // a few jump, one of them onto another box
      Aabb& b = boxes[pick(rng)];
      const Vec3 d = k == 0 ? Vec3(boxes[pick(rng)].lo - b.lo)
                            : Vec3(jump(rng), jump(rng), 0.25 * jump(rng));
      b.lo += d;
      b.hi += d;
    }
  }
  EXPECT_GT(total, size_t(n));
}
INSTANTIATE_TEST_SUITE_P(SweepAndGrid, BroadphaseKept,
                         ::testing::Values(400, Broadphase::kGridMin + 100));

// With two threads the loops over many boxes and candidates (containment in the fat boxes, the
// escaped boxes' new candidates, the exact test of the candidates, the planes) are split in
// chunks: over calls with kept candidates, escaped boxes, whole rebuilds, frozen shapes, a
// plane and a box that turns NaN, the pairs are one thread's, in the same order.
TEST(Broadphase, ThreadsGiveTheSamePairsInTheSameOrder) {
  for (const int n : {700, 3000}) {  // the sweep, the grid
    std::mt19937 rng(31 + n);
    std::vector<Aabb> boxes = scatter(rng, n);
    for (Aabb& b : boxes) {  // denser: more candidates than kParallelWork
      b.lo -= Vec3::Constant(0.2);
      b.hi += Vec3::Constant(0.2);
    }
    std::vector<char> unbounded(n, 0);
    unbounded[5] = 1;
    const std::vector<PlaneProxy> planes = {{5, Vec3::UnitZ(), -0.2}};
    std::vector<char> frozen(n, 0);
    for (int i = 0; i < n; i += 4) frozen[i] = 1;
    frozen[5] = 1;
    const auto keep = [](int i, int j) { return (i + 2 * j) % 7 != 0; };
    std::normal_distribution<double> jitter(0.0, 0.001), jump(0.0, 0.4), drift(0.0, 0.05);
    std::uniform_int_distribution<int> pick(0, n - 1);
    Broadphase one, two;
    Pairs pairs_one, pairs_two;
    size_t total = 0;
    for (int call = 0; call < 24; ++call) {
      const std::vector<char>* fr = call % 3 == 0 ? &frozen : nullptr;
      one.findPairs(boxes, unbounded, planes, 0.01, pairs_one, keep, fr, 1);
      two.findPairs(boxes, unbounded, planes, 0.01, pairs_two, keep, fr, 2);
      ASSERT_EQ(pairs_two, pairs_one) << n << " boxes, call " << call;
      total += pairs_one.size();
      const double nan = std::numeric_limits<double>::quiet_NaN();
      if (call == 10) boxes[17].hi.x() = nan;  // the plain sweep or grid, then kept again
      if (call == 11) boxes[17].hi.x() = boxes[17].lo.x() + 0.1;
      if (call % 8 == 7) {  // everything moves: a whole rebuild
        for (Aabb& b : boxes) {
          const Vec3 d(drift(rng), drift(rng), drift(rng));
          b.lo += d;
          b.hi += d;
        }
        continue;
      }
      for (Aabb& b : boxes) {
        const Vec3 d(jitter(rng), jitter(rng), jitter(rng));
        b.lo += d;
        b.hi += d;
      }
      for (int k = 0; k < 12; ++k) {  // escaped boxes: their candidates found again
        Aabb& b = boxes[pick(rng)];
        const Vec3 d(jump(rng), jump(rng), 0.25 * jump(rng));
        b.lo += d;
        b.hi += d;
      }
    }
    // the grid's calls test more candidates (a superset of the pairs) than kParallelWork
    if (n > Broadphase::kGridMin) {
      EXPECT_GT(total, size_t(24 * Broadphase::kParallelWork));
    }
  }
}

// A box whose bounds are NaN or infinite overlaps nothing, and the finite ones still pair up.
TEST(Broadphase, NonFiniteBoxesPairWithNothing) {
  for (int n : {100, Broadphase::kGridMin + 10}) {
    std::mt19937 rng(5);
    std::vector<Aabb> boxes = scatter(rng, n);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    boxes[10].lo.x() = nan;
    boxes[20].hi.setConstant(nan);
    boxes[30].hi.y() = inf;
    boxes[30].lo.y() = -inf;
    std::vector<char> unbounded(n, 0);
    Broadphase bp;
    Pairs pairs;
    bp.findPairs(boxes, unbounded, {}, 0.0, pairs);
    std::sort(pairs.begin(), pairs.end());
    EXPECT_EQ(pairs, bruteForce(boxes, unbounded, {}, 0.0)) << n << " boxes";
    for (const auto& [i, j] : pairs) EXPECT_TRUE(i != 10 && j != 10 && i != 20 && j != 20);
  }
}

// A NaN sweep key between two boxes that overlap must not hide their pair: sorted with the NaN
// in place, the keys run 0, 2, NaN, 0.5, and box 0's sweep would stop at box 1 (key 2 > its
// hi 1) before it reached box 3.
TEST(Broadphase, NanKeyHidesNoPairOfFiniteBoxes) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Aabb> boxes = {{Vec3(0, 0, 0), Vec3(1, 1, 1)},
                             {Vec3(2, 0, 0), Vec3(3, 1, 1)},
                             {Vec3(nan, 0, 0), Vec3(1, 1, 1)},
                             {Vec3(0.5, 0, 0), Vec3(1.5, 1, 1)}};
  const std::vector<char> unbounded(boxes.size(), 0);
  Broadphase bp;
  Pairs pairs;
  bp.findPairs(boxes, unbounded, {}, 0.0, pairs);
  EXPECT_EQ(pairs, Pairs({{0, 3}}));
}

// Groups of every kind: empty, one key, a few in random order, a large one in random order (a
// static box under many bodies: std::sort), a large ascending one (a plane's), and the last
// shape index as first shape.
TEST(PairKeys, SortGivesStdSortOrder) {
  std::mt19937 rng(7);
  for (int round = 0; round < 20; ++round) {
    const int shapes = 300;
    std::vector<uint64_t> keys;
    for (int b = 1; b < shapes; ++b) keys.push_back(pairKey(0, b));  // ascending, as a plane's
    std::vector<int> partners;
    for (int b = 3; b < shapes; ++b) partners.push_back(b);
    std::shuffle(partners.begin(), partners.end(), rng);
    for (int k = 0; k < 100; ++k) keys.push_back(pairKey(2, partners[k]));  // large, unsorted
    for (int a = 5; a < shapes - 1; a += 1 + int(rng() % 4)) {
      const int n = int(rng() % 6);  // 0 .. 5 partners above a
      for (int k = 0; k < n; ++k) {
        const int b = a + 1 + int(rng() % (shapes - 1 - a));
        const uint64_t key = pairKey(a, b);
        if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
      }
    }
    keys.push_back(pairKey(shapes - 1, shapes));  // first shape = shape_count - 1
    std::shuffle(keys.begin() + (shapes - 1), keys.end(), rng);  // the plane's stay ascending
    std::vector<uint64_t> expected = keys, scratch;
    std::sort(expected.begin(), expected.end());
    std::vector<int> offsets, cursor;
    sortPairKeys(keys, shapes, scratch, offsets, cursor);
    ASSERT_EQ(keys, expected) << "round " << round;
  }
  std::vector<uint64_t> none, scratch;
  std::vector<int> offsets, cursor;
  sortPairKeys(none, 4, scratch, offsets, cursor);
  EXPECT_TRUE(none.empty());
  // Few keys among many shapes (the std::sort path).
  std::vector<uint64_t> few = {pairKey(900, 950), pairKey(3, 7), pairKey(900, 901), pairKey(0, 5)};
  std::vector<uint64_t> expected = few;
  std::sort(expected.begin(), expected.end());
  sortPairKeys(few, 1000, scratch, offsets, cursor);
  EXPECT_EQ(few, expected);
}
