// Properties that must hold for any scene, on seeded random scenes, under every solver
// (all_solvers.hpp):
// - no NaN or inf, and nothing removed for leaving the world, ever;
// - a closed system (no gravity, no static bodies, no joints) conserves linear momentum to
//   round-off, angular momentum too when no position pass moves bodies behind the velocities'
//   back (position_iterations 0), and its kinetic energy never grows;
// - a pile dropped on the ground settles with no contact deeper than the allowed penetration.
#include <gtest/gtest.h>
#include <impulse2d/world.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "all_solvers.hpp"
#include "test_scenes.hpp"

namespace impulse2d {
namespace {

using test::SolverCase;

constexpr unsigned kSeeds[] = {1, 2, 3, 4, 5};

// A random body: box, circle, regular polygon or a two-shape compound, at most 0.6 m from its
// origin, so bodies on a 1.5 m grid start apart.
BodyDef randomBody(std::mt19937& rng, const std::string& name, const Vec2& position) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  BodyDef def;
  def.name = name;
  def.position = position;
  def.angle = 6.28 * unit(rng);
  const int kind = static_cast<int>(rng() % 4);
  ShapeDef shape;
  shape.friction = 0.2 + 0.6 * unit(rng);
  shape.restitution = 0.5 * unit(rng);
  shape.density = 0.5 + 2.0 * unit(rng);
  if (kind == 0 || kind == 3) {
    shape.kind = ShapeKind::Box;
    shape.size = Vec2(0.2 + 0.6 * unit(rng), 0.2 + 0.6 * unit(rng));
  } else if (kind == 1) {
    shape.kind = ShapeKind::Circle;
    shape.radius = 0.1 + 0.3 * unit(rng);
  } else {
    shape.kind = ShapeKind::Polygon;
    const int n = 3 + static_cast<int>(rng() % 6);
    const double r = 0.2 + 0.35 * unit(rng);
    for (int i = 0; i < n; ++i) {
      const double a = 2.0 * kPi * i / n;
      shape.vertices.emplace_back(r * std::cos(a), r * std::sin(a));
    }
  }
  if (kind == 3) {  // compound: the box plus a circle on its side
    shape.size *= 0.5;
    shape.offset = Vec2(-0.2, 0.0);
    def.shapes.push_back(shape);
    shape.kind = ShapeKind::Circle;
    shape.radius = 0.15;
    shape.offset = Vec2(0.3, 0.0);
  }
  def.shapes.push_back(shape);
  return def;
}

// `count` random dynamic bodies on a grid `columns` wide with its lower left cell at `corner`,
// moving at up to `speed` m/s and 3 rad/s.
void addRandomBodies(World& world, std::mt19937& rng, int count, int columns, const Vec2& corner,
                     double speed) {
  std::uniform_real_distribution<double> sym(-1.0, 1.0);
  for (int i = 0; i < count; ++i) {
    const Vec2 cell = corner + 1.5 * Vec2(i % columns, i / columns);
    BodyDef def = randomBody(rng, "b" + std::to_string(i), cell + Vec2(0.1 * sym(rng), 0.0));
    def.linearVelocity = speed * Vec2(sym(rng), sym(rng));
    def.angularVelocity = 3.0 * sym(rng);
    std::string error;
    ASSERT_TRUE(world.createBody(def, &error).valid()) << error;
  }
}

bool finiteState(const World& world) {
  for (const BodyId id : world.bodies()) {
    const Body& b = world.body(id);
    if (!isFinite(b.xf.p) || !std::isfinite(b.angle) || !isFinite(b.linearVelocity) ||
        !std::isfinite(b.angularVelocity)) {
      return false;
    }
  }
  return true;
}

double kineticEnergy(const World& world) {
  double e = 0.0;
  for (const BodyId id : world.bodies()) {
    const Body& b = world.body(id);
    e += 0.5 * b.mass * b.linearVelocity.squaredNorm() +
         0.5 * b.inertia * b.angularVelocity * b.angularVelocity;
  }
  return e;
}

// The scale against which momentum round-off is measured: the sum of the magnitudes.
test::Momentum momentumScale(const World& world) {
  test::Momentum m;
  for (const BodyId id : world.bodies()) {
    const Body& b = world.body(id);
    m.linear += b.mass * b.linearVelocity.cwiseAbs();
    m.angular += std::abs(b.mass * cross(b.center, b.linearVelocity)) +
                 std::abs(b.inertia * b.angularVelocity);
  }
  return m;
}

class Properties : public ::testing::TestWithParam<SolverCase> {
 protected:
  WorldDef settings() const {
    WorldDef def;
    def.solver = GetParam().type;
    return def;
  }
};

TEST_P(Properties, NoNanInRandomScenesWithJointsAndGravity) {
  for (const unsigned seed : kSeeds) {
    std::mt19937 rng(seed);
    World world(settings());
    test::addGround(world, 30.0);
    addRandomBodies(world, rng, 40, 8, Vec2(-5.0, 1.0), 5.0);
    // Joints between grid neighbours, every type.
    const std::vector<BodyId> bodies = world.bodies();
    for (size_t i = 1; i + 1 < bodies.size(); i += 3) {
      JointDef joint;
      joint.name = "j" + std::to_string(i);
      joint.type = static_cast<JointType>(i % 4);
      joint.bodyA = bodies[i];
      joint.bodyB = bodies[i + 1];
      joint.anchor = 0.5 * (world.body(bodies[i]).xf.p + world.body(bodies[i + 1]).xf.p);
      joint.axis = Vec2(1.0, 0.0);
      std::string error;
      ASSERT_TRUE(world.createJoint(joint, &error).valid()) << error;
    }
    for (int step = 0; step < 600; ++step) {
      world.step();
      ASSERT_TRUE(finiteState(world)) << "seed " << seed << " step " << step;
    }
    EXPECT_EQ(world.removedBodyCount(), 0u) << "seed " << seed;
  }
}

// Round-off: relative to the sum of the magnitudes, after 500 steps of a few hundred flops
// each on every body.
constexpr double kMomentumTolerance = 1e-12;
// Kinetic energy may not grow beyond round-off: 1e-9 relative. (Collisions here are at most
// 2 x 3 m/s, above the 1 m/s restitution threshold, with restitution <= 0.5.)
constexpr double kEnergyTolerance = 1e-9;

void runClosedSystem(const WorldDef& def, unsigned seed, bool checkAngular) {
  std::mt19937 rng(seed);
  World world(def);
  world.settings().gravity = Vec2::Zero();
  // Packed so that most bodies collide within the run.
  addRandomBodies(world, rng, 36, 6, Vec2(-4.0, -4.0), 3.0);
  const test::Momentum start = test::momentum(world);
  const test::Momentum scale = momentumScale(world);
  const double energy0 = kineticEnergy(world);
  double energyMax = energy0, worstLinear = 0.0, worstAngular = 0.0;
  size_t contactsSeen = 0;
  for (int step = 0; step < 500; ++step) {
    world.step();
    contactsSeen += world.contactCount();
    const test::Momentum now = test::momentum(world);
    worstLinear = std::max(worstLinear, (now.linear - start.linear).norm() / scale.linear.norm());
    worstAngular = std::max(worstAngular, std::abs(now.angular - start.angular) / scale.angular);
    energyMax = std::max(energyMax, kineticEnergy(world));
  }
  EXPECT_GT(contactsSeen, 20u) << "the bodies must actually collide";
  EXPECT_LE(worstLinear, kMomentumTolerance) << "seed " << seed;
  if (checkAngular) {
    EXPECT_LE(worstAngular, kMomentumTolerance) << "seed " << seed;
  }
  EXPECT_LE(energyMax, energy0 * (1.0 + kEnergyTolerance)) << "seed " << seed;
  std::printf(
      "property: closed system seed %u: momentum drift %.2e linear, %.2e angular; "
      "energy %.4f J -> max %.4f J, end %.4f J\n",
      seed, worstLinear, worstAngular, energy0, energyMax, kineticEnergy(world));
}

TEST_P(Properties, ClosedSystemConservesLinearMomentumAndNeverGainsEnergy) {
  for (const unsigned seed : kSeeds) runClosedSystem(settings(), seed, false);
}

TEST_P(Properties, ClosedSystemWithoutPositionPassConservesAngularMomentum) {
  WorldDef def = settings();
  def.positionIterations = 0;
  for (const unsigned seed : kSeeds) runClosedSystem(def, seed, true);
}

// After settling, no contact is deeper than this. The NGS pass stops once every overlap is
// within 3 linear slops (15 mm); Baumgarte leaves linear_slop plus what gravity sinks a heavy
// body per step before its push-out catches up.
constexpr double kSettledDepth = 3.0 * 0.005;

TEST_P(Properties, PilesSettleWithinTheAllowedPenetration) {
  for (const unsigned seed : kSeeds) {
    std::mt19937 rng(seed);
    World world(settings());
    test::addGround(world, 12.0);
    test::addBox(world, "left", Vec2(-6.5, 5.0), 1.0, 10.0, BodyType::Static);
    test::addBox(world, "right", Vec2(6.5, 5.0), 1.0, 10.0, BodyType::Static);
    addRandomBodies(world, rng, 40, 7, Vec2(-4.5, 1.0), 1.0);
    for (int step = 0; step < 800; ++step) world.step();
    double deepest = 0.0;
    for (const ContactInfo& c : world.contacts()) deepest = std::min(deepest, c.separation);
    EXPECT_GE(deepest, -kSettledDepth) << "seed " << seed;
    std::printf("property: pile seed %u: deepest contact %.2f mm\n", seed, -1e3 * deepest);
  }
}

INSTANTIATE_TEST_SUITE_P(AllSolvers, Properties, ::testing::ValuesIn(test::allSolvers()),
                         test::SolverCaseName());

}  // namespace
}  // namespace impulse2d
