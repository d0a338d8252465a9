#include "rviz_settings.hpp"

#include <cmath>
#include <sstream>

namespace ragdoll_sim {
namespace scene {

namespace {

bool positive(double x) { return std::isfinite(x) && x > 0.0; }
bool nonNegative(double x) { return std::isfinite(x) && x >= 0.0; }

}  // namespace

std::string validateMarkerSettings(const MarkerSettings& s) {
  std::ostringstream e;
  if (!nonNegative(s.arrow_fade)) e << "parameter ~markers/arrow_fade must be >= 0 s, got " << s.arrow_fade;
  else if (!nonNegative(s.impulse_scale))
    e << "parameter ~markers/impulse_scale must be >= 0 m/(N*s), got " << s.impulse_scale;
  else if (!nonNegative(s.force_scale))
    e << "parameter ~markers/force_scale must be >= 0 m/N, got " << s.force_scale;
  else if (!(std::isfinite(s.max_arrow) && s.max_arrow >= 0.05))
    e << "parameter ~markers/max_arrow must be >= 0.05 m, got " << s.max_arrow;
  else if (s.max_arrows < 1)
    e << "parameter ~markers/max_arrows must be >= 1, got " << s.max_arrows;
  else if (!nonNegative(s.impact_flash))
    e << "parameter ~markers/impact_flash must be >= 0 s (0: no flashes), got " << s.impact_flash;
  return e.str();
}

std::string validatePokeSettings(const PokeSettings& s) {
  std::ostringstream e;
  if (!positive(s.impulse)) e << "parameter ~poke/impulse must be > 0 N*s, got " << s.impulse;
  else if (!positive(s.max_distance))
    e << "parameter ~poke/max_distance must be > 0 m, got " << s.max_distance;
  return e.str();
}

std::string validateDragSettings(const DragSettings& s) {
  std::ostringstream e;
  if (!nonNegative(s.stiffness)) e << "parameter ~drag/stiffness must be >= 0 N/m, got " << s.stiffness;
  else if (!nonNegative(s.damping))
    e << "parameter ~drag/damping must be >= 0 N*s/m, got " << s.damping;
  else if (!positive(s.max_force))
    e << "parameter ~drag/max_force must be > 0 N, got " << s.max_force;
  else if (!std::isfinite(s.handle_height))
    e << "parameter ~drag/handle_height must be finite, got " << s.handle_height;
  return e.str();
}

}  // namespace scene
}  // namespace ragdoll_sim
