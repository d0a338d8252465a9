// A box or a convex hull seen as a polytope in its local frame (vertices, faces with outward
// normals and counter-clockwise vertex loops, edges with their two faces) without copying:
// box data come from index tables, hull data from HullData.
#pragma once

#include "ragdoll_sim/shape.hpp"

namespace ragdoll_sim {
namespace np {

struct Poly {
  // Box vertex i has coordinate k positive iff bit k of i is set; face f lies on axis f / 2,
  // on the positive side iff f is even.
  static constexpr int kBoxFaces[6][4] = {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3},
                                          {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}};
  const HullData* hull;  // null for a box
  Vec3 he;

  explicit Poly(const Geometry& g)
      : hull(g.type == ShapeType::ConvexHull ? g.hull.get() : nullptr), he(g.half_extents) {}

  int numVerts() const { return hull ? int(hull->vertices.size()) : 8; }
  Vec3 vertex(int i) const {
    if (hull) return hull->vertices[i];
    return {i & 1 ? he.x() : -he.x(), i & 2 ? he.y() : -he.y(), i & 4 ? he.z() : -he.z()};
  }
  int numFaces() const { return hull ? int(hull->faces.size()) : 6; }
  Vec3 normal(int f) const {
    return hull ? hull->faces[f].normal : Vec3((f & 1 ? -1.0 : 1.0) * Vec3::Unit(f / 2));
  }
  double offset(int f) const { return hull ? hull->faces[f].offset : he[f / 2]; }
  int faceSize(int f) const { return hull ? int(hull->faces[f].verts.size()) : 4; }
  int faceVert(int f, int k) const { return hull ? hull->faces[f].verts[k] : kBoxFaces[f][k]; }
  int numEdges() const { return hull ? int(hull->edges.size()) : 12; }
  // Box edge e runs along axis e / 4 with the other two coordinates' signs in bits 0 and 1.
  void edge(int e, int& v0, int& v1, int& f0, int& f1) const {
    if (hull) {
      v0 = hull->edges[e].first, v1 = hull->edges[e].second;
      f0 = hull->edge_faces[e].first, f1 = hull->edge_faces[e].second;
      return;
    }
    const int i = e / 4, j = (i + 1) % 3, k = (i + 2) % 3;
    const bool sj = e & 1, sk = e & 2;
    v0 = (sj ? 1 << j : 0) | (sk ? 1 << k : 0);
    v1 = v0 | 1 << i;
    f0 = 2 * j + (sj ? 0 : 1);
    f1 = 2 * k + (sk ? 0 : 1);
  }
  Vec3 centroid() const { return hull ? hull->centroid : Vec3(Vec3::Zero()); }
  // Index of a vertex farthest along d.
  int support(const Vec3& d) const {
    if (!hull) return (d.x() > 0 ? 1 : 0) | (d.y() > 0 ? 2 : 0) | (d.z() > 0 ? 4 : 0);
    int best = 0;
    double bd = d.dot(hull->vertices[0]);
    for (int i = 1; i < int(hull->vertices.size()); ++i) {
      const double v = d.dot(hull->vertices[i]);
      if (v > bd) bd = v, best = i;
    }
    return best;
  }
  // Face whose normal is most aligned with d.
  int bestFace(const Vec3& d) const {
    int best = 0;
    double bd = -2;
    for (int f = 0; f < numFaces(); ++f) {
      const double v = d.dot(normal(f));
      if (v > bd) bd = v, best = f;
    }
    return best;
  }
};

}  // namespace np
}  // namespace ragdoll_sim
