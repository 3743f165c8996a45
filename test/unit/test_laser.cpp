// The laser scanner's model without ROS: beam count, REP 117 ranges, seeded noise, the schedule
// in simulated time, and scans of a wall computed by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <impulse2d/laser.hpp>
#include <limits>

#include "test_scenes.hpp"

namespace impulse2d {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(LaserGeometry, BeamCountAsLaserScanCountsThem) {
  EXPECT_EQ(laserBeamCount(LaserDef()), 1081);  // the defaults: 270 degrees at 0.25 degrees
  LaserDef def;
  def.angleMin = -1.0;
  def.angleMax = 1.0;
  def.angleIncrement = 0.5;
  EXPECT_EQ(laserBeamCount(def), 5);
  def.angleIncrement = 0.3;  // the last beam at 0.8, short of angle_max
  EXPECT_EQ(laserBeamCount(def), 7);
  def.angleMax = -1.0;  // one beam
  EXPECT_EQ(laserBeamCount(def), 1);
}

TEST(LaserGeometry, RangesFollowRep117) {
  LaserDef def;  // 0.05 .. 10 m
  EXPECT_EQ(laserRange(def, true, 3.0, 0.0), 3.0f);
  EXPECT_EQ(laserRange(def, true, 3.0, 0.01), 3.01f);
  EXPECT_EQ(laserRange(def, false, 0.0, 0.0), kInf);     // no return
  EXPECT_EQ(laserRange(def, true, 0.04, 0.0), -kInf);    // too near
  EXPECT_EQ(laserRange(def, true, 0.06, -0.02), -kInf);  // the noise took it too near
  EXPECT_EQ(laserRange(def, true, 9.99, 0.02), kInf);    // ... or beyond range_max
  EXPECT_EQ(laserRange(def, true, 10.0, 0.0), 10.0f);
}

TEST(LaserNoise, SeededReproducibleAndStandardNormal) {
  GaussianNoise a(42), b(42), c(43);
  bool differs = false;
  for (int i = 0; i < 100; ++i) {
    const double x = a.next();
    EXPECT_EQ(x, b.next());
    differs |= x != c.next();
  }
  EXPECT_TRUE(differs);
  // 200 000 samples: the mean within 5 standard errors (0.011), the variance within 2%.
  GaussianNoise noise(7);
  double sum = 0.0, squares = 0.0;
  constexpr int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double x = noise.next();
    sum += x;
    squares += x * x;
  }
  EXPECT_NEAR(sum / n, 0.0, 0.011);
  EXPECT_NEAR(squares / n, 1.0, 0.02);
  EXPECT_NE(seedFromName("laser"), seedFromName("laser2"));
  EXPECT_EQ(seedFromName("laser"), seedFromName("laser"));
}

TEST(LaserSchedule, ScansAtTheRateInSimulatedTime) {
  // 10 Hz at 100 steps per second: the steps ending at 0.1, 0.2, ... s.
  ScanSchedule tenHz(10.0, 0.0);
  std::vector<int> dueSteps;
  for (int step = 1; step <= 100; ++step) {
    if (tenHz.due(step * 0.01)) dueSteps.push_back(step);
  }
  ASSERT_EQ(dueSteps.size(), 10u);
  for (int k = 0; k < 10; ++k) EXPECT_EQ(dueSteps[k], 10 * (k + 1));
  // 3 Hz: the first step at or after each third of a second.
  ScanSchedule threeHz(3.0, 0.0);
  dueSteps.clear();
  for (int step = 1; step <= 100; ++step) {
    if (threeHz.due(step * 0.01)) dueSteps.push_back(step);
  }
  EXPECT_EQ(dueSteps, (std::vector<int>{34, 67, 100}));
  // Faster than the steps: once per step.
  ScanSchedule fast(1000.0, 0.0);
  int scans = 0;
  for (int step = 1; step <= 100; ++step) scans += fast.due(step * 0.01) ? 1 : 0;
  EXPECT_EQ(scans, 100);
  // Created at 0.25 s: the next due is 0.3 s.
  ScanSchedule late(10.0, 0.25);
  EXPECT_FALSE(late.due(0.29));
  EXPECT_TRUE(late.due(0.30));
}

// A robot of radius 0.25 at the origin, its laser 0.1 m ahead of its centre, and a wall whose face
// is 3 m ahead of the laser (x = 3.1), 10 m wide.
struct WallScene {
  World world;
  BodyId robot = test::addCircle(world, "robot", Vec2::Zero(), 0.25, BodyType::Dynamic);
  BodyId wall = test::addBox(world, "wall", Vec2(3.2, 0.0), 0.2, 10.0, BodyType::Static);
};

TEST(LaserScan, AWallThreeMetresAheadReadsThreeMetres) {
  WallScene scene;
  LaserDef def;  // defaults: 1081 beams over +-2.356 rad, offset (0.1, 0)
  def.angleMin = -kPi / 4;
  def.angleMax = kPi / 4;
  def.angleIncrement = kPi / 8;  // beams at -45, -22.5, 0, 22.5, 45 degrees
  Laser laser(def, scene.robot, 1);
  std::vector<float> ranges;
  laser.scan(scene.world, &ranges);
  ASSERT_EQ(ranges.size(), 5u);
  EXPECT_NEAR(ranges[2], 3.0, 1e-6);  // the beam that points at it; the robot's own disc unseen
  for (int i : {0, 1, 3, 4}) {
    const double angle = def.angleMin + i * def.angleIncrement;
    EXPECT_NEAR(ranges[i], 3.0 / std::cos(angle), 1e-5) << "beam " << i;
  }
}

TEST(LaserScan, OffsetAngleRangeLimitsAndAMovingBody) {
  WallScene scene;
  LaserDef def;
  def.offset = Vec2(0.0, 0.0);
  def.offsetAngle = kPi / 2;  // the scanner looks along the body's +y
  def.angleMin = -kPi / 2;    // so its first beam looks along +x, at the wall
  def.angleMax = kPi / 2;
  def.angleIncrement = kPi / 2;
  def.rangeMax = 5.0;
  Laser laser(def, scene.robot, 1);
  std::vector<float> ranges;
  laser.scan(scene.world, &ranges);
  ASSERT_EQ(ranges.size(), 3u);
  EXPECT_NEAR(ranges[0], 3.1, 1e-6);
  EXPECT_EQ(ranges[1], kInf);  // along +y: nothing within 5 m
  EXPECT_EQ(ranges[2], kInf);  // along -x
  // Turned a quarter turn clockwise, the robot's scanner looks at the wall with its middle beam.
  scene.world.setTransform(scene.robot, Vec2(1.0, 0.0), -kPi / 2);
  laser.scan(scene.world, &ranges);
  EXPECT_NEAR(ranges[1], 2.1, 1e-6);
  // Nearer than range_min reads -inf.
  scene.world.setTransform(scene.robot, Vec2(3.08, 0.0), -kPi / 2);
  laser.scan(scene.world, &ranges);
  EXPECT_EQ(ranges[1], -kInf);
}

TEST(LaserScan, NoiseIsSeededPerDeviceWithTheStatedSpread) {
  WallScene scene;
  LaserDef def;
  def.angleMin = def.angleMax = 0.0;  // one beam, at the wall, 3 m
  def.noiseStddev = 0.02;
  Laser a(def, scene.robot, 5), b(def, scene.robot, 5), c(def, scene.robot, 6);
  std::vector<float> ra, rb, rc;
  double sum = 0.0, squares = 0.0;
  bool differs = false;
  constexpr int n = 20000;
  for (int i = 0; i < n; ++i) {
    a.scan(scene.world, &ra);
    b.scan(scene.world, &rb);
    c.scan(scene.world, &rc);
    ASSERT_EQ(ra[0], rb[0]);
    differs |= ra[0] != rc[0];
    const double error = ra[0] - 3.0;
    sum += error;
    squares += error * error;
  }
  EXPECT_TRUE(differs);
  EXPECT_NEAR(sum / n, 0.0, 5 * 0.02 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(squares / n), 0.02, 0.0005);
}

}  // namespace
}  // namespace impulse2d

// Mounted as flatland allows (issue 24): upside down, sweeping clockwise, several on one body,
// and intensities from the shapes' reflectance.
namespace impulse2d {
namespace {

TEST(LaserMounting, UpsideDownBeamAngleALiesAtMinusA) {
  WallScene scene;  // the wall along the body's +x
  LaserDef def;
  def.offset = Vec2(0.0, 0.0);
  def.offsetAngle = kPi / 2;  // the scanner's x along the body's +y
  def.angleMin = -kPi / 2;
  def.angleMax = kPi / 2;
  def.angleIncrement = kPi / 2;
  Laser upright(def, scene.robot, 1);
  def.flip = true;
  Laser flipped(def, scene.robot, 1);
  std::vector<float> a, b;
  upright.scan(scene.world, &a);
  flipped.scan(scene.world, &b);
  ASSERT_EQ(a.size(), 3u);
  ASSERT_EQ(b.size(), 3u);
  // Upright, beam -pi/2 (the scanner's -y) is the body's +x: the wall, 3.2 - 0.1 m away.
  EXPECT_NEAR(a[0], 3.1, 1e-6);
  EXPECT_EQ(a[2], kInf);
  // Upside down the scanner's y axis points the other way: beam +pi/2 looks at the wall.
  EXPECT_EQ(b[0], kInf);
  EXPECT_NEAR(b[2], 3.1, 1e-6);
  EXPECT_EQ(b[1], a[1]);  // the beam along the scanner's x is the same either way
}

TEST(LaserMounting, ANegativeIncrementSweepsClockwise) {
  WallScene scene;
  LaserDef def;
  def.angleMin = 0.0;
  def.angleMax = -kPi / 2;
  def.angleIncrement = -kPi / 4;  // beams at 0, -45 and -90 degrees, in that order
  EXPECT_EQ(laserBeamCount(def), 3);
  Laser laser(def, scene.robot, 1);
  std::vector<float> ranges;
  laser.scan(scene.world, &ranges);
  ASSERT_EQ(ranges.size(), 3u);
  EXPECT_NEAR(ranges[0], 3.0, 1e-6);
  EXPECT_NEAR(ranges[1], 3.0 * std::sqrt(2.0), 1e-5);
  EXPECT_EQ(ranges[2], kInf);  // along -y the 10 m wall is out of reach
}

TEST(LaserMounting, IntensitiesAreTheReflectanceOfTheShapeHit) {
  World world;
  const BodyId robot = test::addCircle(world, "robot", Vec2::Zero(), 0.25, BodyType::Dynamic);
  BodyDef wall;
  wall.name = "wall";
  wall.type = BodyType::Static;
  wall.position = Vec2(3.2, 0.0);
  ShapeDef upper, lower;  // two shapes of one body, each its own reflectance
  upper.size = lower.size = Vec2(0.2, 5.0);
  upper.offset = Vec2(0.0, 2.5);
  lower.offset = Vec2(0.0, -2.5);
  upper.reflectance = 0.8;
  lower.reflectance = 0.25;
  wall.shapes = {upper, lower};
  ASSERT_TRUE(world.createBody(wall).valid());
  LaserDef def;
  def.angleMin = -kPi / 4;
  def.angleMax = kPi / 2;
  def.angleIncrement = kPi / 4;  // -45, 0 (the seam), 45, 90 degrees
  def.angleMin += 0.01;          // off the seam: -44.4, 0.6, 45.6, 90.6 degrees
  def.angleMax += 0.01;
  Laser laser(def, robot, 1);
  std::vector<float> ranges, intensities;
  laser.scan(world, &ranges, &intensities);
  ASSERT_EQ(intensities.size(), 4u);
  EXPECT_FLOAT_EQ(intensities[0], 0.25f);
  EXPECT_FLOAT_EQ(intensities[1], 0.8f);
  EXPECT_FLOAT_EQ(intensities[2], 0.8f);
  EXPECT_EQ(ranges[3], kInf);
  EXPECT_EQ(intensities[3], 0.0f);  // no hit: 0
  // A shape without the key reads 0.
  WallScene plain;
  Laser plainLaser(def, plain.robot, 1);
  plainLaser.scan(plain.world, &ranges, &intensities);
  EXPECT_TRUE(std::isfinite(ranges[1]));
  EXPECT_EQ(intensities[1], 0.0f);
}

}  // namespace
}  // namespace impulse2d
