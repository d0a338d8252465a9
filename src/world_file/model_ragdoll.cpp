// A loaded model's links and the joints between them as a RagdollDef, so that spawnRagdoll puts
// a dynamic model (one body or an articulated one) in a World where the world file has it.
#include "world_load.hpp"

namespace ragdoll_sim {
namespace {

using world_load::quote;

// One fixed joint to the world makes its link the root, pinned (a fixed base). A RagdollDef
// has no joints to the world, so moving ones (a door's hinge) or several are left out with a
// note: Scene::loadWorld holds them by a static anchor link.
void worldJoints(const WorldModelDef& m, RagdollDef* d) {
  std::vector<const RagdollJointDef*> to_world;
  for (const RagdollJointDef& j : m.joints)
    if (j.parent < 0) to_world.push_back(&j);
  for (const RagdollJointDef* j : to_world) {
    const std::string jn = "joint " + quote(j->name), link = quote(m.links.at(j->child).name);
    if (to_world.size() == 1 && j->kind == RagdollJointKind::Fixed) {
      d->root = j->child;
      d->fixed_base = true;
      d->notes.push_back(jn + " to the world pins link " + link + ": the root, a fixed base "
                         "(spawn it at that link's pose)");
    } else {
      d->notes.push_back(jn + " to the world pins link " + link + " by a " + jointKindName(j->kind) +
                         " joint: not part of the RagdollDef (Scene::loadWorld holds it by a "
                         "static anchor)");
    }
  }
}

}  // namespace

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
    link.material = l.visual_material;
    link.has_color = l.has_color;
    link.color = l.color;
    bool own_materials = false;
    for (const WorldCollisionDef& c : l.collisions) {
      link.shapes.push_back(c.shape);
      link.shape_sources.push_back(c.source);
      // <mu>/<mu2> hold against a material table entry, as a URDF link's <gazebo> mu1/mu2 do.
      link.shape_friction.push_back(c.has_friction ? 0.5 * (c.mu + c.mu2) : -1.0);
      link.shape_materials.push_back(c.material);
      own_materials |= c.material != link.material;
    }
    if (!own_materials) link.shape_materials.clear();
    d.links.push_back(std::move(link));
  }
  worldJoints(m, &d);
  for (const RagdollJointDef& j : m.joints) {
    if (j.parent < 0) continue;
    d.joints.push_back(j);
    d.no_collide.emplace_back(j.parent, j.child);
  }
  return d;
}

}  // namespace ragdoll_sim
