// Devices a scene attaches to its bodies (the `devices:` list): drives (differential, holonomic,
// Ackermann), a laser scanner, a bumper and an IMU. Plain definitions with the scene format's
// defaults; the models that run them are in devices.hpp, the ROS node gives them topics. Units
// are SI.
#pragma once

#include <impulse2d/math.hpp>

#include <Eigen/Core>

#include <cstdint>
#include <string>

namespace impulse2d {

enum class DeviceType { DiffDrive, Laser, Bumper, Imu, Omni, Ackermann };

/// Every device type, in the order the scene format lists them.
constexpr DeviceType kDeviceTypes[] = {DeviceType::DiffDrive, DeviceType::Omni,
                                       DeviceType::Ackermann, DeviceType::Laser,
                                       DeviceType::Bumper,    DeviceType::Imu};

/// The scene's name of a device type: diff_drive, omni, ackermann, laser, bumper, imu.
inline const char* deviceTypeName(DeviceType type) {
  switch (type) {
    case DeviceType::DiffDrive:
      return "diff_drive";
    case DeviceType::Omni:
      return "omni";
    case DeviceType::Ackermann:
      return "ackermann";
    case DeviceType::Laser:
      return "laser";
    case DeviceType::Bumper:
      return "bumper";
    case DeviceType::Imu:
      return "imu";
  }
  return "unknown";
}

/// The type's name with its article, for messages: "a laser", "an imu".
inline std::string deviceTypeWithArticle(DeviceType type) {
  const std::string name = deviceTypeName(type);
  return (name.find_first_of("aeiou") == 0 ? "an " : "a ") + name;
}

/// Whether the type drives its body (diff_drive, omni, ackermann): one DriveDef, one Drive.
inline bool isDrive(DeviceType type) {
  return type == DeviceType::DiffDrive || type == DeviceType::Omni || type == DeviceType::Ackermann;
}

/// A body driven like a wheeled robot: velocities in its own frame, reached through forces within
/// traction limits (drive.hpp, Drive, says how). Which velocities a command sets depends on the
/// device type: diff_drive forward speed and turn rate; omni also sideways speed; ackermann
/// forward speed and the turn rate a steering angle gives (the members marked ackermann).
struct DriveDef {
  /// geometry_msgs/Twist: linear.x (m/s), linear.y (m/s, omni only), angular.z (rad/s)
  std::string cmdVelTopic = "cmd_vel";
  std::string odomTopic = "odom";  ///< nav_msgs/Odometry
  /// nav_msgs/Odometry of the body's true pose and twist in the world frame (flatland's
  /// odometry/ground_truth, Stage's base_pose_ground_truth); "": groundTruthTopicOf() derives it.
  std::string groundTruthTopic;
  std::string odomFrame = "odom";  ///< tf odom_frame -> body
  bool publishTf = true;
  /// With publishTf: the world frame -> odom_frame from the ground truth, so that world -> odom
  /// -> body is the body's true pose; false when a localiser publishes the odom frame's parent.
  bool groundTruthTf = true;
  double maxLinearAccel = 2.0;   ///< m/s^2, how fast the commanded speed is approached
  double maxAngularAccel = 6.0;  ///< rad/s^2; not ackermann (its turn rate follows the steering)
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
  /// ackermann: m from the rear axle, which is the body's origin, to the front axle (> 0).
  double wheelbase = 0.0;
  double maxSteeringAngle = 0.6;  ///< ackermann: rad, in (0, pi/2)
  double steeringRate = 1.5;      ///< ackermann: rad/s > 0, how fast the steering angle turns
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
  /// Mounted upside down: the scan's frame is rolled half a turn about its x axis, so that beam
  /// angle a points along -a in the body's plane.
  bool flip = false;
};

/// The contacts of one body, published when they change.
struct BumperDef {
  std::string topic = "bumper";  ///< impulse2d/ContactArray
};

/// A drive's ground-truth topic: groundTruthTopic if given, else beside its odometry: the last
/// segment `odom` becomes `ground_truth` (odom -> ground_truth, r1/odom -> r1/ground_truth), any
/// other odometry topic T gets T_ground_truth.
inline std::string groundTruthTopicOf(const DriveDef& def) {
  if (!def.groundTruthTopic.empty()) return def.groundTruthTopic;
  const std::string& odom = def.odomTopic;
  const size_t slash = odom.find_last_of('/');
  const size_t last = slash == std::string::npos ? 0 : slash + 1;
  if (odom.compare(last, std::string::npos, "odom") == 0) {
    return odom.substr(0, last) + "ground_truth";
  }
  return odom + "_ground_truth";
}

/// An inertial measurement unit at a point of the body (top-down worlds), as sensor_msgs/Imu
/// reads: orientation (yaw in the plane, REP 145), angular velocity, and linear acceleration as
/// an accelerometer feels it, i.e. with the floor's support, +9.81 on z. Each of the three
/// figures has Gaussian noise and a constant bias per axis (x, y, z).
struct ImuDef {
  std::string topic = "imu";   ///< sensor_msgs/Imu
  Vec2 offset = Vec2::Zero();  ///< m, the unit's origin in the body frame
  double offsetAngle = 0.0;    ///< rad, its x axis in the body frame
  double updateRate = 50.0;    ///< readings per second of simulated time
  Eigen::Vector3d orientationNoise = Eigen::Vector3d::Zero();         ///< rad, standard deviation
  Eigen::Vector3d angularVelocityNoise = Eigen::Vector3d::Zero();     ///< rad/s
  Eigen::Vector3d linearAccelerationNoise = Eigen::Vector3d::Zero();  ///< m/s^2
  Eigen::Vector3d angularVelocityBias = Eigen::Vector3d::Zero();      ///< rad/s, added throughout
  Eigen::Vector3d linearAccelerationBias = Eigen::Vector3d::Zero();   ///< m/s^2
  bool hasSeed = false;  ///< without a seed, one is derived from the device's name
  uint32_t seed = 0;
};

/// One entry of `devices:`. Only the member of `type` is used (`drive` by every drive type).
struct DeviceDef {
  DeviceType type = DeviceType::DiffDrive;
  std::string name;  ///< unique among the world's devices
  std::string body;  ///< the body it is attached to, by name
  /// Lasers and IMUs: the tf frame of their readings; "": deviceFrameOf() derives it.
  std::string frame;
  DriveDef drive;
  LaserDef laser;
  BumperDef bumper;
  ImuDef imu;
};

/// A laser's or IMU's frame: `frame` if given, else "<body>/<name>".
inline std::string deviceFrameOf(const DeviceDef& def) {
  return def.frame.empty() ? def.body + "/" + def.name : def.frame;
}

}  // namespace impulse2d
