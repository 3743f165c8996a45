// Models against the world node or nodelet (models.test, models_nodelet.test,
// test/ros/models_scene.yaml): one model file placed twice by the scene, each robot in its own
// namespace (/r1/cmd_vel, /r1/odom, /r1/scan; frames r1/odom, r1/base_link); models spawned from
// a file and from YAML text, moved, deleted and refused; ~reset; and /clock published because
// /use_sim_time is set.
#include "robot_test_util.hpp"

#include <impulse2d/DeleteModel.h>
#include <impulse2d/MoveModel.h>
#include <impulse2d/SpawnModel.h>
#include <nav_msgs/Odometry.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_ros/transform_listener.h>

#include <cmath>

namespace impulse2d_test {
namespace {

const char* const kModelFile = "package://impulse2d/config/models/diff_robot.yaml";

class Models : public testing::Test {
 protected:
  void SetUp() override { emptyCall("reset"); }
};

impulse2d::SpawnModel::Response spawnModel(const std::string& name, const std::string& file,
                                           double x, double y, double theta,
                                           const std::string& ns = "",
                                           const std::string& yaml = "") {
  impulse2d::SpawnModel srv;
  srv.request.model_name = name;
  srv.request.robot_namespace = ns;
  srv.request.file = file;
  srv.request.model_yaml = yaml;
  srv.request.pose.x = x;
  srv.request.pose.y = y;
  srv.request.pose.theta = theta;
  EXPECT_TRUE(call("spawn_model", srv));
  return srv.response;
}

impulse2d::MoveModel::Response moveModel(const std::string& name, double x, double y,
                                         double theta) {
  impulse2d::MoveModel srv;
  srv.request.model_name = name;
  srv.request.pose.x = x;
  srv.request.pose.y = y;
  srv.request.pose.theta = theta;
  EXPECT_TRUE(call("move_model", srv));
  return srv.response;
}

impulse2d::DeleteModel::Response deleteModel(const std::string& name) {
  impulse2d::DeleteModel srv;
  srv.request.model_name = name;
  EXPECT_TRUE(call("delete_model", srv));
  return srv.response;
}

TEST_F(Models, TheWorldIsTheClockWhenUseSimTimeIsSet) {
  // models.test sets /use_sim_time and leaves ~publish_clock out.
  Latest<rosgraph_msgs::Clock> clock("/clock");
  ASSERT_TRUE(waitFor([&] { return clock.count() >= 2; }, kWait));
  const ros::Time first = clock.get()->clock;
  ASSERT_TRUE(waitFor([&] { return clock.get()->clock > first; }, kWait));
}

TEST_F(Models, EachRobotOfTheSceneListensAndSpeaksInItsNamespace) {
  PausedWorld paused;
  Latest<nav_msgs::Odometry> odom("/r1/odom");
  Latest<nav_msgs::Odometry> truth("/r2/ground_truth");
  Latest<sensor_msgs::LaserScan> scan("/r1/scan");
  CmdVel cmdVel("/r1/cmd_vel");
  cmdVel.send(0.5);
  ASSERT_TRUE(waitFor(
      [&] {
        stepWorld(1);
        return speedOf("r1/base_link") > 0.0;
      },
      kWait));
  stepWorld(100);
  // r1 drives along +x; r2, from the same file, stays put.
  impulse2d::GetBodyState::Response r1, r2;
  ASSERT_TRUE(getState("r1/base_link", &r1));
  ASSERT_TRUE(getState("r2/base_link", &r2));
  EXPECT_GT(r1.pose.x, 0.2);
  EXPECT_NEAR(r1.pose.y, 0.0, 1e-6);
  EXPECT_NEAR(r2.pose.x, 0.0, 1e-9);
  EXPECT_NEAR(r2.pose.y, 3.0, 1e-9);
  EXPECT_NEAR(r2.pose.theta, M_PI / 2, 1e-9);

  ASSERT_TRUE(waitFor(
      [&] {
        stepWorld(1);  // paused: readings come with steps, once someone listens
        return odom.get() && truth.get() && scan.get();
      },
      kWait));
  ASSERT_TRUE(getState("r1/base_link", &r1));
  EXPECT_EQ(odom.get()->header.frame_id, "r1/odom");
  EXPECT_EQ(odom.get()->child_frame_id, "r1/base_link");
  EXPECT_EQ(truth.get()->child_frame_id, "r2/base_link");
  EXPECT_NEAR(truth.get()->pose.pose.position.y, 3.0, 1e-9);
  EXPECT_EQ(scan.get()->header.frame_id, "r1/base_link/laser");
  // The east wall's face at x = 5.9 ahead of r1's laser (0.12 m before its centre).
  const sensor_msgs::LaserScan& s = *scan.get();
  const size_t ahead = static_cast<size_t>(std::lround(-s.angle_min / s.angle_increment));
  ASSERT_LT(ahead, s.ranges.size());
  EXPECT_NEAR(s.ranges[ahead], 5.9 - r1.pose.x - 0.12, 0.1);

  // tf: world -> r1/odom -> r1/base_link -> r1/base_link/laser.
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  ASSERT_TRUE(waitFor(
      [&] {
        stepWorld(1);  // paused: each step publishes the moving frames once
        return buffer.canTransform("world", "r1/base_link/laser", ros::Time(0)) &&
               buffer.canTransform("r2/odom", "r2/base_link", ros::Time(0));
      },
      kWait));
}

TEST_F(Models, SpawnedMovedAndDeletedWhole) {
  PausedWorld paused;
  impulse2d::SpawnModel::Response spawned = spawnModel("r3", kModelFile, -3.0, -3.0, 0.0);
  ASSERT_TRUE(spawned.success) << spawned.message;
  EXPECT_EQ(spawned.bodies, std::vector<std::string>{"r3/base_link"});
  EXPECT_EQ(spawned.devices, (std::vector<std::string>{"r3/drive", "r3/laser", "r3/bumper"}));
  // Its drive listens on /r3/cmd_vel at once.
  CmdVel cmdVel("/r3/cmd_vel");
  cmdVel.send(1.0, 0.5);
  ASSERT_TRUE(waitFor(
      [&] {
        stepWorld(1);
        return speedOf("r3/base_link") > 0.0;
      },
      kWait));
  stepWorld(50);
  ASSERT_GT(speedOf("r3/base_link"), 0.3);

  // Moved: placed as if spawned at (4, -2) facing -y, and stopped, drive and all.
  impulse2d::MoveModel::Response moved = moveModel("r3", 4.0, -2.0, -M_PI / 2);
  ASSERT_TRUE(moved.success) << moved.message;
  impulse2d::GetBodyState::Response state;
  ASSERT_TRUE(getState("r3/base_link", &state));
  EXPECT_NEAR(state.pose.x, 4.0, 1e-9);
  EXPECT_NEAR(state.pose.y, -2.0, 1e-9);
  EXPECT_NEAR(std::remainder(state.pose.theta + M_PI / 2, 2 * M_PI), 0.0, 1e-9);
  EXPECT_EQ(speedOf("r3/base_link"), 0.0);
  stepWorld(1);
  EXPECT_EQ(speedOf("r3/base_link"), 0.0);  // the drive was halted, not only the body

  // Deleted whole; the name is free again.
  impulse2d::DeleteModel::Response deleted = deleteModel("r3");
  ASSERT_TRUE(deleted.success) << deleted.message;
  EXPECT_FALSE(getState("r3/base_link", &state));
  EXPECT_FALSE(deleteModel("r3").success);
  spawned = spawnModel("r3", kModelFile, -3.0, -3.0, 0.0);
  EXPECT_TRUE(spawned.success) << spawned.message;

  // From YAML text, in a namespace of its own; gone after ~reset, while the scene's come back.
  spawned = spawnModel("crate", "", 2.0, -5.0, 0.0, "props",
                       "bodies: [{name: box, shapes: [{type: box, size: [0.5, 0.5]}]}]");
  ASSERT_TRUE(spawned.success) << spawned.message;
  EXPECT_TRUE(getState("props/box", &state));
  emptyCall("reset");
  EXPECT_FALSE(getState("props/box", &state));
  EXPECT_FALSE(getState("r3/base_link", &state));
  EXPECT_TRUE(getState("r1/base_link", &state));
  EXPECT_TRUE(moveModel("r1", 1.0, 1.0, 0.0).success);
}

TEST_F(Models, BadRequestsAreRefusedAndChangeNothing) {
  struct Case {
    impulse2d::SpawnModel::Response response;
    const char* error;
  };
  const Case cases[] = {
      {spawnModel("r1", kModelFile, 5.0, 5.0, 0.0, "other"),
       "model_name: a model named 'r1' already exists"},
      {spawnModel("r9", kModelFile, 5.0, 5.0, 0.0, "r1"),
       "'r1/drive': name: already used by the device 'r1/drive'"},
      {spawnModel("", kModelFile, 5.0, 5.0, 0.0), "model_name: must not be empty"},
      {spawnModel("r9", "", 5.0, 5.0, 0.0), "file, model_yaml: give one"},
      {spawnModel("r9", kModelFile, 5.0, 5.0, 0.0, "", "bodies: []"), "give one, not both"},
      {spawnModel("r9", "config/models/diff_robot.yaml", 5.0, 5.0, 0.0),
       "file: must be absolute or package://"},
      {spawnModel("r9", "package://no_such_package/m.yaml", 5.0, 5.0, 0.0), "no_such_package"},
      {spawnModel("r9", "/nonexistent/m.yaml", 5.0, 5.0, 0.0), "cannot open"},
      {spawnModel("r9", kModelFile, NAN, 5.0, 0.0), "pose.x: must be finite"},
      {spawnModel("r9", "", 0, 0, 0, "", "world: {}"), "model_yaml: world: unknown key"},
      {spawnModel("r9", "", 0, 0, 0, "bad-ns", "bodies: []"), "namespace: 'bad-ns'"},
  };
  for (const Case& c : cases) {
    EXPECT_FALSE(c.response.success) << c.error;
    EXPECT_NE(c.response.message.find(c.error), std::string::npos) << c.response.message;
  }
  impulse2d::GetBodyState::Response state;
  EXPECT_FALSE(getState("r9/base_link", &state));
  EXPECT_FALSE(getState("other/base_link", &state));
  EXPECT_FALSE(moveModel("nobody", 0, 0, 0).success);
  EXPECT_NE(moveModel("r1", INFINITY, 0, 0).message.find("pose.x: must be finite"),
            std::string::npos);
  EXPECT_NE(moveModel("r1", 2e6, 0, 0).message.find("within 1e6 m"), std::string::npos);
  EXPECT_NE(deleteModel("").message.find("model_name: must not be empty"), std::string::npos);
  ASSERT_TRUE(getState("r1/base_link", &state));
  EXPECT_NEAR(state.pose.x, 0.0, 1e-9);
}

}  // namespace
}  // namespace impulse2d_test
