#include "link_damping.hpp"

#include <cmath>
#include <sstream>

namespace ragdoll_sim {
namespace scene {

std::string validateLinkDamping(const LinkDamping& d, const std::string& where) {
  const std::optional<double>* fields[2] = {&d.linear, &d.angular};
  const char* names[2] = {"linear", "angular"};
  for (int k = 0; k < 2; ++k) {
    if (!*fields[k] || (std::isfinite(**fields[k]) && **fields[k] >= 0.0)) continue;
    std::ostringstream os;
    os << where << "/" << names[k] << " must be a finite number >= 0 (1/s), got " << **fields[k];
    return os.str();
  }
  return "";
}

std::vector<std::string> applyLinkDamping(
    RagdollDef* def, const std::vector<std::pair<std::string, LinkDamping>>& entries) {
  auto apply = [](LinkDef& l, const LinkDamping& d) {
    if (d.linear) l.linear_damping = *d.linear;
    if (d.angular) l.angular_damping = *d.angular;
  };
  for (const auto& [name, d] : entries)
    if (name == "*")
      for (LinkDef& l : def->links) apply(l, d);
  std::vector<std::string> warnings;
  for (const auto& [name, d] : entries) {
    if (name == "*") continue;
    const int k = def->findLink(name);
    if (k < 0) warnings.push_back("~link_damping/" + name + " names no link of the ragdoll; ignored");
    else apply(def->links[static_cast<size_t>(k)], d);
  }
  return warnings;
}

}  // namespace scene
}  // namespace ragdoll_sim
