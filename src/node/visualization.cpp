#include "visualization.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "msg_convert.hpp"

namespace ragdoll_sim {
namespace node {

using scene::RagdollView;

namespace {

using visualization_msgs::Marker;

// HSV (h in degrees, s and v in [0, 1]) to RGB.
Rgba hsv(double h, double s, double v) {
  h = std::fmod(std::fmod(h, 360.0) + 360.0, 360.0) / 60.0;
  const double c = v * s, x = c * (1.0 - std::abs(std::fmod(h, 2.0) - 1.0)), m = v - c;
  double r = 0, g = 0, b = 0;
  switch (static_cast<int>(h)) {
    case 0: r = c, g = x; break;
    case 1: r = x, g = c; break;
    case 2: g = c, b = x; break;
    case 3: g = x, b = c; break;
    case 4: r = x, b = c; break;
    default: r = c, b = x; break;
  }
  return {float(r + m), float(g + m), float(b + m), 1.0f};
}

const char* kArrowNs = "arrows";
const char* kContactNs = "contacts";

}  // namespace

Rgba ragdollColor(size_t i) {
  // Hues 29, 219, 126, 265, 327, 175 degrees: far from each other, from the red impulse and
  // yellow force arrows, the white contacts and the grey ground.
  static const Rgba kPalette[] = {{0.95f, 0.55f, 0.15f, 1.0f}, {0.25f, 0.50f, 0.95f, 1.0f},
                                  {0.30f, 0.80f, 0.35f, 1.0f}, {0.62f, 0.40f, 0.92f, 1.0f},
                                  {0.95f, 0.40f, 0.70f, 1.0f}, {0.20f, 0.75f, 0.70f, 1.0f}};
  const size_t n = sizeof(kPalette) / sizeof(kPalette[0]);
  if (i < n) return kPalette[i];
  // Golden-angle steps spread any number of hues; saturation and value cycle through 3 levels
  // each so that hues that come close again differ in shade.
  const double k = static_cast<double>(i - n);
  return hsv(29.0 + 137.50776 * k, 0.9 - 0.2 * static_cast<double>((i / 3) % 3),
             0.95 - 0.15 * static_cast<double>(i % 3));
}

Rgba objectColor(const LinkDef& link, bool is_static) {
  // Neutral grey apart from the palette hues; static geometry at 60 % brightness.
  Rgba c{0.62f, 0.62f, 0.62f, 1.0f};
  if (link.has_color)
    c = {float(link.color[0]), float(link.color[1]), float(link.color[2]),
         float(link.color[3] > 0 ? link.color[3] : 1.0)};
  if (is_static) {
    c.r *= 0.6f;
    c.g *= 0.6f;
    c.b *= 0.6f;
  }
  return c;
}

Rgba impulseArrowColor() { return {1.0f, 0.15f, 0.15f, 1.0f}; }
Rgba forceArrowColor() { return {1.0f, 0.9f, 0.1f, 1.0f}; }
Rgba contactColor() { return {0.95f, 0.95f, 0.95f, 1.0f}; }

double arrowAlpha(double since_end, double fade) {
  if (since_end <= 0.0) return 1.0;
  if (!(fade > 0.0) || since_end >= fade) return 0.0;
  return 1.0 - since_end / fade;
}

Visualizer::Visualizer(const MarkerSettings& settings, const std::string& frame)
    : settings_(settings), frame_(frame) {}

Marker& Visualizer::addShapeMarker(const std::string& ns, int id, BodyId body,
                                   const Transform& local, int type, const Vec3& scale,
                                   const Rgba& color) {
  Marker m;
  m.header.frame_id = frame_;
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.action = Marker::ADD;
  m.scale.x = scale.x();
  m.scale.y = scale.y();
  m.scale.z = scale.z();
  m.color = toMsg(color);
  m.pose.orientation.w = 1.0;
  out_.markers.push_back(m);
  sources_.push_back({body, local});
  return out_.markers.back();
}

namespace {

// A plane as a thin 20 m x 20 m slab whose top face is the plane (planes are unbounded).
Transform planeSlab(const Geometry& g, double thickness) {
  const Vec3 n = g.normal.normalized();
  return Transform(n * (g.offset - 0.5 * thickness), Quat::FromTwoVectors(Vec3::UnitZ(), n));
}

constexpr double kSlabThickness = 0.02;  // m
constexpr double kSlabSize = 20.0;       // m

}  // namespace

void Visualizer::addBodyMarkers(const World& world, const std::string& ns, int* id, BodyId body,
                                const Rgba& c, bool planes) {
  if (!world.isValid(body)) return;
  for (const ShapeDef& s : world.bodyShapes(body)) {
    const Geometry& g = s.geometry;
    switch (g.type) {
      case ShapeType::Sphere:
        addShapeMarker(ns, (*id)++, body, s.local, Marker::SPHERE, Vec3::Constant(2 * g.radius), c);
        break;
      case ShapeType::Box:
        addShapeMarker(ns, (*id)++, body, s.local, Marker::CUBE, 2 * g.half_extents, c);
        break;
      case ShapeType::Cylinder:
        addShapeMarker(ns, (*id)++, body, s.local, Marker::CYLINDER,
                       Vec3(2 * g.radius, 2 * g.radius, 2 * g.half_height), c);
        break;
      case ShapeType::Capsule: {  // a cylinder and two spheres
        addShapeMarker(ns, (*id)++, body, s.local, Marker::CYLINDER,
                       Vec3(2 * g.radius, 2 * g.radius, 2 * g.half_height), c);
        for (double sign : {1.0, -1.0}) {
          const Transform cap =
              s.local * Transform(Vec3(0, 0, sign * g.half_height), Quat::Identity());
          addShapeMarker(ns, (*id)++, body, cap, Marker::SPHERE, Vec3::Constant(2 * g.radius), c);
        }
        break;
      }
      case ShapeType::ConvexHull: {
        if (!g.hull) break;
        Marker& m =
            addShapeMarker(ns, (*id)++, body, s.local, Marker::TRIANGLE_LIST, Vec3::Ones(), c);
        for (const HullData::Face& f : g.hull->faces)
          for (size_t k = 1; k + 1 < f.verts.size(); ++k)
            for (int v : {f.verts[0], f.verts[k], f.verts[k + 1]})
              m.points.push_back(toPoint(g.hull->vertices[static_cast<size_t>(v)]));
        break;
      }
      case ShapeType::Plane:
        if (!planes) break;
        addShapeMarker(ns, (*id)++, body, s.local * planeSlab(g, kSlabThickness), Marker::CUBE,
                       Vec3(kSlabSize, kSlabSize, kSlabThickness), c);
        break;
    }
  }
}

void Visualizer::setScene(const World& world, const std::vector<RagdollView>& ragdolls,
                          BodyId ground, const std::vector<ObjectView>& objects) {
  out_.markers.clear();
  sources_.clear();
  for (const Arrow& a : arrows_) deleted_.push_back(a.id);
  arrows_.clear();
  rebindInjuryTexts(ragdolls);

  for (size_t r = 0; r < ragdolls.size(); ++r) {
    if (!ragdolls[r].ragdoll) continue;
    int id = 0;
    // Planes on ragdoll links make no sense to draw; their other shapes are drawn.
    for (const BodyId body : ragdolls[r].ragdoll->bodies)
      addBodyMarkers(world, ragdolls[r].name, &id, body, ragdollColor(r), /*planes=*/false);
  }

  bool ground_drawn = false;  // a world's plane replacing the ground is drawn as its object
  for (const ObjectView& o : objects) {
    if (!o.def) continue;
    int id = 0;
    for (size_t i = 0; i < o.bodies.size() && i < o.def->links.size(); ++i) {
      addBodyMarkers(world, o.name, &id, o.bodies[i], objectColor(o.def->links[i], o.is_static),
                     /*planes=*/true);
      ground_drawn = ground_drawn || o.bodies[i] == ground;
    }
  }

  if (!ground_drawn && ground.valid() && world.isValid(ground)) {
    for (const ShapeDef& s : world.bodyShapes(ground)) {
      if (s.geometry.type != ShapeType::Plane) continue;
      addShapeMarker("ground", 0, ground, s.local * planeSlab(s.geometry, kSlabThickness),
                     Marker::CUBE, Vec3(kSlabSize, kSlabSize, kSlabThickness),
                     {0.55f, 0.55f, 0.55f, 0.6f});
      break;
    }
  }
}

Visualizer::Arrow* Visualizer::addArrow(const World& world, BodyId body, const Vec3& world_point,
                                        const Vec3& vector, bool impulse, double end) {
  if (!world.isValid(body) || !world_point.allFinite() || !vector.allFinite() ||
      vector.squaredNorm() == 0.0)
    return nullptr;
  Arrow a;
  a.id = next_arrow_id_;
  next_arrow_id_ = next_arrow_id_ == std::numeric_limits<int>::max() ? 0 : next_arrow_id_ + 1;
  a.impulse = impulse;
  a.body = body;
  a.local_point = world.bodyPose(body).applyInverse(world_point);
  a.vector = vector;
  a.end = end;
  arrows_.push_back(a);
  while (arrows_.size() > static_cast<size_t>(std::max(1, settings_.max_arrows))) {
    deleted_.push_back(arrows_.front().id);
    arrows_.pop_front();
  }
  // Without a subscriber update() never runs: keep only the newest pending DELETEs.
  const size_t max_deleted = 4 * static_cast<size_t>(std::max(1, settings_.max_arrows));
  if (deleted_.size() > max_deleted)
    deleted_.erase(deleted_.begin(), deleted_.end() - static_cast<long>(max_deleted));
  return &arrows_.back();
}

void Visualizer::addImpulse(const World& world, BodyId body, const Vec3& world_point,
                            const Vec3& impulse, double sim_time) {
  addArrow(world, body, world_point, impulse, true, sim_time);
}

void Visualizer::addForce(const World& world, BodyId body, const Vec3& world_point,
                          const Vec3& force, double sim_time, double duration) {
  const double end =
      duration < 0.0 ? std::numeric_limits<double>::infinity() : sim_time + duration;
  addArrow(world, body, world_point, force, false, end);
}

void Visualizer::endForces(double sim_time) {
  for (Arrow& a : arrows_)
    if (!a.impulse && a.pull < 0 && a.end > sim_time) a.end = sim_time;
}

void Visualizer::setPull(int key, const World& world, BodyId body, const Vec3& world_point,
                         const Vec3& force) {
  for (Arrow& a : arrows_) {
    if (a.pull != key) continue;
    if (!world.isValid(body) || !world_point.allFinite() || !force.allFinite()) return;
    a.body = body;
    a.local_point = world.bodyPose(body).applyInverse(world_point);
    a.vector = force;
    return;
  }
  if (force.squaredNorm() == 0.0) return;  // shown once it pulls
  if (Arrow* a = addArrow(world, body, world_point, force, false,
                          std::numeric_limits<double>::infinity()))
    a->pull = key;
}

void Visualizer::endPull(int key, double sim_time) {
  for (Arrow& a : arrows_) {
    if (a.pull != key) continue;
    a.pull = -1;
    a.end = sim_time;
  }
}

Marker& Visualizer::appendMarker(const std::string& ns, int id, const ros::Time& stamp) {
  out_.markers.emplace_back();
  Marker& m = out_.markers.back();
  m.header.frame_id = frame_;
  m.header.stamp = stamp;
  m.ns = ns;
  m.id = id;
  m.pose.orientation.w = 1.0;
  return m;
}

void Visualizer::appendContacts(const World& world, const ros::Time& stamp) {
  std::vector<ContactInfo> contacts = world.contacts();
  // Speculative contacts (apart and pushing nothing) are not touching yet.
  contacts.erase(std::remove_if(contacts.begin(), contacts.end(),
                                [](const ContactInfo& c) {
                                  return c.separation > 0.0 && c.normal_impulse <= 0.0;
                                }),
                 contacts.end());
  if (contacts.empty()) {
    if (contacts_shown_) {
      appendMarker(kContactNs, 0, stamp).action = Marker::DELETE;
      appendMarker(kContactNs, 1, stamp).action = Marker::DELETE;
      contacts_shown_ = false;
    }
    return;
  }
  Marker& points = appendMarker(kContactNs, 0, stamp);
  points.type = Marker::SPHERE_LIST;
  points.action = Marker::ADD;
  points.scale.x = points.scale.y = points.scale.z = 0.03;
  points.color = toMsg(contactColor());
  for (const ContactInfo& c : contacts) points.points.push_back(toPoint(c.point));
  Marker& normals = appendMarker(kContactNs, 1, stamp);
  normals.type = Marker::LINE_LIST;
  normals.action = Marker::ADD;
  normals.scale.x = 0.006;
  normals.color = toMsg(contactColor());
  for (const ContactInfo& c : contacts) {
    normals.points.push_back(toPoint(c.point));
    normals.points.push_back(toPoint(c.point + 0.1 * c.normal));
  }
  contacts_shown_ = true;
}

void Visualizer::appendArrows(const World& world, const ros::Time& stamp, double sim_time) {
  for (auto it = arrows_.begin(); it != arrows_.end();) {
    const double alpha = arrowAlpha(sim_time - it->end, settings_.arrow_fade);
    if (alpha <= 0.0 || !world.isValid(it->body)) {
      deleted_.push_back(it->id);
      it = arrows_.erase(it);
      continue;
    }
    if (it->vector.squaredNorm() == 0.0) {  // a pull at rest: nothing to point along
      ++it;
      continue;
    }
    const double scale = it->impulse ? settings_.impulse_scale : settings_.force_scale;
    const double length = std::clamp(it->vector.norm() * scale, 0.05, settings_.max_arrow);
    const Vec3 head = world.bodyPose(it->body).apply(it->local_point);
    const Vec3 tail = head - it->vector.normalized() * length;
    Marker& m = appendMarker(kArrowNs, it->id, stamp);
    m.type = Marker::ARROW;
    m.action = Marker::ADD;
    m.points.push_back(toPoint(tail));
    m.points.push_back(toPoint(head));
    m.scale.x = 0.02;  // shaft diameter
    m.scale.y = 0.045; // head diameter
    m.scale.z = 0.07;  // head length
    m.color = toMsg(it->impulse ? impulseArrowColor() : forceArrowColor(), alpha);
    ++it;
  }
  for (int id : deleted_) appendMarker(kArrowNs, id, stamp).action = Marker::DELETE;
  deleted_.clear();
}

const visualization_msgs::MarkerArray& Visualizer::update(const World& world,
                                                          const ros::Time& stamp,
                                                          double sim_time) {
  out_.markers.resize(sources_.size());  // drop last call's extras, keep the shapes
  for (size_t k = 0; k < sources_.size(); ++k) {
    Marker& m = out_.markers[k];
    m.header.stamp = stamp;
    toMsg(world.bodyPose(sources_[k].body) * sources_[k].local, &m.pose);
  }
  if (settings_.contacts) {
    appendContacts(world, stamp);
    appendContactForces(world, stamp);
  }
  appendArrows(world, stamp, sim_time);
  appendFlashes(stamp, sim_time);
  appendInjuryTexts(world, stamp);
  return out_;
}

std_msgs::ColorRGBA toMsg(const Rgba& c, double alpha_scale) {
  std_msgs::ColorRGBA m;
  m.r = c.r;
  m.g = c.g;
  m.b = c.b;
  m.a = static_cast<float>(c.a * alpha_scale);
  return m;
}

}  // namespace node
}  // namespace ragdoll_sim
