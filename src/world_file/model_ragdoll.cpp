// A loaded model's links and the joints between them as a RagdollDef, so that spawnRagdoll puts
// a dynamic model (one body or an articulated one) in a World where the world file has it.
#include "world_load.hpp"

namespace ragdoll_sim {

RagdollDef modelRagdollDef(const WorldModelDef& m) {
  RagdollDef d;
  d.name = m.name;
  d.root = 0;
  const Transform root_inv = m.links.empty() ? Transform() : m.links[0].pose.inverse();
  for (const WorldLinkDef& l : m.links) {
    LinkDef link;
    link.name = l.name;
    link.mass = l.mass;
    link.com = l.com;
    link.inertia = l.inertia;
    link.rest_pose = root_inv * l.pose;
    for (const WorldCollisionDef& c : l.collisions) {
      link.shapes.push_back(c.shape);
      link.shape_sources.push_back(c.source);
    }
    d.links.push_back(std::move(link));
  }
  for (const RagdollJointDef& j : m.joints) {
    if (j.parent < 0) {
      d.notes.push_back("joint " + world_load::quote(j.name) + " to the world pins link " +
                        world_load::quote(m.links.at(j.child).name) + "; not part of the RagdollDef");
      continue;
    }
    d.joints.push_back(j);
    d.no_collide.emplace_back(j.parent, j.child);
  }
  return d;
}

}  // namespace ragdoll_sim
