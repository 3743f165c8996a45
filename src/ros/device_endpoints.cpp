// The devices' ROS ends (device_endpoints.hpp).
#include "device_endpoints.hpp"

#include <impulse2d/ContactArray.h>
#include <nav_msgs/Odometry.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/LaserScan.h>

namespace impulse2d {
namespace bridge {
namespace {

std::string signatureOf(const DeviceDef& d) {
  switch (d.type) {
    case DeviceType::DiffDrive:
    case DeviceType::Omni:
    case DeviceType::Ackermann:
      return std::string(deviceTypeName(d.type)) + " " + d.drive.cmdVelTopic + " " +
             d.drive.odomTopic + " " + groundTruthTopicOf(d.drive);
    case DeviceType::Laser:
      return "laser " + d.laser.topic;
    case DeviceType::Bumper:
      return "bumper " + d.bumper.topic;
    case DeviceType::Imu:
      return "imu " + d.imu.topic;
  }
  return "";
}

}  // namespace

DeviceEndpoints::DeviceEndpoints(const ros::NodeHandle& pnh, CmdVelHandler onCmdVel)
    : pnh_(pnh), onCmdVel_(std::move(onCmdVel)) {}

DeviceEndpoints::~DeviceEndpoints() { shutdown(); }

std::shared_ptr<DeviceEndpoints::Endpoint> DeviceEndpoints::open(const DeviceDef& device) {
  auto endpoint = std::make_shared<Endpoint>();
  endpoint->signature = signatureOf(device);
  switch (device.type) {
    case DeviceType::DiffDrive:
    case DeviceType::Omni:
    case DeviceType::Ackermann: {
      endpoint->publisher = pnh_.advertise<nav_msgs::Odometry>(device.drive.odomTopic, 10);
      endpoint->groundTruth =
          pnh_.advertise<nav_msgs::Odometry>(groundTruthTopicOf(device.drive), 10);
      const std::string name = device.name;
      CmdVelHandler handler = onCmdVel_;
      endpoint->cmdVel = pnh_.subscribe<geometry_msgs::Twist>(
          device.drive.cmdVelTopic, 10,
          boost::function<void(const geometry_msgs::Twist::ConstPtr&)>(
              [handler, name](const geometry_msgs::Twist::ConstPtr& msg) { handler(name, *msg); }));
      break;
    }
    case DeviceType::Laser:
      endpoint->publisher = pnh_.advertise<sensor_msgs::LaserScan>(device.laser.topic, 10);
      break;
    case DeviceType::Bumper:
      // Latched: it speaks only on change, so a late subscriber still learns the state.
      endpoint->publisher = pnh_.advertise<impulse2d::ContactArray>(device.bumper.topic, 10, true);
      break;
    case DeviceType::Imu:
      endpoint->publisher = pnh_.advertise<sensor_msgs::Imu>(device.imu.topic, 10);
      break;
  }
  return endpoint;
}

void DeviceEndpoints::sync(const std::vector<DeviceDef>& devices) {
  std::lock_guard<std::mutex> one(syncMutex_);
  std::vector<std::shared_ptr<Endpoint>> closing;
  std::vector<const DeviceDef*> opening;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    std::map<std::string, std::string> wanted;
    for (const DeviceDef& d : devices) wanted[d.name] = signatureOf(d);
    for (auto it = endpoints_.begin(); it != endpoints_.end();) {
      const auto w = wanted.find(it->first);
      if (w == wanted.end() || w->second != it->second->signature) {
        closing.push_back(it->second);
        it = endpoints_.erase(it);
      } else {
        ++it;
      }
    }
    for (const DeviceDef& d : devices) {
      if (!endpoints_.count(d.name)) opening.push_back(&d);
    }
  }
  // Closed first, so that a reopened device's topic is free again.
  for (const std::shared_ptr<Endpoint>& endpoint : closing) {
    endpoint->cmdVel.shutdown();
    endpoint->publisher.shutdown();
    endpoint->groundTruth.shutdown();
  }
  std::map<std::string, std::shared_ptr<Endpoint>> opened;
  for (const DeviceDef* d : opening) opened[d->name] = open(*d);
  std::lock_guard<std::mutex> lock(mutex_);
  endpoints_.insert(opened.begin(), opened.end());
}

void DeviceEndpoints::shutdown() {
  std::map<std::string, std::shared_ptr<Endpoint>> all;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    all.swap(endpoints_);
  }
  for (auto& [name, endpoint] : all) {
    endpoint->cmdVel.shutdown();
    endpoint->publisher.shutdown();
    endpoint->groundTruth.shutdown();
  }
}

std::vector<std::pair<std::string, bool>> DeviceEndpoints::demand() const {
  std::vector<std::pair<std::string, bool>> out;
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& [name, endpoint] : endpoints_) {
    out.emplace_back(name, endpoint->publisher.getNumSubscribers() > 0);
  }
  return out;
}

bool DeviceEndpoints::wantsGroundTruth(const std::string& device) const {
  const std::shared_ptr<Endpoint> endpoint = find(device);
  return endpoint && endpoint->groundTruth.getNumSubscribers() > 0;
}

void DeviceEndpoints::publishGroundTruth(const std::string& device,
                                         const nav_msgs::Odometry& message) const {
  const std::shared_ptr<Endpoint> endpoint = find(device);
  if (endpoint) endpoint->groundTruth.publish(message);
}

std::shared_ptr<DeviceEndpoints::Endpoint> DeviceEndpoints::find(const std::string& device) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = endpoints_.find(device);
  return it == endpoints_.end() ? nullptr : it->second;
}

}  // namespace bridge
}  // namespace impulse2d
