// URDF pre-pass readers of the anatomy extensions (urdf_xml.hpp's Extras): a spherical joint's
// <limit cone_y cone_z twist_lower twist_upper/> and a link's <gazebo><dampingFactor>.
#pragma once

#include <tinyxml2.h>

#include <string>

#include "urdf_xml.hpp"

namespace ragdoll_sim {
namespace urdf_xml {

// A spherical joint's <limit>: its swing-twist attributes into out->spherical_limits[name],
// then the element is removed (urdfdom would read it as a revolute limit). Returns "" or an
// error naming the joint and the attribute.
std::string readSphericalLimit(tinyxml2::XMLElement* joint, const std::string& name, Extras* out);

// <gazebo reference=link><dampingFactor>: into out->link_damping_factor, or a note when it is
// not a number in [0, 1).
void readDampingFactor(const tinyxml2::XMLElement* gazebo, const std::string& link, Extras* out);

}  // namespace urdf_xml
}  // namespace ragdoll_sim
