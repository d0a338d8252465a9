// ragdoll_check --world: a world file loaded without ROS, then a model dropped into it through a
// ROS-free Scene (the node's own layer) and measured as in the URDF mode (drop_check.hpp).
#pragma once

#include <optional>
#include <string>

#include "ragdoll_sim/drop_check.hpp"
#include "ragdoll_sim/math.hpp"

namespace ragdoll_sim {

struct WorldCheckArgs {
  std::string world;             // the world file; "": the default ground alone (--injury)
  std::string model;             // URDF to drop; "": the bundled ragdoll
  std::optional<Vec3> spawn;     // root link position; none: above the highest static point
  bool strict = false;           // unresolved <include>s are errors
  bool drop = true;              // false: the world line, notes and warnings only
  bool injury = false;           // print the head's injury reports of the drop (injury_check.hpp)
  DropSettings settings;
};

// Prints the summary line, notes, warnings and the drop metrics (without a world file: the
// drop metrics only) and, with `injury`, the injury reports; returns the exit code (0 ok, 1
// refused: world, model, materials or spawn, 3 the drop failed its verdict: judgeDrop against
// the world's ground plane).
int checkWorld(const WorldCheckArgs& args, const char* argv0);

// The drop's key=value metrics and its verdict, as the summary lines of both modes end.
std::string dropMetrics(const DropReport& rep, const DropVerdict& verdict);

// `relative` ("urdf/ragdoll.urdf") in this package: found through $ROS_PACKAGE_PATH, next to
// an installed ragdoll_check (<prefix>/lib/ragdoll_sim -> <prefix>/share/ragdoll_sim), else in
// the source tree it was built from; "" when none holds it.
std::string packageFile(const std::string& relative, const char* argv0);

}  // namespace ragdoll_sim
