// Broadphase: the pairs of bounded shapes whose AABBs overlap (Aabb::overlaps), plus every
// (plane, bounded shape) pair whose box reaches within the margin of the plane. Two methods,
// which give exactly the same pair set (the order differs; the world sorts the pairs by key):
//   sweep and prune on one axis (fewer than kGridMin bounded shapes): the axis the box centres
//     spread most along; the proxies' order is kept between steps and re-sorted by insertion
//     sort, near linear when bodies move little per step. Its candidates grow with the length
//     of a row of bodies along the axis, so it scales poorly to many spread-out ragdolls.
//   uniform hash grid (from kGridMin shapes), built afresh at each call: cell side twice the mean
//     largest box side; each box goes into every cell it overlaps, and a pair is reported only
//     in the cell that holds the low corner of its overlap ((max lo_a, lo_b) per axis: inside
//     both boxes, so every overlapping pair is found, and once). Its work grows with the
//     bodies and their neighbours only, but a dense cluster fills cells and makes it slower
//     than the sweep, hence the switch by shape count.
//     Boxes longer than kMaxSpan cells (a pit's walls) or not finite are tested against every
//     box instead.
// Either runs over kept fat boxes (each shape's box grown by kFatRatio of its largest side,
// kept while the box stays inside it), and its candidates (the pairs whose fat boxes overlap)
// are kept between calls: a box inside its fat box cannot overlap a box whose fat box it does
// not overlap, so each call tests only the kept candidates against the exact boxes. When a few
// boxes left their fat boxes, only their candidates are found again (against every fat box);
// when many did, the whole sweep or grid runs again over the fat boxes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include "narrowphase.hpp"

namespace ragdoll_sim {

struct PlaneProxy {
  int shape;
  Vec3 normal;   // world
  double offset; // world: n . x = offset
};

class Broadphase {
 public:
  // accept(i, j), i < j: whether an overlapping pair is kept (the world drops the pairs it
  // never collides before they are stored).
  // A reference to the caller's callable, valid for the one findPairs call, so that each
  // overlapping pair costs one indirect call and no std::function overhead.
  class Filter {
   public:
    Filter(std::nullptr_t = nullptr) {}
    template <class F, class = std::enable_if_t<!std::is_same_v<std::decay_t<F>, Filter>>>
    Filter(const F& f)
        : f_(&f),
          call_([](const void* g, int i, int j) { return (*static_cast<const F*>(g))(i, j); }) {}
    // Not from a temporary (`Filter f = [](int, int) {...};` would dangle): name the callable.
    template <class F, class = std::enable_if_t<!std::is_same_v<std::decay_t<F>, Filter> &&
                                                !std::is_lvalue_reference_v<F>>>
    Filter(F&&) = delete;
    explicit operator bool() const { return call_ != nullptr; }
    bool operator()(int i, int j) const { return call_(f_, i, j); }

   private:
    const void* f_ = nullptr;
    bool (*call_)(const void*, int, int) = nullptr;
  };

  // aabbs[i] is shape i's box (ignored when unbounded[i]); pairs get (i, j) with i < j, in the
  // same order for any `threads`: a loop over many boxes or candidates (kParallelWork tests) is
  // split over the threads in chunks whose pairs are joined in chunk order; a step's test of a
  // few kept candidates costs less than starting a parallel region.
  // frozen (optional, one flag per shape, planes included): pairs of two frozen shapes are
  // left out, unfiltered (the world carries them over from the last step: their boxes and
  // planes have not changed since).
  // accept must give a pair the same answer from call to call until filterChanged(): the kept
  // candidates are filtered once, when they are found.
  void findPairs(const std::vector<Aabb>& aabbs, const std::vector<char>& unbounded,
                 const std::vector<PlaneProxy>& planes, double margin,
                 std::vector<std::pair<int, int>>& pairs, Filter accept = nullptr,
                 const std::vector<char>* frozen = nullptr, int threads = 1);
  // The same over the bounded shapes `bounded` (ascending ids) alone: the others' boxes are
  // not read, so shapes kept elsewhere (static ones: static_tree.hpp) cost nothing here.
  void findPairs(const std::vector<int>& bounded, const std::vector<Aabb>& aabbs,
                 const std::vector<PlaneProxy>& planes, double margin,
                 std::vector<std::pair<int, int>>& pairs, Filter accept = nullptr,
                 const std::vector<char>* frozen = nullptr, int threads = 1);

  // The filter answers differently now: the kept candidates are found again.
  void filterChanged() { kept_valid_ = false; }

  static constexpr int kGridMin = 768;  // bounded shapes from which the grid is used
  // Box tests from which a loop goes to the threads (a test costs a few ns, a parallel region
  // microseconds).
  static constexpr long kParallelWork = 2048;

 private:
  // Sweep and prune over boxes; candidates: the overlapping pairs through addCandidate (the
  // kept candidates), else through addPair.
  void sweep(const std::vector<Aabb>& aabbs, std::vector<std::pair<int, int>>& pairs,
             bool candidates = false);
  // The pairs through the kept candidates (fat boxes); false when a box is not finite (then the
  // plain sweep or grid runs, as the fat boxes cannot bound it).
  bool keptPairs(const std::vector<Aabb>& aabbs, std::vector<std::pair<int, int>>& pairs);
  bool useGrid() const { return int(bounded_.size()) >= kGridMin; }
  // The hash grid over boxes; candidates as for sweep.
  void grid(const std::vector<Aabb>& aabbs, std::vector<std::pair<int, int>>& pairs,
            bool candidates = false);
  // Appends (min, max) of i and j when they are not both frozen and accept_ takes it.
  void addPair(std::vector<std::pair<int, int>>& pairs, int i, int j) const;
  // The same, frozen or not (a kept candidate is tested against frozen_ at each call).
  void addCandidate(std::vector<std::pair<int, int>>& pairs, int i, int j) const;
  void insert(int proxy, const int cell[3]);

  // f(begin, end, out) over [0, n) (items of `work` box tests in all) into `into`, in order,
  // over this call's threads (parallel_for.hpp: collectInChunks).
  template <class T, class F>
  void inChunks(int n, long work, std::vector<std::vector<T>>& scratch, std::vector<T>& into,
                F&& f);

  // scratch, kept between steps to avoid a per-step allocation
  int threads_ = 1;  // this call's threads
  std::vector<std::vector<std::pair<int, int>>> pair_chunks_;
  std::vector<std::vector<int>> id_chunks_;
  std::vector<int> bounded_;  // ids of the bounded shapes, ascending
  std::vector<int> ids_scratch_;  // the unbounded-flags overload's ids
  Filter accept_;  // this call's filter (empty: keep all)
  const std::vector<char>* frozen_ = nullptr;  // this call's frozen shapes (null: none)
  bool bothFrozen(int i, int j) const { return frozen_ && (*frozen_)[i] && (*frozen_)[j]; }

  // sweep and prune
  static constexpr double kSwitchRatio = 1.5;  // another axis must spread this much more
  struct SweepBounds {
    double hi, lo_u, hi_u, lo_w, hi_w;  // hi on the sweep axis; both bounds on the other two
  };
  int axis_ = 0;
  std::vector<int> order_;           // kept between steps
  std::vector<char> seen_;
  std::vector<double> key_;          // lo on the sweep axis, in sweep order
  std::vector<SweepBounds> bounds_;  // in sweep order
  size_t find_work_ = 0;  // candidates the last whole sweep or grid looked at

  // kept candidates
  static constexpr double kFatRatio = 0.2;  // fat margin per side over the box's largest side
  bool kept_valid_ = false;
  std::vector<int> kept_bounded_;              // bounded_ when the candidates were found
  std::vector<Aabb> fat_;                      // per shape id
  std::vector<char> moved_;                    // per shape id, all 0 between calls
  std::vector<int> escaped_;                   // shapes whose box left its fat box
  std::vector<std::pair<int, int>> candidates_;  // pairs whose fat boxes overlap

  // hash grid
  static constexpr double kMaxSpan = 8.0;     // cells per axis before a box counts as large
  static constexpr int kCellLimit = 1 << 20;  // cell coordinates clamped to +-this
  struct CellRange {
    int lo[3], hi[3];
  };
  struct Slot {
    uint64_t key;
    int cell[3];
    int head;  // first entry of the cell's list, -1: free slot
  };
  std::vector<int> gridded_, large_;
  std::vector<CellRange> range_;  // per shape (filled for the gridded ones)
  std::vector<Slot> table_;       // open addressing, a power of two; free again after a call
  std::vector<int> used_;         // occupied slots, in order of first use
  std::vector<int> next_, entry_proxy_, cell_ids_;
};

}  // namespace ragdoll_sim
