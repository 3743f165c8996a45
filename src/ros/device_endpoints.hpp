// The ROS ends of the world's devices: a drive's cmd_vel subscriber and odom publisher, a laser's
// scan publisher, a bumper's latched publisher. Kept in step with the devices the world holds;
// an unchanged device keeps its endpoints (across ~reset, so subscribers stay connected).
#pragma once

#include "sim_world.hpp"

#include <geometry_msgs/Twist.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace impulse2d {
namespace bridge {

class DeviceEndpoints {
 public:
  /// Called on a spinner thread for every cmd_vel message, with the drive's name.
  using CmdVelHandler = std::function<void(const std::string&, const geometry_msgs::Twist&)>;

  DeviceEndpoints(const ros::NodeHandle& pnh, CmdVelHandler onCmdVel);
  ~DeviceEndpoints();
  DeviceEndpoints(const DeviceEndpoints&) = delete;
  DeviceEndpoints& operator=(const DeviceEndpoints&) = delete;

  /// Opens the endpoints of new devices and closes those of devices that are gone. Closing a
  /// subscriber waits for its running callbacks, which take the world's lock: never call this
  /// holding it.
  void sync(const std::vector<DeviceDef>& devices);
  /// Closes everything (before the handler's owner goes away).
  void shutdown();

  /// Whether anyone subscribes to each laser's and bumper's topic, by device name.
  std::vector<std::pair<std::string, bool>> demand() const;
  /// Publishes on the named device's topic, if it has one of that kind and, for odometry,
  /// someone listens. Safe from any thread, also while sync() runs.
  template <typename Message>
  void publish(const std::string& device, const Message& message) const {
    const std::shared_ptr<Endpoint> endpoint = find(device);
    if (endpoint && endpoint->publisher.getNumSubscribers() > 0)
      endpoint->publisher.publish(message);
  }
  /// Whether anyone listens to the named drive's ground truth, and publishing it.
  bool wantsGroundTruth(const std::string& device) const;
  void publishGroundTruth(const std::string& device, const nav_msgs::Odometry& message) const;

 private:
  struct Endpoint {
    std::string signature;       // type and topics: a device whose signature changed is reopened
    ros::Publisher publisher;    // odom, scan, imu or bumper
    ros::Publisher groundTruth;  // drives
    ros::Subscriber cmdVel;      // drives
  };
  std::shared_ptr<Endpoint> open(const DeviceDef& device);
  std::shared_ptr<Endpoint> find(const std::string& device) const;

  ros::NodeHandle pnh_;
  CmdVelHandler onCmdVel_;
  std::mutex syncMutex_;      // one sync at a time
  mutable std::mutex mutex_;  // guards endpoints_, never held across a ROS call that may block
  std::map<std::string, std::shared_ptr<Endpoint>> endpoints_;
};

}  // namespace bridge
}  // namespace impulse2d
