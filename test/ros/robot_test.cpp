// Robots in the loop against the world node (robot.test, test/ros/robot_scene.yaml): cmd_vel
// moves the robot through the physics and its odometry agrees with the ground truth; the wall
// 3 m ahead appears at 3 m in the scan; the bumper reports the wall when the robot reaches it; a
// drive without commands stops; the frames on tf; devices through ~load_scene; ~ray_cast and
// ~query_point.
#include "robot_test_util.hpp"

#include <impulse2d/ContactArray.h>
#include <impulse2d/LoadScene.h>
#include <impulse2d/QueryPoint.h>
#include <impulse2d/RayCast.h>
#include <impulse2d/SetBodyState.h>
#include <nav_msgs/Odometry.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_ros/transform_listener.h>

#include <cmath>

namespace impulse2d_test {
namespace {

impulse2d::LoadScene::Response loadScene(const std::string& yaml) {
  impulse2d::LoadScene srv;
  srv.request.yaml = yaml;
  call("load_scene", srv);
  return srv.response;
}

class Robot : public testing::Test {
 protected:
  void SetUp() override { emptyCall("reset"); }
};

TEST_F(Robot, HalfAMetrePerSecondForTwoSecondsMovesOneMetreAndTheOdometryAgrees) {
  PausedWorld paused;
  emptyCall("reset");
  Latest<nav_msgs::Odometry> odom(worldNs() + "/odom");
  Latest<rosgraph_msgs::Clock> clock("/clock");
  CmdVel cmdVel("cmd_vel");
  impulse2d::GetBodyState::Response start;
  ASSERT_TRUE(getState("robot", &start));

  // Step by step until the command has arrived; steps before it leave the robot at rest. The
  // step that first moves it is the first of 200 (2 s of simulated time) at 0.5 m/s.
  cmdVel.send(0.5);
  ASSERT_TRUE(waitFor(
      [&] {
        stepWorld(1);
        return speedOf("robot") > 0.0;
      },
      kWait));
  stepWorld(199);
  cmdVel.send(0.0);
  ros::WallDuration(0.5).sleep();
  // Had the zero come late, each step before it would add 5 mm: count them (none, normally).
  int late = 0;
  for (; late < 100; ++late) {
    stepWorld(1);
    if (speedOf("robot") < 0.499) break;  // the first step towards 0 leaves 0.48 m/s
  }
  EXPECT_LE(late, 5);
  stepWorld(100);  // the ramp down takes 25 steps
  EXPECT_LT(speedOf("robot"), 1e-9);

  impulse2d::GetBodyState::Response end;
  ASSERT_TRUE(getState("robot", &end));
  const double moved = end.pose.x - start.pose.x;
  const double expected = 1.0 + 0.005 * late;  // the ramps of 2 m/s^2 up and down cancel
  EXPECT_NEAR(moved, expected, 0.02 * expected) << late << " late steps";
  EXPECT_NEAR(end.pose.y, start.pose.y, 1e-6);
  EXPECT_NEAR(end.pose.theta, start.pose.theta, 1e-6);

  // The odometry, in the frame of the robot's start pose, agrees with the ground truth. It is
  // published with tf when the simulated time moved: wait for the one of the last step, whose
  // time /clock tells once the world is paused (it sends /clock then too).
  const int clocks = clock.count();
  ASSERT_TRUE(waitFor([&] { return clock.count() >= clocks + 2; }, kWait));
  const ros::Time last = clock.get()->clock;
  ASSERT_TRUE(waitFor([&] { return odom.get() && odom.get()->header.stamp == last; }, kWait));
  const nav_msgs::Odometry::ConstPtr reading = odom.get();
  EXPECT_EQ(reading->header.frame_id, "odom");
  EXPECT_EQ(reading->child_frame_id, "robot");
  EXPECT_NEAR(reading->pose.pose.position.x, moved, 0.01);
  EXPECT_NEAR(reading->pose.pose.position.y, 0.0, 0.01);
  EXPECT_EQ(reading->twist.twist.linear.x, 0.0);
  EXPECT_EQ(reading->pose.covariance[0], 0.001);    // x
  EXPECT_EQ(reading->pose.covariance[14], 1e6);     // z: not in the plane
  EXPECT_EQ(reading->twist.covariance[35], 0.001);  // turning about z
}

TEST_F(Robot, AWallThreeMetresAheadAppearsAtThreeMetres) {
  Latest<sensor_msgs::LaserScan> scan(worldNs() + "/scan");
  ASSERT_TRUE(waitFor([&] { return scan.count() >= 2; }, kWait));
  const sensor_msgs::LaserScan::ConstPtr msg = scan.get();
  EXPECT_EQ(msg->header.frame_id, "robot/laser");
  ASSERT_EQ(msg->ranges.size(), 301u);
  EXPECT_NEAR(msg->angle_min, -1.5, 1e-6);
  EXPECT_NEAR(msg->angle_max, 1.5, 1e-5);
  EXPECT_NEAR(msg->angle_increment, 0.01, 1e-9);
  EXPECT_NEAR(msg->scan_time, 0.05, 1e-9);   // 20 Hz of simulated time
  EXPECT_NEAR(msg->ranges[150], 3.0, 0.01);  // the beam at angle 0 points at the wall
  EXPECT_NEAR(msg->ranges[120], 3.0 / std::cos(0.3), 0.01);  // 0.93 m aside, on the 3 m wall
  // Along -1.5 rad the beam passes the wall's end: no return within 10 m reads +inf (REP 117).
  EXPECT_TRUE(std::isinf(msg->ranges[0]) && msg->ranges[0] > 0.0) << msg->ranges[0];
}

TEST_F(Robot, TheBumperReportsTheWallWhenTheRobotReachesIt) {
  Latest<impulse2d::ContactArray> bumper(worldNs() + "/bumper");
  // After the reset it touches nothing (a message from before the reset may come first: the
  // topic is latched).
  ASSERT_TRUE(waitFor(
      [&] {
        const impulse2d::ContactArray::ConstPtr msg = bumper.get();
        return msg && msg->contacts.empty();
      },
      kWait));
  impulse2d::SetBodyState place;
  place.request.name = "robot";
  place.request.pose.x = 2.5;  // its front 0.35 m from the wall
  ASSERT_TRUE(call("set_body_state", place) && place.response.success);
  CmdVel cmdVel("cmd_vel");
  cmdVel.send(0.3);
  const bool touched = waitFor(
      [&] {
        const impulse2d::ContactArray::ConstPtr msg = bumper.get();
        return msg && !msg->contacts.empty() && msg->contacts[0].body_b == "wall";
      },
      kWait);
  cmdVel.send(0.0);
  ASSERT_TRUE(touched);
  const impulse2d::Contact& contact = bumper.get()->contacts[0];
  EXPECT_EQ(contact.body_a, "robot");
  EXPECT_NEAR(contact.normal.x, 1.0, 1e-6);  // from the robot to the wall
  EXPECT_NEAR(contact.point.x, 3.1, 0.02);
}

TEST_F(Robot, WithoutCmdVelTheDriveStops) {
  Latest<nav_msgs::Odometry> odom(worldNs() + "/rover/odom");
  impulse2d::GetBodyState::Response start;
  ASSERT_TRUE(getState("rover", &start));
  CmdVel cmdVel("rover/cmd_vel");
  cmdVel.send(0.5);  // once: its drive stops 0.5 s of simulated time later
  ASSERT_TRUE(waitFor([&] { return speedOf("rover") > 0.3; }, kWait));
  ASSERT_TRUE(waitFor([&] { return speedOf("rover") < 1e-9; }, kWait));
  impulse2d::GetBodyState::Response end;
  ASSERT_TRUE(getState("rover", &end));
  // Up to speed in 0.25 s, on until 0.5 s, down in 0.25 s: about 0.25 m, not on and on.
  EXPECT_NEAR(end.pose.x - start.pose.x, 0.25, 0.05);
  ASSERT_TRUE(
      waitFor([&] { return odom.get() && odom.get()->twist.twist.linear.x == 0.0; }, kWait));
  EXPECT_EQ(odom.get()->header.frame_id, "rover_odom");
}

TEST_F(Robot, FramesOnTf) {
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  auto lookup = [&](const std::string& parent, const std::string& child) {
    EXPECT_TRUE(waitFor([&] { return buffer.canTransform(parent, child, ros::Time(0)); }, kWait))
        << parent << " -> " << child;
    return buffer.lookupTransform(parent, child, ros::Time(0)).transform;
  };
  // The laser 0.1 m ahead of the robot's origin, on /tf_static.
  const geometry_msgs::Transform laser = lookup("robot", "robot/laser");
  EXPECT_NEAR(laser.translation.x, 0.1, 1e-9);
  EXPECT_NEAR(laser.translation.y, 0.0, 1e-9);
  // REP 105: odom -> robot from the odometry, and world -> odom so that world -> robot is the
  // ground truth.
  lookup("odom", "robot");
  lookup("world", "odom");
  lookup("rover_odom", "rover");
  impulse2d::GetBodyState::Response truth;
  ASSERT_TRUE(getState("rover", &truth));
  const geometry_msgs::Transform rover = lookup("world", "rover");
  EXPECT_NEAR(rover.translation.x, truth.pose.x, 1e-6);
  EXPECT_NEAR(rover.translation.y, truth.pose.y, 1e-6);
}

TEST_F(Robot, DevicesComeAndGoWithScenesAndBodies) {
  const std::string crate =
      "bodies: [{name: crate, position: [0.0, -3.0], shapes: [{}]}]\n"
      "devices: [{type: laser, name: crate_laser, body: crate, topic: crate_scan}]";
  impulse2d::LoadScene::Response res = loadScene(crate);
  ASSERT_TRUE(res.success) << res.message;
  Latest<sensor_msgs::LaserScan> scan(worldNs() + "/crate_scan");
  ASSERT_TRUE(waitFor([&] { return scan.count() >= 1; }, kWait));
  EXPECT_EQ(scan.get()->header.frame_id, "crate/crate_laser");
  // Deleting the body takes its laser along: the same scene loads again.
  ASSERT_TRUE(remove("crate"));
  res = loadScene(crate);
  EXPECT_TRUE(res.success) << res.message;

  // Refused whole, naming the device and key; nothing is added.
  const std::vector<std::pair<std::string, std::string>> refused = {
      {"devices: [{type: sonar, name: s, body: robot}]",
       "devices[0] 's': type: must be diff_drive, omni, ackermann, laser, bumper or imu"},
      {"devices: [{type: bumper, name: b2, body: robot, topic: scan}]",
       "devices[0] 'b2': topic: 'scan' is already used by the device 'laser'"},
      {"bodies: [{name: box2, shapes: [{}]}]\n"
       "devices: [{type: bumper, name: b3, body: nobody, topic: bumper3}]",
       "devices[0] 'b3': body: no body named 'nobody'"},
      {"devices: [{type: laser, name: l4, body: robot, range_max: -1}]",
       "devices[0] 'l4': range_max: must be finite and > 0"},
  };
  for (const auto& [yaml, message] : refused) {
    res = loadScene(yaml);
    EXPECT_FALSE(res.success) << yaml;
    EXPECT_NE(res.message.find(message), std::string::npos) << res.message;
  }
  impulse2d::GetBodyState::Response unused;
  EXPECT_FALSE(getState("box2", &unused));
}

TEST_F(Robot, RayCastAndPointQueryServices) {
  impulse2d::RayCast ray;
  ray.request.start.x = 0.0;
  ray.request.end.x = 10.0;
  ray.request.ignore_bodies = {"robot"};
  ASSERT_TRUE(call("ray_cast", ray));
  ASSERT_TRUE(ray.response.success) << ray.response.message;
  EXPECT_TRUE(ray.response.hit);
  EXPECT_EQ(ray.response.body, "wall");
  EXPECT_NEAR(ray.response.point.x, 3.1, 1e-9);
  EXPECT_NEAR(ray.response.normal.x, -1.0, 1e-9);
  EXPECT_NEAR(ray.response.fraction, 0.31, 1e-9);
  EXPECT_NEAR(ray.response.distance, 3.1, 1e-9);
  // From inside the robot, the robot itself at once.
  ray.request.ignore_bodies.clear();
  ASSERT_TRUE(call("ray_cast", ray));
  EXPECT_EQ(ray.response.body, "robot");
  EXPECT_EQ(ray.response.fraction, 0.0);
  // Into empty space.
  ray.request.end.x = -10.0;
  ray.request.start.x = -1.0;
  ASSERT_TRUE(call("ray_cast", ray));
  EXPECT_TRUE(ray.response.success);
  EXPECT_FALSE(ray.response.hit);
  // Refused, naming the field.
  ray.request.ignore_bodies = {"nobody"};
  ASSERT_TRUE(call("ray_cast", ray));
  EXPECT_FALSE(ray.response.success);
  EXPECT_EQ(ray.response.message, "ignore_bodies[0]: no body named 'nobody'");
  ray.request.ignore_bodies.clear();
  ray.request.start.y = NAN;
  ASSERT_TRUE(call("ray_cast", ray));
  EXPECT_EQ(ray.response.message, "start: must be finite");

  impulse2d::QueryPoint query;
  query.request.point.x = 3.2;
  ASSERT_TRUE(call("query_point", query));
  EXPECT_EQ(query.response.bodies, std::vector<std::string>{"wall"});
  query.request.point.x = 1.0;
  ASSERT_TRUE(call("query_point", query));
  EXPECT_TRUE(query.response.success);
  EXPECT_TRUE(query.response.bodies.empty());
  query.request.point.x = INFINITY;
  ASSERT_TRUE(call("query_point", query));
  EXPECT_FALSE(query.response.success);
  EXPECT_EQ(query.response.message, "point: must be finite");
}

}  // namespace
}  // namespace impulse2d_test
