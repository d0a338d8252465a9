// The collide phase's data (collide.cpp): per shape its box and frame, the broadphase pairs,
// and the contacts kept from step to step, sorted by pair key.
//
// Each pair is collided at the poses of the step start, in a frame at its dynamic body's centre
// (translation invariance, body.hpp). Separated pairs are skipped by their cached axis; touching
// pairs that barely moved keep their manifold (manifold_cache.hpp); impulses are carried over by
// feature id (warm starting, scaled where the substep changed: warmStartScale). Pairs of two
// shapes that keep last step's box (sleeping or static bodies) or plane are carried over instead
// of found again: their overlap cannot have changed.
//
// The shapes of static bodies are kept apart (static_tree.hpp): their boxes are computed and
// their tree built only after a static shape was added, removed or moved, and each step the
// other shapes' boxes query the tree; the broadphase sees the other shapes alone. So a step
// costs nothing per static shape or body that no moving shape comes near.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "broadphase.hpp"
#include "contact.hpp"
#include "manifold_cache.hpp"
#include "static_tree.hpp"

namespace ragdoll_sim {

struct CollideData {
  Broadphase broadphase;
  StaticTree static_tree;  // the bounded shapes of static bodies
  // Bounded shapes of dynamic bodies, of static bodies, and planes (alive, ascending ids), and
  // per shape whether it is in static_shapes: rebuilt when a shape is added or removed.
  std::vector<int> moving_shapes, static_shapes, plane_shapes;
  std::vector<char> is_static_shape;
  bool shape_lists_dirty = true;
  // A static shape was added, removed or moved (or the speculative distance changed): the
  // next collide computes the static boxes again and rebuilds static_tree.
  bool static_dirty = true;
  int64_t static_boxes_computed = 0;  // static boxes computed so far (the tests count them)
  std::vector<Contact> contacts, next_contacts;
  std::vector<uint64_t> contact_keys;  // contacts[k].key, sorted
  std::vector<uint64_t> carried_keys, merged_keys;
  std::vector<char> frozen;  // per shape: box or plane as in the last step
  std::vector<PlaneProxy> last_planes;
  // The broadphase filter changed (pairs enabled or disabled): the next collide finds every
  // pair again instead of carrying sleeping ones over, and the broadphase its candidates.
  bool pairs_dirty = true;
  // Per contact (same index): its manifold in the shapes' frames (manifold_cache.hpp).
  std::vector<ManifoldCache> manifold_caches, next_manifold_caches;
  std::vector<Aabb> aabbs;
  // Per shape: its box in aabbs is that of the current pose, kept while the body is static or
  // asleep (such a body has zero velocity and does not move, so the box is recomputed only
  // after the body woke, was set or was reset).
  std::vector<char> aabb_kept;
  // Per shape: its shapeFrame, formed in collide (a bounded shape's with its box, and kept with
  // it; a plane's every step) and read by each pair's narrowphase frame (shapePoseFrom), which
  // only adds the centre's offset from the pair's origin.
  std::vector<Transform> shape_frames;
  std::vector<char> unbounded;
  std::vector<PlaneProxy> planes;
  std::vector<std::pair<int, int>> pairs;
  std::vector<std::vector<std::pair<int, int>>> static_pair_chunks;  // collectInChunks' scratch
  std::vector<uint64_t> pair_keys;
  std::vector<int> old_contact;
  // The narrowphase's order of the pairs: by their first dynamic body (ascending, stable), so
  // that each thread's share holds the bodies whose islands it solved (islands and their runs
  // are in body order), as in the boxes; in key order a plane's pairs come first, all bodies'
  // together. Made again when the pairs changed.
  std::vector<int> pair_order, order_counts;
  std::vector<int> sort_offsets, sort_cursor;  // sortPairKeys' scratch
};

}  // namespace ragdoll_sim
