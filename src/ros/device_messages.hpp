// The devices' readings as ROS messages, and the tf frames that go with them: odometry
// (REP 105), laser scans (REP 117), bumper contacts, and frames fixed to bodies.
#pragma once

#include "conversions.hpp"
#include "sim_world.hpp"

#include <geometry_msgs/TransformStamped.h>
#include <impulse2d/ContactArray.h>
#include <nav_msgs/Odometry.h>
#include <ros/time.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/LaserScan.h>

#include <string>

namespace impulse2d {
namespace bridge {

/// The unused 3D axes of a planar odometry's covariance (z, and the turns out of the plane).
constexpr double kUnusedVariance = 1e6;

/// nav_msgs/Odometry in `def.odomFrame`, child the body: pose from the odometry, twist in the
/// body frame (linear.x, angular about the plane's normal), the variances on the diagonals.
nav_msgs::Odometry toOdometry(Plane plane, const OdometryReading& odom, const ros::Time& stamp);

/// nav_msgs/Odometry of the body's true pose in `worldFrame` and its true twist in the body
/// frame (REP 105: the twist is the child's), covariances 0: exact.
nav_msgs::Odometry toGroundTruth(Plane plane, const std::string& worldFrame,
                                 const OdometryReading& odom, const ros::Time& stamp);

/// odom_frame -> body, from the odometry.
geometry_msgs::TransformStamped odomToBody(Plane plane, const OdometryReading& odom,
                                           const ros::Time& stamp);
/// world frame -> odom_frame such that world -> odom -> body is the body's true pose.
geometry_msgs::TransformStamped worldToOdom(Plane plane, const std::string& worldFrame,
                                            const OdometryReading& odom, const ros::Time& stamp);

/// A scan as sensor_msgs/LaserScan: angle_max is the last beam's angle, scan_time the period,
/// time_increment 0 (every beam is cast at the same instant), intensities the shapes'
/// reflectance.
sensor_msgs::LaserScan toLaserScan(const ScanReading& scan, const ros::Time& stamp);

/// The smallest variance an IMU's covariance states: an axis without noise is exact, but ROS
/// reads an all-zero covariance as unknown.
constexpr double kExactVariance = 1e-9;

/// An IMU reading as sensor_msgs/Imu in the unit's frame: covariances diagonal, each axis its
/// noise's variance (at least kExactVariance).
sensor_msgs::Imu toImu(const ImuReading& reading, const ros::Time& stamp);

/// A bumper's contacts, in the world frame's 2D coordinates as ~contacts has them.
impulse2d::ContactArray toContactArray(const BumperReading& change, const std::string& worldFrame,
                                       const ros::Time& stamp);

/// A fixed frame for /tf_static. A laser's x-y plane (where LaserScan puts its beams) is turned
/// into the world's plane: in xz that is +90 degrees about its x axis.
geometry_msgs::TransformStamped fixedTransform(Plane plane, const std::string& worldFrame,
                                               const FixedFrame& frame, const ros::Time& stamp);

}  // namespace bridge
}  // namespace impulse2d
