#include "broadphase.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <type_traits>

#include "parallel_for.hpp"

namespace ragdoll_sim {
namespace {

bool finite(const Aabb& b) { return b.lo.allFinite() && b.hi.allFinite(); }

}  // namespace

template <class T, class F>
void Broadphase::inChunks(int n, long work, std::vector<std::vector<T>>& scratch,
                          std::vector<T>& into, F&& f) {
  collectInChunks(n, collectChunk(n), threads_, work >= kParallelWork, scratch, into, f);
}

void Broadphase::addCandidate(std::vector<std::pair<int, int>>& pairs, int i, int j) const {
  const int a = std::min(i, j), b = std::max(i, j);
  if (!accept_ || accept_(a, b)) pairs.emplace_back(a, b);
}

void Broadphase::addPair(std::vector<std::pair<int, int>>& pairs, int i, int j) const {
  if (!bothFrozen(i, j)) addCandidate(pairs, i, j);
}

void Broadphase::findPairs(const std::vector<Aabb>& aabbs, const std::vector<char>& unbounded,
                           const std::vector<PlaneProxy>& planes, double margin,
                           std::vector<std::pair<int, int>>& pairs, Filter accept,
                           const std::vector<char>* frozen, int threads) {
  ids_scratch_.clear();
  for (int i = 0; i < int(aabbs.size()); ++i)
    if (!unbounded[i]) ids_scratch_.push_back(i);
  findPairs(ids_scratch_, aabbs, planes, margin, pairs, accept, frozen, threads);
}

void Broadphase::findPairs(const std::vector<int>& bounded, const std::vector<Aabb>& aabbs,
                           const std::vector<PlaneProxy>& planes, double margin,
                           std::vector<std::pair<int, int>>& pairs, Filter accept,
                           const std::vector<char>* frozen, int threads) {
  accept_ = accept;
  frozen_ = frozen;
  threads_ = threads;
  pairs.clear();
  bounded_.assign(bounded.begin(), bounded.end());
  if (!keptPairs(aabbs, pairs)) {
    kept_valid_ = false;
    if (useGrid()) grid(aabbs, pairs);
    else sweep(aabbs, pairs);
  }

  const int m = int(bounded_.size());
  for (const PlaneProxy& p : planes) {
    inChunks(m, m, pair_chunks_, pairs, [&](int begin, int end, auto& out) {
      const int* ids = bounded_.data();
      const Aabb* boxes = aabbs.data();
      const Vec3 normal = p.normal, extent_weights = p.normal.cwiseAbs();
      const double reach = p.offset + margin;
      for (int k = begin; k < end; ++k) {
        const Aabb& b = boxes[ids[k]];
        const Vec3 c = 0.5 * (b.lo + b.hi), e = 0.5 * (b.hi - b.lo);
        if (normal.dot(c) - extent_weights.dot(e) <= reach) addPair(out, p.shape, ids[k]);
      }
    });
  }
  accept_ = nullptr;
  frozen_ = nullptr;
  threads_ = 1;
}

void Broadphase::sweep(const std::vector<Aabb>& aabbs, std::vector<std::pair<int, int>>& pairs,
                       bool candidates) {
  // Keep the previous order, drop stale or unbounded ids, append new ones. seen_ is all 0
  // between calls (cleared through bounded_), so that a call costs nothing per shape left out.
  seen_.resize(aabbs.size(), 0);
  // 1: bounded, 2: bounded and already in the order. A box with a NaN bound overlaps nothing
  // and stays out: its NaN key would leave the order unsorted, and the sweep would miss pairs.
  for (int id : bounded_)
    if (!aabbs[id].lo.hasNaN() && !aabbs[id].hi.hasNaN()) seen_[id] = 1;
  size_t kept = 0;
  for (int id : order_)
    if (id < int(seen_.size()) && seen_[id] == 1) {
      order_[kept++] = id;
      seen_[id] = 2;
    }
  order_.resize(kept);
  for (int id : bounded_)
    if (seen_[id] == 1) order_.push_back(id);
  for (int id : bounded_) seen_[id] = 0;

  // Sweep along the axis the box centres spread most on (a row of ragdolls along y overlaps
  // in x), switching only when another axis spreads clearly more, so that the kept order stays
  // nearly sorted from step to step.
  Vec3 sum = Vec3::Zero(), sum2 = Vec3::Zero();
  for (int id : order_) {
    const Vec3 c = 0.5 * (aabbs[id].lo + aabbs[id].hi);
    sum += c;
    sum2 += c.cwiseProduct(c);
  }
  if (!order_.empty()) {
    const double inv = 1.0 / double(order_.size());
    const Vec3 var = sum2 * inv - (sum * inv).cwiseProduct(sum * inv);
    int best;
    var.maxCoeff(&best);
    if (best != axis_ && var[best] > kSwitchRatio * var[axis_]) axis_ = best;
  }
  // The sweep keys sit in a contiguous array sorted along with the ids, and the other bounds
  // are gathered once into sweep order: the sort and the sweep stream through memory instead
  // of reading a box through its id at every comparison.
  const int ax = axis_, ax1 = (ax + 1) % 3, ax2 = (ax + 2) % 3;
  const size_t m = order_.size();
  key_.resize(m);
  for (size_t k = 0; k < m; ++k) key_[k] = aabbs[order_[k]].lo[ax];
  for (size_t i = 1; i < m; ++i) {
    const int id = order_[i];
    const double key = key_[i];
    size_t j = i;
    while (j > 0 && key_[j - 1] > key) {
      order_[j] = order_[j - 1];
      key_[j] = key_[j - 1];
      --j;
    }
    order_[j] = id;
    key_[j] = key;
  }
  bounds_.resize(m);
  for (size_t k = 0; k < m; ++k) {
    const Aabb& b = aabbs[order_[k]];
    bounds_[k] = {b.hi[ax], b.lo[ax1], b.hi[ax1], b.lo[ax2], b.hi[ax2]};
  }
  // Each box against those after it in the sweep order; find_work_: the candidates looked at.
  size_t work = 0;
  for (size_t i = 0; i < m; ++i) {
    const SweepBounds a = bounds_[i];
    const double lo = key_[i];
    size_t j = i + 1;
    for (; j < m; ++j) {
      if (key_[j] > a.hi) break;
      const SweepBounds& b = bounds_[j];
      if (lo <= b.hi && b.lo_u <= a.hi_u && a.lo_u <= b.hi_u && b.lo_w <= a.hi_w &&
          a.lo_w <= b.hi_w) {  // Aabb::overlaps
        if (candidates) addCandidate(pairs, order_[i], order_[j]);
        else addPair(pairs, order_[i], order_[j]);
      }
    }
    work += j - i - 1;
  }
  find_work_ = work;
}

bool Broadphase::keptPairs(const std::vector<Aabb>& aabbs,
                           std::vector<std::pair<int, int>>& pairs) {
  const auto fatBox = [](const Aabb& b) {
    const double grow = kFatRatio * (b.hi - b.lo).maxCoeff();
    return Aabb{b.lo - Vec3::Constant(grow), b.hi + Vec3::Constant(grow)};
  };
  fat_.resize(aabbs.size());
  moved_.resize(aabbs.size(), 0);
  escaped_.clear();
  const bool rebuild = !kept_valid_ || kept_bounded_ != bounded_;
  if (rebuild) {
    for (int id : bounded_) {
      if (!finite(aabbs[id])) return false;
      fat_[id] = fatBox(aabbs[id]);
    }
  } else {
    std::atomic<bool> bad{false};  // a box not finite
    const int n = int(bounded_.size());
    inChunks(n, n, id_chunks_, escaped_, [&](int begin, int end, std::vector<int>& out) {
      const int* ids = bounded_.data();
      const Aabb *fat = fat_.data(), *boxes = aabbs.data();
      for (int i = begin; i < end; ++i) {
        const int id = ids[i];
        if (fat[id].contains(boxes[id])) continue;  // (a NaN bound is never inside)
        if (!finite(boxes[id])) bad.store(true, std::memory_order_relaxed);
        else out.push_back(id);
      }
    });
    if (bad.load(std::memory_order_relaxed)) return false;
    for (int id : escaped_) fat_[id] = fatBox(aabbs[id]);
  }
  const size_t m = bounded_.size(), k = escaped_.size();
  if (rebuild || k * m > find_work_) {
    // Many boxes left (or nothing is kept): the whole sweep or grid over the fat boxes.
    candidates_.clear();
    if (useGrid()) grid(fat_, candidates_, true);
    else sweep(fat_, candidates_, true);
    kept_bounded_ = bounded_;
    kept_valid_ = true;
  } else if (k > 0) {
    // A few left: drop their candidates, then test each against every fat box (a pair of two
    // of them once, from its lower id).
    for (int id : escaped_) moved_[id] = 1;
    candidates_.erase(std::remove_if(candidates_.begin(), candidates_.end(),
                                     [&](const std::pair<int, int>& p) {
                                       return moved_[p.first] || moved_[p.second];
                                     }),
                      candidates_.end());
    inChunks(int(k), long(k * m), pair_chunks_, candidates_,
             [&](int begin, int end, std::vector<std::pair<int, int>>& out) {
               const int* ids = bounded_.data();
               const Aabb* fat = fat_.data();
               const char* moved = moved_.data();
               for (int e = begin; e < end; ++e) {
                 const int s = escaped_[e];
                 const Aabb a = fat[s];
                 for (size_t x = 0; x < m; ++x) {
                   const int t = ids[x];
                   if (t != s && !(moved[t] && t < s) && a.overlaps(fat[t]))
                     addCandidate(out, s, t);
                 }
               }
             });
    for (int id : escaped_) moved_[id] = 0;
  }
  // The exact boxes of the candidates.
  const int c = int(candidates_.size());
  inChunks(c, c, pair_chunks_, pairs, [&](int begin, int end, auto& out) {
    // locals: an append may write anywhere, so fields read through the capture would be read
    // again at every candidate
    const std::pair<int, int>* cand = candidates_.data();
    const Aabb* boxes = aabbs.data();
    const char* frozen = frozen_ ? frozen_->data() : nullptr;
    for (int i = begin; i < end; ++i) {
      const auto [a, b] = cand[i];
      if (boxes[a].overlaps(boxes[b]) && !(frozen && frozen[a] && frozen[b]))
        out.emplace_back(a, b);
    }
  });
  return true;
}

void Broadphase::insert(int proxy, const int cell[3]) {
  const uint64_t key = (uint64_t(cell[0] + kCellLimit) << 42) |
                       (uint64_t(cell[1] + kCellLimit) << 21) | uint64_t(cell[2] + kCellLimit);
  const size_t mask = table_.size() - 1;
  size_t s = size_t((key * 0x9E3779B97F4A7C15ull) >> 32) & mask;
  while (table_[s].head >= 0 && table_[s].key != key) s = (s + 1) & mask;
  Slot& slot = table_[s];
  if (slot.head < 0) {
    slot.key = key;
    std::copy(cell, cell + 3, slot.cell);
    used_.push_back(int(s));
  }
  next_.push_back(slot.head);
  entry_proxy_.push_back(proxy);
  slot.head = int(next_.size()) - 1;
}

void Broadphase::grid(const std::vector<Aabb>& aabbs, std::vector<std::pair<int, int>>& pairs,
                      bool candidates) {
  order_.clear();  // the sweep starts afresh if the shapes drop below kGridMin
  double side_sum = 0.0;
  int finite_count = 0;
  for (int i : bounded_)
    if (finite(aabbs[i])) {
      side_sum += (aabbs[i].hi - aabbs[i].lo).maxCoeff();
      ++finite_count;
    }
  double cell = finite_count > 0 ? 2.0 * side_sum / finite_count : 1.0;
  if (!(cell > 1e-9) || !std::isfinite(cell)) cell = 1.0;
  const double inv = 1.0 / cell, lim = double(kCellLimit);

  gridded_.clear();
  large_.clear();
  range_.resize(aabbs.size());
  size_t entries = 0;
  for (int i : bounded_) {
    const Aabb& b = aabbs[i];
    if (!finite(b) || (b.hi - b.lo).maxCoeff() > kMaxSpan * cell) {
      large_.push_back(i);
      continue;
    }
    CellRange& r = range_[i];
    size_t count = 1;
    for (int a = 0; a < 3; ++a) {
      r.lo[a] = int(std::clamp(std::floor(b.lo[a] * inv), -lim, lim - 1.0));
      r.hi[a] = int(std::clamp(std::floor(b.hi[a] * inv), -lim, lim - 1.0));
      count *= size_t(r.hi[a] - r.lo[a] + 1);
    }
    entries += count;
    gridded_.push_back(i);
  }

  size_t size = std::max<size_t>(table_.size(), 16);
  while (size < 2 * entries) size *= 2;
  if (size != table_.size()) table_.assign(size, Slot{0, {0, 0, 0}, -1});
  used_.clear();
  next_.clear();
  entry_proxy_.clear();
  for (int i : gridded_) {
    const CellRange& r = range_[i];
    int c[3];
    for (c[0] = r.lo[0]; c[0] <= r.hi[0]; ++c[0])
      for (c[1] = r.lo[1]; c[1] <= r.hi[1]; ++c[1])
        for (c[2] = r.lo[2]; c[2] <= r.hi[2]; ++c[2]) insert(i, c);
  }

  const auto emit = [&](int i, int j) {
    if (candidates) addCandidate(pairs, i, j);
    else addPair(pairs, i, j);
  };
  size_t work = 0;
  // Two instances of the loop, so that the frozen test stays out of this tight loop where
  // nothing is frozen.
  const auto cellPairs = [&](auto with_frozen) {
    for (int s : used_) {
      const Slot& slot = table_[s];
      cell_ids_.clear();
      for (int e = slot.head; e >= 0; e = next_[e]) cell_ids_.push_back(entry_proxy_[e]);
      const size_t m = cell_ids_.size();
      work += m * (m - 1) / 2;
      for (size_t x = 0; x < m; ++x) {
        const int i = cell_ids_[x];
        const CellRange& ri = range_[i];
        // A frozen box skips the other frozen ones before any test (a sleeping pile fills
        // cells).
        constexpr bool kFrozen = decltype(with_frozen)::value;
        const char* skip = kFrozen && (*frozen_)[i] ? frozen_->data() : nullptr;
        for (size_t y = x + 1; y < m; ++y) {
          const int j = cell_ids_[y];
          if (kFrozen && skip && skip[j]) continue;
          const CellRange& rj = range_[j];
          // Only in the cell of the overlap's low corner (floor is monotonic: that cell is the
          // per-axis max of the two boxes' low cells).
          if (std::max(ri.lo[0], rj.lo[0]) != slot.cell[0] ||
              std::max(ri.lo[1], rj.lo[1]) != slot.cell[1] ||
              std::max(ri.lo[2], rj.lo[2]) != slot.cell[2])
            continue;
          if (aabbs[i].overlaps(aabbs[j])) emit(i, j);
        }
      }
    }
  };
  if (frozen_ && !candidates) cellPairs(std::true_type());
  else cellPairs(std::false_type());
  for (int s : used_) table_[s].head = -1;

  // Large boxes against every bounded box (each large-large pair once).
  for (size_t k = 0; k < large_.size(); ++k) {
    const int i = large_[k];
    for (int j : gridded_)
      if (aabbs[i].overlaps(aabbs[j])) emit(i, j);
    for (size_t l = k + 1; l < large_.size(); ++l) {
      const int j = large_[l];
      if (aabbs[i].overlaps(aabbs[j])) emit(i, j);
    }
    work += gridded_.size() + large_.size() - k - 1;
  }
  find_work_ = work;
}

}  // namespace ragdoll_sim
