// SimWorld's devices without a master: the start scene's devices after a URDF model, commands,
// readings only while active, devices leaving with their bodies and coming back with ~reset,
// refusals that add nothing, and the frames fixed to bodies.
#include "../../src/ros/sim_world.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>

namespace impulse2d {
namespace bridge {
namespace {

const char* const kRoom = R"(
world: {plane: xy, gravity: [0, 0], frame_id: world}
bodies:
  - {name: wall, type: static, position: [3.2, 0.0], shapes: [{type: box, size: [0.2, 3.0]}]}
devices:
  - {type: diff_drive, name: drive, body: robot/base_link, cmd_timeout: 0.0}
  - {type: laser, name: laser, body: robot/base_link, offset: [0.15, 0.0, 0.0]}
  - {type: bumper, name: bumper, body: robot/base_link}
)";

std::string robotUrdf() {
  std::ifstream in(std::string(IMPULSE2D_SOURCE_DIR) + "/config/round_robot.urdf");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The node's start: the scene, the URDF model, then the scene's devices.
void start(SimWorld& sim) {
  std::string error;
  ASSERT_TRUE(sim.loadStartScene(kRoom, &error)) << error;
  UrdfRequest robot;
  robot.modelName = "robot";
  robot.xml = robotUrdf();
  UrdfSpawned spawned;
  ASSERT_TRUE(sim.spawnUrdf(robot, true, &spawned, &error)) << error;
  ASSERT_TRUE(sim.attachStartDevices(&error)) << error;
}

bool hasFrame(const SimWorld& sim, const std::string& name, const std::string& parent) {
  const std::vector<FixedFrame> frames = sim.fixedFrames();
  return std::any_of(frames.begin(), frames.end(),
                     [&](const FixedFrame& f) { return f.name == name && f.parent == parent; });
}

TEST(SimWorldDevices, StartDevicesMayNameTheUrdfModelsBodies) {
  SimWorld sim;
  start(sim);
  ASSERT_EQ(sim.devices().size(), 3u);
  EXPECT_TRUE(hasFrame(sim, "robot/base_link/laser", "robot/base_link"));
  EXPECT_TRUE(hasFrame(sim, "robot/laser_link", "robot/base_link"));  // merged URDF links
  EXPECT_TRUE(hasFrame(sim, "robot/left_wheel", "robot/base_link"));

  // Driven at 0.5 m/s for a second of simulated time, after the ramp.
  std::string error;
  ASSERT_TRUE(sim.commandDrive("drive", 0.5, 0.0, 0.0, &error)) << error;
  for (int i = 0; i < 100; ++i) sim.step();
  const std::vector<OdometryReading> odom = sim.odometry();
  ASSERT_EQ(odom.size(), 1u);
  EXPECT_EQ(odom[0].body, "robot/base_link");
  EXPECT_DOUBLE_EQ(odom[0].speed, 0.5);
  EXPECT_NEAR(odom[0].position.x(), 0.5 - 0.0625, 1e-9);
  // The physics within what its sub-steps make of the ramp (test_drive.cpp).
  EXPECT_NEAR(odom[0].truePosition.x(), odom[0].position.x(), 1e-3);

  EXPECT_FALSE(sim.commandDrive("laser", 0.5, 0.0, 0.0, &error));
  EXPECT_EQ(error, "no drive named 'laser'");
  EXPECT_FALSE(sim.commandDrive("drive", NAN, 0.0, 0.0, &error));
  EXPECT_FALSE(sim.commandDrive("drive", 0.0, NAN, 0.0, &error));

  // Refused at start: the whole scene goes, the URDF model stays.
  SimWorld bad;
  ASSERT_TRUE(bad.loadStartScene(
      "world: {plane: xy}\ndevices: [{type: bumper, name: b, body: robot/nothing}]", &error));
  EXPECT_FALSE(bad.attachStartDevices(&error));
  EXPECT_EQ(error, "devices[0] 'b': body: no body named 'robot/nothing' in the scene or the world");
}

TEST(SimWorldDevices, ReadingsOnlyWhileActiveAndDevicesLeaveWithTheirBodies) {
  SimWorld sim;
  start(sim);
  for (int i = 0; i < 20; ++i) sim.step();
  EXPECT_TRUE(sim.takeScans().empty());  // nobody listens
  EXPECT_TRUE(sim.takeBumperChanges().empty());
  sim.setDeviceActive("laser", true);
  sim.setDeviceActive("bumper", true);
  for (int i = 0; i < 10; ++i) sim.step();  // 0.3 s: the scan of 10 Hz at 0.3 s
  const std::vector<ScanReading> scans = sim.takeScans();
  ASSERT_EQ(scans.size(), 1u);
  EXPECT_EQ(scans[0].frame, "robot/base_link/laser");
  EXPECT_EQ(scans[0].stampNs, 300000000);
  EXPECT_EQ(scans[0].ranges.size(), 1081u);
  const std::vector<BumperReading> bumps = sim.takeBumperChanges();
  ASSERT_EQ(bumps.size(), 1u);  // the first reading: touching nothing
  EXPECT_TRUE(bumps[0].contacts.empty());

  const uint64_t version = sim.deviceVersion();
  std::string error;
  ASSERT_TRUE(sim.deleteBody("robot/base_link", &error)) << error;
  EXPECT_TRUE(sim.devices().empty());
  EXPECT_NE(sim.deviceVersion(), version);
  EXPECT_FALSE(hasFrame(sim, "robot/laser_link", "robot/base_link"));
  sim.reset();  // back with the start state
  EXPECT_EQ(sim.devices().size(), 3u);
  EXPECT_TRUE(hasFrame(sim, "robot/laser_link", "robot/base_link"));
}

TEST(SimWorldDevices, LoadedScenesAddDevicesAllOrNothing) {
  SimWorld sim;
  start(sim);
  sim.setTopicRules([](const std::string& t) { return t[0] == '/' ? t : "/impulse2d/" + t; },
                    {"/impulse2d/contacts"});
  std::string error;
  // The relative "scan" is the node's "/impulse2d/scan": taken.
  EXPECT_FALSE(
      sim.addScene("bodies: [{name: box, shapes: [{}]}]\n"
                   "devices: [{type: laser, name: l2, body: box, topic: /impulse2d/scan}]",
                   &error));
  EXPECT_EQ(error,
            "devices[0] 'l2': topic: '/impulse2d/scan' is already used by the device 'laser' "
            "(topic)");
  EXPECT_FALSE(
      sim.addScene("devices: [{type: bumper, name: b2, body: wall, topic: contacts}]", &error));
  EXPECT_EQ(error, "devices[0] 'b2': topic: 'contacts' is already used by the node itself");
  BodySnapshot unused;
  EXPECT_FALSE(sim.getBodyState("box", &unused, &error));  // nothing of the scenes was added
  ASSERT_TRUE(
      sim.addScene("bodies: [{name: box, shapes: [{}]}]\n"
                   "devices: [{type: laser, name: l2, body: box, topic: scan2}]",
                   &error))
      << error;
  EXPECT_EQ(sim.devices().size(), 4u);
  EXPECT_TRUE(hasFrame(sim, "box/l2", "box"));
}

}  // namespace
}  // namespace bridge
}  // namespace impulse2d
