#include "interaction.hpp"

#include <cmath>
#include <sstream>

#include <visualization_msgs/InteractiveMarker.h>

#include "msg_convert.hpp"

namespace ragdoll_sim {
namespace node {

using scene::CommandCheck;
using scene::LinkPick;
using scene::LinkTable;
using scene::RagdollView;

namespace {

using visualization_msgs::InteractiveMarkerFeedback;

std::string fmt(const Vec3& v) {
  std::ostringstream s;
  s << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return s.str();
}

geometry_msgs::Pose poseAt(const Vec3& p) {
  geometry_msgs::Pose m;
  m.position.x = p.x();
  m.position.y = p.y();
  m.position.z = p.z();
  m.orientation.w = 1.0;
  return m;
}

bool isWorldFrame(const std::string& frame, const std::string& world) {
  return frame.empty() || frame == world || frame == "/" + world;
}

}  // namespace

Interaction::Interaction(const ros::NodeHandle& nh, const ros::NodeHandle& pnh,
                         const InteractionSettings& settings, Visualizer* visualizer)
    : nh_(nh), pnh_(pnh), settings_(settings), visualizer_(visualizer) {
  if (settings_.poke.enabled)
    clicked_sub_ = nh_.subscribe("clicked_point", 10, &Interaction::onClickedPoint, this);
  // No spin thread: feedback arrives on the global queue the node's loop spins, so callbacks
  // never run during a physics step.
  if (settings_.drag.enabled)
    server_ = std::make_unique<interactive_markers::InteractiveMarkerServer>(
        pnh_.resolveName("drag"), "", false);
}

Interaction::~Interaction() = default;

void Interaction::setScene(World* world, const std::vector<RagdollView>& ragdolls) {
  world_ = world;
  ragdolls_ = ragdolls;
  link_tables_.clear();
  for (const RagdollView& r : ragdolls_) link_tables_.push_back(r.def ? LinkTable(*r.def) : LinkTable());
  if (!server_) return;

  server_->clear();
  drags_.clear();
  menus_.clear();
  menu_links_.clear();
  for (size_t r = 0; r < ragdolls_.size(); ++r) {
    const RagdollView& view = ragdolls_[r];
    if (!view.def || !view.ragdoll) continue;
    Drag d;
    d.marker = view.name;
    d.ragdoll = static_cast<int>(r);
    const int fallback = scene::dragLink(*view.def, "");
    if (fallback < 0) continue;  // a model without links
    d.link = scene::dragLink(*view.def, settings_.drag.link);
    if (d.link < 0) {
      ROS_WARN("~drag/link '%s' is not a link of '%s'; dragging its '%s' instead",
               settings_.drag.link.c_str(), view.name.c_str(),
               view.def->links[static_cast<size_t>(fallback)].name.c_str());
      d.link = fallback;
    }
    drags_.push_back(d);

    // Context menu: "drag link" > every link of the model.
    auto menu = std::make_unique<interactive_markers::MenuHandler>();
    const auto parent = menu->insert("drag link");
    std::vector<interactive_markers::MenuHandler::EntryHandle> entries;
    for (const LinkDef& l : view.def->links)
      entries.push_back(menu->insert(parent, l.name,
                                     [this](const InteractiveMarkerFeedback::ConstPtr& fb) {
                                       onMenuLink(fb);
                                     }));
    menus_.push_back(std::move(menu));
    menu_links_.push_back(std::move(entries));
  }
  for (size_t k = 0; k < drags_.size(); ++k) {
    insertDragMarker(drags_[k]);
    menus_[k]->apply(*server_, drags_[k].marker);
  }
  server_->applyChanges();
}

void Interaction::insertDragMarker(const Drag& d) {
  const RagdollView& view = ragdolls_[static_cast<size_t>(d.ragdoll)];
  visualization_msgs::InteractiveMarker im;
  im.header.frame_id = settings_.world_frame;
  im.name = d.marker;
  im.description = "drag " + view.def->links[static_cast<size_t>(d.link)].name;
  im.scale = 0.3;
  im.pose = poseAt(handleAt(grabPoint(d)));

  // A pale, see-through ball: dragged in the view plane (MOVE_3D), right-click for the menu.
  visualization_msgs::Marker ball;
  ball.type = visualization_msgs::Marker::SPHERE;
  ball.scale.x = ball.scale.y = ball.scale.z = 0.12;
  ball.color.r = ball.color.g = ball.color.b = 0.92f;
  ball.color.a = 0.55f;
  ball.pose.orientation.w = 1.0;
  visualization_msgs::InteractiveMarkerControl control;
  control.name = "move";
  control.interaction_mode = visualization_msgs::InteractiveMarkerControl::MOVE_3D;
  control.always_visible = true;
  control.orientation.w = 1.0;
  control.markers.push_back(ball);
  im.controls.push_back(control);

  server_->insert(im, [this](const InteractiveMarkerFeedback::ConstPtr& fb) { onDragFeedback(fb); });
}

Interaction::Drag* Interaction::findDrag(const std::string& marker) {
  for (Drag& d : drags_)
    if (d.marker == marker) return &d;
  return nullptr;
}

Vec3 Interaction::handleAt(const Vec3& grab) const {
  return grab + Vec3(0.0, 0.0, settings_.drag.handle_height);
}

Vec3 Interaction::grabPoint(const Drag& d) const {
  return world_->comPosition(
      ragdolls_[static_cast<size_t>(d.ragdoll)].ragdoll->bodies[static_cast<size_t>(d.link)]);
}

bool Interaction::checkDrag(const Drag& d, const Vec3& target) {
  const RagdollView& view = ragdolls_[static_cast<size_t>(d.ragdoll)];
  const BodyId body = view.ragdoll->bodies[static_cast<size_t>(d.link)];
  const Vec3 p = grabPoint(d);
  ForceCommand cmd;
  cmd.link = view.def->links[static_cast<size_t>(d.link)].name;
  cmd.frame = "world";
  cmd.point = p;
  cmd.force = scene::dragForce(p, world_->pointVelocity(body, p), target, settings_.drag,
                               settings_.limits.max_force);
  const CommandCheck check =
      scene::checkForce(cmd, link_tables_[static_cast<size_t>(d.ragdoll)], settings_.limits,
                        [&](int link) { return world_->bodyPose(view.ragdoll->bodies[static_cast<size_t>(link)]); });
  if (!check.ok) {
    ROS_WARN_THROTTLE(1.0, "drag of '%s': %s; drag dropped", d.marker.c_str(), check.error.c_str());
    return false;
  }
  return true;
}

void Interaction::onDragFeedback(const visualization_msgs::InteractiveMarkerFeedbackConstPtr& fb) {
  Drag* d = findDrag(fb->marker_name);
  if (!d || !world_) return;
  switch (fb->event_type) {
    case InteractiveMarkerFeedback::MOUSE_DOWN:
    case InteractiveMarkerFeedback::POSE_UPDATE: {
      if (!isWorldFrame(fb->header.frame_id, settings_.world_frame)) {
        ROS_WARN_THROTTLE(1.0, "drag of '%s': pose in frame '%s', expected '%s'; drag dropped",
                          d->marker.c_str(), fb->header.frame_id.c_str(),
                          settings_.world_frame.c_str());
        release(d);
        return;
      }
      const Vec3 handle = toVec(fb->pose.position);
      if (!handle.allFinite()) {
        ROS_WARN_THROTTLE(1.0, "drag of '%s': handle position %s is not finite; drag dropped",
                          d->marker.c_str(), fmt(handle).c_str());
        release(d);
        return;
      }
      const Vec3 target = handle - handleAt(Vec3::Zero());
      if (!checkDrag(*d, target)) {
        release(d);
        return;
      }
      if (!d->active) {
        ++drags_started_;
        ROS_INFO("drag of '%s' link '%s' started at sim time %.3f s", d->marker.c_str(),
                 ragdolls_[static_cast<size_t>(d->ragdoll)].def->links[static_cast<size_t>(d->link)].name.c_str(),
                 sim_time_);
      }
      d->active = true;
      d->target = target;
      d->shown = handle;
      break;
    }
    case InteractiveMarkerFeedback::MOUSE_UP:
      if (d->active) ROS_INFO("drag of '%s' released at sim time %.3f s", d->marker.c_str(), sim_time_);
      release(d);
      break;
    default:
      break;
  }
}

void Interaction::release(Drag* d) {
  d->active = false;
  if (visualizer_) visualizer_->endPull(static_cast<int>(d - drags_.data()), sim_time_);
  // The server took the client's pose (maybe a rejected one): update() puts the handle back.
  d->shown = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
}

void Interaction::onMenuLink(const visualization_msgs::InteractiveMarkerFeedbackConstPtr& fb) {
  Drag* d = findDrag(fb->marker_name);
  if (!d) return;
  const size_t k = static_cast<size_t>(d - drags_.data());
  const auto& entries = menu_links_[k];
  for (size_t l = 0; l < entries.size(); ++l) {
    if (entries[l] != fb->menu_entry_id) continue;
    d->link = static_cast<int>(l);
    release(d);
    insertDragMarker(*d);  // new description and pose; the menu stays attached
    menus_[k]->reApply(*server_);
    server_->applyChanges();
    ROS_INFO("drag of '%s' now holds link '%s'", d->marker.c_str(),
             ragdolls_[static_cast<size_t>(d->ragdoll)].def->links[l].name.c_str());
    return;
  }
}

void Interaction::onClickedPoint(const geometry_msgs::PointStamped::ConstPtr& msg) {
  if (!world_) return;
  const Vec3 point(msg->point.x, msg->point.y, msg->point.z);
  if (!isWorldFrame(msg->header.frame_id, settings_.world_frame)) {
    ROS_WARN_THROTTLE(1.0, "clicked point in frame '%s', expected '%s' (the rviz fixed frame); "
                      "poke dropped", msg->header.frame_id.c_str(), settings_.world_frame.c_str());
    return;
  }
  if (!point.allFinite()) {
    ROS_WARN_THROTTLE(1.0, "clicked point %s is not finite; poke dropped", fmt(point).c_str());
    return;
  }
  const LinkPick pick =
      scene::pickNearestLink(*world_, ragdolls_, point, settings_.poke.max_distance);
  if (!pick.valid()) {
    ROS_WARN_THROTTLE(1.0, "clicked point %s is %.3f m from the nearest link, more than "
                      "~poke/max_distance = %.3f m; poke dropped", fmt(point).c_str(),
                      pick.distance, settings_.poke.max_distance);
    return;
  }
  const RagdollView& view = ragdolls_[static_cast<size_t>(pick.ragdoll)];
  const BodyId body = view.ragdoll->bodies[static_cast<size_t>(pick.link)];
  ImpulseCommand cmd;
  cmd.link = view.def->links[static_cast<size_t>(pick.link)].name;
  cmd.frame = "world";
  cmd.point = point;
  cmd.impulse = scene::pokeImpulse(point, world_->comPosition(body), settings_.poke.impulse);
  if (cmd.impulse.squaredNorm() == 0.0) {
    ROS_WARN_THROTTLE(1.0, "clicked point %s is the centre of mass of '%s': no direction to "
                      "push; poke dropped", fmt(point).c_str(), cmd.link.c_str());
    return;
  }
  const CommandCheck check =
      scene::checkImpulse(cmd, link_tables_[static_cast<size_t>(pick.ragdoll)], settings_.limits,
                          [&](int link) { return world_->bodyPose(view.ragdoll->bodies[static_cast<size_t>(link)]); });
  if (!check.ok) {
    ROS_WARN_THROTTLE(1.0, "poke: %s; poke dropped", check.error.c_str());
    return;
  }
  world_->applyLinearImpulse(body, cmd.impulse, point);
  ++pokes_;
  if (visualizer_) visualizer_->addImpulse(*world_, body, point, cmd.impulse, sim_time_);
  ROS_INFO_THROTTLE(1.0, "poke: %g N*s on '%s' of '%s' at %s towards its centre of mass (%llu "
                    "pokes so far; at most one such line a second)", settings_.poke.impulse,
                    cmd.link.c_str(), view.name.c_str(), fmt(point).c_str(),
                    static_cast<unsigned long long>(pokes_));
}

void Interaction::beforeStep(double sim_time) {
  sim_time_ = sim_time;
  if (!world_) return;
  for (const Drag& d : drags_) {
    if (!d.active) continue;
    const BodyId body =
        ragdolls_[static_cast<size_t>(d.ragdoll)].ragdoll->bodies[static_cast<size_t>(d.link)];
    const Vec3 p = grabPoint(d);
    world_->applyForce(body,
                       scene::dragForce(p, world_->pointVelocity(body, p), d.target,
                                        settings_.drag, settings_.limits.max_force),
                       p);
  }
}

void Interaction::update(double sim_time) {
  sim_time_ = sim_time;
  if (!server_ || !world_) return;
  bool changed = false;
  for (size_t k = 0; k < drags_.size(); ++k) {
    Drag& d = drags_[k];
    if (d.active) {
      if (visualizer_) {
        const BodyId body =
            ragdolls_[static_cast<size_t>(d.ragdoll)].ragdoll->bodies[static_cast<size_t>(d.link)];
        const Vec3 p = grabPoint(d);
        visualizer_->setPull(static_cast<int>(k), *world_, body, p,
                             scene::dragForce(p, world_->pointVelocity(body, p), d.target,
                                              settings_.drag, settings_.limits.max_force));
      }
      continue;
    }
    const Vec3 p = handleAt(grabPoint(d));
    if (d.shown.allFinite() && (p - d.shown).norm() < 0.002) continue;  // no update for < 2 mm
    server_->setPose(d.marker, poseAt(p));
    d.shown = p;
    changed = true;
  }
  if (changed) server_->applyChanges();
}

}  // namespace node
}  // namespace ragdoll_sim
