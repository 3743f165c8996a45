// Devices a scene attaches to its bodies (the `devices:` list): a differential drive, a laser
// scanner and a bumper. Plain definitions with the scene format's defaults; the models that run
// them are in devices.hpp, the ROS node gives them topics. Units are SI.
#pragma once

#include <impulse2d/math.hpp>

#include <cstdint>
#include <string>

namespace impulse2d {

enum class DeviceType { DiffDrive, Laser, Bumper };

/// The scene's name of a device type: diff_drive, laser, bumper.
inline const char* deviceTypeName(DeviceType type) {
  switch (type) {
    case DeviceType::DiffDrive:
      return "diff_drive";
    case DeviceType::Laser:
      return "laser";
    case DeviceType::Bumper:
      return "bumper";
  }
  return "unknown";
}

/// A body driven like a differential-drive robot: forward speed along its x axis and turn rate,
/// reached through forces within traction limits (drive.hpp, Drive, says how).
struct DriveDef {
  std::string cmdVelTopic = "cmd_vel";  ///< geometry_msgs/Twist: linear.x (m/s), angular.z (rad/s)
  std::string odomTopic = "odom";       ///< nav_msgs/Odometry
  std::string odomFrame = "odom";       ///< tf odom_frame -> body
  bool publishTf = true;
  /// With publishTf: the world frame -> odom_frame from the ground truth, so that world -> odom
  /// -> body is the body's true pose; false when a localiser publishes the odom frame's parent.
  bool groundTruthTf = true;
  double maxLinearAccel = 2.0;   ///< m/s^2, how fast the commanded speed is approached
  double maxAngularAccel = 6.0;  ///< rad/s^2
  double cmdTimeout = 0.5;       ///< s of simulated time without a command: stop; 0 = never
  /// N, the most the wheels push the body (forward and sideways together); <= 0: its weight,
  /// mass x 9.81 (wheels with friction 1 on a level floor).
  double maxForce = 0.0;
  /// N m about the centre of mass; <= 0: maxForce x the body's farthest shape point.
  double maxTorque = 0.0;
  /// Variances of the odometry's x (m^2), y (m^2) and heading (rad^2), and of its twist.
  Vec2 poseVarianceXy = Vec2(0.001, 0.001);
  double poseVarianceTheta = 0.001;
  Vec2 twistVarianceXy = Vec2(0.001, 0.001);
  double twistVarianceTheta = 0.001;
};

/// A planar laser scanner: a fan of rays from a point on the body.
struct LaserDef {
  Vec2 offset = Vec2(0.1, 0.0);     ///< m, the scanner's origin in the body frame
  double offsetAngle = 0.0;         ///< rad, its x axis (angle 0 of the scan) in the body frame
  std::string topic = "scan";       ///< sensor_msgs/LaserScan
  double rangeMin = 0.05;           ///< m; nearer hits read -inf (REP 117)
  double rangeMax = 10.0;           ///< m; no hit within it reads +inf
  double angleMin = -2.356;         ///< rad, the first beam
  double angleMax = 2.356;          ///< rad, the last beam lies at or before it
  double angleIncrement = 0.00436;  ///< rad between beams
  double updateRate = 10.0;         ///< scans per second of simulated time
  double noiseStddev = 0.0;         ///< m, Gaussian noise added to each range
  bool hasSeed = false;             ///< without a seed, one is derived from the device's name
  uint32_t seed = 0;
};

/// The contacts of one body, published when they change.
struct BumperDef {
  std::string topic = "bumper";  ///< impulse2d/ContactArray
};

/// One entry of `devices:`. Only the member of `type` is used.
struct DeviceDef {
  DeviceType type = DeviceType::DiffDrive;
  std::string name;  ///< unique among the world's devices
  std::string body;  ///< the body it is attached to, by name
  DriveDef drive;
  LaserDef laser;
  BumperDef bumper;
};

}  // namespace impulse2d
