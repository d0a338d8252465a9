// First pass over the URDF text (tinyxml2), before urdfdom sees it: one clear error naming the
// element for malformed files (urdfdom's own messages are vague or come in bunches), and the
// extensions urdfdom drops or rejects, rewritten into what it accepts and remembered here.
#pragma once

#include <array>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "ragdoll_sim/ragdoll.hpp"

namespace ragdoll_sim {
namespace urdf_xml {

struct Extras {
  std::string text;  // the document for urdfdom
  // <capsule radius length> (a common extension: a cylinder of `length` with hemispherical
  // caps, axis z) is handed to urdfdom as a <cylinder>; link -> ordinals of those elements
  // among the link's <collision> / <visual> elements.
  std::map<std::string, std::set<int>> capsule_collisions, capsule_visuals;
  std::set<std::string> spherical_joints;  // type="spherical", handed over as "floating"
  // A spherical joint's <limit cone_y cone_z twist_lower twist_upper/> (anatomy_xml.hpp).
  std::map<std::string, SwingTwistLimits> spherical_limits;
  std::map<std::string, double> link_damping_factor;  // <gazebo reference=L><dampingFactor>
  std::set<std::string> preserved_fixed;   // <gazebo reference=J><preserveFixedJoint>true
  std::map<std::string, double> link_friction;  // <gazebo reference=L> mean of mu1 / mu2
  // <gazebo reference=L><ragdoll_sim:material>, else its Gazebo <material> script name as
  // written ("Gazebo/Wood"): a material table name (LinkDef::material).
  std::map<std::string, std::string> link_material;
  // The rgba of L's first <visual><material> with a colour (its own <color> or a named
  // robot-level <material>).
  std::map<std::string, std::array<double, 4>> link_color;
  std::vector<std::string> notes;
};

// Returns "" on success, else one error naming the element: empty input, not XML, a root other
// than <robot>, links / joints without or with duplicate names, a joint without <parent> /
// <child> or naming an undefined link, a link with two parents, a cycle, several roots, a
// non-numeric or non-finite <origin>. Also gives an empty joint <dynamics/> damping="0" (URDF's
// default, which urdfdom rejects) and notes <dynamics> attributes that are not used.
std::string preprocess(const std::string& xml, Extras* out);

}  // namespace urdf_xml
}  // namespace ragdoll_sim
