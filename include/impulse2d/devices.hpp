// The devices of one world, run around its steps: drives before, odometry, scans and bumpers
// after. The ROS node and impulse2d_sim both keep one; the node gives each device its topics.
#pragma once

#include <impulse2d/bumper.hpp>
#include <impulse2d/device_defs.hpp>
#include <impulse2d/drive.hpp>
#include <impulse2d/imu.hpp>
#include <impulse2d/laser.hpp>
#include <impulse2d/world.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace impulse2d {

/// One device with its model (the member of its type) and its latest reading.
struct Device {
  DeviceDef def;
  BodyId body;
  uint64_t id = 0;               ///< unique over the set's life
  std::unique_ptr<Drive> drive;  ///< diff_drive, omni, ackermann
  std::unique_ptr<Laser> laser;
  std::unique_ptr<ScanSchedule> schedule;  ///< lasers and IMUs: when a reading falls due
  std::unique_ptr<Bumper> bumper;
  std::unique_ptr<Imu> imu;
  /// Lasers, bumpers and IMUs report only while someone reads them (the node sets this from its
  /// subscribers); drives always run, they are part of the physics.
  bool active = false;
  bool fresh = false;         ///< afterStep took a reading: a scan, an IMU's, a bumper's change
  double readingTime = 0.0;   ///< s of simulated time of that reading
  std::vector<float> ranges;  ///< lasers: the last scan
  std::vector<float> intensities;  ///< lasers: the last scan's, beam by beam
  ImuSample imuReading;            ///< IMUs: the last reading
};

/// What the world around the devices is: the set checks new devices against it.
struct DeviceContext {
  std::string plane = "xz";          ///< the world's plane; drives need xy
  std::string worldFrame = "world";  ///< no odom frame may take its name
  /// How a topic as a scene gives it is compared with others (the node resolves relative names
  /// into its private namespace); identity when not set.
  std::function<std::string(const std::string&)> resolveTopic;
  /// Topics the devices may not take (the node's own), as resolveTopic gives them.
  std::vector<std::string> reservedTopics;
};

class DeviceSet {
 public:
  /// Empty when `defs` can join the devices here: at most kMaxDevices in all; names unique; every
  /// topic used by one device only and not reserved; drives and IMUs only in plane xy; drives one
  /// per body; every frame a device publishes (a drive's odom frame with publish_tf, a laser's
  /// or IMU's frame) one device's, neither the world frame nor its body's name.
  /// Otherwise one line naming the device and key, e.g.
  ///   "devices[1] 'scan2': topic: 'scan' is already used by the device 'laser'".
  /// Bodies are not looked at: addScene checks them.
  std::string check(const std::vector<DeviceDef>& defs, const DeviceContext& context) const;
  /// check(), then creates every device of `defs` on the bodies it names (they must exist), at
  /// simulated time `now`; or none.
  bool add(const std::vector<DeviceDef>& defs, const World& world, const DeviceContext& context,
           double now, std::string* error);
  /// Removes the devices whose body the world no longer has.
  void dropDetached(const World& world);
  void clear();

  /// Before the world steps from time `now` (s): the drives push.
  void beforeStep(World& world, double now);
  /// After the step that ended at `now`: odometry, the IMUs follow their bodies; the due scans
  /// and IMU readings and the bumpers of active devices, marked `fresh`.
  void afterStep(const World& world, double now);

  std::vector<Device>& devices() { return devices_; }
  const std::vector<Device>& devices() const { return devices_; }
  Device* find(const std::string& name);
  /// Changes whenever devices are added or removed.
  uint64_t version() const { return version_; }

 private:
  std::vector<Device> devices_;
  uint64_t nextId_ = 1;
  uint64_t version_ = 0;
};

}  // namespace impulse2d
