// Convex hull of a point set: incremental construction (O(n h), fine for a few hundred points).
// Start from a maximal tetrahedron; each point farther than a tolerance outside some triangle
// removes the triangles it sees and is joined to their horizon (keeping the winding, so the
// normals stay outward). Points within the tolerance of the hull are ignored, which makes
// coplanar and duplicate input harmless. Triangles on one supporting plane form exactly one
// convex face on a convex hull, so grouping by plane and walking the group's boundary (edges
// used once) gives the merged polygon, counter-clockwise seen from outside.
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>

#include "ragdoll_sim/shape.hpp"

namespace ragdoll_sim {

namespace {

struct Tri {
  int v[3];
  Vec3 n;
  double d;
  bool alive;
};

Tri makeTri(const std::vector<Vec3>& p, int a, int b, int c) {
  Vec3 n = (p[b] - p[a]).cross(p[c] - p[a]);
  const double len = n.norm();
  n = len > 0 ? Vec3(n / len) : Vec3::Zero();
  return {{a, b, c}, n, n.dot(p[a]), true};
}

int farthest(const std::vector<Vec3>& p, const std::function<double(const Vec3&)>& dist) {
  int best = 0;
  for (int i = 1; i < int(p.size()); ++i)
    if (dist(p[i]) > dist(p[best])) best = i;
  return best;
}

// Triangles of the hull of p, or empty if the points span less than 3 dimensions.
std::vector<Tri> hullTriangles(const std::vector<Vec3>& p, double eps) {
  const int i0 = farthest(p, [&](const Vec3& x) { return -x.x(); });
  const int i1 = farthest(p, [&](const Vec3& x) { return (x - p[i0]).squaredNorm(); });
  const Vec3 u = (p[i1] - p[i0]).normalized();
  const int i2 = farthest(p, [&](const Vec3& x) { return (x - p[i0]).cross(u).squaredNorm(); });
  const Vec3 n = (p[i1] - p[i0]).cross(p[i2] - p[i0]);
  if (n.norm() <= eps * (p[i1] - p[i0]).norm()) return {};
  const Vec3 nn = n.normalized();
  const int i3 = farthest(p, [&](const Vec3& x) { return std::abs(nn.dot(x - p[i0])); });
  if (std::abs(nn.dot(p[i3] - p[i0])) <= eps) return {};

  std::vector<Tri> tris;
  const int t[4] = {i0, i1, i2, i3};
  const int faces[4][3] = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {0, 2, 3}};
  for (const auto& f : faces) {
    Tri tri = makeTri(p, t[f[0]], t[f[1]], t[f[2]]);
    const int opp = t[6 - f[0] - f[1] - f[2]];
    if (tri.n.dot(p[opp]) > tri.d) tri = makeTri(p, t[f[0]], t[f[2]], t[f[1]]);
    tris.push_back(tri);
  }

  std::vector<std::pair<int, int>> horizon;
  for (int i = 0; i < int(p.size()); ++i) {
    horizon.clear();
    for (Tri& tri : tris) {
      if (!tri.alive || tri.n.dot(p[i]) - tri.d <= eps) continue;
      tri.alive = false;
      for (int k = 0; k < 3; ++k) {
        const std::pair<int, int> e{tri.v[k], tri.v[(k + 1) % 3]};
        auto rev = std::find(horizon.begin(), horizon.end(), std::make_pair(e.second, e.first));
        if (rev != horizon.end())
          horizon.erase(rev);
        else
          horizon.push_back(e);
      }
    }
    for (const auto& e : horizon) tris.push_back(makeTri(p, e.first, e.second, i));
    tris.erase(std::remove_if(tris.begin(), tris.end(), [](const Tri& t) { return !t.alive; }),
               tris.end());
  }
  return tris;
}

}  // namespace

std::shared_ptr<const HullData> HullData::build(const std::vector<Vec3>& points) {
  if (points.size() < 4) return nullptr;
  Vec3 lo = points[0], hi = points[0];
  for (const Vec3& x : points) {
    if (!x.allFinite()) return nullptr;
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  const double eps = 1e-9 * std::max((hi - lo).norm(), 1e-300);
  const std::vector<Tri> tris = hullTriangles(points, eps);
  if (tris.empty()) return nullptr;

  // Group triangles by supporting plane; each group's boundary loop is one face polygon.
  std::vector<int> group(tris.size(), -1);
  std::vector<std::vector<int>> loops;
  for (size_t t = 0; t < tris.size(); ++t) {
    if (group[t] >= 0 || tris[t].n.isZero()) continue;
    const int g = int(loops.size());
    std::map<int, int> next;  // boundary: directed edges whose reverse is not in the group
    for (size_t s = t; s < tris.size(); ++s) {
      if (group[s] >= 0 || tris[s].n.dot(tris[t].n) < 1.0 - 1e-10) continue;
      bool coplanar = true;
      for (int v : tris[s].v) coplanar &= std::abs(tris[t].n.dot(points[v]) - tris[t].d) <= 10 * eps;
      if (!coplanar) continue;
      group[s] = g;
      for (int k = 0; k < 3; ++k) {
        const int a = tris[s].v[k], b = tris[s].v[(k + 1) % 3];
        auto rev = next.find(b);
        if (rev != next.end() && rev->second == a)
          next.erase(rev);
        else
          next[a] = b;
      }
    }
    std::vector<int> loop{next.begin()->first};
    while (int(loop.size()) <= int(next.size())) {
      auto b = next.find(loop.back());
      if (b == next.end() || b->second == loop.front()) break;
      loop.push_back(b->second);
    }
    // Drop vertices lying on a straight run of the boundary.
    std::vector<int> clean;
    for (size_t k = 0; k < loop.size(); ++k) {
      const Vec3& a = points[loop[(k + loop.size() - 1) % loop.size()]];
      const Vec3& b = points[loop[k]];
      const Vec3& c = points[loop[(k + 1) % loop.size()]];
      if ((b - a).cross(c - b).norm() > eps * (c - a).norm()) clean.push_back(loop[k]);
    }
    if (clean.size() >= 3) loops.push_back(clean);
  }

  auto hull = std::make_shared<HullData>();
  std::map<int, int> remap;
  for (auto& loop : loops)
    for (int& v : loop) {
      auto it = remap.emplace(v, int(hull->vertices.size())).first;
      if (it->second == int(hull->vertices.size())) hull->vertices.push_back(points[v]);
      v = it->second;
    }
  for (const Vec3& v : hull->vertices) hull->centroid += v / double(hull->vertices.size());

  std::map<std::pair<int, int>, int> edge_index;
  for (const auto& loop : loops) {
    Face f;
    f.verts = loop;
    Vec3 n = Vec3::Zero(), c = Vec3::Zero();  // Newell normal (twice the area), centre
    for (size_t k = 0; k < loop.size(); ++k) {
      const Vec3& a = hull->vertices[loop[k]];
      n += a.cross(hull->vertices[loop[(k + 1) % loop.size()]]);
      c += a / double(loop.size());
    }
    f.normal = n.normalized();
    f.offset = f.normal.dot(c);
    const int fi = int(hull->faces.size());
    hull->faces.push_back(f);
    for (size_t k = 0; k < loop.size(); ++k) {
      const int a = loop[k], b = loop[(k + 1) % loop.size()];
      const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
      auto it = edge_index.find(key);
      if (it == edge_index.end()) {
        edge_index[key] = int(hull->edges.size());
        hull->edges.push_back(key);
        hull->edge_faces.push_back({fi, fi});
      } else {
        hull->edge_faces[it->second].second = fi;
      }
    }
  }
  return hull;
}

}  // namespace ragdoll_sim
