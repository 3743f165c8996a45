// The devices' ROS messages and frames without a master: odometry with its covariances in
// either plane, world -> odom from the ground truth, LaserScan fields, frames fixed to bodies.
#include "../../src/ros/device_messages.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

namespace impulse2d {
namespace bridge {
namespace {

Eigen::Quaterniond quaternion(const geometry_msgs::Quaternion& q) {
  return Eigen::Quaterniond(q.w, q.x, q.y, q.z);
}

OdometryReading reading() {
  OdometryReading odom;
  odom.device = "drive";
  odom.body = "robot";
  odom.def.poseVarianceXy = Vec2(0.1, 0.2);
  odom.def.poseVarianceTheta = 0.3;
  odom.def.twistVarianceXy = Vec2(0.4, 0.5);
  odom.def.twistVarianceTheta = 0.6;
  odom.position = Vec2(1.0, 0.0);
  odom.angle = kPi / 4;
  odom.speed = 0.5;
  odom.turnRate = 0.25;
  odom.truePosition = Vec2(2.0, 1.0);
  odom.trueAngle = kPi / 2;
  return odom;
}

TEST(DeviceMessages, OdometryInTheOdomFrameWithPlanarCovariances) {
  const nav_msgs::Odometry xy = toOdometry(Plane::XY, reading(), ros::Time(3.0));
  EXPECT_EQ(xy.header.frame_id, "odom");
  EXPECT_EQ(xy.child_frame_id, "robot");
  EXPECT_EQ(xy.header.stamp, ros::Time(3.0));
  EXPECT_EQ(xy.pose.pose.position.x, 1.0);
  EXPECT_EQ(xy.twist.twist.linear.x, 0.5);
  EXPECT_EQ(xy.twist.twist.angular.z, 0.25);
  // Row-major 6 x 6 over (x, y, z, about x, about y, about z): the plane's three on the diagonal.
  const double pose[6] = {0.1, 0.2, kUnusedVariance, kUnusedVariance, kUnusedVariance, 0.3};
  const double twist[6] = {0.4, 0.5, kUnusedVariance, kUnusedVariance, kUnusedVariance, 0.6};
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      EXPECT_EQ(xy.pose.covariance[6 * i + j], i == j ? pose[i] : 0.0) << i << ", " << j;
      EXPECT_EQ(xy.twist.covariance[6 * i + j], i == j ? twist[i] : 0.0) << i << ", " << j;
    }
  }
  // In the side view the plane's y is 3D z and its turns are about -y.
  const nav_msgs::Odometry xz = toOdometry(Plane::XZ, reading(), ros::Time(3.0));
  EXPECT_EQ(xz.pose.covariance[14], 0.2);
  EXPECT_EQ(xz.pose.covariance[28], 0.3);
  EXPECT_EQ(xz.pose.covariance[7], kUnusedVariance);
  EXPECT_EQ(xz.twist.twist.angular.y, -0.25);
}

TEST(DeviceMessages, WorldToOdomThenOdomToBodyIsTheGroundTruth) {
  const OdometryReading odom = reading();
  const geometry_msgs::TransformStamped worldOdom =
      worldToOdom(Plane::XY, "world", odom, ros::Time(1.0));
  const geometry_msgs::TransformStamped odomBody = odomToBody(Plane::XY, odom, ros::Time(1.0));
  EXPECT_EQ(worldOdom.header.frame_id, "world");
  EXPECT_EQ(worldOdom.child_frame_id, "odom");
  EXPECT_EQ(odomBody.header.frame_id, "odom");
  EXPECT_EQ(odomBody.child_frame_id, "robot");
  auto isometry = [](const geometry_msgs::Transform& t) {
    Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
    out.translation() = Eigen::Vector3d(t.translation.x, t.translation.y, t.translation.z);
    out.linear() = quaternion(t.rotation).toRotationMatrix();
    return out;
  };
  const Eigen::Isometry3d chain = isometry(worldOdom.transform) * isometry(odomBody.transform);
  EXPECT_TRUE(chain.translation().isApprox(Eigen::Vector3d(2.0, 1.0, 0.0), 1e-12));
  EXPECT_TRUE(chain.linear().isApprox(
      Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix(), 1e-12));
}

TEST(DeviceMessages, LaserScanFields) {
  ScanReading scan;
  scan.frame = "robot/laser";
  scan.def.angleMin = -1.0;
  scan.def.angleMax = 1.0;
  scan.def.angleIncrement = 0.3;  // beams at -1.0 .. 0.8
  scan.def.updateRate = 20.0;
  scan.beams = 7;
  scan.ranges.assign(7, 2.0f);
  const sensor_msgs::LaserScan msg = toLaserScan(scan, ros::Time(2.0));
  EXPECT_EQ(msg.header.frame_id, "robot/laser");
  EXPECT_FLOAT_EQ(msg.angle_max, 0.8f);  // the last beam's angle, as LaserScan defines it
  EXPECT_FLOAT_EQ(msg.angle_increment, 0.3f);
  EXPECT_EQ(msg.time_increment, 0.0f);
  EXPECT_FLOAT_EQ(msg.scan_time, 0.05f);
  EXPECT_FLOAT_EQ(msg.range_min, 0.05f);
  EXPECT_FLOAT_EQ(msg.range_max, 10.0f);
  EXPECT_EQ(msg.ranges.size(), 7u);
}

TEST(DeviceMessages, LaserFramesLieInTheWorldsPlane) {
  FixedFrame laser;
  laser.name = "robot/laser";
  laser.parent = "robot";
  laser.laser = true;
  laser.offset = Vec2(0.1, 0.2);
  // Top-down: the laser's x-y plane is the world's.
  const geometry_msgs::TransformStamped xy =
      fixedTransform(Plane::XY, "world", laser, ros::Time(0.0));
  EXPECT_EQ(xy.header.frame_id, "robot");
  EXPECT_EQ(xy.transform.translation.y, 0.2);
  EXPECT_TRUE(quaternion(xy.transform.rotation).isApprox(Eigen::Quaterniond::Identity()));
  // Side view: turned so that its x stays the body's x and its y is the plane's y (3D z); its
  // z, the beams' axis of rotation, is the plane's normal -y.
  const geometry_msgs::TransformStamped xz =
      fixedTransform(Plane::XZ, "world", laser, ros::Time(0.0));
  EXPECT_EQ(xz.transform.translation.z, 0.2);
  const Eigen::Matrix3d r = quaternion(xz.transform.rotation).toRotationMatrix();
  EXPECT_TRUE(r.col(0).isApprox(Eigen::Vector3d::UnitX(), 1e-12)) << r;
  EXPECT_TRUE(r.col(1).isApprox(Eigen::Vector3d::UnitZ(), 1e-12)) << r;
  EXPECT_TRUE(r.col(2).isApprox(-Eigen::Vector3d::UnitY(), 1e-12)) << r;
  // A URDF frame fixed to the world.
  FixedFrame link;
  link.name = "arm/world";
  link.pose.translation() = Eigen::Vector3d(3.0, 0.0, 1.0);
  const geometry_msgs::TransformStamped fixed =
      fixedTransform(Plane::XZ, "map", link, ros::Time(0.0));
  EXPECT_EQ(fixed.header.frame_id, "map");
  EXPECT_EQ(fixed.child_frame_id, "arm/world");
  EXPECT_EQ(fixed.transform.translation.x, 3.0);
  EXPECT_EQ(fixed.transform.translation.z, 1.0);
}

}  // namespace
}  // namespace bridge
}  // namespace impulse2d
