// The devices' readings as ROS messages (device_messages.hpp).
#include "device_messages.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace impulse2d {
namespace bridge {
namespace {

// A 2D diagonal (x, y, theta) as the 6 x 6 row-major covariance of a 3D pose or twist
// (x, y, z, turns about x, y, z), the axes the plane does not use set to kUnusedVariance.
boost::array<double, 36> covariance(Plane plane, const Vec2& xy, double theta) {
  boost::array<double, 36> c{};
  double diagonal[6] = {kUnusedVariance, kUnusedVariance, kUnusedVariance,
                        kUnusedVariance, kUnusedVariance, kUnusedVariance};
  diagonal[0] = xy.x();
  if (plane == Plane::XY) {
    diagonal[1] = xy.y();
    diagonal[5] = theta;
  } else {
    diagonal[2] = xy.y();
    diagonal[4] = theta;
  }
  for (int i = 0; i < 6; ++i) c[7 * i] = diagonal[i];
  return c;
}

geometry_msgs::Quaternion toMsg(const Eigen::Quaterniond& q) {
  geometry_msgs::Quaternion m;
  m.w = q.w();
  m.x = q.x();
  m.y = q.y();
  m.z = q.z();
  return m;
}

Eigen::Quaterniond fromMsg(const geometry_msgs::Quaternion& m) {
  return Eigen::Quaterniond(m.w, m.x, m.y, m.z);
}

geometry_msgs::TransformStamped stamped(const std::string& parent, const std::string& child,
                                        const ros::Time& stamp) {
  geometry_msgs::TransformStamped t;
  t.header.frame_id = parent;
  t.header.stamp = stamp;
  t.child_frame_id = child;
  return t;
}

}  // namespace

nav_msgs::Odometry toOdometry(Plane plane, const OdometryReading& odom, const ros::Time& stamp) {
  nav_msgs::Odometry msg;
  msg.header.frame_id = odom.def.odomFrame;
  msg.header.stamp = stamp;
  msg.child_frame_id = odom.body;
  msg.pose.pose = toPose(plane, odom.position, odom.angle);
  msg.pose.covariance = covariance(plane, odom.def.poseVarianceXy, odom.def.poseVarianceTheta);
  msg.twist.twist.linear.x = odom.speed;  // the body's x is 3D x in both planes
  if (plane == Plane::XY) {
    msg.twist.twist.linear.y = odom.sideSpeed;  // drives are top-down only
    msg.twist.twist.angular.z = odom.turnRate;
  } else {
    msg.twist.twist.angular.y = -odom.turnRate;  // about the xz plane's normal, -y
  }
  msg.twist.covariance = covariance(plane, odom.def.twistVarianceXy, odom.def.twistVarianceTheta);
  return msg;
}

nav_msgs::Odometry toGroundTruth(Plane plane, const std::string& worldFrame,
                                 const OdometryReading& odom, const ros::Time& stamp) {
  nav_msgs::Odometry msg;
  msg.header.frame_id = worldFrame;
  msg.header.stamp = stamp;
  msg.child_frame_id = odom.body;
  msg.pose.pose = toPose(plane, odom.truePosition, odom.trueAngle);
  const Vec2 v = Rot(odom.trueAngle).applyInverse(odom.trueVelocity);  // in the body's frame
  msg.twist.twist.linear.x = v.x();
  if (plane == Plane::XY) {
    msg.twist.twist.linear.y = v.y();
    msg.twist.twist.angular.z = odom.trueTurnRate;
  } else {
    msg.twist.twist.linear.z = v.y();
    msg.twist.twist.angular.y = -odom.trueTurnRate;
  }
  return msg;
}

geometry_msgs::TransformStamped odomToBody(Plane plane, const OdometryReading& odom,
                                           const ros::Time& stamp) {
  geometry_msgs::TransformStamped t = stamped(odom.def.odomFrame, odom.body, stamp);
  t.transform = toTransform(plane, odom.position, odom.angle);
  return t;
}

geometry_msgs::TransformStamped worldToOdom(Plane plane, const std::string& worldFrame,
                                            const OdometryReading& odom, const ros::Time& stamp) {
  // world <- odom = (world <- body) (odom <- body)^-1
  const double angle = odom.trueAngle - odom.angle;
  const Vec2 position = odom.truePosition - Rot(angle).apply(odom.position);
  geometry_msgs::TransformStamped t = stamped(worldFrame, odom.def.odomFrame, stamp);
  t.transform = toTransform(plane, position, angle);
  return t;
}

sensor_msgs::LaserScan toLaserScan(const ScanReading& scan, const ros::Time& stamp) {
  sensor_msgs::LaserScan msg;
  msg.header.frame_id = scan.frame;
  msg.header.stamp = stamp;
  msg.angle_min = static_cast<float>(scan.def.angleMin);
  msg.angle_max =
      static_cast<float>(scan.def.angleMin + (scan.beams - 1) * scan.def.angleIncrement);
  msg.angle_increment = static_cast<float>(scan.def.angleIncrement);
  msg.time_increment = 0.0f;
  msg.scan_time = static_cast<float>(1.0 / scan.def.updateRate);
  msg.range_min = static_cast<float>(scan.def.rangeMin);
  msg.range_max = static_cast<float>(scan.def.rangeMax);
  msg.ranges = scan.ranges;
  msg.intensities = scan.intensities;
  return msg;
}

sensor_msgs::Imu toImu(const ImuReading& reading, const ros::Time& stamp) {
  sensor_msgs::Imu msg;
  msg.header.frame_id = reading.frame;
  msg.header.stamp = stamp;
  msg.orientation = toMsg(reading.orientation);
  const Eigen::Vector3d& w = reading.angularVelocity;
  msg.angular_velocity.x = w.x();
  msg.angular_velocity.y = w.y();
  msg.angular_velocity.z = w.z();
  const Eigen::Vector3d& a = reading.linearAcceleration;
  msg.linear_acceleration.x = a.x();
  msg.linear_acceleration.y = a.y();
  msg.linear_acceleration.z = a.z();
  auto diagonal = [](const Eigen::Vector3d& stddev, boost::array<double, 9>* c) {
    c->fill(0.0);
    for (int i = 0; i < 3; ++i) (*c)[4 * i] = std::max(stddev[i] * stddev[i], kExactVariance);
  };
  diagonal(reading.def.orientationNoise, &msg.orientation_covariance);
  diagonal(reading.def.angularVelocityNoise, &msg.angular_velocity_covariance);
  diagonal(reading.def.linearAccelerationNoise, &msg.linear_acceleration_covariance);
  return msg;
}

impulse2d::ContactArray toContactArray(const BumperReading& change, const std::string& worldFrame,
                                       const ros::Time& stamp) {
  impulse2d::ContactArray msg;
  msg.header.frame_id = worldFrame;
  msg.header.stamp = stamp;
  for (const ContactSnapshot& c : change.contacts) msg.contacts.push_back(toContactMsg(c));
  return msg;
}

geometry_msgs::TransformStamped fixedTransform(Plane plane, const std::string& worldFrame,
                                               const FixedFrame& frame, const ros::Time& stamp) {
  geometry_msgs::TransformStamped t =
      stamped(frame.parent.empty() ? worldFrame : frame.parent, frame.name, stamp);
  if (frame.laser) {
    t.transform = toTransform(plane, frame.offset, frame.offsetAngle);
    Eigen::Quaterniond turn = Eigen::Quaterniond::Identity();
    if (plane == Plane::XZ) turn = Eigen::AngleAxisd(0.5 * kPi, Eigen::Vector3d::UnitX());
    if (frame.flip) turn = turn * Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX());
    if (plane == Plane::XZ || frame.flip) {
      t.transform.rotation = toMsg(fromMsg(t.transform.rotation) * turn);
    }
    return t;
  }
  t.transform.translation.x = frame.pose.translation().x();
  t.transform.translation.y = frame.pose.translation().y();
  t.transform.translation.z = frame.pose.translation().z();
  t.transform.rotation = toMsg(Eigen::Quaterniond(frame.pose.linear()).normalized());
  return t;
}

}  // namespace bridge
}  // namespace impulse2d
