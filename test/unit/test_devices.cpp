// The bumper's model and the device set without ROS: contacts seen from the bumper's body, change
// detection, the checks devices get against each other, and who runs when.
#include <gtest/gtest.h>

#include <impulse2d/devices.hpp>
#include <impulse2d/scene.hpp>

#include "test_scenes.hpp"

namespace impulse2d {
namespace {

WorldDef topDown() {
  WorldDef def;
  def.gravity = Vec2::Zero();
  return def;
}

TEST(Bumper, ReportsTheBodiesItTouchesWhenTheyChange) {
  World world(topDown());
  const BodyId wall = test::addBox(world, "wall", Vec2(0.0, 0.0), 0.2, 4.0, BodyType::Static);
  // The robot rests against the wall's right face (x = 0.1) and is the contact's body B.
  const BodyId robot = test::addCircle(world, "robot", Vec2(0.35, 0.0), 0.25, BodyType::Dynamic);
  Bumper bumper(BumperDef(), robot);
  EXPECT_TRUE(bumper.update(world));  // the first update reports, touching nothing yet
  EXPECT_TRUE(bumper.contacts().empty());
  EXPECT_FALSE(bumper.update(world));
  world.step();
  ASSERT_TRUE(bumper.update(world));
  ASSERT_EQ(bumper.contacts().size(), 1u);
  const ContactInfo& c = bumper.contacts()[0];
  EXPECT_EQ(c.bodyA, robot);  // turned round: the bumper's body is A,
  EXPECT_EQ(c.bodyB, wall);
  EXPECT_NEAR(c.normal.x(), -1.0, 1e-12);  // and the normal points from it at the wall
  EXPECT_NEAR(c.point.x(), 0.1, 0.01);
  world.step();
  EXPECT_FALSE(bumper.update(world));  // the same wall
  bumper.forget();
  EXPECT_TRUE(bumper.update(world));  // a new listener hears the state
  world.setTransform(robot, Vec2(2.0, 0.0), 0.0);
  world.step();
  EXPECT_TRUE(bumper.update(world));
  EXPECT_TRUE(bumper.contacts().empty());
}

DeviceDef device(DeviceType type, const std::string& name, const std::string& body) {
  DeviceDef def;
  def.type = type;
  def.name = name;
  def.body = body;
  return def;
}

DeviceContext xyContext() {
  DeviceContext context;
  context.plane = "xy";
  context.reservedTopics = {"contacts", "markers"};
  return context;
}

TEST(DeviceSet, RefusesClashesNamingTheDeviceAndKey) {
  DeviceSet set;
  World world(topDown());
  test::addCircle(world, "robot", Vec2::Zero(), 0.25, BodyType::Dynamic);
  test::addCircle(world, "other", Vec2(2, 0), 0.25, BodyType::Dynamic);
  std::string error;
  ASSERT_TRUE(set.add({device(DeviceType::DiffDrive, "drive", "robot"),
                       device(DeviceType::Laser, "laser", "robot")},
                      world, xyContext(), 0.0, &error))
      << error;
  struct Case {
    DeviceDef def;
    const char* expect;
  };
  DeviceDef sameTopic = device(DeviceType::Laser, "laser2", "other");
  DeviceDef cmdVelAsScan = device(DeviceType::Bumper, "bump", "other");
  cmdVelAsScan.bumper.topic = "cmd_vel";
  DeviceDef reserved = device(DeviceType::Bumper, "bump", "other");
  reserved.bumper.topic = "contacts";
  DeviceDef secondDrive = device(DeviceType::DiffDrive, "drive2", "robot");
  secondDrive.drive.cmdVelTopic = "cmd_vel2";
  secondDrive.drive.odomTopic = "odom2";
  DeviceDef sameOdomFrame = device(DeviceType::DiffDrive, "drive2", "other");
  sameOdomFrame.drive.cmdVelTopic = "cmd_vel2";
  sameOdomFrame.drive.odomTopic = "odom2";
  DeviceDef worldOdomFrame = sameOdomFrame;
  worldOdomFrame.drive.odomFrame = "world";
  // Every published frame has one publisher: lasers' and IMUs' frames, and odom frames.
  DeviceDef sameLaserFrame = device(DeviceType::Laser, "laser2", "other");
  sameLaserFrame.laser.topic = "scan2";
  sameLaserFrame.frame = "robot/laser";
  DeviceDef laserFrameIsOdom = sameLaserFrame;
  laserFrameIsOdom.frame = "odom";
  DeviceDef laserFrameIsBody = sameLaserFrame;
  laserFrameIsBody.frame = "other";
  const Case cases[] = {
      {sameLaserFrame,
       "devices[0] 'laser2': frame: 'robot/laser' is already published by the device 'laser'"},
      {laserFrameIsOdom,
       "devices[0] 'laser2': frame: 'odom' is already published by the device 'drive'"},
      {laserFrameIsBody,
       "devices[0] 'laser2': frame: must differ from the world frame and from its body's frame"},
      {device(DeviceType::Bumper, "laser", "other"),
       "devices[0] 'laser': name: already used by the device 'laser'"},
      {sameTopic,
       "devices[0] 'laser2': topic: 'scan' is already used by the device 'laser' (topic)"},
      {cmdVelAsScan,
       "devices[0] 'bump': topic: 'cmd_vel' is already used by the device 'drive' (cmd_vel_topic)"},
      {reserved, "devices[0] 'bump': topic: 'contacts' is already used by the node itself"},
      {secondDrive, "devices[0] 'drive2': body: 'robot' is already driven by the device 'drive'"},
      {sameOdomFrame,
       "devices[0] 'drive2': odom_frame: 'odom' is already published by the device 'drive'"},
      {worldOdomFrame, "devices[0] 'drive2': odom_frame: must differ from the world frame 'world'"},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(set.check({c.def}, xyContext()), c.expect);
    EXPECT_FALSE(set.add({c.def}, world, xyContext(), 0.0, &error));
    EXPECT_EQ(set.devices().size(), 2u);  // nothing added
  }
  // Two new devices clashing with each other.
  EXPECT_EQ(set.check({device(DeviceType::Bumper, "b1", "other"),
                       device(DeviceType::Bumper, "b2", "other")},
                      xyContext()),
            "devices[1] 'b2': topic: 'bumper' is already used by devices[0] 'b1' (topic)");
  // A drive outside the top-down plane.
  DeviceContext side = xyContext();
  side.plane = "xz";
  DeviceSet empty;
  EXPECT_NE(empty.check({device(DeviceType::DiffDrive, "d", "robot")}, side)
                .find("devices[0] 'd': type: a diff_drive drives on the floor of a top-down world"),
            std::string::npos);
  EXPECT_EQ(empty.check({device(DeviceType::Laser, "l", "robot")}, side), "");
}

TEST(DeviceSet, DevicesGoWithTheirBodiesAndRunOnlyWhenActive) {
  World world(topDown());
  const BodyId robot = test::addCircle(world, "robot", Vec2::Zero(), 0.25, BodyType::Dynamic);
  test::addBox(world, "wall", Vec2(3.2, 0.0), 0.2, 10.0, BodyType::Static);
  DeviceSet set;
  std::string error;
  DeviceDef laser = device(DeviceType::Laser, "laser", "robot");
  laser.laser.updateRate = 50.0;
  ASSERT_TRUE(set.add({laser, device(DeviceType::Bumper, "bumper", "robot"),
                       device(DeviceType::DiffDrive, "drive", "robot")},
                      world, xyContext(), 0.0, &error))
      << error;
  const uint64_t version = set.version();
  double now = 0.0;
  auto step = [&] {
    set.beforeStep(world, now);
    world.step();
    now += world.settings().timeStep;
    set.afterStep(world, now);
  };
  for (int i = 0; i < 10; ++i) step();
  for (const Device& d : set.devices()) EXPECT_FALSE(d.fresh) << d.def.name;  // nobody listens
  for (Device& d : set.devices()) d.active = true;
  step();
  step();  // 0.12 s: a 50 Hz scan is due every other step; the bumper's first reading
  Device& scanner = *set.find("laser");
  EXPECT_TRUE(scanner.fresh);
  EXPECT_NEAR(scanner.readingTime, 0.12, 1e-12);
  ASSERT_EQ(scanner.ranges.size(), 1081u);
  EXPECT_NEAR(scanner.ranges[540], 3.0, 1e-5);  // the beam at -0.0016 rad
  EXPECT_TRUE(set.find("bumper")->fresh);
  // The drive runs whoever listens: commanded, it moves the robot.
  set.find("drive")->drive->command(0.5, 0.0, now);
  for (int i = 0; i < 50; ++i) step();
  EXPECT_GT(world.body(robot).xf.p.x(), 0.1);

  world.destroyBody(robot);
  set.dropDetached(world);
  EXPECT_TRUE(set.devices().empty());
  EXPECT_NE(set.version(), version);
}

TEST(DeviceSet, AScenesDevicesAreCheckedWhenItIsAdded) {
  Scene scene;
  std::string error;
  ASSERT_TRUE(parseScene(R"(
world: {plane: xy, gravity: [0, 0]}
bodies: [{name: robot, shapes: [{type: circle, radius: 0.2}]}]
devices:
  - {type: diff_drive, name: drive, body: robot, cmd_vel_topic: /robot/cmd_vel, odom_topic: odom,
     odom_frame: robot_odom, publish_tf: false, ground_truth_tf: false, max_linear_accel: 1.5,
     max_angular_accel: 3.0, cmd_timeout: 0.0, max_force: 50.0, max_torque: 5.0,
     pose_variance: [0.01, 0.02, 0.03], twist_variance: [0.04, 0.05, 0.06]}
  - {type: laser, name: front, body: robot, offset: [0.2, 0.1, 0.5], topic: front_scan,
     range_min: 0.1, range_max: 30.0, angle_min: -1.0, angle_max: 1.0, angle_increment: 0.01,
     update_rate: 40.0, noise_stddev: 0.01, seed: 4294967295}
  - {type: bumper, name: bumper, body: robot, topic: /robot/bumper}
)",
                         &scene, &error))
      << error;
  ASSERT_EQ(scene.devices.size(), 3u);
  const DriveDef& d = scene.devices[0].drive;
  EXPECT_EQ(d.cmdVelTopic, "/robot/cmd_vel");
  EXPECT_EQ(d.odomFrame, "robot_odom");
  EXPECT_FALSE(d.publishTf);
  EXPECT_FALSE(d.groundTruthTf);
  EXPECT_EQ(d.maxLinearAccel, 1.5);
  EXPECT_EQ(d.maxAngularAccel, 3.0);
  EXPECT_EQ(d.cmdTimeout, 0.0);
  EXPECT_EQ(d.maxForce, 50.0);
  EXPECT_EQ(d.maxTorque, 5.0);
  EXPECT_EQ(d.poseVarianceXy, Vec2(0.01, 0.02));
  EXPECT_EQ(d.poseVarianceTheta, 0.03);
  EXPECT_EQ(d.twistVarianceXy, Vec2(0.04, 0.05));
  EXPECT_EQ(d.twistVarianceTheta, 0.06);
  const LaserDef& l = scene.devices[1].laser;
  EXPECT_EQ(l.offset, Vec2(0.2, 0.1));
  EXPECT_EQ(l.offsetAngle, 0.5);
  EXPECT_EQ(l.topic, "front_scan");
  EXPECT_EQ(l.rangeMin, 0.1);
  EXPECT_EQ(l.rangeMax, 30.0);
  EXPECT_EQ(l.angleMin, -1.0);
  EXPECT_EQ(l.angleMax, 1.0);
  EXPECT_EQ(l.angleIncrement, 0.01);
  EXPECT_EQ(l.updateRate, 40.0);
  EXPECT_EQ(l.noiseStddev, 0.01);
  EXPECT_TRUE(l.hasSeed);
  EXPECT_EQ(l.seed, 4294967295u);
  EXPECT_EQ(scene.devices[2].bumper.topic, "/robot/bumper");

  // Left out, every key takes the definitions' defaults.
  ASSERT_TRUE(
      parseScene("devices: [{type: diff_drive, name: d, body: r}, {type: laser, name: l, "
                 "body: r}, {type: bumper, name: b, body: r}]",
                 &scene, &error))
      << error;
  const DriveDef dd;
  EXPECT_EQ(scene.devices[0].drive.cmdVelTopic, dd.cmdVelTopic);
  EXPECT_EQ(scene.devices[0].drive.maxLinearAccel, dd.maxLinearAccel);
  EXPECT_EQ(scene.devices[0].drive.cmdTimeout, dd.cmdTimeout);
  EXPECT_TRUE(scene.devices[0].drive.publishTf);
  EXPECT_EQ(scene.devices[1].laser.offset, LaserDef().offset);
  EXPECT_EQ(scene.devices[1].laser.angleIncrement, LaserDef().angleIncrement);
  EXPECT_FALSE(scene.devices[1].laser.hasSeed);
  EXPECT_EQ(scene.devices[2].bumper.topic, "bumper");

  // Devices may name bodies already in the world; a missing body refuses the whole scene.
  World world(topDown());
  test::addCircle(world, "r", Vec2::Zero(), 0.25, BodyType::Dynamic);
  EXPECT_TRUE(addScene(scene, world, &error)) << error;
  ASSERT_TRUE(
      parseScene("bodies: [{name: crate, shapes: [{}]}]\n"
                 "devices: [{type: bumper, name: b, body: nobody}]",
                 &scene, &error));
  EXPECT_FALSE(addScene(scene, world, &error));
  EXPECT_EQ(error, "devices[0] 'b': body: no body named 'nobody' in the scene or the world");
  EXPECT_FALSE(world.findBody("crate").valid());
}

}  // namespace
}  // namespace impulse2d

namespace impulse2d {
namespace {

TEST(DeviceSet, EachDrivePublishesItsGroundTruthBesideItsOdometry) {
  DriveDef def;
  EXPECT_EQ(groundTruthTopicOf(def), "ground_truth");
  def.odomTopic = "r1/odom";
  EXPECT_EQ(groundTruthTopicOf(def), "r1/ground_truth");
  def.odomTopic = "/odom";
  EXPECT_EQ(groundTruthTopicOf(def), "/ground_truth");
  def.odomTopic = "wheel_odom";
  EXPECT_EQ(groundTruthTopicOf(def), "wheel_odom_ground_truth");
  def.groundTruthTopic = "truth";
  EXPECT_EQ(groundTruthTopicOf(def), "truth");
  // The derived topic is checked like the others.
  World world(topDown());
  test::addCircle(world, "robot", Vec2::Zero(), 0.25, BodyType::Dynamic);
  DeviceDef drive = device(DeviceType::DiffDrive, "drive", "robot");
  DeviceDef laser = device(DeviceType::Laser, "laser", "robot");
  laser.laser.topic = "ground_truth";
  DeviceSet set;
  std::string error;
  EXPECT_FALSE(set.add({drive, laser}, world, xyContext(), 0.0, &error));
  EXPECT_EQ(error,
            "devices[1] 'laser': topic: 'ground_truth' is already used by devices[0] 'drive' "
            "(ground_truth_topic)");
}

}  // namespace
}  // namespace impulse2d
