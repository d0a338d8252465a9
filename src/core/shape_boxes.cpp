// The moving shapes' boxes and frames of the collide phase, by kind several at a time in double
// lanes (shape_boxes_kernel.hpp: the bits of computeBox, one at a time).
#include <algorithm>
#include <cstddef>

#include "lane_width.hpp"
#include "parallel_for.hpp"
#include "shape_boxes_kernel.hpp"
#include "world_impl.hpp"

namespace ragdoll_sim {

static_assert(int(ShapeType::Sphere) == shape_boxes::kSphereBox &&
                  int(ShapeType::Capsule) == shape_boxes::kCapsuleBox &&
                  int(ShapeType::Box) == shape_boxes::kBoxBox &&
                  int(ShapeType::Cylinder) == shape_boxes::kCylinderBox,
              "a shape's type is its box kind");
static_assert(offsetof(Geometry, half_height) == offsetof(Geometry, radius) + sizeof(double),
              "a round shape's job reads its radius and half height as two doubles");

void World::Impl::computeBox(int s, double dt) {
  const BodyMotion& m = motions[shapes[s].body];
  const Transform& f = shape_frames[s] = shapeFrame(s);
  Aabb box = computeAabb(shapeDef(s).geometry, {m.x + f.p, f.q});
  const Vec3 grow = Vec3::Constant(def.solver.speculative_distance) + (m.v * dt).cwiseAbs();
  box.lo -= grow;
  box.hi += grow;
  aabbs[s] = box;
}

namespace {
// Jobs [0, n) of one kind by lane width (byLaneWidth).
void runKind(int kind, const shape_boxes::ShapeBoxJob* jobs, int n, double spec, double dt) {
  using shape_boxes::shapeBoxesOf;
  byLaneWidth(jobs, n, [&](int width, const shape_boxes::ShapeBoxJob* j, int count) {
    if (width == 4) shape_boxes_w4::shapeBoxes(kind, j, count, spec, dt);
    else shapeBoxesOf<double_lanes::Double2>(kind, j, count, spec, dt);
  });
}
}  // namespace

// A sleeping body's boxes stay (aabb_kept) and are frozen when pairs are carried; the others are
// computed, a chunk of shapes at a time, each chunk's shapes sorted into their kinds' jobs.
void World::Impl::movingBoxes(double dt, bool carry) {
  using shape_boxes::ShapeBoxJob;
  constexpr int kChunk = 64;
  const int moving = int(moving_shapes.size());
  const double spec = def.solver.speculative_distance;
  const auto chunk = [&](int c) {
    ShapeBoxJob jobs[shape_boxes::kBoxKinds][kChunk];
    int count[shape_boxes::kBoxKinds] = {};
    const int end = std::min(moving, (c + 1) * kChunk);
    for (int k = c * kChunk; k < end; ++k) {
      // The step's solve has pushed these lines out of the cache; the lanes wait on them alone.
      if (k + 8 < moving) {
        const ShapeRef& r = shapes[moving_shapes[k + 8]];
        const char* pm = reinterpret_cast<const char*>(&motions[r.body]);
        __builtin_prefetch(pm);
        __builtin_prefetch(pm + 64);
        __builtin_prefetch(pm + 128);
        __builtin_prefetch(&bodies[r.body]);
      }
      if (k + 4 < moving) {
        const ShapeDef& d = shapeDef(moving_shapes[k + 4]);
        __builtin_prefetch(&d);
        __builtin_prefetch(reinterpret_cast<const char*>(&d) + 64);
        __builtin_prefetch(reinterpret_cast<const char*>(&d) + 128);
      }
      const int s = moving_shapes[k];
      const BodyMotion& m = motions[shapes[s].body];
      frozen[s] = carry && !m.awake && aabb_kept[s];
      if (!m.awake && aabb_kept[s]) continue;
      aabb_kept[s] = !m.awake;
      const ShapeDef& d = shapeDef(s);
      const Geometry& g = d.geometry;
      if (g.type == ShapeType::ConvexHull) {
        computeBox(s, dt);
        continue;
      }
      const int kind = int(g.type);
      Transform& f = shape_frames[s];
      Aabb& box = aabbs[s];
      jobs[kind][count[kind]++] = {
          m.x.data(),       m.q.coeffs().data(), m.v.data(),        m.local_com.data(),
          d.local.p.data(), d.local.q.coeffs().data(),
          kind == shape_boxes::kBoxBox ? g.half_extents.data() : &g.radius,
          f.p.data(),       f.q.coeffs().data(), box.lo.data(),     box.hi.data()};
    }
    for (int kind = 0; kind < shape_boxes::kBoxKinds; ++kind)
      runKind(kind, jobs[kind], count[kind], spec, dt);
  };
  const int chunks = (moving + kChunk - 1) / kChunk;
  // A parallel region costs more than two chunks' boxes take on one thread (c, 120 shapes:
  // 2.7 us alone, 5 us on two).
  if (chunks >= 4 && threadCount() > 1) return parallelForSplit(chunks, threadCount(), chunk);
  for (int c = 0; c < chunks; ++c) chunk(c);
}

}  // namespace ragdoll_sim
