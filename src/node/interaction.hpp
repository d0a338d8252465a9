// Interaction: poking and dragging ragdolls from rviz.
//   - Poke: the "Publish Point" tool publishes /clicked_point (geometry_msgs/PointStamped, in
//     the world frame); the nearest link of any ragdoll within ~poke/max_distance gets an
//     impulse of ~poke/impulse N*s at that point towards its centre of mass.
//   - Drag: one interactive marker per ragdoll (server <node>/drag, rviz "InteractiveMarkers"
//     display on <node>/drag/update) sits on the drag link (~drag/link, or its context menu).
//     While the user drags it, a spring-damper (~drag/*) pulls the link's centre of mass
//     towards it every physics step; released, the force stops and the handle follows the
//     link again. The handle floats ~drag/handle_height above the link (not hidden inside it);
//     the spring pulls the link's centre of mass towards the handle minus that offset.
// Both build the same ImpulseCommand / ForceCommand the command topics do and pass the same
// checks (commands.hpp): bad input only warns (throttled) and is dropped. A poke's INFO line is
// throttled too (a click publisher at 1 kHz would flood the log); ~stats counts every one.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <geometry_msgs/PointStamped.h>
#include <interactive_markers/interactive_marker_server.h>
#include <interactive_markers/menu_handler.h>
#include <ros/ros.h>
#include <visualization_msgs/InteractiveMarkerFeedback.h>

#include "commands.hpp"
#include "interaction_laws.hpp"
#include "ragdoll_view.hpp"
#include "visualization.hpp"

namespace ragdoll_sim {
namespace node {

struct InteractionSettings {
  scene::PokeSettings poke;
  scene::DragSettings drag;
  std::string world_frame = "world";
  CommandLimits limits;
};

class Interaction {
 public:
  // nh: where /clicked_point is resolved (the global namespace); pnh: the node's private one
  // (the drag server). `visualizer` (may be null) gets an arrow per poke and per drag.
  Interaction(const ros::NodeHandle& nh, const ros::NodeHandle& pnh,
              const InteractionSettings& settings, Visualizer* visualizer);
  ~Interaction();

  // The world and ragdolls every callback acts on (not owned); call again whenever either
  // changes (reset, spawn). Drags in progress end.
  void setScene(World* world, const std::vector<scene::RagdollView>& ragdolls);

  // Before each physics step: the drag springs' forces.
  void beforeStep(double sim_time);
  // At the publish rate: idle drag handles follow their links; active ones show their pull.
  void update(double sim_time);

  // Pokes applied and drags started since start-up (~stats). They are counted here, where they
  // are applied: they act on the World directly, not through the Scene's commands.
  uint64_t pokes() const { return pokes_; }
  uint64_t drags() const { return drags_started_; }

 private:
  struct Drag {
    std::string marker;       // interactive marker name (= ragdoll name)
    int ragdoll = -1;
    int link = -1;
    bool active = false;      // the user holds it
    Vec3 target = Vec3::Zero();
    Vec3 shown = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());  // handle position
  };

  void onClickedPoint(const geometry_msgs::PointStamped::ConstPtr& msg);
  void onDragFeedback(const visualization_msgs::InteractiveMarkerFeedbackConstPtr& fb);
  void onMenuLink(const visualization_msgs::InteractiveMarkerFeedbackConstPtr& fb);
  void insertDragMarker(const Drag& d);
  Vec3 grabPoint(const Drag& d) const;  // world centre of mass of the held link
  Vec3 handleAt(const Vec3& grab) const;  // where the handle of a grab point is shown
  // ForceCommand checks of the spring force at this instant; false (with a warning) to drop.
  bool checkDrag(const Drag& d, const Vec3& target);
  Drag* findDrag(const std::string& marker);
  void release(Drag* d);  // the spring stops; the handle goes back to the link

  ros::NodeHandle nh_, pnh_;
  InteractionSettings settings_;
  Visualizer* visualizer_;
  World* world_ = nullptr;
  std::vector<scene::RagdollView> ragdolls_;
  std::vector<scene::LinkTable> link_tables_;  // one per ragdoll, for the command checks
  std::vector<Drag> drags_;
  double sim_time_ = 0.0;
  uint64_t pokes_ = 0, drags_started_ = 0;

  ros::Subscriber clicked_sub_;
  std::unique_ptr<interactive_markers::InteractiveMarkerServer> server_;
  std::vector<std::unique_ptr<interactive_markers::MenuHandler>> menus_;  // one per ragdoll
  std::vector<std::vector<interactive_markers::MenuHandler::EntryHandle>> menu_links_;
};

}  // namespace node
}  // namespace ragdoll_sim
