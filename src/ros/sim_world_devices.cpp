// SimWorld's devices: adding them with scenes, commands in, readings out, and the frames fixed to
// bodies (lasers, URDF links) for tf. No ROS header may appear here (see sim_world.hpp).
#include "sim_world.hpp"

#include <impulse2d/devices.hpp>
#include <impulse2d/scene.hpp>
#include <impulse2d/world.hpp>

#include <algorithm>
#include <cmath>

namespace impulse2d {
namespace bridge {
namespace {

// Readings the node did not take are dropped beyond this (it takes them after every step).
constexpr size_t kMaxQueuedReadings = 64;

template <typename Reading>
void enqueue(std::vector<Reading>* queue, Reading reading) {
  if (queue->size() >= kMaxQueuedReadings) queue->erase(queue->begin());
  queue->push_back(std::move(reading));
}

}  // namespace

void SimWorld::setTopicRules(std::function<std::string(const std::string&)> resolve,
                             std::vector<std::string> reserved) {
  resolveTopic_ = std::move(resolve);
  reservedTopics_ = std::move(reserved);
}

DeviceContext SimWorld::deviceContext() const {
  DeviceContext context;
  context.plane = plane_;
  context.worldFrame = frameId_;
  context.resolveTopic = resolveTopic_;
  context.reservedTopics = reservedTopics_;
  return context;
}

bool SimWorld::addDevices(const std::vector<DeviceDef>& devices, std::string* error) {
  if (devices.empty()) return true;
  // A scene of devices only: addScene checks that their bodies exist and adds nothing else.
  Scene onlyDevices;
  onlyDevices.devices = devices;
  if (!impulse2d::addScene(onlyDevices, *world_, error)) return false;
  if (!devices_->add(devices, *world_, deviceContext(), 1e-9 * static_cast<double>(simTimeNs_),
                     error)) {
    return false;
  }
  ++staticVersion_;  // laser frames
  return true;
}

std::vector<DeviceDef> SimWorld::devices() const {
  std::vector<DeviceDef> out;
  for (const Device& device : devices_->devices()) out.push_back(device.def);
  return out;
}

uint64_t SimWorld::deviceVersion() const { return devices_->version(); }

bool SimWorld::commandDrive(const std::string& device, double vx, double vy, double w,
                            std::string* error) {
  Device* found = devices_->find(device);
  if (found == nullptr || !found->drive) {
    *error = "no drive named '" + device + "'";
    return false;
  }
  if (!std::isfinite(vx) || !std::isfinite(vy) || !std::isfinite(w)) {
    *error = "linear.x, linear.y, angular.z: must be finite";
    return false;
  }
  found->drive->command(vx, vy, w, 1e-9 * static_cast<double>(simTimeNs_));
  return true;
}

void SimWorld::setDeviceActive(const std::string& device, bool active) {
  Device* found = devices_->find(device);
  if (found != nullptr) found->active = active;
}

std::vector<OdometryReading> SimWorld::odometry() const {
  std::vector<OdometryReading> out;
  for (const Device& device : devices_->devices()) {
    if (!device.drive || !world_->isValid(device.body)) continue;
    const Body& body = world_->body(device.body);
    OdometryReading r;
    r.device = device.def.name;
    r.body = body.name;
    r.def = device.def.drive;
    r.position = device.drive->odometry().position;
    r.angle = device.drive->odometry().angle;
    r.speed = device.drive->speed();
    r.sideSpeed = device.drive->sideSpeed();
    r.turnRate = device.drive->turnRate();
    r.truePosition = body.xf.p;
    r.trueAngle = body.angle;
    r.trueVelocity = body.velocityAt(body.xf.p);
    r.trueTurnRate = body.angularVelocity;
    out.push_back(std::move(r));
  }
  return out;
}

void SimWorld::collectDeviceReadings(bool bodiesRemoved) {
  for (Device& device : devices_->devices()) {
    if (!device.fresh) continue;
    device.fresh = false;
    if (device.laser) {
      ScanReading scan;
      scan.device = device.def.name;
      scan.frame = deviceFrameOf(device.def);
      scan.def = device.def.laser;
      scan.beams = device.laser->beamCount();
      scan.stampNs = simTimeNs_;
      scan.ranges = device.ranges;
      scan.intensities = device.intensities;
      enqueue(&scans_, std::move(scan));
    } else if (device.imu) {
      ImuReading reading;
      reading.device = device.def.name;
      reading.frame = deviceFrameOf(device.def);
      reading.def = device.def.imu;
      reading.stampNs = simTimeNs_;
      reading.orientation = device.imuReading.orientation;
      reading.angularVelocity = device.imuReading.angularVelocity;
      reading.linearAcceleration = device.imuReading.linearAcceleration;
      enqueue(&imuReadings_, std::move(reading));
    } else if (device.bumper) {
      BumperReading change;
      change.device = device.def.name;
      change.stampNs = simTimeNs_;
      for (const ContactInfo& c : device.bumper->contacts()) {
        change.contacts.push_back(snapshotOf(c));
      }
      enqueue(&bumperChanges_, std::move(change));
    }
  }
  // Bodies the step removed take their devices and frames along.
  if (!bodiesRemoved) return;
  const uint64_t version = devices_->version();
  devices_->dropDetached(*world_);
  if (devices_->version() != version) ++staticVersion_;
  pruneUrdfFrames();
}

std::vector<ScanReading> SimWorld::takeScans() {
  std::vector<ScanReading> out;
  out.swap(scans_);
  return out;
}

std::vector<ImuReading> SimWorld::takeImuReadings() {
  std::vector<ImuReading> out;
  out.swap(imuReadings_);
  return out;
}

std::vector<BumperReading> SimWorld::takeBumperChanges() {
  std::vector<BumperReading> out;
  out.swap(bumperChanges_);
  return out;
}

void SimWorld::pruneUrdfFrames() {
  urdfFrames_.erase(
      std::remove_if(urdfFrames_.begin(), urdfFrames_.end(),
                     [&](const FixedFrame& f) { return !world_->findBody(f.owner).valid(); }),
      urdfFrames_.end());
}

std::vector<FixedFrame> SimWorld::fixedFrames() const {
  std::vector<FixedFrame> out;
  for (const FixedFrame& frame : urdfFrames_) {
    if (world_->findBody(frame.owner).valid()) out.push_back(frame);
  }
  for (const Device& device : devices_->devices()) {
    if (!(device.laser || device.imu) || !world_->isValid(device.body)) continue;
    FixedFrame frame;
    frame.name = deviceFrameOf(device.def);
    frame.parent = device.def.body;
    frame.owner = device.def.body;
    frame.laser = true;
    frame.offset = device.laser ? device.def.laser.offset : device.def.imu.offset;
    frame.offsetAngle = device.laser ? device.def.laser.offsetAngle : device.def.imu.offsetAngle;
    frame.flip = device.laser && device.def.laser.flip;
    out.push_back(frame);
  }
  return out;
}

}  // namespace bridge
}  // namespace impulse2d
