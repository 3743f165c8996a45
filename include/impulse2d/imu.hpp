// The IMU's model: what an inertial unit fixed to a body reads, from the body's motion over the
// last step, with seeded noise and a constant bias per axis. ROS-free; the node turns a reading
// into sensor_msgs/Imu.
#pragma once

#include <impulse2d/device_defs.hpp>
#include <impulse2d/laser.hpp>
#include <impulse2d/world.hpp>

#include <Eigen/Geometry>

namespace impulse2d {

/// The standard gravity an accelerometer in a top-down world feels as the floor's support (m/s^2),
/// the figure the drives' default traction also takes.
constexpr double kFloorGravity = 9.81;

/// One reading in the unit's frame (x forward, y left, z up out of the plane).
struct ImuSample {
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< of the unit in the world
  Eigen::Vector3d angularVelocity = Eigen::Vector3d::Zero();        ///< rad/s
  Eigen::Vector3d linearAcceleration = Eigen::Vector3d::Zero();     ///< m/s^2, specific force
};

/// An IMU on a body of a top-down world. Each step the unit follows the body, so a reading is
/// ready whenever one falls due:
///   - orientation: the unit's heading, body angle + offset angle, about z;
///   - angular velocity: the body's turn rate on z;
///   - linear acceleration: the mount point's acceleration over the last step minus the world's
///     gravity (a unit at rest on a slope reads the slope's pull upwards), and kFloorGravity on z.
///     The centre of mass's part is its velocity change over the step, turned into the body frame
///     at the mid-step heading (exact for motion on a circle); the mount point adds the angular
///     acceleration's and the turn's parts, alpha x r - w^2 r.
/// Every figure then gets its axis's bias and Gaussian noise (the noise of the orientation as
/// roll, pitch and yaw).
class Imu {
 public:
  Imu(const ImuDef& def, BodyId body, uint32_t seed, const World& world);

  const ImuDef& def() const { return def_; }
  BodyId body() const { return body_; }

  /// After each step of the world: takes the body's new motion.
  void follow(const World& world);
  /// The true reading now, without bias or noise.
  const ImuSample& truth() const { return truth_; }
  /// A reading as the unit reports it: the truth with bias and noise.
  ImuSample read();

 private:
  struct Motion {
    Vec2 velocity = Vec2::Zero();  // of the centre of mass, world
    double angularVelocity = 0.0;
    double angle = 0.0;
  };
  static Motion motionOf(const Body& body);

  ImuDef def_;
  BodyId body_;
  GaussianNoise noise_;
  Motion last_;
  ImuSample truth_;
};

}  // namespace impulse2d
