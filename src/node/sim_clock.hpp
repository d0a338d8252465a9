// Stamps of sim time and /clock. On /use_sim_time the node is the clock: stamps are sim time
// and /clock carries each value before anything stamped with it goes out. Otherwise stamps
// are the wall time at start-up plus sim time (stamp differences equal sim-time differences).
#pragma once

#include <cstdint>
#include <string>

#include <ros/ros.h>

namespace ragdoll_sim {
namespace node {

class SimClock {
 public:
  // Reads /use_sim_time and ~publish_clock; false with *error for a ~publish_clock of the
  // wrong type.
  bool init(const ros::NodeHandle& pnh, std::string* error);
  // /clock, when this node publishes it (call after init, with the other publishers).
  void advertise(ros::NodeHandle& nh);

  ros::Time stamp(int64_t sim_ns) const;
  int64_t originNs() const { return static_cast<int64_t>(origin_.toNSec()); }
  bool simTime() const { return sim_time_; }
  bool publishing() const { return publish_clock_; }
  // At ~clock_rate (Hz of sim time; 0: every step), or now with `force` if not yet sent.
  void publish(int64_t sim_ns, bool force, double clock_rate);

 private:
  ros::Time origin_;            // stamp of sim time 0
  bool sim_time_ = false;       // /use_sim_time
  bool publish_clock_ = false;  // this node publishes /clock
  int64_t last_ns_ = -1, next_ns_ = 0;
  ros::Publisher pub_;
};

}  // namespace node
}  // namespace ragdoll_sim
