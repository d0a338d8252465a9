// Graph colouring for the wide solver (the contact rows use it, contact_wide.hpp): the constraints
// of one island part are split into colours so that no two constraints of a colour share a
// dynamic body; a colour's constraints then touch disjoint bodies, so solving them 4 or 8 at
// once in lanes gives the same bits as solving them one after another, in any order.
//
// Greedy colouring in input order (as Box2D v3's constraint_graph.c): each constraint takes the
// first colour (FirstFit) or the smallest colour (Balanced) that holds neither of its dynamic
// bodies; one that finds none among max_colours goes to the overflow set, which the solver
// solves scalar. The per-colour body bit sets are kept transposed, one word per body with a
// bit per colour, so a constraint finds its colour in O(1) (the lowest bit of the free colours)
// and the bits are cleared by walking the constraints again, never the whole body range.
// Bodies that the solve never writes (static, sleeping: the identity solver bodies) take no
// bit: any number of constraints of a colour may share them.
//
// The result depends only on the constraints and their order: not on the body numbering, the
// thread count or the lane width (the packing reads the colours, the colouring never reads the
// width). A permuted input is coloured again in its own order, so colours and their count may
// differ, and are valid either way. Under FirstFit a constraint's colour depends only on the
// constraints before it that share its bodies: islands merged into one graph (a thread's run)
// keep the colours each takes alone, so the grouping of islands changes no colour. Balanced
// compares colour sizes over the whole input and has no such guarantee.
//
// Each kind of constraint (contacts, joint point parts, joint limits and motors) is coloured on
// its own graph: the sweep solves the kinds one after another and a wide record holds one kind,
// so rows of different kinds never share a batch and need not avoid each other's bodies, which
// keeps the colours fewer and the lanes fuller. A caller that wants one graph for several kinds
// passes their constraints as one list.
#pragma once

#include <cstdint>
#include <vector>

namespace ragdoll_sim {

// One constraint between two bodies. A body index is in [0, body_count) of ConstraintGraph::
// colour; dynamic_* false: the solve never writes that body (static or asleep), so it does not
// count and its index is not read.
struct GraphEdge {
  int body_a = -1, body_b = -1;
  bool dynamic_a = true, dynamic_b = true;
};

enum class ColourPolicy : uint8_t {
  FirstFit,  // the lowest free colour: Box2D's rule, the first colours fullest
  Balanced,  // the free colour with the fewest constraints so far (ties: the lowest)
};

class ConstraintGraph {
 public:
  static constexpr int kMaxColours = 24;  // the most colours before the overflow set
  static constexpr int kOverflow = -1;    // colourOf() of a constraint in the overflow set

  // Colours edges[0, n). body_count: one more than the largest dynamic body index.
  // max_colours in [1, kMaxColours] (fewer: a test of the overflow). Allocates only while n,
  // body_count or the colour count grow past what an earlier call needed.
  void colour(const GraphEdge* edges, int n, int body_count, int max_colours = kMaxColours,
              ColourPolicy policy = ColourPolicy::FirstFit);
  void colour(const std::vector<GraphEdge>& edges, int body_count,
              int max_colours = kMaxColours, ColourPolicy policy = ColourPolicy::FirstFit) {
    colour(edges.data(), int(edges.size()), body_count, max_colours, policy);
  }

  int size() const { return int(colour_of_.size()); }  // constraints of the last colour()
  int colourCount() const { return colour_count_; }    // colours used, the overflow not counted
  int colourOf(int i) const { return colour_of_[i]; }  // in [0, colourCount()) or kOverflow
  // The constraints of colour c in input order: order()[colourBegin(c), colourBegin(c + 1));
  // c = colourCount() is the overflow set, ending at size().
  const std::vector<int>& order() const { return order_; }
  int colourBegin(int c) const { return begin_[c]; }
  int colourSize(int c) const { return begin_[c + 1] - begin_[c]; }
  int overflowSize() const { return size() - begin_[colour_count_]; }

 private:
  void clearBits(const GraphEdge* edges, int n);

  std::vector<uint32_t> body_colours_;  // per body: bit c set while colour c holds it
  std::vector<int> colour_of_, order_;
  std::vector<int> begin_;  // colour_count_ + 2 offsets into order_ (colours, then overflow)
  int counts_[kMaxColours + 1] = {};
  int colour_count_ = 0;
};

// The colours in wide records of `width` lanes: each colour's constraints in groups of width,
// in the colour's order, one record per group; the last record of a colour padded (its mask
// has a bit per used lane, the padding lanes hold -1). The overflow set is not packed.
class LanePacking {
 public:
  // width: 4 or 8 (std::invalid_argument otherwise). With kind (one per constraint), each
  // colour's constraints are ordered by kind first (stable): a record's lanes then mostly share
  // the rows of one kind of constraint, which a record solves for all its lanes.
  void pack(const ConstraintGraph& graph, int width, const std::vector<int>* kind = nullptr);

  int width() const { return width_; }
  int recordCount() const { return int(masks_.size()); }
  // Records of colour c: [recordBegin(c), recordBegin(c + 1)).
  int recordBegin(int c) const { return record_begin_[c]; }
  // Lane k of record r: a constraint index, or -1 for padding.
  int lane(int r, int k) const { return lanes_[r * width_ + k]; }
  uint8_t mask(int r) const { return masks_[r]; }
  int usedLanes() const { return used_; }
  // Used lanes over all lanes of the records (1 when there are none).
  double fill() const { return masks_.empty() ? 1.0 : double(used_) / (double(masks_.size()) * width_); }

 private:
  int width_ = 4, used_ = 0;
  std::vector<int> lanes_;
  std::vector<uint8_t> masks_;
  std::vector<int> record_begin_;
};

}  // namespace ragdoll_sim
