// Meshes for the URDF loader: resolving a <mesh filename> to a file and reading its vertices
// (assimp: STL, DAE, OBJ and the rest it knows) for a convex hull.
#pragma once

#include <string>
#include <vector>

#include "ragdoll_sim/math.hpp"

namespace ragdoll_sim {
namespace mesh {

// The file a URDF mesh URI names, or "" with *why set:
//   package://pkg/rel  -> <dir of pkg>/rel, pkg found (rospack-free) as an ancestor of base_dir
//                         named pkg, or in package_paths (each a package or a tree of them:
//                         a folder holding a package.xml whose <name> is pkg, 4 levels deep)
//   file:///abs        -> /abs
//   /abs, rel          -> as is, rel relative to base_dir
std::string resolveUri(const std::string& uri, const std::string& base_dir,
                       const std::vector<std::string>& package_paths, std::string* why);

// ROS_PACKAGE_PATH split at ':' (empty entries dropped).
std::vector<std::string> packagePathFromEnv();

// Every vertex of every mesh in the file, node transforms applied, times `scale`.
// false with *error when assimp cannot read it or it holds no vertex. `volume`, when given,
// receives the volume its faces enclose (divergence theorem; meaningful for closed meshes).
bool readVertices(const std::string& path, const Vec3& scale, std::vector<Vec3>* out,
                  std::string* error, double* volume = nullptr);

// The farthest point in each of ~`directions` directions spread over the sphere (duplicates
// removed): their hull is the mesh's hull with few vertices, inside it and touching it in
// every one of those directions.
std::vector<Vec3> supportPoints(const std::vector<Vec3>& points, int directions);

}  // namespace mesh
}  // namespace ragdoll_sim
