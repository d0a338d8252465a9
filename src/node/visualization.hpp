// Visualizer: the node's rviz markers (visualization_msgs/MarkerArray) built from the World and
// the list of ragdolls: every collision shape in its ragdoll's colour (namespace = ragdoll
// name), the ground, optional contact points, normals and force arrows, arrows for applied
// impulses and forces that fade out over sim time and are then deleted, impact flashes and
// the injury text over a head after a fall (visualization_events.cpp).
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include <ros/time.h>
#include <std_msgs/ColorRGBA.h>
#include <visualization_msgs/MarkerArray.h>

#include "ragdoll_sim/ragdoll.hpp"
#include "ragdoll_sim/scene.hpp"
#include "ragdoll_sim/world.hpp"
#include "ragdoll_view.hpp"
#include "rviz_settings.hpp"

namespace ragdoll_sim {
namespace node {

// The Visualizer's settings are the ROS-free rviz settings of the Scene layer.
using scene::MarkerSettings;

struct Rgba {
  float r = 1, g = 1, b = 1, a = 1;
};

// An object (Scene objects, dynamic or static) as the Visualizer draws it: each link in its
// LinkDef colour when it has one, else neutral grey; static ones darker.
struct ObjectView {
  std::string name;  // marker namespace
  const RagdollDef* def = nullptr;
  std::vector<BodyId> bodies;  // one per def->links entry
  bool is_static = false;
};

// An object link's colour: its own (has_color) or neutral grey, darkened when static.
Rgba objectColor(const LinkDef& link, bool is_static);

// Colour of the i-th ragdoll: a palette of six well-separated hues (none near the arrow or
// contact colours below), then golden-angle hues.
Rgba ragdollColor(size_t i);
Rgba impulseArrowColor();
Rgba forceArrowColor();
Rgba contactColor();
Rgba impactColor();
std_msgs::ColorRGBA toMsg(const Rgba& c, double alpha_scale = 1.0);

// The text over a head once a fall ended: "<ragdoll>: peak <g> g, HIC15 <hic>".
std::string injuryText(const InjuryReport& r);

// Opacity of an arrow whose push ended `since_end` s of sim time ago (negative: still going):
// 1 until the end, then linear down to 0 at `fade`. Faded (delete it) when this is 0.
double arrowAlpha(double since_end, double fade);

class Visualizer {
 public:
  Visualizer(const MarkerSettings& settings, const std::string& frame);

  // Rebuilds the shape markers for these ragdolls, objects (and the ground plane of `ground`,
  // if valid) and drops every arrow. Call after the world, the ragdolls or objects changed.
  void setScene(const World& world, const std::vector<scene::RagdollView>& ragdolls,
                BodyId ground, const std::vector<ObjectView>& objects = {});

  // An arrow pointing at `world_point` on `body` (it moves with the body) along `vector`.
  void addImpulse(const World& world, BodyId body, const Vec3& world_point, const Vec3& impulse,
                  double sim_time);
  // A force acting for `duration` s (negative: until endForces).
  void addForce(const World& world, BodyId body, const Vec3& world_point, const Vec3& force,
                double sim_time, double duration);
  // Forces that act until cleared end now (~clear_forces): their arrows start to fade.
  void endForces(double sim_time);
  // A force that changes every step (a drag spring), shown by one arrow per `key` that is
  // updated in place; endPull lets it fade. Not ended by endForces.
  void setPull(int key, const World& world, BodyId body, const Vec3& world_point,
               const Vec3& force);
  void endPull(int key, double sim_time);

  // After every Scene step (NodeContext::stepOnce): its impacts become flashes, the falls that
  // ended injury texts. Two size tests when neither happened.
  void recordStep(const Scene& scene);
  // A sphere at the impact's point, diameter impulse * impulse_scale (5 cm to max_arrow),
  // fading over impact_flash s of sim time from the event's time.
  void addImpact(const ImpactEvent& event);
  // The report's text over link `link` (its head) of ragdoll `ragdoll`, whose body is `head`
  // now; it replaces that ragdoll's last one and stays while the ragdoll does.
  void setInjury(const std::string& ragdoll, int link, BodyId head, const InjuryReport& report);

  // The markers at this instant: shapes posed from the world, contacts, arrows (faded ones
  // once as DELETE), flashes, injury texts. The reference stays valid until the next call.
  const visualization_msgs::MarkerArray& update(const World& world, const ros::Time& stamp,
                                                double sim_time);

  size_t shapeMarkerCount() const { return sources_.size(); }
  size_t arrowCount() const { return arrows_.size(); }
  size_t flashCount() const { return flashes_.size(); }
  size_t injuryTextCount() const { return texts_.size(); }

 private:
  struct Source {
    BodyId body;
    Transform local;  // marker frame in the body frame
  };
  struct Arrow {
    int id = 0;
    bool impulse = true;
    BodyId body;
    Vec3 local_point = Vec3::Zero();  // head, fixed in the body
    Vec3 vector = Vec3::Zero();       // world
    double end = 0.0;                 // sim time the push ends (an impulse: when applied)
    int pull = -1;                    // setPull key while the pull lasts
  };
  // The new arrow (null when the input is not finite or zero).
  Arrow* addArrow(const World& world, BodyId body, const Vec3& world_point, const Vec3& vector,
                  bool impulse, double end);
  visualization_msgs::Marker& addShapeMarker(const std::string& ns, int id, BodyId body,
                                             const Transform& local, int type, const Vec3& scale,
                                             const Rgba& color);
  // One marker per collision shape of `body` (planes as a slab, or left out), ids from *id on.
  void addBodyMarkers(const World& world, const std::string& ns, int* id, BodyId body,
                      const Rgba& color, bool planes);
  struct Flash {
    int id = 0;
    Vec3 point = Vec3::Zero();
    double diameter = 0.0;  // m
    double time = 0.0;      // sim time of the impact
  };
  struct InjuryMark {
    std::string ragdoll;
    int link = -1;
    BodyId head;
    std::string text;
    int id = 0;
  };
  void appendContacts(const World& world, const ros::Time& stamp);
  void appendContactForces(const World& world, const ros::Time& stamp);
  void appendFlashes(const ros::Time& stamp, double sim_time);
  void appendInjuryTexts(const World& world, const ros::Time& stamp);
  // Injury texts follow their ragdoll into a new World, or go with it (setScene).
  void rebindInjuryTexts(const std::vector<scene::RagdollView>& ragdolls);
  void appendArrows(const World& world, const ros::Time& stamp, double sim_time);
  visualization_msgs::Marker& appendMarker(const std::string& ns, int id, const ros::Time& stamp);

  MarkerSettings settings_;
  std::string frame_;
  visualization_msgs::MarkerArray out_;  // shape markers first (updated in place), then extras
  std::vector<Source> sources_;          // one per shape marker
  std::deque<Arrow> arrows_;
  std::vector<int> deleted_;             // arrow ids to send one DELETE for
  int next_arrow_id_ = 0;
  bool contacts_shown_ = false;          // contact markers are in rviz (DELETE them when none)
  std::vector<ContactReport> reports_;   // scratch of the contact force arrows
  int force_arrows_shown_ = 0;           // contact force arrows in rviz (ids 0..n-1)
  std::deque<Flash> flashes_;
  std::vector<int> flashes_deleted_;
  int next_flash_id_ = 0;
  std::vector<InjuryMark> texts_;
  std::vector<int> texts_deleted_;
  int next_text_id_ = 0;
};

}  // namespace node
}  // namespace ragdoll_sim
