// The IMU's model without ROS, each figure against the body's known motion: a spin and a drive
// on a circle (the turn's pull at the mount point), a push of known force, free fall in a tilted
// plane, the orientation, and noise and bias per axis with a seed; and the device set running it
// at its rate in top-down worlds only.
#include <gtest/gtest.h>

#include <cmath>
#include <impulse2d/devices.hpp>
#include <impulse2d/imu.hpp>

#include "test_scenes.hpp"

namespace impulse2d {
namespace {

constexpr double kDt = 0.01;

WorldDef plane(const Vec2& gravity = Vec2::Zero()) {
  WorldDef def;
  def.gravity = gravity;
  def.timeStep = kDt;
  return def;
}

double yawOf(const Eigen::Quaterniond& q) {
  return std::atan2(2.0 * (q.w() * q.z() + q.x() * q.y()),
                    1.0 - 2.0 * (q.y() * q.y() + q.z() * q.z()));
}

// A 10 kg disc of radius 0.25 m at the origin with a unit mounted at `offset` and `angle`.
struct ImuWorld {
  World world;
  BodyId body;
  Imu imu;

  explicit ImuWorld(const Vec2& offset = Vec2::Zero(), double angle = 0.0,
                    const Vec2& gravity = Vec2::Zero(), ImuDef def = ImuDef())
      : world(plane(gravity)),
        body(test::addCircle(world, "robot", Vec2::Zero(), 0.25, BodyType::Dynamic,
                             10.0 / (kPi * 0.25 * 0.25))),
        imu(mounted(def, offset, angle), body, 7, world) {}

  static ImuDef mounted(ImuDef def, const Vec2& offset, double angle) {
    def.offset = offset;
    def.offsetAngle = angle;
    return def;
  }
  void step(int steps = 1) {
    for (int i = 0; i < steps; ++i) {
      world.step();
      imu.follow(world);
    }
  }
};

TEST(Imu, ASpinAtConstantRateReadsTheRateAndTheTurnsPullAtTheMount) {
  const double w = 2.0, r = 0.2;
  ImuWorld u(Vec2(r, 0.0));
  u.world.setVelocity(u.body, Vec2::Zero(), w);
  u.step(137);
  const ImuSample& s = u.imu.truth();
  EXPECT_NEAR(s.angularVelocity.z(), w, 1e-12);
  EXPECT_EQ(s.angularVelocity.x(), 0.0);
  // The mount point goes round a circle of radius r: w^2 r towards the centre, the unit's -x.
  EXPECT_NEAR(s.linearAcceleration.x(), -w * w * r, 1e-9);
  EXPECT_NEAR(s.linearAcceleration.y(), 0.0, 1e-9);
  EXPECT_EQ(s.linearAcceleration.z(), kFloorGravity);  // the floor's support, as REP 145 has it
  EXPECT_NEAR(std::remainder(yawOf(s.orientation) - u.world.body(u.body).angle, 2 * kPi), 0.0,
              1e-12);
  // At the centre of mass a spin feels nothing in the plane.
  ImuWorld centred;
  centred.world.setVelocity(centred.body, Vec2::Zero(), w);
  centred.step(50);
  EXPECT_NEAR(centred.imu.truth().linearAcceleration.head<2>().norm(), 0.0, 1e-12);
}

TEST(Imu, DrivenOnACircleItReadsTheCentripetalAccelerationSideways) {
  // A diff drive at 0.5 m/s turning at 0.8 rad/s: v w = 0.4 m/s^2 towards the turn's centre,
  // the body's +y.
  ImuWorld u;
  DriveDef def;
  def.cmdTimeout = 0.0;
  Drive drive(def, u.body, u.world);
  drive.command(0.5, 0.8, 0.0);
  double now = 0.0;
  for (int i = 0; i < 300; ++i) {
    drive.beforeStep(u.world, now);
    u.world.step();
    now += kDt;
    drive.afterStep(kDt);
    u.imu.follow(u.world);
  }
  const ImuSample& s = u.imu.truth();
  EXPECT_NEAR(s.angularVelocity.z(), 0.8, 1e-6);
  EXPECT_NEAR(s.linearAcceleration.y(), 0.5 * 0.8, 1e-4);
  // The drive moves the body along its heading half a step ahead, so its velocity, and the pull
  // square to it, lean w dt / 2 = 4 mrad off the body's axes: v w sin(w dt / 2) on x.
  EXPECT_NEAR(s.linearAcceleration.x(), 0.5 * 0.8 * std::sin(0.5 * 0.8 * kDt), 1e-5);
}

TEST(Imu, APushOfKnownForceReadsForceOverMassInTheUnitsFrame) {
  // The body turned a quarter turn, the unit a further quarter turn on it: the unit's x points
  // along the world's -x. 20 N along world +x on 10 kg: 2 m/s^2 along the unit's -x.
  ImuWorld u(Vec2::Zero(), kPi / 2);
  u.world.setTransform(u.body, Vec2::Zero(), kPi / 2);
  for (int i = 0; i < 25; ++i) {
    u.world.applyForce(u.body, Vec2(20.0, 0.0), u.world.body(u.body).center);
    u.step();
  }
  const ImuSample& s = u.imu.truth();
  EXPECT_NEAR(s.linearAcceleration.x(), -2.0, 1e-9);
  EXPECT_NEAR(s.linearAcceleration.y(), 0.0, 1e-9);
  EXPECT_NEAR(yawOf(s.orientation), kPi, 1e-12);
  // The push stops: so does the reading, one step later.
  u.step();
  EXPECT_NEAR(u.imu.truth().linearAcceleration.head<2>().norm(), 0.0, 1e-9);
}

TEST(Imu, FallingFreelyInATiltedPlaneItFeelsNothingAndResting) {
  // Gravity in the plane (a tilted floor): falling, the unit reads 0 there.
  ImuWorld falling(Vec2::Zero(), 0.0, Vec2(0.0, -2.0));
  falling.step(30);
  EXPECT_NEAR(falling.imu.truth().linearAcceleration.head<2>().norm(), 0.0, 1e-9);
  // Resting on a ledge below, it reads the ledge's push: 2 m/s^2 up the slope, +y.
  ImuWorld resting(Vec2::Zero(), 0.0, Vec2(0.0, -2.0));
  test::addBox(resting.world, "ledge", Vec2(0.0, -0.5), 2.0, 0.5, BodyType::Static);
  resting.step(200);
  EXPECT_NEAR(resting.imu.truth().linearAcceleration.x(), 0.0, 1e-6);
  EXPECT_NEAR(resting.imu.truth().linearAcceleration.y(), 2.0, 0.02);
}

TEST(Imu, NoiseAndBiasPerAxisWithASeed) {
  ImuDef def;
  def.angularVelocityNoise = Eigen::Vector3d(0.01, 0.02, 0.03);
  def.angularVelocityBias = Eigen::Vector3d(0.0, 0.0, 0.05);
  def.linearAccelerationNoise = Eigen::Vector3d(0.1, 0.2, 0.3);
  def.linearAccelerationBias = Eigen::Vector3d(0.5, -0.5, 0.0);
  def.orientationNoise = Eigen::Vector3d(0.0, 0.0, 0.01);
  ImuWorld u(Vec2::Zero(), 0.0, Vec2::Zero(), def);
  u.step();
  Imu twin(u.imu.def(), u.body, 7, u.world), other(u.imu.def(), u.body, 8, u.world);
  twin.follow(u.world);
  other.follow(u.world);
  constexpr int n = 20000;
  Eigen::Vector3d sumW = Eigen::Vector3d::Zero(), sumA = Eigen::Vector3d::Zero();
  Eigen::Vector3d squaresW = Eigen::Vector3d::Zero(), squaresA = Eigen::Vector3d::Zero();
  double sumYaw = 0.0, squaresYaw = 0.0;
  bool differs = false;
  for (int i = 0; i < n; ++i) {
    const ImuSample s = u.imu.read();
    const ImuSample t = twin.read();
    ASSERT_EQ(s.linearAcceleration, t.linearAcceleration);
    differs |= other.read().linearAcceleration != s.linearAcceleration;
    const Eigen::Vector3d dw = s.angularVelocity - def.angularVelocityBias;
    const Eigen::Vector3d da =
        s.linearAcceleration - def.linearAccelerationBias - Eigen::Vector3d(0, 0, kFloorGravity);
    sumW += dw;
    sumA += da;
    squaresW += dw.cwiseProduct(dw);
    squaresA += da.cwiseProduct(da);
    const double yaw = yawOf(s.orientation);
    sumYaw += yaw;
    squaresYaw += yaw * yaw;
  }
  EXPECT_TRUE(differs);
  for (int i = 0; i < 3; ++i) {
    const double sw = def.angularVelocityNoise[i], sa = def.linearAccelerationNoise[i];
    EXPECT_NEAR(sumW[i] / n, 0.0, 5 * sw / std::sqrt(n)) << "axis " << i;
    EXPECT_NEAR(sumA[i] / n, 0.0, 5 * sa / std::sqrt(n)) << "axis " << i;
    EXPECT_NEAR(std::sqrt(squaresW[i] / n), sw, 0.03 * sw) << "axis " << i;
    EXPECT_NEAR(std::sqrt(squaresA[i] / n), sa, 0.03 * sa) << "axis " << i;
  }
  EXPECT_NEAR(sumYaw / n, 0.0, 5 * 0.01 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(squaresYaw / n), 0.01, 0.0003);
}

TEST(Imu, TheDeviceSetReadsItAtItsRateInTopDownWorldsOnly) {
  World world(plane());
  const BodyId robot = test::addCircle(world, "robot", Vec2::Zero(), 0.25, BodyType::Dynamic);
  world.setVelocity(robot, Vec2::Zero(), 1.0);
  DeviceDef imu;
  imu.type = DeviceType::Imu;
  imu.name = "imu";
  imu.body = "robot";
  imu.imu.updateRate = 25.0;  // every fourth step of 0.01 s
  DeviceContext side;
  side.plane = "xz";
  DeviceSet set;
  std::string error;
  EXPECT_FALSE(set.add({imu}, world, side, 0.0, &error));
  EXPECT_EQ(error,
            "devices[0] 'imu': type: an imu rides on the floor of a top-down world (plane xy), "
            "where z is up; this world's plane is xz");
  DeviceContext top;
  top.plane = "xy";
  ASSERT_TRUE(set.add({imu}, world, top, 0.0, &error)) << error;
  Device& device = set.devices().front();
  device.active = true;
  double now = 0.0;
  int readings = 0;
  for (int i = 0; i < 100; ++i) {
    world.step();
    now += world.settings().timeStep;
    set.afterStep(world, now);
    if (device.fresh) {
      ++readings;
      device.fresh = false;
      EXPECT_NEAR(device.imuReading.angularVelocity.z(), 1.0, 1e-12);
    }
  }
  EXPECT_EQ(readings, 25);
}

}  // namespace
}  // namespace impulse2d
