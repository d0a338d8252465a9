// Scene reports of the last step by name: which link or object a body is, the touching pairs
// with their bodies named, and impact events (scene_reports.hpp).
#include <algorithm>
#include <cstdint>

#include "scene_impl.hpp"

namespace ragdoll_sim {

using scene::RagdollInstance;
using scene::StaticObject;

namespace {

bool names(const std::vector<BodyId>& bodies, int link, BodyId body) {
  return link >= 0 && static_cast<size_t>(link) < bodies.size() &&
         bodies[static_cast<size_t>(link)] == body;
}

}  // namespace

BodyRef Scene::Impl::refOf(BodyId body) const {
  if (!world || !body.valid()) return BodyRef();
  const size_t i = static_cast<size_t>(body.index);
  if (!body_refs_stale && i < body_refs.size()) {
    const BodyRef& r = body_refs[i];
    // An owner's entry is checked against its ids, so a change the stale flag missed still
    // shows; an entry of no owner is trusted (ids are not reused within one World).
    if (r.ragdoll >= 0 && static_cast<size_t>(r.ragdoll) < ragdolls.size() &&
        names(ragdolls[static_cast<size_t>(r.ragdoll)].ragdoll.bodies, r.link, body))
      return r;
    if (r.static_object >= 0 && static_cast<size_t>(r.static_object) < statics.size() &&
        names(statics[static_cast<size_t>(r.static_object)].bodies, r.link, body))
      return r;
    if (r.ragdoll < 0 && r.static_object < 0) return r;
  }
  // Rebuilt over every slot of the World, so each id that exists now has its entry.
  body_refs.assign(static_cast<size_t>(std::max(world->bodyCount(), body.index + 1)), BodyRef());
  for (size_t k = 0; k < ragdolls.size(); ++k) {
    const std::vector<BodyId>& bodies = ragdolls[k].ragdoll.bodies;
    for (size_t l = 0; l < bodies.size(); ++l)
      if (bodies[l].valid() && static_cast<size_t>(bodies[l].index) < body_refs.size())
        body_refs[static_cast<size_t>(bodies[l].index)] = {int(k), -1, int(l)};
  }
  for (size_t s = 0; s < statics.size(); ++s) {
    const std::vector<BodyId>& bodies = statics[s].bodies;
    for (size_t l = 0; l < bodies.size(); ++l)
      if (bodies[l].valid() && static_cast<size_t>(bodies[l].index) < body_refs.size())
        body_refs[static_cast<size_t>(bodies[l].index)] = {-1, int(s), int(l)};
  }
  body_refs_stale = false;
  return body_refs[i];
}

BodyRef Scene::bodyRef(BodyId body) const { return impl_->refOf(body); }

std::string Scene::bodyName(const BodyRef& body) const { return impl_->nameOf(body); }

std::string Scene::Impl::nameOf(const BodyRef& body) const {
  const Impl& s = *this;
  auto linkName = [](const RagdollDef& def, int link) -> std::string {
    if (link < 0 || static_cast<size_t>(link) >= def.links.size()) return "";
    return def.links[static_cast<size_t>(link)].name;
  };
  if (body.ragdoll >= 0) {
    if (static_cast<size_t>(body.ragdoll) >= s.ragdolls.size()) return "";
    const RagdollInstance& r = s.ragdolls[static_cast<size_t>(body.ragdoll)];
    const std::string link = linkName(r.def, body.link);
    return link.empty() ? "" : r.name + "/" + link;
  }
  if (body.static_object >= 0) {
    if (static_cast<size_t>(body.static_object) >= s.statics.size()) return "";
    const StaticObject& o = s.statics[static_cast<size_t>(body.static_object)];
    const std::string link = linkName(o.def, body.link);
    return link.empty() ? "" : o.name + "/" + link;
  }
  return "ground";
}

void Scene::contacts(std::vector<SceneContact>& out) const {
  const Impl& s = *impl_;
  out.clear();
  if (!s.world) return;
  s.world->contactReports(s.contact_scratch);
  for (const ContactReport& c : s.contact_scratch) {
    out.emplace_back();
    out.back().a = s.refOf(c.body_a);
    out.back().b = s.refOf(c.body_b);
    out.back().report = c;
  }
}

// ------------------------------------------------------------------------------------------
// Impacts

// The rule: impacts turn impulse tracking on; turning them off turns it off again unless it
// was already on when they turned it on (someone else asked for it through world()).
void Scene::Impl::applyImpactTracking() {
  if (!world) return;
  if (def.impacts.enabled) {
    tracking_was_on = world->contactImpulseTracking();
    world->setContactImpulseTracking(true);
  } else if (!tracking_was_on) {
    world->setContactImpulseTracking(false);
  }
}

void Scene::setImpacts(const ImpactDef& def) {
  Impl& s = *impl_;
  const bool was = s.def.impacts.enabled;
  s.def.impacts = def;
  if (!def.enabled) s.impact_events.clear();
  if (was != def.enabled) s.applyImpactTracking();
}

const std::vector<ImpactEvent>& Scene::impacts() const { return impl_->impact_events; }

// Per (link, other body) pair: its shape pairs' points summed. When both bodies are links the
// event names the one with the lower BodyId (body_a of the World's reports, whose pairs follow
// creation order), so each touching pair of links gives one event.
void Scene::Impl::findImpacts() {
  if (!def.impacts.enabled) return;
  impact_events.clear();
  world->contactReports(contact_scratch);
  impact_keys.clear();
  for (size_t i = 0; i < contact_scratch.size(); ++i) {
    const ContactReport& c = contact_scratch[i];
    const bool a_link = refOf(c.body_a).ragdoll >= 0, b_link = refOf(c.body_b).ragdoll >= 0;
    if (!a_link && !b_link) continue;  // no link of a ragdoll or dynamic object
    const bool link_is_a = a_link && (!b_link || c.body_a.index < c.body_b.index);
    const BodyId link = link_is_a ? c.body_a : c.body_b, other = link_is_a ? c.body_b : c.body_a;
    const uint64_t key = (uint64_t(uint32_t(link.index)) << 32) | uint32_t(other.index);
    impact_keys.emplace_back(key, static_cast<int>(i));
  }
  std::sort(impact_keys.begin(), impact_keys.end());
  for (size_t first = 0; first < impact_keys.size();) {
    size_t end = first;
    while (end < impact_keys.size() && impact_keys[end].first == impact_keys[first].first) ++end;
    const BodyId link_body{int32_t(impact_keys[first].first >> 32)};
    const BodyId other_body{int32_t(impact_keys[first].first & 0xffffffffu)};
    ImpactEvent e;
    Vec3 weighted_point = Vec3::Zero(), plain_point = Vec3::Zero(), normal = Vec3::Zero();
    Vec3 first_normal = Vec3::UnitZ();
    int points = 0;
    for (size_t j = first; j < end; ++j) {
      const ContactReport& c = contact_scratch[static_cast<size_t>(impact_keys[j].second)];
      const Vec3 into_link = c.body_a == link_body ? Vec3(-c.normal) : c.normal;
      if (j == first) first_normal = into_link;
      for (int p = 0; p < c.count && p < static_cast<int>(c.points.size()); ++p) {
        const ContactPointReport& q = c.points[static_cast<size_t>(p)];
        e.impulse += q.step_impulse;
        // The pair's peak when its points peak in the same substep (a flat landing), else an
        // upper bound: the World keeps each point's peak, not their sum per substep.
        e.peak_force += q.peak_force;
        weighted_point += q.step_impulse * q.point;
        plain_point += q.point;
        normal += q.step_impulse * into_link;
        if (points == 0 || q.closing_speed > e.closing_speed) {
          e.closing_speed = q.closing_speed;
          e.separating_speed = q.separating_speed;
        }
        ++points;
      }
    }
    first = end;
    if (points == 0) continue;
    const ImpactDef& d = def.impacts;
    if (!(e.impulse >= d.min_impulse) && !(e.closing_speed >= d.min_speed)) continue;
    e.point = e.impulse > 0.0 ? Vec3(weighted_point / e.impulse) : Vec3(plain_point / points);
    e.normal = normal.norm() > 0.0 ? Vec3(normal.normalized()) : first_normal;
    const BodyRef link = refOf(link_body);
    const RagdollInstance& r = ragdolls[static_cast<size_t>(link.ragdoll)];
    e.ragdoll = r.name;
    e.link = r.def.links[static_cast<size_t>(link.link)].name;
    e.other = nameOf(refOf(other_body));
    e.time = simTime();
    impact_events.push_back(std::move(e));
  }
}

}  // namespace ragdoll_sim
