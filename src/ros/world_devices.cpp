// WorldNode's devices: their topics opened and closed with the world's devices, cmd_vel in,
// scans, bumper changes and odometry out; and the ~ray_cast and ~query_point services.
#include "device_messages.hpp"
#include "world_node.hpp"

#include <algorithm>

namespace impulse2d {
namespace bridge {

void WorldNode::setUpDevices() {
  // Device topics are compared as resolved names, so that "scan" and "/impulse2d/scan" clash.
  const ros::NodeHandle pnh = pnh_;
  auto resolve = [pnh](const std::string& topic) {
    try {
      return pnh.resolveName(topic);
    } catch (const ros::InvalidNameException&) {
      return topic;  // the scene loader's rules are stricter than ROS's; kept for safety
    }
  };
  std::vector<std::string> reserved;
  for (const char* own : {"contacts", "markers", "joint_command", "removed_bodies", "map"}) {
    reserved.push_back(resolve(own));
  }
  reserved.push_back(nh_.resolveName("joint_states"));
  for (const char* global : {"/tf", "/tf_static", "/clock", "/diagnostics", "/rosout"}) {
    reserved.push_back(global);
  }
  sim_.setTopicRules(resolve, reserved);
  deviceEndpoints_ = std::make_unique<DeviceEndpoints>(
      pnh_, [this](const std::string& device, const geometry_msgs::Twist& twist) {
        onCmdVel(device, twist);
      });
}

void WorldNode::syncDevices() {
  std::lock_guard<std::mutex> one(deviceSyncMutex_);
  std::vector<DeviceDef> devices;
  uint64_t version = 0;
  {
    Lock lock(*this);
    version = sim_.deviceVersion();
    if (devicesSynced_ && version == syncedDeviceVersion_) return;
    devices = sim_.devices();
  }
  deviceEndpoints_->sync(devices);
  syncedDeviceVersion_ = version;
  devicesSynced_ = true;
}

void WorldNode::publishDeviceReadings() {
  for (const ScanReading& scan : sim_.takeScans()) {
    deviceEndpoints_->publish(scan.device, toLaserScan(scan, stampFor(scan.stampNs)));
  }
  for (const ImuReading& reading : sim_.takeImuReadings()) {
    deviceEndpoints_->publish(reading.device, toImu(reading, stampFor(reading.stampNs)));
  }
  for (const BumperReading& change : sim_.takeBumperChanges()) {
    deviceEndpoints_->publish(change.device,
                              toContactArray(change, sim_.frameId(), stampFor(change.stampNs)));
  }
}

void WorldNode::updateDeviceDemand() {
  const std::vector<std::pair<std::string, bool>> demand = deviceEndpoints_->demand();
  Lock lock(*this);
  for (const auto& [device, wanted] : demand) sim_.setDeviceActive(device, wanted);
}

void WorldNode::onCmdVel(const std::string& device, const geometry_msgs::Twist& twist) {
  std::string error;
  {
    Lock lock(*this);
    sim_.commandDrive(device, twist.linear.x, twist.linear.y, twist.angular.z, &error);
  }
  if (!error.empty()) {
    ROS_WARN_THROTTLE(1.0, "[%s] cmd_vel of '%s': %s", name_.c_str(), device.c_str(),
                      error.c_str());
  }
}

void WorldNode::publishOdometry(Plane plane, const std::string& worldFrame, const ros::Time& stamp,
                                const std::vector<OdometryReading>& odometry,
                                std::vector<geometry_msgs::TransformStamped>* tf,
                                std::vector<std::string>* driven) {
  for (const OdometryReading& odom : odometry) {
    deviceEndpoints_->publish(odom.device, toOdometry(plane, odom, stamp));
    if (deviceEndpoints_->wantsGroundTruth(odom.device)) {
      deviceEndpoints_->publishGroundTruth(odom.device,
                                           toGroundTruth(plane, worldFrame, odom, stamp));
    }
    if (!odom.def.publishTf) continue;
    tf->push_back(odomToBody(plane, odom, stamp));
    if (odom.def.groundTruthTf) tf->push_back(worldToOdom(plane, worldFrame, odom, stamp));
    driven->push_back(odom.body);
  }
}

bool WorldNode::rayCast(RayCast::Request& req, RayCast::Response& res) {
  RayCastAnswer answer;
  std::string error;
  {
    Lock lock(*this);
    sim_.rayCast(Vec2(req.start.x, req.start.y), Vec2(req.end.x, req.end.y), req.ignore_bodies,
                 &answer, &error);
  }
  res.success = error.empty();
  res.message = error.empty() ? "ok" : error;
  res.hit = answer.hit;
  res.body = answer.body;
  res.point.x = answer.point.x();
  res.point.y = answer.point.y();
  res.normal.x = answer.normal.x() + 0.0;  // + 0.0: no -0.0 for readers
  res.normal.y = answer.normal.y() + 0.0;
  res.fraction = answer.fraction;
  res.distance = answer.fraction * std::hypot(req.end.x - req.start.x, req.end.y - req.start.y);
  return true;
}

bool WorldNode::queryPoint(QueryPoint::Request& req, QueryPoint::Response& res) {
  std::string error;
  {
    Lock lock(*this);
    sim_.queryPoint(Vec2(req.point.x, req.point.y), &res.bodies, &error);
  }
  res.success = error.empty();
  res.message = error.empty() ? "ok" : error;
  return true;
}

}  // namespace bridge
}  // namespace impulse2d
