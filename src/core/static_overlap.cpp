// World::staticOverlap: how deep a set of bodies reaches into the static shapes (spawn checks).
#include <cmath>

#include "gjk.hpp"
#include "narrowphase.hpp"
#include "world_impl.hpp"

namespace ragdoll_sim {

namespace {

// Depth of shape g at pose x below the plane (normal n, offset off: n.x = off on it), 0 when
// it does not reach below: the core's support point along -n, less the core's radius.
double depthBelowPlane(const Geometry& g, const Transform& x, const Vec3& n, double off) {
  const np::ConvexCore core{&g, x};
  const Vec3 lowest = core.support(-n) - core.radius() * n;
  return std::max(0.0, off - n.dot(lowest));
}

}  // namespace

StaticOverlap World::staticOverlap(const std::vector<BodyId>& ids) const {
  const Impl& w = *impl_;
  for (BodyId id : ids) w.checkBody(id);
  StaticOverlap out;
  const int n = int(w.shapes.size());
  for (int s = 0; s < n; ++s) {  // the static shapes
    const ShapeRef& rs = w.shapes[s];
    if (!rs.alive || w.bodies[rs.body].def.type != BodyType::Static) continue;
    const Geometry& gs = w.shapeDef(s).geometry;
    const Transform fs = w.shapeFrame(s);
    const Transform xs(w.motions[rs.body].x + fs.p, fs.q);
    const Vec3 plane_n = xs.q * gs.normal;
    const double plane_off = gs.offset + plane_n.dot(xs.p);
    for (BodyId id : ids) {
      if (w.bodies[id.index].def.type == BodyType::Static) continue;
      const Body& b = w.bodies[id.index];
      for (size_t k = 0; k < b.shape_ids.size(); ++k) {
        const int t = b.shape_ids[k];
        if (!w.shapes[t].alive) continue;
        const Geometry& g = w.shapeDef(t).geometry;
        if (isUnbounded(g)) continue;
        const Transform ft = w.shapeFrame(t);
        const Transform xt(w.motions[id.index].x + ft.p, ft.q);
        double depth = 0.0;
        Vec3 dir = plane_n;
        if (isUnbounded(gs)) {  // exact: the lowest point of the shape
          depth = depthBelowPlane(g, xt, plane_n, plane_off);
        } else {  // the narrowphase's deepest point, along its normal (static to body)
          Manifold m;
          collide(gs, xs, g, xt, 0.0, m);
          for (int p = 0; p < m.count; ++p) depth = std::max(depth, -m.points[p].separation);
          dir = m.normal;
        }
        if (depth > out.depth) {
          out.depth = depth;
          out.direction = dir;
          out.body = id;
          out.shape = int(k);
          out.static_body = BodyId{rs.body};
        }
      }
    }
  }
  return out;
}

}  // namespace ragdoll_sim
