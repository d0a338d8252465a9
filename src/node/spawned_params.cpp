#include "spawned_params.hpp"

#include <algorithm>

#include <ros/master.h>
#include <ros/names.h>

namespace ragdoll_sim {
namespace node {

namespace {

constexpr const char* kRecord = "spawned_ragdolls";

std::string descriptionParam(const std::string& name) { return name + "/robot_description"; }

}  // namespace

SpawnedParams::SpawnedParams(const ros::NodeHandle& nh, const ros::NodeHandle& pnh)
    : nh_(nh), pnh_(pnh) {}

void SpawnedParams::deleteLeftovers() {
  std::vector<std::string> left;
  if (!pnh_.getParam(kRecord, left)) return;
  std::vector<std::string> deleted;
  for (const std::string& name : left) {
    std::string why;  // a hand-edited entry that is no graph name is left alone
    if (name.empty() || !ros::names::validate(name, why)) continue;
    if (nh_.deleteParam(descriptionParam(name)))
      deleted.push_back(nh_.resolveName(descriptionParam(name)));
  }
  pnh_.deleteParam(kRecord);
  if (deleted.empty()) return;
  std::string list;
  for (const std::string& d : deleted) list += (list.empty() ? "" : ", ") + d;
  ROS_WARN("deleted %s: left on the parameter server by an earlier ragdoll_sim node that did not "
           "shut down cleanly; those ragdolls are not simulated (spawn them again)",
           list.c_str());
}

void SpawnedParams::add(const std::string& name, const std::string& urdf) {
  nh_.setParam(descriptionParam(name), urdf);
  if (std::find(names_.begin(), names_.end(), name) == names_.end()) names_.push_back(name);
  writeRecord();
}

void SpawnedParams::remove(const std::string& name) {
  const auto it = std::find(names_.begin(), names_.end(), name);
  if (it == names_.end()) return;
  nh_.deleteParam(descriptionParam(name));
  names_.erase(it);
  writeRecord();
}

void SpawnedParams::removeAll() {
  if (names_.empty()) return;
  // A master gone first (roslaunch or rostest ending) would make every call wait for it.
  ros::master::setRetryTimeout(ros::WallDuration(1.0));
  if (!ros::master::check()) {
    ROS_WARN("the master does not answer: the parameters of %zu spawned ragdoll(s) stay (the "
             "next node in this namespace deletes them)", names_.size());
    return;
  }
  for (const std::string& name : names_) nh_.deleteParam(descriptionParam(name));
  names_.clear();
  pnh_.deleteParam(kRecord);
}

void SpawnedParams::writeRecord() {
  if (names_.empty()) pnh_.deleteParam(kRecord);
  else pnh_.setParam(kRecord, names_);
}

}  // namespace node
}  // namespace ragdoll_sim
