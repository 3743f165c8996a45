// Real robots' URDFs top-down (issue 25): in plane xy a joint about an axis in the floor (a
// wheel's) is folded into its parent's body, the wheel's lying cylinder becoming the rectangle
// seen from above and its mass the body's; strict keeps today's refusal, and so does the xz plane.
// The robot's gazebo_ros plugins and sensors become its devices.
#include <impulse2d/urdf.hpp>
#include <impulse2d/world.hpp>

#include <gtest/gtest.h>

#include "urdf_fixture.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

namespace impulse2d {
namespace {

std::string fixture(const std::string& name) { return test::urdfFixture(name); }

bool parse(const std::string& xml, const std::string& plane, bool strict, UrdfModel* out,
           std::string* error) {
  UrdfPlacement placement;
  placement.modelName = "tb";
  placement.plane = plane;
  placement.strict = strict;
  return parseUrdf(xml, placement, out, error);
}

// `base` (an open <robot> with a link base_footprint) with one ray sensor on that link, whose
// body is `sensor`; parsed top-down, and expected to load.
UrdfModel parseWithLaser(const std::string& base, const std::string& sensor) {
  UrdfModel model;
  std::string error;
  EXPECT_TRUE(parse(base + R"(<gazebo reference="base_footprint"><sensor type="ray" name="s">)" +
                        sensor + "</sensor></gazebo></robot>",
                    "xy", false, &model, &error))
      << error;
  return model;
}

TEST(UrdfFolding, ATeachingRobotsWheelsFoldIntoItsBaseSeenFromAbove) {
  UrdfModel model;
  std::string error;
  ASSERT_TRUE(parse(fixture("teaching_robot.urdf"), "xy", false, &model, &error)) << error;
  // One rigid body: the footprint with the base, both wheels, the caster and the laser mast.
  ASSERT_EQ(model.scene.bodies.size(), 1u);
  EXPECT_TRUE(model.scene.joints.empty());
  const BodyDef& base = model.scene.bodies[0];
  EXPECT_EQ(base.name, "tb/base_footprint");
  ASSERT_EQ(base.shapes.size(), 5u);  // base box, two wheels, caster sphere, laser cylinder
  // The wheels' cylinders (r 0.033, 0.018 long) lie along y: 0.066 along x, 0.018 along y.
  int wheels = 0;
  for (const ShapeDef& shape : base.shapes) {
    if (shape.kind != ShapeKind::Box || std::abs(std::abs(shape.offset.y()) - 0.08) > 1e-9) {
      continue;
    }
    ++wheels;
    EXPECT_NEAR(shape.size.x(), 0.018, 1e-12);
    EXPECT_NEAR(shape.size.y(), 0.066, 1e-12);
    EXPECT_NEAR(std::abs(std::sin(shape.angle)), 1.0, 1e-6);  // its length along y
    EXPECT_NEAR(shape.offset.x(), 0.0, 1e-12);
  }
  EXPECT_EQ(wheels, 2);
  EXPECT_NEAR(base.mass, 0.83 + 2 * 0.03, 1e-12);  // the wheels' masses join the base's

  // Both wheel joints are folded, each a wheel of radius 0.033 turning about +y, and said so.
  ASSERT_EQ(model.folded.size(), 2u);
  for (const UrdfFoldedJoint& wheel : model.folded) {
    EXPECT_EQ(wheel.body, "tb/base_footprint");
    EXPECT_NEAR(wheel.wheelRadius, 0.033, 1e-12);
    EXPECT_NEAR(wheel.planeAxis.y(), 1.0, 1e-6);
    EXPECT_NEAR(std::abs(wheel.center.y()), 0.08, 1e-12);
  }
  EXPECT_EQ(model.folded[0].name, "tb/wheel_left_joint");
  EXPECT_EQ(model.folded[0].link, "tb/wheel_left_link");
  EXPECT_GT(model.folded[0].center.y(), 0.0);
  bool said = false;
  for (const std::string& w : model.warnings) {
    said = said || w.find("joint 'wheel_left_joint': folded into body 'tb/base_footprint'") == 0;
  }
  EXPECT_TRUE(said);
  // The wheels' frames turn on /tf: they are not among the frames fixed to the body.
  for (const UrdfFrame& frame : model.frames) {
    EXPECT_NE(frame.name, "tb/wheel_left_link");
    EXPECT_NE(frame.name, "tb/wheel_right_link");
  }

  // The robot stands in a world and drives about like any body.
  World world(WorldDef{});
  world.settings().gravity = Vec2::Zero();
  ASSERT_TRUE(addScene(model.scene, world, &error)) << error;
  EXPECT_EQ(world.bodyCount(), 1u);
}

const DeviceDef* deviceNamed(const UrdfModel& model, const std::string& name) {
  for (const DeviceDef& d : model.scene.devices) {
    if (d.name == name) return &d;
  }
  return nullptr;
}

TEST(UrdfGazebo, TheRobotsGazeboPluginsBecomeItsDevices) {
  UrdfModel model;
  std::string error;
  ASSERT_TRUE(parse(fixture("teaching_robot.urdf"), "xy", false, &model, &error)) << error;
  ASSERT_EQ(model.scene.devices.size(), 2u);
  // libgazebo_ros_diff_drive.so on robotBaseFrame base_footprint, its topics at the root (no
  // robotNamespace), as gazebo_ros publishes them.
  const DeviceDef* drive = deviceNamed(model, "tb/diff_drive_controller");
  ASSERT_NE(drive, nullptr);
  EXPECT_EQ(drive->type, DeviceType::DiffDrive);
  EXPECT_EQ(drive->body, "tb/base_footprint");
  EXPECT_EQ(drive->drive.cmdVelTopic, "/cmd_vel");
  EXPECT_EQ(drive->drive.odomTopic, "/odom");
  EXPECT_EQ(drive->drive.odomFrame, "tb/odom");
  EXPECT_TRUE(drive->drive.publishTf);
  EXPECT_EQ(drive->drive.maxLinearAccel, 1.0);
  EXPECT_NEAR(drive->drive.maxForce, 2 * 10.0 / 0.033, 1e-9);       // two wheels' torque at r
  EXPECT_NEAR(drive->drive.maxTorque, 10.0 / 0.033 * 0.160, 1e-9);  // in turn, at half the track
  // The LDS on base_scan: 360 samples over a full turn (the last, repeating the first, left
  // out), 0.12 to 3.5 m, 5 Hz, 1 cm noise, its frame base_scan on the mast.
  const DeviceDef* laser = deviceNamed(model, "tb/lds_lfcd_sensor");
  ASSERT_NE(laser, nullptr);
  EXPECT_EQ(laser->type, DeviceType::Laser);
  EXPECT_EQ(laser->body, "tb/base_footprint");
  EXPECT_EQ(laser->laser.topic, "/scan");
  EXPECT_EQ(laser->frame, "tb/base_scan");
  EXPECT_NEAR(laser->laser.offset.x(), -0.032, 1e-12);
  EXPECT_NEAR(laser->laser.offset.y(), 0.0, 1e-12);
  EXPECT_NEAR(laser->laser.angleMin, 0.0, 1e-12);
  EXPECT_NEAR(laser->laser.angleIncrement, 6.28319 / 359.0, 1e-12);
  EXPECT_EQ(static_cast<int>(std::floor((laser->laser.angleMax - laser->laser.angleMin) /
                                        laser->laser.angleIncrement)) +
                1,
            359);
  EXPECT_EQ(laser->laser.rangeMin, 0.12);
  EXPECT_EQ(laser->laser.rangeMax, 3.5);
  EXPECT_EQ(laser->laser.updateRate, 5.0);
  EXPECT_EQ(laser->laser.noiseStddev, 0.01);
  // The laser's frame is the sensor's now: the link's own frame leaves the fixed frames.
  for (const UrdfFrame& frame : model.frames) EXPECT_NE(frame.name, "tb/base_scan");

  // In the side view the drive has no floor, and the horizontal scanner cannot scan the plane:
  // both left out with a word.
  UrdfModel side;
  std::string xml = fixture("teaching_robot.urdf");
  // (the side view refuses the rolled wheels; without them the robot loads)
  for (const char* wheel : {"wheel_left", "wheel_right"}) {
    const size_t a = xml.find(std::string("<joint name=\"") + wheel + "_joint\"");
    const size_t b = xml.find("</link>", a) + 7;
    xml.erase(a, b - a);
  }
  ASSERT_TRUE(parse(xml, "xz", false, &side, &error)) << error;
  EXPECT_TRUE(side.scene.devices.empty());
  int said = 0;
  for (const std::string& w : side.warnings) {
    said += w.find("needs a top-down") != std::string::npos;
    said += w.find("skipped: it is tilted out of the floor's plane") != std::string::npos;
  }
  EXPECT_EQ(said, 2);
}

TEST(UrdfGazebo, BadPluginValuesAreRefusedNamingTheElement) {
  const std::string base =
      R"(<robot name="r"><link name="base_footprint"><collision><geometry><box size="0.3 0.3 0.1"/></geometry></collision></link>)";
  struct Case {
    std::string gazebo;
    std::string error;
  };
  const Case cases[] = {
      {R"(<gazebo><plugin name="d" filename="libgazebo_ros_diff_drive.so"><robotBaseFrame>nowhere</robotBaseFrame></plugin></gazebo>)",
       "robotBaseFrame 'nowhere' is no link of the model"},
      {R"(<gazebo><plugin name="d" filename="libgazebo_ros_diff_drive.so"><wheelTorque>lots</wheelTorque></plugin></gazebo>)",
       "wheelTorque"},
      {R"(<gazebo><plugin name="d" filename="libgazebo_ros_diff_drive.so"><commandTopic>bad topic</commandTopic></plugin></gazebo>)",
       "commandTopic '/bad topic'"},
      {R"(<gazebo reference="base_footprint"><sensor type="ray" name="s"><ray><range><min>2</min><max>1</max></range></ray><plugin name="p" filename="libgazebo_ros_laser.so"/></sensor></gazebo>)",
       "range min and max"},
      {R"(<gazebo reference="base_footprint"><sensor type="ray" name="s"><ray><range><min>0</min><max>1e9</max></range></ray><plugin name="p" filename="libgazebo_ros_laser.so"/></sensor></gazebo>)",
       "at most 1e6 Hz)"},
      {R"(<gazebo><plugin name="d" filename="libgazebo_ros_diff_drive.so"><wheelAcceleration>1e9</wheelAcceleration></plugin></gazebo>)",
       "wheelAcceleration must be at most 1e6"},
      // Frames follow the scene format's rule for names, as tf would carry them.
      {R"(<gazebo><plugin name="d" filename="libgazebo_ros_diff_drive.so"><odometryFrame>odom frame</odometryFrame></plugin></gazebo>)",
       "odometryFrame 'tb/odom frame': may only contain"},
      {R"(<gazebo reference="base_footprint"><sensor type="ray" name="s"><plugin name="p" filename="libgazebo_ros_laser.so"><frameName>my laser</frameName></plugin></sensor></gazebo>)",
       "frameName 'tb/my laser': may only contain"},
      {R"(<gazebo><plugin name="i" filename="libgazebo_ros_imu.so"><bodyName>base_footprint</bodyName><frameName>imu!</frameName></plugin></gazebo>)",
       "frameName 'tb/imu!': may only contain"},
  };
  for (const Case& c : cases) {
    UrdfModel model;
    std::string error;
    EXPECT_FALSE(parse(base + c.gazebo + "</robot>", "xy", false, &model, &error)) << c.gazebo;
    EXPECT_NE(error.find(c.error), std::string::npos) << error;
    EXPECT_TRUE(model.scene.bodies.empty());
  }
  // An unknown plugin and a scanner tilted out of the floor are left out with a word each; the
  // robot loads.
  UrdfModel model;
  std::string error;
  ASSERT_TRUE(parse(
      base + R"(<gazebo><plugin name="x" filename="libsomething.so"/></gazebo>)" +
          R"(<gazebo reference="base_footprint"><sensor type="ray" name="s"><pose>0 0 0 0 0.7 0</pose><plugin name="p" filename="libgazebo_ros_laser.so"/></sensor></gazebo></robot>)",
      "xy", false, &model, &error))
      << error;
  EXPECT_TRUE(model.scene.devices.empty());
  ASSERT_EQ(model.warnings.size(), 2u);
  // A scanner whose frameName is its body's own frame reads in a frame of its own.
  const UrdfModel own = parseWithLaser(
      base,
      R"(<plugin name="p" filename="libgazebo_ros_laser.so"><frameName>base_footprint</frameName></plugin>)");
  ASSERT_EQ(own.scene.devices.size(), 1u);
  EXPECT_EQ(deviceFrameOf(own.scene.devices[0]), "tb/base_footprint/s");
  EXPECT_NE(model.warnings[0].find("plugin 'x' ('libsomething.so'): skipped"), std::string::npos);
  EXPECT_NE(model.warnings[1].find("sensor 's': skipped: it is tilted"), std::string::npos);
  // A file name is the user's text: a line break in it does not break the one-line message.
  UrdfModel broken;
  ASSERT_TRUE(
      parse(base + R"(<gazebo><plugin name="x" filename="lib&#10;thing.so"/></gazebo></robot>)",
            "xy", false, &broken, &error))
      << error;
  ASSERT_EQ(broken.warnings.size(), 1u);
  EXPECT_EQ(broken.warnings[0].find('\n'), std::string::npos) << broken.warnings[0];
  EXPECT_NE(broken.warnings[0].find("('lib?thing.so')"), std::string::npos) << broken.warnings[0];
  // More beams than a scanner may have: the defaults stay, and the warning says so.
  const UrdfModel wide = parseWithLaser(
      base,
      R"(<ray><scan><horizontal><samples>200000</samples><min_angle>-1</min_angle><max_angle>1</max_angle></horizontal></scan></ray><plugin name="p" filename="libgazebo_ros_laser.so"/>)");
  ASSERT_EQ(wide.scene.devices.size(), 1u);
  EXPECT_EQ(wide.scene.devices[0].laser.angleMin, LaserDef().angleMin);
  ASSERT_EQ(wide.warnings.size(), 1u);
  EXPECT_NE(wide.warnings[0].find("samples beyond 100000 beams: kept the scanner's default beams"),
            std::string::npos)
      << wide.warnings[0];
}

TEST(UrdfFolding, StrictAndTheSideViewRefuseAsBefore) {
  const std::string xml = fixture("teaching_robot.urdf");
  for (const auto& [plane, strict] : {std::pair<std::string, bool>{"xy", true}, {"xz", false}}) {
    UrdfModel model;
    std::string error;
    EXPECT_FALSE(parse(xml, plane, strict, &model, &error)) << plane;
    EXPECT_NE(error.find("joint 'wheel_left_joint': its origin turns link 'wheel_left_link' out "
                         "of the " +
                         plane + " plane"),
              std::string::npos)
        << error;
    EXPECT_TRUE(model.folded.empty());
  }
}

TEST(UrdfFolding, ATiltingSensorFoldsAndStaysAtZero) {
  // A sensor head on a revolute joint about x: folded, not a wheel (no coaxial cylinder).
  const std::string xml = R"(<robot name="r">
  <link name="base"><collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision>
    <inertial><mass value="2"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <joint name="tilt" type="revolute"><parent link="base"/><child link="head"/>
    <origin xyz="0.1 0 0.2"/><axis xyz="1 0 0"/><limit lower="-0.5" upper="0.5" effort="1" velocity="1"/></joint>
  <link name="head"><collision><geometry><box size="0.05 0.1 0.05"/></geometry></collision></link>
  <joint name="pan" type="continuous"><parent link="base"/><child link="turret"/>
    <origin xyz="-0.1 0 0.1"/><axis xyz="0 0 1"/></joint>
  <link name="turret"><collision><geometry><cylinder radius="0.05" length="0.05"/></geometry></collision>
    <inertial><mass value="0.2"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
</robot>)";
  UrdfModel model;
  std::string error;
  ASSERT_TRUE(parse(xml, "xy", false, &model, &error)) << error;
  ASSERT_EQ(model.folded.size(), 1u);
  EXPECT_EQ(model.folded[0].name, "tb/tilt");
  EXPECT_EQ(model.folded[0].wheelRadius, 0.0);
  // The pan joint turns about the vertical: it stays a revolute joint between two bodies.
  ASSERT_EQ(model.scene.joints.size(), 1u);
  EXPECT_EQ(model.scene.joints[0].def.name, "tb/pan");
  EXPECT_EQ(model.scene.bodies.size(), 2u);
}

}  // namespace
}  // namespace impulse2d
