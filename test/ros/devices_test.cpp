// The devices of issue 24 against the world node or nodelet (devices.test, devices_nodelet.test,
// test/ros/devices_scene.yaml), read through their stock message types: an omni base moving
// sideways, an Ackermann car held to its steering limit, an IMU on a spinning disc, and two
// lasers on one body, one upside down and sweeping clockwise, with intensities.
#include "robot_test_util.hpp"

#include <impulse2d/SetBodyState.h>
#include <nav_msgs/Odometry.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_ros/transform_listener.h>

#include <Eigen/Geometry>

#include <cmath>

namespace impulse2d_test {
namespace {

class Devices : public testing::Test {
 protected:
  void SetUp() override { emptyCall("reset"); }
};

// Steps one at a time until `body` moves (the command has arrived), then `more` steps.
void stepFromFirstMotion(const std::string& body, uint32_t more) {
  ASSERT_TRUE(waitFor(
      [&] {
        stepWorld(1);
        return speedOf(body) > 0.0;
      },
      kWait));
  stepWorld(more);
}

TEST_F(Devices, AnOmniBaseMovesSidewaysAndItsOdometrySaysSo) {
  PausedWorld paused;
  emptyCall("reset");
  Latest<nav_msgs::Odometry> odom(worldNs() + "/base/odom");
  Latest<nav_msgs::Odometry> truth(worldNs() + "/base/ground_truth");
  CmdVel cmdVel("base/cmd_vel");
  cmdVel.send(0.0, 0.0, 0.5);  // linear.y: 0.5 m/s to the left
  stepFromFirstMotion("rover", 199);
  impulse2d::GetBodyState::Response state;
  ASSERT_TRUE(getState("rover", &state));
  // 2 s at 0.5 m/s less half the 0.25 s ramp: 0.9375 m along +y, none along x, no turn.
  EXPECT_NEAR(state.pose.y, 0.9375, 0.02);
  EXPECT_NEAR(state.pose.x, 0.0, 1e-6);
  EXPECT_NEAR(state.pose.theta, 0.0, 1e-6);
  EXPECT_NEAR(state.twist.linear.y, 0.5, 1e-6);
  // The world is paused: the odometry of the last step arrives, whatever came before it.
  stepWorld(1);
  ASSERT_TRUE(waitFor(
      [&] {
        const nav_msgs::Odometry::ConstPtr m = odom.get();
        return m && std::abs(m->pose.pose.position.y - state.pose.y) < 0.01;
      },
      kWait));
  EXPECT_EQ(odom.get()->header.frame_id, "base_odom");
  EXPECT_NEAR(odom.get()->twist.twist.linear.y, 0.5, 1e-9);
  EXPECT_NEAR(odom.get()->twist.twist.linear.x, 0.0, 1e-9);
  // The ground truth beside it (base/odom -> base/ground_truth): the body's own pose in the world
  // frame and its twist in its own frame, as ~get_body_state has them.
  ASSERT_TRUE(getState("rover", &state));
  ASSERT_TRUE(waitFor(
      [&] {
        const nav_msgs::Odometry::ConstPtr m = truth.get();
        return m && std::abs(m->pose.pose.position.y - state.pose.y) < 1e-9;
      },
      kWait));
  EXPECT_EQ(truth.get()->header.frame_id, "world");
  EXPECT_EQ(truth.get()->child_frame_id, "rover");
  EXPECT_NEAR(truth.get()->pose.pose.position.x, state.pose.x, 1e-9);
  EXPECT_NEAR(truth.get()->twist.twist.linear.y, 0.5, 1e-6);
}

TEST_F(Devices, AnAckermannCarTurnsNoTighterThanItsSteeringAllows) {
  PausedWorld paused;
  emptyCall("reset");
  Latest<nav_msgs::Odometry> odom(worldNs() + "/car/odom");
  CmdVel cmdVel("car/cmd_vel");
  cmdVel.send(1.0, 5.0);  // a radius of 0.2 m asked for; the tightest is 0.4 / tan(0.5) = 0.73 m
  stepFromFirstMotion("car", 300);
  const double limitRate = 1.0 * std::tan(0.5) / 0.4;  // v tan(max_steering_angle) / wheelbase
  impulse2d::GetBodyState::Response state;
  ASSERT_TRUE(getState("car", &state));
  EXPECT_NEAR(state.twist.angular.z, limitRate, 1e-3);
  stepWorld(1);
  ASSERT_TRUE(waitFor(
      [&] {
        const nav_msgs::Odometry::ConstPtr m = odom.get();
        return m && std::abs(m->twist.twist.angular.z - limitRate) < 1e-6;
      },
      kWait));
  const nav_msgs::Odometry::ConstPtr reading = odom.get();
  EXPECT_EQ(reading->child_frame_id, "car");
  EXPECT_NEAR(reading->twist.twist.linear.x, 1.0, 1e-9);  // the rear axle's speed
  EXPECT_NEAR(reading->twist.twist.angular.z, limitRate, 1e-9);
  EXPECT_GE(reading->twist.twist.linear.x / reading->twist.twist.angular.z,
            0.4 / std::tan(0.5) - 1e-9);
}

TEST_F(Devices, AnImuOnASpinningDiscReadsTheRateAndThePullAtItsMount) {
  Latest<sensor_msgs::Imu> imu(worldNs() + "/imu");
  impulse2d::SetBodyState spin;
  spin.request.name = "spinner";
  spin.request.pose.y = -6.0;
  spin.request.twist.angular.z = 2.0;
  ASSERT_TRUE(call("set_body_state", spin) && spin.response.success) << spin.response.message;
  const int before = imu.count();
  ASSERT_TRUE(waitFor([&] { return imu.count() >= before + 3; }, kWait));
  const sensor_msgs::Imu::ConstPtr msg = imu.get();
  EXPECT_EQ(msg->header.frame_id, "spinner/imu");
  EXPECT_NEAR(msg->angular_velocity.z, 2.0, 0.05);  // noise of 0.01 rad/s
  EXPECT_EQ(msg->angular_velocity.x, 0.0);
  // 0.2 m off the centre at 2 rad/s: w^2 r = 0.8 m/s^2 towards the centre, the unit's -x.
  EXPECT_NEAR(msg->linear_acceleration.x, -0.8, 1e-6);
  EXPECT_NEAR(msg->linear_acceleration.y, 0.0, 1e-6);
  EXPECT_NEAR(msg->linear_acceleration.z, 9.81 + 0.1, 1e-9);  // the floor's support, and a bias
  // Yaw only (REP 145), a unit quaternion.
  EXPECT_NEAR(msg->orientation.x, 0.0, 1e-12);
  EXPECT_NEAR(msg->orientation.y, 0.0, 1e-12);
  EXPECT_NEAR(std::hypot(msg->orientation.z, msg->orientation.w), 1.0, 1e-9);
  // Covariances: each axis's noise squared; a noise-free axis 1e-9, not 0 (which reads unknown).
  EXPECT_NEAR(msg->angular_velocity_covariance[8], 1e-4, 1e-12);
  EXPECT_EQ(msg->angular_velocity_covariance[0], 1e-9);
  EXPECT_EQ(msg->angular_velocity_covariance[1], 0.0);
  EXPECT_EQ(msg->linear_acceleration_covariance[4], 1e-9);
  EXPECT_EQ(msg->orientation_covariance[8], 1e-9);
}

TEST_F(Devices, TwoLasersOnOneBodyOneUpsideDownAndClockwiseWithIntensities) {
  Latest<sensor_msgs::LaserScan> front(worldNs() + "/front_scan");
  Latest<sensor_msgs::LaserScan> under(worldNs() + "/under_scan");
  ASSERT_TRUE(waitFor([&] { return front.count() >= 2 && under.count() >= 2; }, kWait));
  const sensor_msgs::LaserScan::ConstPtr f = front.get();
  EXPECT_EQ(f->header.frame_id, "rover/front");
  ASSERT_EQ(f->ranges.size(), 5u);
  ASSERT_EQ(f->intensities.size(), 5u);
  for (int i = 0; i < 5; ++i) {
    const double angle = -0.5 + 0.25 * i;
    EXPECT_NEAR(f->ranges[i], 3.0 / std::cos(angle), 1e-4) << i;
    EXPECT_FLOAT_EQ(f->intensities[i], 0.5f) << i;  // the wall's reflectance
  }
  const sensor_msgs::LaserScan::ConstPtr u = under.get();
  EXPECT_EQ(u->header.frame_id, "rover/under");
  EXPECT_NEAR(u->angle_min, 0.0, 1e-9);
  EXPECT_NEAR(u->angle_max, -0.5, 1e-6);
  EXPECT_NEAR(u->angle_increment, -0.25, 1e-9);
  ASSERT_EQ(u->ranges.size(), 3u);

  // Where RViz puts each beam's hit: the point at its range along its angle in the scan's frame,
  // through tf into the world. Upside down (the frame rolled half a turn) every hit lands on the
  // wall's face, x = 3.1, on the +y side.
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  ASSERT_TRUE(
      waitFor([&] { return buffer.canTransform("world", "rover/under", ros::Time(0)); }, kWait));
  const geometry_msgs::Transform t =
      buffer.lookupTransform("world", "rover/under", ros::Time(0)).transform;
  const Eigen::Quaterniond q(t.rotation.w, t.rotation.x, t.rotation.y, t.rotation.z);
  EXPECT_NEAR(std::abs(q.x()), 1.0, 1e-9);  // half a turn about x
  for (size_t i = 0; i < u->ranges.size(); ++i) {
    const double angle = u->angle_min + u->angle_increment * i;
    const Eigen::Vector3d inScan(u->ranges[i] * std::cos(angle), u->ranges[i] * std::sin(angle),
                                 0.0);
    const Eigen::Vector3d inWorld =
        q * inScan + Eigen::Vector3d(t.translation.x, t.translation.y, t.translation.z);
    EXPECT_NEAR(inWorld.x(), 3.1, 1e-4) << i;
    EXPECT_NEAR(inWorld.y(), 3.0 * std::tan(0.25 * i), 1e-4) << i;
    EXPECT_FLOAT_EQ(u->intensities[i], 0.5f) << i;
  }
}

}  // namespace
}  // namespace impulse2d_test
