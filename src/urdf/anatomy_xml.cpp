#include "anatomy_xml.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "ragdoll_sim/ragdoll.hpp"

namespace ragdoll_sim {
namespace urdf_xml {

namespace {

std::string quote(const std::string& s) { return "'" + s + "'"; }

// A finite number and nothing else (surrounding blanks allowed).
bool number(const char* text, double* v) {
  if (!text) return false;
  char* end = nullptr;
  *v = std::strtod(text, &end);
  while (end && (*end == ' ' || *end == '\t' || *end == '\r' || *end == '\n')) ++end;
  return end != text && end && *end == '\0' && std::isfinite(*v);
}

}  // namespace

std::string readSphericalLimit(tinyxml2::XMLElement* joint, const std::string& name, Extras* out) {
  tinyxml2::XMLElement* limit = joint->FirstChildElement("limit");
  if (!limit) return "";
  const std::string where = "joint " + quote(name) + ": <limit> ";
  SwingTwistLimits l;
  double* fields[4] = {&l.cone_1, &l.cone_2, &l.twist_lower, &l.twist_upper};
  const char* names[4] = {"cone_y", "cone_z", "twist_lower", "twist_upper"};
  bool any = false;
  for (const tinyxml2::XMLAttribute* a = limit->FirstAttribute(); a; a = a->Next()) {
    const std::string an = a->Name();
    int k = 0;
    while (k < 4 && an != names[k]) ++k;
    if (k == 4) {
      out->notes.push_back(where + "attribute " + quote(an) +
                           " ignored (a spherical joint takes cone_y, cone_z, twist_lower, "
                           "twist_upper)");
      continue;
    }
    if (!number(a->Value(), fields[k]))
      return where + an + " must be a number (rad), got " + quote(a->Value());
    any = true;
  }
  const std::string e = swingTwistLimitsError(l, {names[0], names[1], names[2], names[3]});
  if (!e.empty()) return where + e;
  if (any) out->spherical_limits[name] = l;
  joint->DeleteChild(limit);
  return "";
}

void readDampingFactor(const tinyxml2::XMLElement* gazebo, const std::string& link, Extras* out) {
  const tinyxml2::XMLElement* e = gazebo->FirstChildElement("dampingFactor");
  if (!e) return;
  double d;
  if (number(e->GetText(), &d) && d >= 0.0 && d < 1.0) {
    out->link_damping_factor[link] = d;
    return;
  }
  out->notes.push_back("<gazebo reference=" + quote(link) +
                       "> <dampingFactor> is not a number in [0, 1); ignored");
}

}  // namespace urdf_xml
}  // namespace ragdoll_sim
