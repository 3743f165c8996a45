// The drives' model without ROS: ramps, dead reckoning, and the drive moving a body through the
// physics (straight, turning, stopping on a timeout, blocked, pushed, on a slope); the holonomic
// drive's sideways motion and the car's steering.
#include <gtest/gtest.h>

#include <cmath>
#include <impulse2d/drive.hpp>

#include "test_scenes.hpp"

namespace impulse2d {
namespace {

constexpr double kDt = 0.01;

TEST(Ramp, MovesTowardsTheTargetByAtMostRateTimesDt) {
  EXPECT_DOUBLE_EQ(rampTowards(0.0, 0.5, 2.0, kDt), 0.02);
  EXPECT_DOUBLE_EQ(rampTowards(0.49, 0.5, 2.0, kDt), 0.5);
  EXPECT_DOUBLE_EQ(rampTowards(0.5, -0.5, 2.0, kDt), 0.48);
  EXPECT_DOUBLE_EQ(rampTowards(-0.01, 0.0, 2.0, kDt), 0.0);
}

TEST(Odometry, StraightLinesAndArcs) {
  Pose2 start;
  start.position = Vec2(1.0, 2.0);
  start.angle = kPi / 2;
  const Pose2 straight = integrateArc(start, 0.5, 0.0, 2.0);
  EXPECT_NEAR(straight.position.x(), 1.0, 1e-15);
  EXPECT_NEAR(straight.position.y(), 3.0, 1e-15);
  // A quarter turn of radius r = v / w = 2 / pi from the origin facing +x ends at (r, r).
  const Pose2 quarter = integrateArc(Pose2(), 1.0, kPi / 2, 1.0);
  EXPECT_NEAR(quarter.position.x(), 2.0 / kPi, 1e-15);
  EXPECT_NEAR(quarter.position.y(), 2.0 / kPi, 1e-15);
  EXPECT_NEAR(quarter.angle, kPi / 2, 1e-15);
  // A full circle in 1000 small steps comes back where it started.
  Pose2 pose;
  for (int i = 0; i < 1000; ++i) pose = integrateArc(pose, 0.5, 2.0 * kPi / 10.0, 0.01);
  EXPECT_NEAR(pose.position.norm(), 0.0, 1e-12);
  EXPECT_NEAR(pose.angle, 2.0 * kPi, 1e-12);
  // Turns below 1e-6 rad per step take the chord along the mid heading: v dt (cos, sin)(w dt / 2).
  const Pose2 tiny = integrateArc(Pose2(), 1.0, 1e-5, 0.01);
  EXPECT_NEAR(tiny.position.x(), 0.01 * std::cos(0.5e-7), 1e-18);
  EXPECT_NEAR(tiny.position.y(), 0.01 * std::sin(0.5e-7), 1e-18);
}

// A top-down world (no gravity) with a round robot of 0.25 m radius and 10 kg at the origin.
struct DriveWorld {
  World world;
  BodyId robot;
  Drive drive;
  double now = 0.0;

  explicit DriveWorld(const DriveDef& def = DriveDef(), const Vec2& gravity = Vec2::Zero(),
                      DeviceType type = DeviceType::DiffDrive)
      : world(settings(gravity)),
        robot(test::addCircle(world, "robot", Vec2::Zero(), 0.25, BodyType::Dynamic,
                              10.0 / (kPi * 0.25 * 0.25))),
        drive(def, robot, world, type) {}

  static WorldDef settings(const Vec2& gravity) {
    WorldDef def;
    def.gravity = gravity;
    def.timeStep = kDt;
    return def;
  }
  void step(int steps = 1) {
    for (int i = 0; i < steps; ++i) {
      drive.beforeStep(world, now);
      world.step();
      now += kDt;
      drive.afterStep(kDt);
    }
  }
  const Body& body() const { return world.body(robot); }
};

TEST(Drive, HalfAMetrePerSecondForTwoSecondsThenZeroMovesOneMetre) {
  DriveWorld w;
  EXPECT_NEAR(w.body().mass, 10.0, 1e-12);
  for (int i = 0; i < 200; ++i) {
    w.drive.command(0.5, 0.0, w.now);  // a planner at 100 Hz
    w.step();
  }
  EXPECT_DOUBLE_EQ(w.drive.speed(), 0.5);
  w.drive.command(0.0, 0.0, w.now);
  w.step(100);
  // The ramps of 2 m/s^2 up and down cancel: 0.5 m/s x 2 s.
  EXPECT_NEAR(w.drive.odometry().position.x(), 1.0, 1e-12);
  EXPECT_NEAR(w.drive.odometry().position.y(), 0.0, 1e-12);
  EXPECT_NEAR(w.body().xf.p.x(), 1.0, 1e-9);
  EXPECT_NEAR(w.body().xf.p.y(), 0.0, 1e-12);
  EXPECT_NEAR(w.body().linearVelocity.norm(), 0.0, 1e-12);
  EXPECT_EQ(w.drive.speed(), 0.0);
}

TEST(Drive, TurningFollowsTheOdometrysArc) {
  DriveWorld w;
  for (int i = 0; i < 400; ++i) {
    w.drive.command(0.5, 0.8, w.now);
    w.step();
  }
  const Pose2& odom = w.drive.odometry();
  // 4 s at 0.8 rad/s, less the ramp's 0.8 / 6 s at half the rate: 3.2 - 0.0533 rad.
  EXPECT_NEAR(odom.angle, 0.8 * 4.0 - 0.5 * 0.8 * (0.8 / 6.0), 0.005);
  // The physics follows within what its sub-steps make of each step: a constant force changes
  // the velocity evenly through the n sub-steps, so the mean velocity over the step leans
  // (n - 1) / 2n of a step's turn (0.4 x 0.8 rad/s x 0.01 s) back towards last step's heading,
  // where the odometry's arc takes the mean heading. About 0.2% of the 2.2 m driven.
  EXPECT_NEAR(w.body().angle, odom.angle, 1e-3);
  EXPECT_NEAR((w.body().xf.p - odom.position).norm(), 0.0, 0.01);
  EXPECT_GT(odom.position.norm(), 1.0);  // it went somewhere: half a circle of 0.625 m radius
}

TEST(Drive, StopsWhenCommandsStopComing) {
  DriveDef def;
  def.cmdTimeout = 0.5;
  DriveWorld w(def);
  w.drive.command(0.5, 0.0, 0.0);  // one command, never repeated
  w.step(50);
  EXPECT_FALSE(w.drive.timedOut(w.now - 1e-9));
  EXPECT_DOUBLE_EQ(w.drive.speed(), 0.5);
  w.step(200);
  EXPECT_TRUE(w.drive.timedOut(w.now));
  EXPECT_EQ(w.drive.speed(), 0.0);
  EXPECT_NEAR(w.body().linearVelocity.norm(), 0.0, 1e-12);
  // Up in 0.25 s, on until 0.5 s, down in 0.25 s: 0.0625 + 0.125 + 0.0625 m, a step either way.
  EXPECT_NEAR(w.body().xf.p.x(), 0.25, 0.006);
  // A timeout of 0 never stops it.
  DriveDef forever;
  forever.cmdTimeout = 0.0;
  DriveWorld v(forever);
  v.drive.command(0.5, 0.0, 0.0);
  v.step(300);
  EXPECT_DOUBLE_EQ(v.drive.speed(), 0.5);
}

TEST(Drive, BlockedByAWallItPushesWithMaxForceAndTheOdometryRunsOn) {
  DriveDef def;
  def.cmdTimeout = 0.0;
  DriveWorld w(def);
  // A wall whose face is 0.5 m ahead of the robot's front.
  const BodyId wall = test::addBox(w.world, "wall", Vec2(0.85, 0.0), 0.2, 4.0, BodyType::Static);
  w.drive.command(0.5, 0.0, 0.0);
  w.step(400);
  EXPECT_NEAR(w.body().xf.p.x(), 0.5, 0.01);        // stopped at the wall
  EXPECT_GT(w.drive.odometry().position.x(), 1.5);  // the wheels kept turning
  // Its push on the wall: the contact's impulse per step is max_force dt (10 kg x 9.81 N).
  double impulse = 0.0;
  for (const ContactInfo& c : w.world.contacts()) {
    if (c.bodyA == wall || c.bodyB == wall) impulse += c.normalImpulse;
  }
  EXPECT_NEAR(impulse / kDt, 10.0 * 9.81, 0.5);
}

TEST(Drive, HoldsAgainstAppliedForcesWithinMaxForceAndGivesWayBeyond) {
  DriveWorld hold;
  for (int i = 0; i < 100; ++i) {
    hold.world.applyForce(hold.robot, Vec2(0.0, 0.5 * 98.1), hold.body().center);
    hold.step();
  }
  EXPECT_NEAR(hold.body().xf.p.norm(), 0.0, 1e-12);
  // Twice max_force: the drive's max_force is left, 98.1 N on 10 kg, 9.81 m/s^2.
  DriveWorld pushed;
  for (int i = 0; i < 100; ++i) {
    pushed.world.applyForce(pushed.robot, Vec2(0.0, 2.0 * 98.1), pushed.body().center);
    pushed.step();
  }
  EXPECT_NEAR(pushed.body().linearVelocity.y(), 9.81, 1e-6);
  EXPECT_NEAR(pushed.body().linearVelocity.x(), 0.0, 1e-12);
}

TEST(Drive, OnASlopeItHoldsWhileMaxForceAllowsThenSlides) {
  // A floor tilted so that 2 m/s^2 of gravity pulls along -y, across the robot's heading.
  DriveWorld gentle(DriveDef(), Vec2(0.0, -2.0));
  gentle.drive.command(0.5, 0.0, 0.0);
  gentle.step(40);
  EXPECT_NEAR(gentle.body().linearVelocity.x(), 0.5, 1e-9);
  EXPECT_NEAR(gentle.body().linearVelocity.y(), 0.0, 1e-9);
  // A traction limit below the pull: the body slides down at (20 - 15) N / 10 kg = 0.5 m/s^2,
  // and the odometry does not see it.
  DriveDef weak;
  weak.maxForce = 15.0;
  DriveWorld steep(weak, Vec2(0.0, -2.0));
  steep.step(100);
  EXPECT_NEAR(steep.body().linearVelocity.y(), -0.5, 1e-9);
  EXPECT_EQ(steep.drive.odometry().position.norm(), 0.0);
}

TEST(Drive, IgnoresNonFiniteCommandsAndLetsARestingBodySleep) {
  DriveWorld w;
  w.drive.command(NAN, 0.0, 0.0);
  w.drive.command(0.0, INFINITY, 0.0);
  w.step(10);
  EXPECT_EQ(w.drive.speed(), 0.0);
  EXPECT_EQ(w.drive.turnRate(), 0.0);
  w.drive.command(0.3, 0.0, w.now);
  w.step(20);
  w.drive.command(0.0, 0.0, w.now);
  w.step(200);
  EXPECT_FALSE(w.body().awake);  // stopped, the drive leaves it alone
}

}  // namespace
}  // namespace impulse2d

namespace impulse2d {
namespace {

TEST(Odometry, SidewaysArcsIntegrateTheBodyFramesVelocity) {
  // Sideways at 1 m/s while turning a quarter turn in 1 s: the arc of radius 2 / pi to the left
  // of a robot facing +y... i.e. the same arc as driving forward, turned a quarter turn.
  const Pose2 sideways = integrateArc(Pose2(), Vec2(0.0, 1.0), kPi / 2, 1.0);
  EXPECT_NEAR(sideways.position.x(), -2.0 / kPi, 1e-15);
  EXPECT_NEAR(sideways.position.y(), 2.0 / kPi, 1e-15);
  EXPECT_NEAR(sideways.angle, kPi / 2, 1e-15);
  // Forward only, it is the scalar arc.
  const Pose2 a = integrateArc(Pose2(), Vec2(0.7, 0.0), 0.3, 0.5);
  const Pose2 b = integrateArc(Pose2(), 0.7, 0.3, 0.5);
  EXPECT_NEAR((a.position - b.position).norm(), 0.0, 1e-15);
  // Small turns: the chord along the mid-step heading.
  const Pose2 tiny = integrateArc(Pose2(), Vec2(0.0, 1.0), 1e-5, 0.01);
  EXPECT_NEAR(tiny.position.x(), -0.01 * std::sin(0.5e-7), 1e-18);
  EXPECT_NEAR(tiny.position.y(), 0.01 * std::cos(0.5e-7), 1e-18);
}

TEST(Omni, MovesSidewaysAndDiagonallyWithTheAccelerationLimitOnBoth) {
  DriveWorld w(DriveDef(), Vec2::Zero(), DeviceType::Omni);
  // 0.3 m/s sideways and 0.4 forward: 0.5 m/s in all, reached in 0.25 s at 2 m/s^2.
  for (int i = 0; i < 200; ++i) {
    w.drive.command(0.4, 0.3, 0.0, w.now);
    w.step();
  }
  EXPECT_NEAR(w.drive.speed(), 0.4, 1e-12);
  EXPECT_NEAR(w.drive.sideSpeed(), 0.3, 1e-12);
  // 2 s less half the ramp: 0.5 x (2 - 0.125) m along the direction (0.8, 0.6).
  const double travelled = 0.5 * (2.0 - 0.125);
  EXPECT_NEAR(w.drive.odometry().position.x(), 0.8 * travelled, 1e-9);
  EXPECT_NEAR(w.drive.odometry().position.y(), 0.6 * travelled, 1e-9);
  // The body follows within what its sub-steps make of the ramp: 0.3 mm.
  EXPECT_NEAR((w.body().xf.p - w.drive.odometry().position).norm(), 0.0, 5e-4);
  EXPECT_NEAR(w.body().angle, 0.0, 1e-12);
  EXPECT_NEAR(w.body().linearVelocity.x(), 0.4, 1e-9);
  EXPECT_NEAR(w.body().linearVelocity.y(), 0.3, 1e-9);
}

TEST(Omni, TurnsWhileMovingSidewaysAndStopsOnTimeout) {
  DriveWorld w(DriveDef(), Vec2::Zero(), DeviceType::Omni);
  for (int i = 0; i < 300; ++i) {
    w.drive.command(0.0, 0.5, 0.5, w.now);
    w.step();
  }
  // Sideways at 0.5 m/s turning at 0.5 rad/s: a circle of 1 m radius, which the body follows.
  EXPECT_NEAR(w.body().angle, w.drive.odometry().angle, 1e-3);
  EXPECT_NEAR((w.body().xf.p - w.drive.odometry().position).norm(), 0.0, 0.01);
  EXPECT_NEAR(w.body().linearVelocity.norm(), 0.5, 1e-3);
  // The body's velocity is along its own +y.
  const Vec2 along = w.body().xf.q.applyInverse(w.body().linearVelocity);
  EXPECT_NEAR(along.x(), 0.0, 0.005);
  w.step(100);  // no more commands: after 0.5 s the target is 0
  EXPECT_EQ(w.drive.sideSpeed(), 0.0);
  EXPECT_NEAR(w.body().linearVelocity.norm(), 0.0, 1e-9);
  // A diff_drive ignores linear.y.
  DriveWorld d;
  for (int i = 0; i < 50; ++i) {
    d.drive.command(0.0, 0.5, 0.0, d.now);
    d.step();
  }
  EXPECT_EQ(d.drive.sideSpeed(), 0.0);
  EXPECT_NEAR(d.body().xf.p.norm(), 0.0, 1e-12);
}

DriveDef car(double wheelbase, double maxSteering) {
  DriveDef def;
  def.wheelbase = wheelbase;
  def.maxSteeringAngle = maxSteering;
  def.steeringRate = 2.0;
  def.cmdTimeout = 0.0;
  return def;
}

TEST(Ackermann, SteeringForIsTheBicycleModelWithinTheLimit) {
  // w = v tan(angle) / L
  EXPECT_NEAR(steeringFor(1.0, 0.5, 0.4, 0.6, 0.0), std::atan(0.2), 1e-15);
  EXPECT_NEAR(steeringFor(-1.0, 0.5, 0.4, 0.6, 0.0), -std::atan(0.2), 1e-15);  // reversing
  EXPECT_EQ(steeringFor(1.0, 10.0, 0.4, 0.6, 0.0), 0.6);
  EXPECT_EQ(steeringFor(1.0, -10.0, 0.4, 0.6, 0.0), -0.6);
  EXPECT_EQ(steeringFor(0.0, 1.0, 0.4, 0.6, 0.3), 0.3);  // at rest: no angle turns it
}

TEST(Ackermann, TurnsAtTheAskedRateWhenTheSteeringAllowsIt) {
  DriveWorld w(car(0.4, 0.6), Vec2::Zero(), DeviceType::Ackermann);
  for (int i = 0; i < 300; ++i) {
    w.drive.command(1.0, 0.5, w.now);
    w.step();
  }
  EXPECT_NEAR(w.drive.steeringAngle(), std::atan(0.5 * 0.4 / 1.0), 1e-12);
  EXPECT_NEAR(w.drive.turnRate(), 0.5, 1e-12);
  EXPECT_NEAR(w.body().angularVelocity, 0.5, 1e-6);
  // The rear axle (the body's origin) moves along the heading half a step back (the drive aims
  // along the mid-step heading): no sideways slip there.
  const Vec2 origin = w.body().velocityAt(w.body().xf.p);
  const Rot midStep(w.body().angle - 0.5 * 0.5 * kDt);
  EXPECT_NEAR(midStep.applyInverse(origin).y(), 0.0, 1e-6);
  EXPECT_NEAR(midStep.applyInverse(origin).x(), 1.0, 1e-6);
  EXPECT_NEAR((w.body().xf.p - w.drive.odometry().position).norm(), 0.0, 0.01);
}

TEST(Ackermann, TheTurningRadiusRespectsTheSteeringLimit) {
  const double wheelbase = 0.5, limit = 0.4;
  const double tightest = wheelbase / std::tan(limit);  // 1.18 m
  DriveWorld w(car(wheelbase, limit), Vec2::Zero(), DeviceType::Ackermann);
  // Asking for 3 rad/s at 1 m/s, a radius of 0.33 m, gets the tightest turn instead.
  for (int i = 0; i < 200; ++i) {
    w.drive.command(1.0, 3.0, w.now);
    w.step();
  }
  EXPECT_NEAR(w.drive.steeringAngle(), limit, 1e-12);
  const double radius = w.body().linearVelocity.norm() / std::abs(w.body().angularVelocity);
  EXPECT_NEAR(radius, tightest, 0.01);
  // Over a whole turn at the limit, the rear axle stays on that circle: its points all lie
  // `tightest` from the centre the first quarter turn shows.
  std::vector<Vec2> path;
  for (int i = 0; i < 800; ++i) {
    w.drive.command(1.0, 3.0, w.now);
    w.step();
    path.push_back(w.body().xf.p);
  }
  const Vec2 heading = w.body().xf.q.apply(Vec2(1.0, 0.0));
  const Vec2 center = w.body().xf.p + tightest * Vec2(-heading.y(), heading.x());
  for (const Vec2& p : path) EXPECT_NEAR((p - center).norm(), tightest, 0.02);
}

TEST(Ackermann, TheSteeringTurnsAtItsRateAndACarAtRestCannotTurn) {
  DriveWorld w(car(0.4, 0.6), Vec2::Zero(), DeviceType::Ackermann);
  w.drive.command(0.0, 1.0, w.now);
  w.step(100);
  EXPECT_EQ(w.drive.steeringAngle(), 0.0);
  EXPECT_NEAR(w.body().angle, 0.0, 1e-12);
  // Moving: the wheels turn at 2 rad/s towards the limit of 0.6 rad, 0.3 s.
  for (int i = 0; i < 10; ++i) {
    w.drive.command(0.5, 10.0, w.now);
    w.step();
  }
  EXPECT_NEAR(w.drive.steeringAngle(), 0.2, 1e-12);
  for (int i = 0; i < 30; ++i) {
    w.drive.command(0.5, 10.0, w.now);
    w.step();
  }
  EXPECT_NEAR(w.drive.steeringAngle(), 0.6, 1e-12);
  // Reversing with the wheels turned left swings the nose right: the turn rate's sign follows v.
  for (int i = 0; i < 200; ++i) {
    w.drive.command(-0.5, -0.5 * std::tan(0.6) / 0.4, w.now);
    w.step();
  }
  EXPECT_NEAR(w.drive.steeringAngle(), 0.6, 1e-12);
  EXPECT_LT(w.body().angularVelocity, 0.0);
}

}  // namespace
}  // namespace impulse2d
