// The Visualizer's markers of what the contacts did (visualization.hpp): the force of each
// touching pair as an arrow, a flash per impact event, and the head injury text of a fall.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "msg_convert.hpp"
#include "visualization.hpp"

namespace ragdoll_sim {
namespace node {

namespace {

using visualization_msgs::Marker;

const char* kContactForceNs = "contact_forces";
const char* kImpactNs = "impacts";
const char* kInjuryNs = "injury";

constexpr double kMinFlash = 0.05;        // m, the smallest flash diameter
constexpr double kTextAboveHead = 0.35;   // m over the head link's origin (world z)
constexpr double kTextHeight = 0.1;       // m, rviz text size
constexpr double kMinContactArrow = 1e-3; // m: shorter contact force arrows are left out

int nextId(int* id) {
  const int out = *id;
  *id = *id == std::numeric_limits<int>::max() ? 0 : *id + 1;
  return out;
}

}  // namespace

Rgba impactColor() { return {1.0f, 0.45f, 0.05f, 0.8f}; }

std::string injuryText(const InjuryReport& r) {
  char text[160];
  std::snprintf(text, sizeof text, "%s: peak %.1f g, HIC15 %.0f", r.ragdoll.c_str(), r.peak_g,
                r.hic15);
  return text;
}

void Visualizer::recordStep(const Scene& scene) {
  if (!scene.impacts().empty() && settings_.impact_flash > 0.0)
    for (const ImpactEvent& e : scene.impacts()) addImpact(e);
  if (scene.injuryReports().empty()) return;
  for (const InjuryReport& r : scene.injuryReports()) {
    const int k = r.ragdoll.empty() ? -1 : scene.find(r.ragdoll);
    if (k < 0) continue;  // removed with its ragdoll: nothing to hang it on
    const int link = scene.findLink(k, r.head_link);
    if (link < 0) continue;
    setInjury(r.ragdoll, link, scene.bodies(k).bodies.at(static_cast<size_t>(link)), r);
  }
}

void Visualizer::addImpact(const ImpactEvent& e) {
  if (!(settings_.impact_flash > 0.0) || !e.point.allFinite() || !std::isfinite(e.impulse) ||
      !std::isfinite(e.time))
    return;
  Flash f;
  f.id = nextId(&next_flash_id_);
  f.point = e.point;
  f.diameter = std::clamp(e.impulse * settings_.impulse_scale, kMinFlash,
                          std::max(kMinFlash, settings_.max_arrow));
  f.time = e.time;
  flashes_.push_back(f);
  const size_t cap = static_cast<size_t>(std::max(1, settings_.max_arrows));
  while (flashes_.size() > cap) {
    flashes_deleted_.push_back(flashes_.front().id);
    flashes_.pop_front();
  }
  // Without a subscriber update() never runs: keep only the newest pending DELETEs.
  if (flashes_deleted_.size() > 4 * cap)
    flashes_deleted_.erase(flashes_deleted_.begin(),
                           flashes_deleted_.end() - static_cast<long>(4 * cap));
}

void Visualizer::setInjury(const std::string& ragdoll, int link, BodyId head,
                           const InjuryReport& report) {
  for (InjuryMark& t : texts_)
    if (t.ragdoll == ragdoll) {
      t.link = link;
      t.head = head;
      t.text = injuryText(report);
      return;
    }
  texts_.push_back({ragdoll, link, head, injuryText(report), nextId(&next_text_id_)});
}

void Visualizer::rebindInjuryTexts(const std::vector<scene::RagdollView>& ragdolls) {
  for (auto it = texts_.begin(); it != texts_.end();) {
    const auto view = std::find_if(ragdolls.begin(), ragdolls.end(),
                                   [&](const scene::RagdollView& v) { return v.name == it->ragdoll; });
    if (view == ragdolls.end() || !view->ragdoll || it->link < 0 ||
        static_cast<size_t>(it->link) >= view->ragdoll->bodies.size()) {
      texts_deleted_.push_back(it->id);
      it = texts_.erase(it);
      continue;
    }
    it->head = view->ragdoll->bodies[static_cast<size_t>(it->link)];
    ++it;
  }
}

// One arrow per touching pair, from its force-weighted centre along the force on its dynamic
// body (on B unless B is static): the ground's push on a foot points up out of the ground.
void Visualizer::appendContactForces(const World& world, const ros::Time& stamp) {
  int shown = 0;
  if (settings_.force_scale > 0.0) {
    world.contactReports(reports_);
    for (const ContactReport& c : reports_) {
      const bool on_b = world.isValid(c.body_b) &&
                        world.bodyDef(c.body_b).type == BodyType::Dynamic;
      const Vec3 force = on_b ? c.force_b : c.force_a;
      Vec3 centre = Vec3::Zero();
      double weight = 0.0;
      for (int p = 0; p < c.count && p < static_cast<int>(c.points.size()); ++p) {
        const ContactPointReport& q = c.points[static_cast<size_t>(p)];
        centre += (q.normal_force + 1e-9) * q.point;
        weight += q.normal_force + 1e-9;
      }
      if (weight <= 0.0 || !force.allFinite()) continue;
      centre /= weight;
      const double length = std::min(force.norm() * settings_.force_scale, settings_.max_arrow);
      if (!(length >= kMinContactArrow) || !centre.allFinite()) continue;
      Marker& m = appendMarker(kContactForceNs, shown++, stamp);
      m.type = Marker::ARROW;
      m.action = Marker::ADD;
      m.points.push_back(toPoint(centre));
      m.points.push_back(toPoint(centre + force.normalized() * length));
      m.scale.x = 0.012;  // shaft diameter
      m.scale.y = 0.03;   // head diameter
      m.scale.z = 0.04;   // head length
      m.color = toMsg(contactColor());
    }
  }
  for (int id = shown; id < force_arrows_shown_; ++id)
    appendMarker(kContactForceNs, id, stamp).action = Marker::DELETE;
  force_arrows_shown_ = shown;
}

void Visualizer::appendFlashes(const ros::Time& stamp, double sim_time) {
  for (auto it = flashes_.begin(); it != flashes_.end();) {
    const double alpha = 1.0 - (sim_time - it->time) / settings_.impact_flash;
    if (!(alpha > 0.0)) {
      flashes_deleted_.push_back(it->id);
      it = flashes_.erase(it);
      continue;
    }
    Marker& m = appendMarker(kImpactNs, it->id, stamp);
    m.type = Marker::SPHERE;
    m.action = Marker::ADD;
    m.pose.position = toPoint(it->point);
    m.scale.x = m.scale.y = m.scale.z = it->diameter;
    m.color = toMsg(impactColor(), std::min(1.0, alpha));
    ++it;
  }
  for (int id : flashes_deleted_) appendMarker(kImpactNs, id, stamp).action = Marker::DELETE;
  flashes_deleted_.clear();
}

void Visualizer::appendInjuryTexts(const World& world, const ros::Time& stamp) {
  for (const InjuryMark& t : texts_) {
    if (!world.isValid(t.head)) continue;
    Marker& m = appendMarker(kInjuryNs, t.id, stamp);
    m.type = Marker::TEXT_VIEW_FACING;
    m.action = Marker::ADD;
    m.pose.position = toPoint(world.bodyPose(t.head).p + Vec3(0, 0, kTextAboveHead));
    m.scale.z = kTextHeight;
    m.color = toMsg(contactColor());
    m.text = t.text;
  }
  for (int id : texts_deleted_) appendMarker(kInjuryNs, id, stamp).action = Marker::DELETE;
  texts_deleted_.clear();
}

}  // namespace node
}  // namespace ragdoll_sim
