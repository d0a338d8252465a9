// The parameters a ~spawn sets (<name>/robot_description, for robot_state_publisher and
// tools) and their record ~spawned_ragdolls on the parameter server: they go with the ragdoll
// and at a clean shutdown, and a node starting after one that died (kill -9) deletes what
// that one left, so no tool takes a dead node's ragdoll for a simulated one.
#pragma once

#include <string>
#include <vector>

#include <ros/ros.h>

namespace ragdoll_sim {
namespace node {

class SpawnedParams {
 public:
  // nh: where <name>/robot_description goes; pnh: the node's ~ (its record).
  SpawnedParams(const ros::NodeHandle& nh, const ros::NodeHandle& pnh);

  // At start-up: deletes the parameters an earlier node in this namespace left, with a WARN
  // naming them.
  void deleteLeftovers();
  void add(const std::string& name, const std::string& urdf);
  void remove(const std::string& name);
  // At a clean shutdown.
  void removeAll();

 private:
  void writeRecord();

  ros::NodeHandle nh_, pnh_;
  std::vector<std::string> names_;
};

}  // namespace node
}  // namespace ragdoll_sim
