// A real robot's URDF top-down without a master (issue 25): its wheels folded into the base
// still report joint_states, at the angle they rolled to with the base's motion, and their frames
// turn on /tf.
#include "../../src/ros/sim_world.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

namespace impulse2d {
namespace bridge {
namespace {

// The teaching robot's URDF; without its <gazebo> elements unless `withPlugins`.
std::string teachingRobot(bool withPlugins) {
  std::ifstream in(std::string(IMPULSE2D_SOURCE_DIR) + "/test/urdf/teaching_robot.urdf");
  std::stringstream text;
  text << in.rdbuf();
  std::string xml = text.str();
  if (!withPlugins) xml = xml.substr(0, xml.find("<gazebo>")) + "</robot>\n";
  return xml;
}

double positionOf(const SimWorld& sim, const std::string& joint) {
  for (const JointReading& r : sim.urdfJointStates()) {
    if (r.name == joint) return r.position;
  }
  ADD_FAILURE() << joint << " is not in joint_states";
  return NAN;
}

// A top-down world without gravity holding the teaching robot as model "tb".
void spawnTeachingRobot(SimWorld& sim, bool withPlugins, UrdfRequest* robot, UrdfSpawned* spawned) {
  std::string error;
  ASSERT_TRUE(sim.loadStartScene("world: {plane: xy, gravity: [0, 0], time_step: 0.01}\n", &error))
      << error;
  robot->modelName = "tb";
  robot->xml = teachingRobot(withPlugins);
  ASSERT_TRUE(sim.spawnUrdf(*robot, false, spawned, &error)) << error;
}

TEST(SimWorldWheels, FoldedWheelsRollWithTheBaseWithoutADrive) {
  SimWorld sim;
  std::string error;
  UrdfRequest robot;
  UrdfSpawned spawned;
  ASSERT_NO_FATAL_FAILURE(spawnTeachingRobot(sim, false, &robot, &spawned));
  EXPECT_EQ(spawned.bodies, std::vector<std::string>{"tb/base_footprint"});
  EXPECT_EQ(positionOf(sim, "tb/wheel_left_joint"), 0.0);

  // 1 s straight ahead at 0.2 m/s: both wheels (r = 0.033 m) turn 0.2 / 0.033 rad.
  ASSERT_TRUE(
      sim.setBodyState("tb/base_footprint", Vec2::Zero(), 0.0, Vec2(0.2, 0.0), 0.0, &error));
  for (int i = 0; i < 100; ++i) sim.step();
  EXPECT_NEAR(positionOf(sim, "tb/wheel_left_joint"), 0.2 / 0.033, 1e-9);
  EXPECT_NEAR(positionOf(sim, "tb/wheel_right_joint"), 0.2 / 0.033, 1e-9);

  // 1 s turning on the spot at 1 rad/s: the left wheel (0.08 m to the left) rolls back, the
  // right one ahead, 0.08 / 0.033 rad each.
  BodySnapshot at;
  ASSERT_TRUE(sim.getBodyState("tb/base_footprint", &at, &error));
  ASSERT_TRUE(
      sim.setBodyState("tb/base_footprint", at.position, at.angle, Vec2::Zero(), 1.0, &error));
  for (int i = 0; i < 100; ++i) sim.step();
  EXPECT_NEAR(positionOf(sim, "tb/wheel_left_joint"), (0.2 - 0.08) / 0.033, 1e-6);
  EXPECT_NEAR(positionOf(sim, "tb/wheel_right_joint"), (0.2 + 0.08) / 0.033, 1e-6);

  // The wheel's frame hangs under the base, turned by its joint position about its axis.
  const std::vector<FixedFrame> frames = sim.rollingFrames();
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].name, "tb/wheel_left_link");
  EXPECT_EQ(frames[0].parent, "tb/base_footprint");
  EXPECT_NEAR(frames[0].pose.translation().y(), 0.08, 1e-12);
  const Eigen::AngleAxisd turned(frames[0].pose.linear());
  EXPECT_GT(std::abs(turned.angle()), 0.1);

  // Strict: the same robot is refused, as before.
  robot.modelName = "tb2";
  robot.strict = true;
  EXPECT_FALSE(sim.spawnUrdf(robot, false, &spawned, &error));
  EXPECT_NE(error.find("out of the xy plane"), std::string::npos) << error;
}

TEST(SimWorldWheels, TheGazeboDiffDriveDrivesTheRobotAndTurnsItsWheels) {
  SimWorld sim;
  std::string error;
  UrdfRequest robot;
  UrdfSpawned spawned;
  ASSERT_NO_FATAL_FAILURE(spawnTeachingRobot(sim, true, &robot, &spawned));
  EXPECT_EQ(spawned.devices,
            (std::vector<std::string>{"tb/diff_drive_controller", "tb/lds_lfcd_sensor"}));
  // 1 s at 0.2 m/s, reached at wheelAcceleration 1 m/s^2: 0.181 m, and the wheels (r 0.033 m)
  // turn with the drive's wheel speeds.
  for (int i = 0; i < 100; ++i) {
    if (i % 10 == 0) {  // cmd_vel at 10 Hz, within the drive's 0.5 s timeout
      ASSERT_TRUE(sim.commandDrive("tb/diff_drive_controller", 0.2, 0.0, 0.0, &error)) << error;
    }
    sim.step();
  }
  BodySnapshot at;
  ASSERT_TRUE(sim.getBodyState("tb/base_footprint", &at, &error));
  EXPECT_NEAR(at.position.x(), 0.181, 0.005);
  EXPECT_NEAR(positionOf(sim, "tb/wheel_left_joint"), 0.181 / 0.033, 1e-6);
  EXPECT_NEAR(positionOf(sim, "tb/wheel_right_joint"), 0.181 / 0.033, 1e-6);
  // A second robot from the same URDF would take the same root topics: refused, nothing added.
  robot.modelName = "tb2";
  EXPECT_FALSE(sim.spawnUrdf(robot, false, &spawned, &error));
  EXPECT_NE(error.find("'/cmd_vel' is already used"), std::string::npos) << error;
  EXPECT_FALSE(sim.getBodyState("tb2/base_footprint", &at, &error));
}

}  // namespace
}  // namespace bridge
}  // namespace impulse2d
