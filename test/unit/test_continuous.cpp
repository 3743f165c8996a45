// GJK distance, time of impact, and the continuous pass that keeps fast bodies from tunnelling.
#include <gtest/gtest.h>
#include <impulse2d/world.hpp>

#include <random>

#include "all_solvers.hpp"
#include "distance.hpp"
#include "test_scenes.hpp"

namespace impulse2d {
namespace {

using test::boxShape;
using test::circleShape;

TEST(Distance, HandComputedCases) {
  const Shape box = boxShape(2.0, 2.0), ball = circleShape(0.5);
  // Face to face: unit boxes 3 m apart centre to centre -> 1 m gap.
  EXPECT_NEAR(shapeDistance(box, Transform(), box, Transform(Vec2(3, 0), Rot())).distance, 1.0,
              1e-12);
  // Corner to corner along the diagonal.
  const DistanceResult corner = shapeDistance(box, Transform(), box, Transform(Vec2(3, 3), Rot()));
  EXPECT_NEAR(corner.distance, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR((corner.pointA - Vec2(1, 1)).norm(), 0.0, 1e-12);
  // Circle above a rotated box's corner.
  const DistanceResult tilted =
      shapeDistance(box, Transform(Vec2::Zero(), Rot(kPi / 4)), ball, Transform(Vec2(0, 3), Rot()));
  EXPECT_NEAR(tilted.distance, 3.0 - std::sqrt(2.0) - 0.5, 1e-12);
  // Overlap reports zero.
  EXPECT_EQ(shapeDistance(box, Transform(), ball, Transform(Vec2(0.5, 0.5), Rot())).distance, 0.0);
}

TEST(Distance, AgreesWithBruteForceOnRandomBoxes) {
  // Between separated convex polygons the distance is attained at a vertex of one against an
  // edge of the other: check all of those.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> pos(-4.0, 4.0), angle(-kPi, kPi), size(0.2, 2.0);
  int separated = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Shape a = boxShape(size(rng), size(rng));
    const Shape b = boxShape(size(rng), size(rng));
    const double ax = pos(rng), ay = pos(rng), aa = angle(rng);
    const double bx = pos(rng), by = pos(rng), ba = angle(rng);
    const Transform xfA(Vec2(ax, ay), Rot(aa)), xfB(Vec2(bx, by), Rot(ba));
    const double gjk = shapeDistance(a, xfA, b, xfB).distance;
    Polygon pa = transformed(a.polygon, xfA), pb = transformed(b.polygon, xfB);
    auto segmentDistance = [](const Vec2& p, const Vec2& s0, const Vec2& s1) {
      const Vec2 e = s1 - s0;
      const double t = std::clamp((p - s0).dot(e) / e.squaredNorm(), 0.0, 1.0);
      return (p - (s0 + t * e)).norm();
    };
    double brute = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        brute = std::min(brute,
                         segmentDistance(pa.vertices[i], pb.vertices[j], pb.vertices[(j + 1) % 4]));
        brute = std::min(brute,
                         segmentDistance(pb.vertices[i], pa.vertices[j], pa.vertices[(j + 1) % 4]));
      }
    }
    if (gjk > 0.0) {
      ++separated;
      EXPECT_NEAR(gjk, brute, 1e-9) << "trial " << trial;
    }
  }
  EXPECT_GT(separated, 1000);
}

TEST(Distance, TimeOfImpactStopsJustShortOfTheSurface) {
  const Shape wall = boxShape(0.1, 4.0), ball = circleShape(0.05);
  Sweep still;  // the wall at the origin
  Sweep flight;
  flight.c0 = Vec2(-5.0, 0.0);
  flight.c1 = Vec2(5.0, 0.0);
  const double target = 0.005;
  const double t = timeOfImpact(ball, flight, wall, still, target);
  // Contact when the ball's centre is at x = -0.05 - 0.05; the gap left is within [target, 1.25
  // target].
  const double gap = -(flight.at(t).p.x() + 0.05) - 0.05;
  EXPECT_GE(gap, target - 1e-9);
  EXPECT_LE(gap, 1.25 * target + 1e-9);
  // Moving away never hits.
  std::swap(flight.c0, flight.c1);
  flight.c0 = Vec2(-1.0, 0.0);
  flight.c1 = Vec2(-6.0, 0.0);
  EXPECT_EQ(timeOfImpact(ball, flight, wall, still, target), 1.0);
}

TEST(Continuous, BulletDoesNotPassThroughAThinWall) {
  World world;
  world.settings().gravity = Vec2::Zero();
  const BodyId wall = test::addBox(world, "wall", Vec2(0, 0), 0.1, 4.0, BodyType::Static);
  (void)wall;
  BodyDef bullet;
  bullet.name = "bullet";
  bullet.position = Vec2(-3.0, 0.3);
  bullet.linearVelocity = Vec2(300.0, 0.0);  // 3 m per step: 30 wall thicknesses
  bullet.bullet = true;
  ShapeDef ball;
  ball.kind = ShapeKind::Circle;
  ball.radius = 0.05;
  bullet.shapes.push_back(ball);
  const BodyId id = world.createBody(bullet);
  for (int i = 0; i < 100; ++i) {
    world.step();
    ASSERT_LT(world.body(id).xf.p.x(), -0.05 + 1e-6) << "step " << i;
  }
}

// Steps 300 times: `box`, falling onto 5 cm ground whose top is at y = 0, never comes out below it
// (a corner-first hit may leave it half in the ground for a step: its centre of mass is stopped at
// the surface at worst) and comes to rest on it.
void expectLandsOnGround(World& world, BodyId box) {
  for (int i = 0; i < 300; ++i) {
    world.step();
    ASSERT_GE(world.body(box).xf.p.y(), -1e-9) << "step " << i;
  }
  EXPECT_NEAR(world.body(box).xf.p.y(), 0.25, 0.01) << "it came to rest on the ground";
}

TEST(Continuous, FastBoxLandsOnThinGroundAndADynamicTargetStopsABullet) {
  World world;
  // 5 cm ground, a 0.5 m box arriving at 100 m/s: 1 m per step, 20 ground thicknesses.
  const BodyId ground =
      test::addBox(world, "ground", Vec2(0, -0.025), 20.0, 0.05, BodyType::Static);
  (void)ground;
  const BodyId box = test::addBox(world, "box", Vec2(0, 20.0), 0.5, 0.5, BodyType::Dynamic);
  world.setVelocity(box, Vec2(0.0, -100.0), 0.0);
  expectLandsOnGround(world, box);

  // A bullet against a thin free-floating dynamic plank: it must hit it, not skip over it.
  World space;
  space.settings().gravity = Vec2::Zero();
  const BodyId plank = test::addBox(space, "plank", Vec2(0, 0), 0.05, 2.0, BodyType::Dynamic);
  BodyDef def;
  def.name = "bullet";
  def.position = Vec2(-5.0, 0.0);
  def.linearVelocity = Vec2(300.0, 0.0);
  def.bullet = true;
  ShapeDef ball;
  ball.kind = ShapeKind::Circle;
  ball.radius = 0.05;
  def.shapes.push_back(ball);
  space.createBody(def);
  for (int i = 0; i < 10; ++i) space.step();
  EXPECT_GT(space.body(plank).linearVelocity.x(), 1.0) << "the plank was hit";
}

// Continuous collision sweeps bodies that are not bullets against the static shapes only, kept
// in a tree of their own: it must follow a static body that is moved, and forget one destroyed.
TEST(Continuous, FastBoxSeesAStaticBodyWhereItWasMovedAndNotOneDestroyed) {
  World world;
  // 5 cm ground made far away and moved under a 0.5 m box arriving at 100 m/s (1 m a step), and
  // a second ground across its path, destroyed before it gets there.
  const BodyId ground = test::addBox(world, "ground", Vec2(100, 100), 20.0, 0.05, BodyType::Static);
  const BodyId gone = test::addBox(world, "gone", Vec2(0, 10.0), 20.0, 0.05, BodyType::Static);
  const BodyId box = test::addBox(world, "box", Vec2(0, 20.0), 0.5, 0.5, BodyType::Dynamic);
  ASSERT_TRUE(world.setTransform(ground, Vec2(0, -0.025), 0.0));
  ASSERT_TRUE(world.destroyBody(gone));
  world.setVelocity(box, Vec2(0.0, -100.0), 0.0);
  expectLandsOnGround(world, box);
}

// Rods up to 2 m long, falling at 20-200 m/s and spinning at up to 200 rad/s (a tip at 200 m/s,
// turning 2 rad in a step) onto 5 cm ground: a corner hit may leave one end in contact while the
// rest swings round, which the continuous pass must stop before it passes the ground's middle.
TEST(Continuous, SpinningRodsNeverEndUpBelowThinGround) {
  for (SolverType solver : kAllSolvers) {
    SCOPED_TRACE(solverName(solver));
    for (int i = 0; i < 200; ++i) {
      WorldDef def;
      def.solver = solver;
      World world(def);
      test::addBox(world, "ground", Vec2(0, -0.025), 40.0, 0.05, BodyType::Static);
      const double speed = 20.0 + (i % 10) * 20.0, spin = -200.0 + (i / 10) * 20.0;
      const double length = 0.2 + (i % 7) * 0.3;
      const BodyId rod = test::addBox(world, "rod", Vec2(0.1 * (i % 5), 3.0 + length), length, 0.1,
                                      BodyType::Dynamic);
      world.setVelocity(rod, Vec2(0.3 * (i % 3), -speed), spin);
      for (int k = 0; k < 300; ++k) {
        world.step();
        const Body& b = world.body(rod);
        if (std::abs(b.center.x()) > 19.0) break;  // slid off the end of the ground
        ASSERT_GE(b.center.y(), -0.025) << "trial " << i << " step " << k;
      }
    }
  }
}

// A body resting over two slops deep and turning fast (a ragdoll's forearm on the ground in
// v3_rain) is swept from a pose already as deep as the continuous pass allows. It must still move:
// put back at its start every step, it stood frozen with its velocity while its joints tore open.
TEST(Continuous, ATurningBodyRestingDeepIsNotHeldAtItsStart) {
  for (SolverType solver : kAllSolvers) {
    SCOPED_TRACE(solverName(solver));
    for (double spin : {-20.0, -10.0, 10.0, 20.0}) {
      WorldDef def;
      def.solver = solver;
      World world(def);
      test::addBox(world, "ground", Vec2(0, -0.25), 10.0, 0.5, BodyType::Static);
      // Deeper than the pass's own allowance here (2 slops: the stick is 4 cm thick), and within
      // the 3 slops that the NGS passes leave alone.
      const double depth = 2.2 * def.linearSlop;
      const BodyId stick =
          test::addBox(world, "stick", Vec2(0, 0.02 - depth), 0.5, 0.04, BodyType::Dynamic);
      world.setVelocity(stick, Vec2(1.0, 2.0), spin);
      int held = 0;
      for (int k = 0; k < 10; ++k) {
        const Vec2 before = world.body(stick).center;
        const double angleBefore = world.body(stick).angle;
        world.step();
        const Body& b = world.body(stick);
        const bool moving = b.linearVelocity.norm() + std::abs(b.angularVelocity) * 0.25 > 0.5;
        if (moving && (b.center - before).norm() < 1e-9 && std::abs(b.angle - angleBefore) < 1e-9) {
          ++held;
        }
      }
      EXPECT_EQ(held, 0) << "spin " << spin;
    }
  }
}

// The sweeps of fast bodies that are not bullets run in parallel; bullets, which see the bodies
// put back before them, run in order after. A hail of fast boxes (many blocks of sweeps) through
// which bullets fly must end in the same state on any number of threads, under every solver.
TEST(Continuous, AHailOfFastBoxesAndBulletsIsTheSameOnAnyNumberOfThreads) {
  for (const test::SolverCase& solver : test::allSolvers()) {
    auto run = [&](int threads) {
      WorldDef def;
      def.solver = solver.type;
      def.threads = threads;
      World world(def);
      test::addBox(world, "ground", Vec2(0.0, -0.05), 40.0, 0.1, BodyType::Static);
      std::mt19937 rng(7);
      std::uniform_real_distribution<double> x(-15.0, 15.0), speed(20.0, 60.0), spin(-30.0, 30.0);
      for (int i = 0; i < 200; ++i) {
        const BodyId box = test::addBox(world, "box" + std::to_string(i),
                                        Vec2(x(rng), 0.5 + 0.02 * i), 0.1, 0.1, BodyType::Dynamic);
        world.setVelocity(box, Vec2(0.0, -speed(rng)), spin(rng));
      }
      for (int i = 0; i < 6; ++i) {
        BodyDef bullet;
        bullet.name = "bullet" + std::to_string(i);
        bullet.type = BodyType::Dynamic;
        bullet.bullet = true;
        bullet.position = Vec2(-18.0, 0.1 + 0.15 * i);
        ShapeDef shape;
        shape.kind = ShapeKind::Circle;
        shape.radius = 0.04;
        shape.density = 20.0;
        bullet.shapes.push_back(shape);
        world.setVelocity(world.createBody(bullet), Vec2(300.0, 0.0), 0.0);
      }
      for (int step = 0; step < 60; ++step) world.step();
      return world.hash();
    };
    const uint64_t one = run(1);
    for (const int threads : {2, 3}) EXPECT_EQ(run(threads), one) << solver.name << ", " << threads;
  }
}

}  // namespace
}  // namespace impulse2d
