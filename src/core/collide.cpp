// The collide phase: broadphase pairs -> narrowphase manifolds at the poses of the step start
// (the boxes and the pairs in parallel). Data: collide.hpp.
#include <algorithm>
#include <atomic>
#include <cmath>

#include "constants.hpp"
#include "gjk.hpp"
#include "group_by.hpp"
#include "parallel_for.hpp"
#include "phase_clock.hpp"
#include "world_impl.hpp"

namespace ragdoll_sim {

// The pair's coefficients from the material table (when the manifold is made, and for every
// kept contact by World::setMaterials).
void World::Impl::applyPairMaterial(Contact& c, const ShapeDef& da, const ShapeDef& db) const {
  const Material pair = def.materials.resolve(da.material, db.material);
  c.static_friction = pair.static_friction;
  c.kinetic_friction = pair.kinetic_friction;
  c.restitution = pair.restitution;
  c.rolling = pair.rolling_resistance > 0.0
                  ? pair.rolling_resistance * std::max(rollingRadius(da.geometry), rollingRadius(db.geometry))
                  : 0.0;
  c.contact_hertz = pair.contact_hertz;
  c.contact_damping_ratio = pair.contact_damping_ratio;
}

// The per-shape lists collide walks (collide.hpp), after a shape was added or removed.
void World::Impl::rebuildShapeLists() {
  const int n = int(shapes.size());
  moving_shapes.clear();
  static_shapes.clear();
  plane_shapes.clear();
  is_static_shape.assign(n, 0);
  unbounded.assign(n, 1);  // removed shapes too: in no pair (neither bounded nor a plane)
  frozen.assign(n, 0);
  for (int s = 0; s < n; ++s) {
    if (!shapes[s].alive) continue;
    if (isUnbounded(shapeDef(s).geometry)) {
      plane_shapes.push_back(s);
      continue;
    }
    unbounded[s] = 0;
    if (isDynamic(shapes[s].body) || !tuning.static_tree) {
      moving_shapes.push_back(s);
    } else {
      static_shapes.push_back(s);
      is_static_shape[s] = 1;
    }
  }
  shape_lists_dirty = false;
}

// pair_order (collide.hpp) for this step's pair_keys: a counting sort by the pair's origin body.
void World::Impl::orderPairs(int count) {
  const auto originOf = [&](int i) {
    const uint64_t key = pair_keys[i];
    return pairOrigin(shapes[int(key >> 32)].body, shapes[int(uint32_t(key))].body);
  };
  order_counts.assign(bodies.size() + 1, 0);
  for (int i = 0; i < count; ++i) ++order_counts[originOf(i) + 1];
  for (size_t b = 1; b < order_counts.size(); ++b) order_counts[b] += order_counts[b - 1];
  pair_order.resize(count);
  for (int i = 0; i < count; ++i) pair_order[order_counts[originOf(i)]++] = i;
}

void World::Impl::collide(double dt) {
  PhaseClock clock(profiling);
  const int n = int(shapes.size());
  aabbs.resize(n);
  aabb_kept.resize(n, 0);
  shape_frames.resize(n);
  if (shape_lists_dirty || int(is_static_shape.size()) != n) rebuildShapeLists();
  const bool carry = tuning.carry_sleeping_pairs && !pairs_dirty;
  const double spec = def.solver.speculative_distance;
  // Boxes of the dynamic bodies' shapes (shape_boxes.cpp).
  const int moving = int(moving_shapes.size());
  movingBoxes(dt, carry);
  // Static boxes and their tree only after a static shape was added, removed or moved.
  const bool static_rebuilt = static_dirty;
  if (static_dirty) {
    for (int s : static_shapes) {
      aabb_kept[s] = 1;
      computeBox(s, dt);
    }
    static_boxes_computed += int64_t(static_shapes.size());
    static_tree.build(static_shapes, aabbs);
    static_dirty = false;
  }
  clock.lap(profile.boxes);
  // The few planes (their frames every step).
  planes.swap(last_planes);
  planes.clear();
  for (int s : plane_shapes) {
    const Transform& f = shape_frames[s] = shapeFrame(s);
    const Vec3 nw = f.q * shapeDef(s).geometry.normal;
    const Vec3 p = motions[shapes[s].body].x + f.p;  // world
    planes.push_back({s, nw, shapeDef(s).geometry.offset + nw.dot(p)});
    const size_t k = planes.size() - 1;  // frozen: the same plane as in the last step
    const PlaneProxy* last = k < last_planes.size() ? &last_planes[k] : nullptr;
    frozen[s] = carry && last && last->shape == s && last->normal == nw &&
                last->offset == planes.back().offset;
  }
  // Keep pairs between different bodies, at least one dynamic, not disabled (checked inside
  // the broadphase); sort by key to merge with last step's contacts (also sorted by key). The
  // keys are sorted, not the contacts (a Contact is ~400 bytes).
  // A pair of two frozen shapes (boxes and planes as in the last step, which sleeping bodies
  // and static ones keep) overlaps now iff it did then, and the filter has not changed since
  // (pairs_dirty): such pairs are carried over from the last step's keys instead of found and
  // filtered again. With few frozen shapes among the dynamic ones and the planes (every
  // ragdoll awake) the broadphase's frozen test costs more than it saves: then nothing is
  // carried. Static shapes are frozen unless their tree was rebuilt in this step.
  int frozen_count = 0;
  for (int s : moving_shapes) frozen_count += frozen[s];
  for (int s : plane_shapes) frozen_count += frozen[s];
  const bool carry_now = carry && 4 * frozen_count >= moving + int(plane_shapes.size());
  if (carry && !carry_now) {
    for (int s : moving_shapes) frozen[s] = 0;
    for (int s : plane_shapes) frozen[s] = 0;
  }
  const bool static_frozen = carry_now && !static_rebuilt;
  const auto frozenNow = [&](int s) { return is_static_shape[s] ? static_frozen : frozen[s] != 0; };
  const auto accept = [this](int sa, int sb) {
    const int ba = shapes[sa].body, bb = shapes[sb].body;
    return ba != bb && (isDynamic(ba) || isDynamic(bb)) && !neverCollide(ba, bb);
  };
  if (pairs_dirty) broadphase.filterChanged();
  broadphase.findPairs(moving_shapes, aabbs, planes, spec, pairs, accept,
                       carry_now ? &frozen : nullptr, threadCount());
  // The static shapes: each dynamic shape's box queries their tree (a sleeping one only when
  // the tree changed: its other pairs are carried), and a plane of a dynamic body (rare) tests
  // them all, as the broadphase tests its planes.
  const auto addStatic = [&](std::vector<std::pair<int, int>>& out, int d, int s) {
    if (accept(d, s)) out.emplace_back(std::min(d, s), std::max(d, s));
  };
  if (!static_tree.empty()) {
    // in chunks of the shapes, joined in their order (a query costs about kStaticQueryWork box
    // tests)
    constexpr long kStaticQueryWork = 8;
    const bool split = long(moving) * kStaticQueryWork >= Broadphase::kParallelWork;
    collectInChunks(moving, collectChunk(moving), threadCount(), split, static_pair_chunks, pairs,
                    [&](int begin, int end, std::vector<std::pair<int, int>>& out) {
                      for (int k = begin; k < end; ++k) {
                        const int d = moving_shapes[k];
                        if (static_frozen && frozen[d]) continue;
                        static_tree.query(aabbs[d], [&](int s) { addStatic(out, d, s); });
                      }
                    });
  }
  for (const PlaneProxy& p : planes) {
    if (!isDynamic(shapes[p.shape].body)) continue;
    for (int s : static_shapes) {
      if (frozenNow(p.shape) && frozenNow(s)) continue;
      const Aabb& b = aabbs[s];
      const Vec3 c = 0.5 * (b.lo + b.hi), e = 0.5 * (b.hi - b.lo);
      if (p.normal.dot(c) - p.normal.cwiseAbs().dot(e) <= p.offset + spec)
        addStatic(pairs, p.shape, s);
    }
  }
  pairs_dirty = false;
  pair_keys.clear();
  for (const auto& [sa, sb] : pairs) pair_keys.push_back(pairKey(sa, sb));
  sortPairKeys(pair_keys, n, merged_keys, sort_offsets, sort_cursor);  // scratch: merged_keys
  carried_keys.clear();
  if (carry_now)
    for (const uint64_t key : contact_keys)
      if (frozenNow(int(key >> 32)) && frozenNow(int(uint32_t(key)))) carried_keys.push_back(key);
  if (!carried_keys.empty()) {
    merged_keys.resize(pair_keys.size() + carried_keys.size());
    std::merge(pair_keys.begin(), pair_keys.end(), carried_keys.begin(), carried_keys.end(),
               merged_keys.begin());
    pair_keys.swap(merged_keys);
  }
  // When the pairs are last step's (a scene at rest), each contact is updated where it is
  // instead of being copied (~400 bytes) into a new array; otherwise the pairs go to new arrays
  // and are merged with last step's contacts (both sorted by key).
  const bool in_place = pair_keys == contact_keys;
  const int count = int(pair_keys.size());
  if (!in_place) {
    // Sized only: every contact is set in the parallel loop below.
    next_contacts.resize(pair_keys.size());
    next_manifold_caches.resize(pair_keys.size());
    old_contact.assign(pair_keys.size(), -1);
    size_t old = 0;
    const size_t old_count = contact_keys.size();  // contacts[k].key: 8 bytes apart, not ~400
    for (size_t i = 0; i < pair_keys.size(); ++i) {
      while (old < old_count && contact_keys[old] < pair_keys[i]) ++old;
      if (old < old_count && contact_keys[old] == pair_keys[i]) old_contact[i] = int(old);
    }
  }
  clock.lap(profile.pairs);
  // Manifold cache (manifold_cache.hpp): a feature a kept manifold lacks is at least
  // (speculative - cache distance) away, so both bodies must move less than that in the step,
  // (|v| + extent |w|) dt, for it not to be reached unseen. (Separated pairs need no such
  // check: the collision at the step start decides the step's contacts.)
  const double cache_distance = tuning.manifold_cache_distance;
  const bool cache_on = cache_distance > 0.0 && cache_distance < spec;
  const double cache_speed = (spec - cache_distance) / dt;
  const auto slow = [&](int b) {
    const BodyMotion& m = motions[b];
    return m.v.norm() + m.extent * m.w.norm() <= cache_speed;
  };
  // The narrowphase on each pair independently (in parallel; each writes only its own
  // contact). c may be the old contact itself (in_place): it is read before it is reset.
  const auto collidePair = [&](int i) {
    const int o = in_place ? i : old_contact[i];
    Contact& c = in_place ? contacts[i] : next_contacts[i];
    ManifoldCache& cache = in_place ? manifold_caches[i] : next_manifold_caches[i];
    const auto keep = [&] {  // the old contact and cache, as they were
      if (in_place) return;
      c = contacts[o];
      cache = manifold_caches[o];
    };
    const int sa = int(pair_keys[i] >> 32), sb = int(uint32_t(pair_keys[i]));
    const int ba = shapes[sa].body, bb = shapes[sb].body;
    const bool asleep = !motions[ba].awake && !motions[bb].awake;
    if (o >= 0 && asleep) {  // the manifold and impulses stay as they were
      keep();
      return;
    }
    // The pair is collided in a frame at the centre of its (first) dynamic body: the
    // manifold's points are relative to it (Contact::origin).
    const Vec3 origin = motions[pairOrigin(ba, bb)].x;
    const Transform xa = shapePoseFrom(sa, origin), xb = shapePoseFrom(sb, origin);
    // Kept (manifold_cache.hpp): a separated pair still beyond the band, or a touching pair
    // whose manifold moves along with the shapes (ids and impulses stay).
    if (o >= 0 && manifold_caches[o].valid &&
        (manifold_caches[o].separated() || (slow(ba) && slow(bb))) &&
        manifold_caches[o].holds(xa, xb, cache_distance)) {
      keep();
      if (!cache.separated()) {
        c.origin = origin;
        cache.apply(shapeDef(sa).geometry, xa, shapeDef(sb).geometry, xb, c.manifold);
        c.sep_axis = c.manifold.normal;
      }
      return;
    }
    // What the new contact carries over from the old one (copied first when they are one).
    Contact saved;
    const Contact* last = &saved;
    if (o >= 0 && in_place) saved = c;
    else if (o >= 0) last = &contacts[o];
    c = Contact();
    c.key = pair_keys[i];
    c.shape_a = sa;
    c.shape_b = sb;
    c.body_a = ba;
    c.body_b = bb;
    c.origin = origin;
    cache.valid = false;
    if (asleep) return;
    const ShapeDef &da = shapeDef(sa), &db = shapeDef(sb);
    if (last->sep_valid) {
      const np::ConvexCore ca{&da.geometry, xa}, cb{&db.geometry, xb};
      const Vec3& n = last->sep_axis;
      const double gap = n.dot(cb.support(-n)) - cb.radius() - n.dot(ca.support(n)) - ca.radius();
      if (gap > spec) {
        c.sep_axis = n;
        c.sep_valid = true;
        c.manifold.count = 0;
        // The axis's gap bounds the distance too: the cache keeps the pair while its motion
        // stays within the clearance, a relative pose instead of two support points per step.
        c.manifold.gap = gap;
        cache.store(c.manifold, da.geometry, xa, db.geometry, xb, spec, cache_on);
        return;
      }
    }
    // Last step's normal of the pair (kept as sep_axis) starts GJK near its answer.
    const Vec3* guess = o >= 0 ? &last->sep_axis : nullptr;
    ragdoll_sim::collide(da.geometry, xa, db.geometry, xb, spec, c.manifold, guess);
    cache.store(c.manifold, da.geometry, xa, db.geometry, xb, spec, cache_on);
    // Cache the normal of a separated pair as its axis (not for planes: they are cheap).
    c.sep_valid = c.manifold.count == 0 && !unbounded[sa] && !unbounded[sb];
    c.sep_axis = c.manifold.normal;
    applyPairMaterial(c, da, db);
    matchImpulses(*last, c);
  };
  // One thread takes the pairs in key order (the order only places them on the threads).
  const bool ordered = splitOverThreads(count, threadCount());
  if (!in_place) pair_order.clear();
  if (ordered && int(pair_order.size()) != count) orderPairs(count);
  // The island schedule is built from which contacts touch (scheduleIslands).
  std::atomic<bool> touching_changed{false};
  parallelFor(count, threadCount(), [&](int k) {
    const int i = ordered ? pair_order[k] : k;
    const bool touched = in_place && contacts[i].manifold.count > 0;
    collidePair(i);
    if (in_place && (contacts[i].manifold.count > 0) != touched)
      touching_changed.store(true, std::memory_order_relaxed);
  });
  clock.lap(profile.narrowphase);
  if (!in_place || touching_changed.load(std::memory_order_relaxed)) schedule_fresh = false;
  if (in_place) return;
  manifold_caches.swap(next_manifold_caches);
  contacts.swap(next_contacts);
  contact_keys.swap(pair_keys);
}

}  // namespace ragdoll_sim
