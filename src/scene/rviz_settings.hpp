// Settings of the rviz side of the node (ROS-free; read by node_config.cpp): the markers
// (visualization.hpp), poking with the "Publish Point" tool and dragging with the interactive
// marker (interaction.hpp).
#pragma once

#include <cstddef>
#include <string>

namespace ragdoll_sim {
namespace scene {

// ~markers/*.
struct MarkerSettings {
  // Contact points (spheres), normals (lines) and the force of each touching pair (arrows of
  // force_scale, from the pair's centre along the force on its dynamic body).
  bool contacts = false;
  double arrow_fade = 1.0;       // s of sim time an arrow takes to fade once its push is over
  double impulse_scale = 0.02;   // m of arrow (and impact flash diameter) per N*s
  // m of arrow per N: applied forces (5 cm at least) and contact forces (0: none of those)
  double force_scale = 0.002;
  double max_arrow = 1.0;        // m, the longest arrow (the shortest is 5 cm)
  int max_arrows = 64;           // beyond this many the oldest arrows (and flashes) go first
  double impact_flash = 0.3;     // s of sim time an impact's sphere fades over; 0: none
};

// ~poke/*: a clicked point (/clicked_point) hits the nearest link.
struct PokeSettings {
  bool enabled = true;
  double impulse = 10.0;      // N*s, at the point towards the link's centre of mass
  double max_distance = 0.3;  // m, points farther than this from every link are refused
};

// ~drag/*: an interactive marker pulls one link with a spring-damper while it is dragged.
struct DragSettings {
  bool enabled = true;
  std::string link;           // "" = "torso" if the model has one, else the root link
  double stiffness = 1000.0;  // N/m
  double damping = 100.0;     // N*s/m, on the grabbed point's velocity
  double max_force = 2000.0;  // N, cap on |force| (~max_force caps it too)
  // m, the handle floats this far above the held point (world z) so that it is not hidden
  // inside the link; the spring pulls the point towards the handle minus this offset.
  double handle_height = 0.4;
};

// Range checks; "" when valid, else a message naming the parameter.
std::string validateMarkerSettings(const MarkerSettings& s);
std::string validatePokeSettings(const PokeSettings& s);
std::string validateDragSettings(const DragSettings& s);

}  // namespace scene
}  // namespace ragdoll_sim
