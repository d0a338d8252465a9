// A loaded model's links and the joints between them as a RagdollDef, so that spawnRagdoll puts
// a dynamic model (one body or an articulated one) in a World where the world file has it.
#include "world_load.hpp"

namespace ragdoll_sim {
namespace {

using world_load::quote;

// A joint to the world pins the model's root link (a fixed base); RagdollDef has no joints to
// the world, so one on another link cannot be kept: rather than pin the wrong link, the model
// stays free and a warning says how to pin it.
void worldJoint(const WorldModelDef& m, const RagdollJointDef& j, RagdollDef* d) {
  const std::string jn = "joint " + quote(j.name), link = quote(m.links.at(j.child).name);
  if (j.child != 0) {
    d->warnings.push_back(jn + " to the world holds link " + link + ", not the model's root " +
                          quote(m.links[0].name) + ": left out, the model is free (a joint to "
                          "the world pins the model's first link only)");
    return;
  }
  if (d->fixed_base) {
    d->notes.push_back(jn + " to the world holds the pinned root " + link + " again");
    return;
  }
  d->fixed_base = true;
  d->notes.push_back(jn + " to the world pins link " + link + ", the model's root (a fixed base)");
  if (j.kind != RagdollJointKind::Fixed)
    d->warnings.push_back(jn + ": a " + jointKindName(j.kind) + " joint to the world holds as a fixed "
                          "one (the root link is pinned and does not move)");
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
  for (const RagdollJointDef& j : m.joints) {
    if (j.parent < 0) {
      worldJoint(m, j, &d);
      continue;
    }
    d.joints.push_back(j);
    d.no_collide.emplace_back(j.parent, j.child);
  }
  return d;
}

}  // namespace ragdoll_sim
