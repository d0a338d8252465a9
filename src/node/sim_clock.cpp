#include "sim_clock.hpp"

#include <algorithm>
#include <cmath>

#include <rosgraph_msgs/Clock.h>

namespace ragdoll_sim {
namespace node {

bool SimClock::init(const ros::NodeHandle& pnh, std::string* error) {
  ros::param::param("/use_sim_time", sim_time_, false);
  publish_clock_ = sim_time_;
  if (pnh.hasParam("publish_clock") && !pnh.getParam("publish_clock", publish_clock_)) {
    *error = "parameter " + pnh.resolveName("publish_clock") + " must be a bool";
    return false;
  }
  // Without sim time: the wall time now (ros::Time::now() is the wall clock then).
  origin_ = sim_time_ ? ros::Time(0, 0) : ros::Time::now();
  return true;
}

void SimClock::advertise(ros::NodeHandle& nh) {
  // /clock ticks every step (1 kHz): a queue of 1 s of ticks, so that a subscriber stalled by
  // a busy machine loses no tick.
  if (publish_clock_) pub_ = nh.advertise<rosgraph_msgs::Clock>("/clock", 1000);
}

ros::Time SimClock::stamp(int64_t sim_ns) const {
  ros::Time t;
  t.fromNSec(origin_.toNSec() + static_cast<uint64_t>(sim_ns));
  return t;
}

void SimClock::publish(int64_t sim_ns, bool force, double clock_rate) {
  if (!publish_clock_ || sim_ns == last_ns_) return;
  if (!force && clock_rate > 0.0 && sim_ns < next_ns_) return;
  rosgraph_msgs::Clock c;
  c.clock = stamp(sim_ns);
  pub_.publish(c);
  last_ns_ = sim_ns;
  if (clock_rate > 0.0) next_ns_ = sim_ns + std::max<int64_t>(1, std::llround(1e9 / clock_rate));
}

}  // namespace node
}  // namespace ragdoll_sim
