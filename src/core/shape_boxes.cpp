// The moving shapes' boxes and frames of the collide phase, by kind several at a time in double
// lanes (shape_boxes_kernel.hpp: the bits of computeBox, one at a time).
#include <algorithm>

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
// Jobs [0, n) of one kind: four at a time in AVX lanes where the CPU has AVX2, then two in SSE2
// lanes, the last one alone.
void runKind(int kind, const shape_boxes::ShapeBoxJob* jobs, int n, double spec, double dt) {
  using shape_boxes::shapeBoxes;
  using double_lanes::Double2;
  const int n4 = cpuHasAvx2() ? n / 4 * 4 : 0;
  const int n2 = n4 + (n - n4) / 2 * 2;
  if (n4 > 0) shape_boxes_w4::shapeBoxes(kind, jobs, n4, spec, dt);
  const auto rest = [&](auto lanes_tag, int begin, int count) {
    using D = decltype(lanes_tag);
    switch (kind) {
      case shape_boxes::kSphereBox:
        return shapeBoxes<shape_boxes::kSphereBox, D>(jobs + begin, count, spec, dt);
      case shape_boxes::kCapsuleBox:
        return shapeBoxes<shape_boxes::kCapsuleBox, D>(jobs + begin, count, spec, dt);
      case shape_boxes::kBoxBox:
        return shapeBoxes<shape_boxes::kBoxBox, D>(jobs + begin, count, spec, dt);
      default:
        return shapeBoxes<shape_boxes::kCylinderBox, D>(jobs + begin, count, spec, dt);
    }
  };
  if (n2 > n4) rest(Double2(), n4, n2 - n4);
  if (n > n2) rest(0.0, n2, n - n2);
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
