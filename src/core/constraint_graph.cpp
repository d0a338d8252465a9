// Greedy graph colouring and lane packing (constraint_graph.hpp).
#include "constraint_graph.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace ragdoll_sim {

namespace {

int lowestBit(uint32_t x) { return __builtin_ctz(x); }

// The free colour with the fewest constraints so far, the lowest on ties; a colour not yet
// open (index >= used) only when no open one is free.
int balancedColour(uint32_t free, int used, const int* counts) {
  const uint32_t open = used >= 32 ? free : free & ((uint32_t(1) << used) - 1);
  if (open == 0) return lowestBit(free);
  int best = -1;
  for (uint32_t m = open; m != 0; m &= m - 1) {
    const int c = lowestBit(m);
    if (best < 0 || counts[c] < counts[best]) best = c;
  }
  return best;
}

}  // namespace

void ConstraintGraph::colour(const GraphEdge* edges, int n, int body_count, int max_colours,
                             ColourPolicy policy) {
  if (max_colours < 1 || max_colours > kMaxColours)
    throw std::invalid_argument("ConstraintGraph: max_colours " + std::to_string(max_colours) +
                                " is outside [1, " + std::to_string(kMaxColours) + "]");
  if (int(body_colours_.size()) < body_count) body_colours_.resize(body_count, 0);
  colour_of_.resize(n);
  std::fill(counts_, counts_ + kMaxColours + 1, 0);
  const uint32_t allowed = (uint32_t(1) << max_colours) - 1;
  int used = 0;
  for (int i = 0; i < n; ++i) {
    const GraphEdge& e = edges[i];
    const bool bad_a = e.dynamic_a && unsigned(e.body_a) >= unsigned(body_count);
    const bool bad_b = e.dynamic_b && unsigned(e.body_b) >= unsigned(body_count);
    if (bad_a || bad_b) {
      clearBits(edges, i);
      throw std::invalid_argument("ConstraintGraph: constraint " + std::to_string(i) +
                                  " has dynamic body " +
                                  std::to_string(bad_a ? e.body_a : e.body_b) +
                                  " outside [0, " + std::to_string(body_count) + ")");
    }
    const uint32_t taken = (e.dynamic_a ? body_colours_[e.body_a] : 0u) |
                           (e.dynamic_b ? body_colours_[e.body_b] : 0u);
    const uint32_t free = ~taken & allowed;
    if (free == 0) {
      colour_of_[i] = kOverflow;
      ++counts_[kMaxColours];
      continue;
    }
    const int c = policy == ColourPolicy::FirstFit ? lowestBit(free) : balancedColour(free, used, counts_);
    const uint32_t bit = uint32_t(1) << c;
    if (e.dynamic_a) body_colours_[e.body_a] |= bit;
    if (e.dynamic_b) body_colours_[e.body_b] |= bit;
    colour_of_[i] = c;
    ++counts_[c];
    used = std::max(used, c + 1);
  }
  clearBits(edges, n);
  colour_count_ = used;
  // Counting sort by colour, stable: the colours in order, then the overflow set.
  begin_.resize(used + 2);
  int cursor[kMaxColours + 1];
  begin_[0] = 0;
  for (int c = 0; c < used; ++c) begin_[c + 1] = begin_[c] + counts_[c];
  begin_[used + 1] = n;
  for (int c = 0; c <= used; ++c) cursor[c] = begin_[c];
  order_.resize(n);
  for (int i = 0; i < n; ++i) {
    const int c = colour_of_[i] == kOverflow ? used : colour_of_[i];
    order_[cursor[c]++] = i;
  }
}

// Only the bodies of these constraints took bits.
void ConstraintGraph::clearBits(const GraphEdge* edges, int n) {
  for (int i = 0; i < n; ++i) {
    if (edges[i].dynamic_a) body_colours_[edges[i].body_a] = 0;
    if (edges[i].dynamic_b) body_colours_[edges[i].body_b] = 0;
  }
}

void LanePacking::pack(const ConstraintGraph& graph, int width, const std::vector<int>* kind) {
  if (width != 4 && width != 8)
    throw std::invalid_argument("LanePacking: width " + std::to_string(width) +
                                " is neither 4 nor 8");
  width_ = width;
  const int colours = graph.colourCount();
  record_begin_.resize(colours + 1);
  record_begin_[0] = 0;
  for (int c = 0; c < colours; ++c)
    record_begin_[c + 1] = record_begin_[c] + (graph.colourSize(c) + width - 1) / width;
  const int records = record_begin_[colours];
  lanes_.assign(size_t(records) * width, -1);
  masks_.assign(records, 0);
  used_ = 0;
  const std::vector<int>& order = graph.order();
  const int shift = width == 8 ? 3 : 2;
  for (int c = 0; c < colours; ++c) {
    const int first = graph.colourBegin(c), size = graph.colourSize(c);
    // a colour's lanes are contiguous: its records follow each other
    const auto lanes = lanes_.begin() + (size_t(record_begin_[c]) << shift);
    std::copy(order.begin() + first, order.begin() + first + size, lanes);
    if (kind)
      std::stable_sort(lanes, lanes + size, [&](int x, int y) { return (*kind)[x] < (*kind)[y]; });
    for (int r = record_begin_[c]; r < record_begin_[c + 1]; ++r) {
      const int left = size - ((r - record_begin_[c]) << shift);
      masks_[r] = uint8_t(left >= width ? (1u << width) - 1 : (1u << left) - 1);
    }
    used_ += size;
  }
}

}  // namespace ragdoll_sim
