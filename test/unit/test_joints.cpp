// Prismatic, weld and distance joints: closed-form motions with stated tolerances, validation
// messages naming the YAML key, collide_connected, and joints going with their bodies.
#include <gtest/gtest.h>
#include <impulse2d/world.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "test_scenes.hpp"

namespace impulse2d {
namespace {

using test::momentum;
using test::Momentum;

using test::addBox;
using test::addCircle;

const auto& kSolvers = kAllSolvers;

WorldDef worldDef(SolverType solver, const Vec2& gravity = Vec2(0.0, -9.81)) {
  WorldDef def;
  def.solver = solver;
  def.gravity = gravity;
  return def;
}

// Mean period from the upward zero crossings of f(t) - centre, interpolated within the step.
template <class Sample>
double measurePeriod(World& world, double duration, double centre, Sample sample) {
  std::vector<double> crossings;
  double previous = sample() - centre;
  while (world.time() < duration) {
    world.step();
    const double x = sample() - centre;
    if (previous < 0.0 && x >= 0.0) {
      crossings.push_back(world.time() - world.settings().timeStep * x / (x - previous));
    }
    previous = x;
  }
  if (crossings.size() < 3) return std::numeric_limits<double>::quiet_NaN();
  return (crossings.back() - crossings.front()) / (crossings.size() - 1);
}

// --- prismatic ---

// A rail at 45 degrees through the origin, fixed in a static body; B is a 1 x 0.5 box whose
// centre is 0.5 m to the side of the anchor, so gravity also twists it about the rail.
struct Rail {
  BodyId ground, slider;
  JointId joint;
  Vec2 axis;
};

Rail makeRail(World& world, JointDef joint = JointDef()) {
  Rail rail;
  rail.axis = Vec2(1.0, 1.0).normalized();
  rail.ground = addBox(world, "ground", Vec2::Zero(), 0.2, 0.2, BodyType::Static);
  rail.slider = addBox(world, "slider", Vec2(0.5, 0.0), 1.0, 0.5, BodyType::Dynamic);
  joint.type = JointType::Prismatic;
  joint.bodyA = rail.ground;
  joint.bodyB = rail.slider;
  joint.anchor = Vec2::Zero();
  joint.axis = Vec2(2.0, 2.0);  // not unit on purpose
  std::string error;
  rail.joint = world.createJoint(joint, &error);
  EXPECT_TRUE(rail.joint.valid()) << error;
  return rail;
}

TEST(Prismatic, SlidesDownATiltedRailLikeAFrictionlessBead) {
  // No rotation and no motion across the rail: only gravity's component along it remains,
  // a = g |u . g_dir| = 9.81 sin(45 deg), downhill.
  const double expected = 9.81 * std::sin(kPi / 4.0);
  for (SolverType solver : kSolvers) {
    SCOPED_TRACE(solverName(solver));
    World world(worldDef(solver));
    const Rail rail = makeRail(world);
    double worstOff = 0.0, worstTurn = 0.0;
    double v1 = 0.0;
    for (int i = 1; i <= 150; ++i) {
      world.step();
      const Body& b = world.body(rail.slider);
      const Vec2 anchorB = b.xf.apply(Vec2(-0.5, 0.0));  // the anchor point on B
      worstOff = std::max(worstOff, std::abs(cross(rail.axis, anchorB)));
      worstTurn = std::max(worstTurn, std::abs(b.angle));
      if (i == 50) v1 = world.jointState(rail.joint).velocity;
    }
    const JointState state = world.jointState(rail.joint);
    const double acceleration = -(state.velocity - v1) / 1.0;
    EXPECT_NEAR(acceleration, expected, 0.01 * expected);
    EXPECT_NEAR(state.velocity, world.body(rail.slider).linearVelocity.dot(rail.axis), 1e-9);
    EXPECT_NEAR(state.position, (state.anchorB - state.anchorA).dot(rail.axis), 1e-9);
    EXPECT_LT(worstOff, 1e-3) << "m off the rail";
    EXPECT_LT(worstTurn, 1e-3) << "rad turned";
  }
}

TEST(Prismatic, LimitsStopTheSliderAtBothEnds) {
  for (SolverType solver : kSolvers) {
    SCOPED_TRACE(solverName(solver));
    JointDef joint;
    joint.enableLimit = true;
    joint.lower = -1.0;
    joint.upper = 0.5;
    World world(worldDef(solver));
    const Rail rail = makeRail(world, joint);
    double lowest = 0.0;
    for (int i = 0; i < 200; ++i) {
      world.step();
      lowest = std::min(lowest, world.jointState(rail.joint).position);
    }
    EXPECT_GT(lowest, -1.0 - 0.01);
    EXPECT_NEAR(world.jointState(rail.joint).position, -1.0, 0.01);

    // Thrown up the rail at 8 m/s it would travel 8^2 / (2 a) = 4.6 m: the upper limit stops it.
    world.setVelocity(rail.slider, 8.0 * rail.axis, 0.0);
    double highest = -1.0;
    for (int i = 0; i < 100; ++i) {
      world.step();
      highest = std::max(highest, world.jointState(rail.joint).position);
    }
    EXPECT_LT(highest, 0.5 + 0.01);
    EXPECT_GT(highest, 0.5 - 0.01) << "it reached the upper limit";
  }
}

TEST(Prismatic, MotorDrivesAtItsSpeedWithinItsForce) {
  const WorldDef def = worldDef(SolverType::Baumgarte, Vec2::Zero());
  JointDef joint;
  joint.enableMotor = true;
  joint.motorSpeed = -1.5;
  joint.maxMotorTorque = 1000.0;  // N
  World strong(def);
  const Rail fast = makeRail(strong, joint);
  for (int i = 0; i < 10; ++i) strong.step();
  EXPECT_NEAR(strong.jointState(fast.joint).velocity, -1.5, 1e-6);
  EXPECT_NEAR(strong.body(fast.slider).angle, 0.0, 1e-9);

  // Saturated, the motor pushes with exactly its maximum force: a = F / m.
  joint.maxMotorTorque = 0.2;
  World weak(def);
  const Rail slow = makeRail(weak, joint);
  for (int i = 0; i < 100; ++i) weak.step();
  const double mass = weak.body(slow.slider).mass;
  EXPECT_NEAR(weak.jointState(slow.joint).velocity, -0.2 / mass * weak.time(), 1e-9);
}

// --- weld ---

TEST(Weld, HoldsACantileverStraight) {
  // A 3 m beam welded to a wall, whole or as two welded halves (which needs the iterations to
  // converge across both joints). Longer rigid chains are the Baumgarte solver's weak spot: with
  // the default beta 0.2 and 8 iterations, three or more welded segments oscillate and fold.
  for (SolverType solver : kSolvers) {
    for (int segments : {1, 2}) {
      SCOPED_TRACE(std::string(solverName(solver)) + ", segments " + std::to_string(segments));
      World world(worldDef(solver));
      BodyId previous = addBox(world, "wall", Vec2(-0.5, 0.0), 1.0, 4.0, BodyType::Static);
      const double length = 3.0 / segments;
      for (int i = 0; i < segments; ++i) {
        const BodyId segment =
            addBox(world, "beam" + std::to_string(i), Vec2((i + 0.5) * length, 0.0), length, 0.2,
                   BodyType::Dynamic);
        JointDef joint;
        joint.type = JointType::Weld;
        joint.bodyA = previous;
        joint.bodyB = segment;
        joint.anchor = Vec2(i * length, 0.0);
        ASSERT_TRUE(world.createJoint(joint).valid());
        previous = segment;
      }
      double worst = 0.0;
      for (int i = 0; i < 200; ++i) {  // 2 s
        world.step();
        worst =
            std::max(worst, std::abs(world.body(previous).xf.apply(Vec2(0.5 * length, 0.0)).y()));
      }
      EXPECT_LT(worst, 0.01) << "m of tip deflection";
    }
  }
}

TEST(Weld, SoftWeldSwingsAtItsFrequency) {
  // The anchor is at B's centre of mass, so the angle row alone carries the motion: a torsional
  // spring k = I w^2 on inertia I oscillates at exactly the requested frequency.
  for (SolverType solver : kSolvers) {
    SCOPED_TRACE(solverName(solver));
    World world(worldDef(solver));
    const BodyId wall = addBox(world, "wall", Vec2(-1.0, 0.0), 0.2, 0.2, BodyType::Static);
    const BodyId paddle = addBox(world, "paddle", Vec2(1.0, 0.0), 2.0, 0.3, BodyType::Dynamic);
    const JointDef joint = test::weldDef(wall, paddle, Vec2(1.0, 0.0), 2.0);
    const JointId id = world.createJoint(joint);
    ASSERT_TRUE(id.valid());
    world.setVelocity(paddle, Vec2::Zero(), 1.0);
    const double period =
        measurePeriod(world, 3.0, 0.0, [&] { return world.jointState(id).position; });
    EXPECT_NEAR(period, 1.0 / joint.frequency, 0.1 / joint.frequency);
    const JointState state = world.jointState(id);
    EXPECT_LT((state.anchorA - state.anchorB).norm(), 1e-3);
  }
}

// --- distance ---

using test::distanceDef;

TEST(Distance, RigidRodKeepsItsLengthWhileSwinging) {
  // With the Baumgarte solver the rod grows (v dt)^2 / (2 L) per step (a chord instead of an
  // arc), of which the bias removes the fraction beta: the error settles near
  // (v dt)^2 / (2 L beta), about 0.6 mm for this 30 degree swing and 2.5 mm for 60 degrees.
  // NGS removes it in the position pass.
  for (SolverType solver : kSolvers) {
    SCOPED_TRACE(solverName(solver));
    World world(worldDef(solver));
    const BodyId pivot = addBox(world, "pivot", Vec2::Zero(), 0.1, 0.1, BodyType::Static);
    // The rod ends at the bob's edge, 1 m from the pivot, not at its centre.
    const Vec2 bobAt(std::sin(kPi / 6.0), -std::cos(kPi / 6.0));
    const BodyId bob = addCircle(world, "bob", 1.2 * bobAt, 0.2, BodyType::Dynamic);
    JointDef joint = distanceDef(pivot, bob, Vec2::Zero());
    joint.anchorB = bobAt;
    joint.useAnchorB = true;
    const JointId id = world.createJoint(joint);
    ASSERT_TRUE(id.valid());
    EXPECT_NEAR(world.jointState(id).position, 1.0, 1e-12) << "length <= 0: measured";
    double worst = 0.0, lowest = 0.0;
    for (int i = 0; i < 300; ++i) {
      world.step();
      worst = std::max(worst, std::abs(world.jointState(id).position - 1.0));
      lowest = std::min(lowest, world.body(bob).xf.p.y());
    }
    EXPECT_LT(worst, 1e-3) << "m of length error";
    EXPECT_LT(lowest, -1.19) << "it swung through the bottom";
  }
}

TEST(Distance, SpringOscillatesAtItsFrequency) {
  // A point-like mass on a spring to a static anchor: k = m w^2, so the period is 1 / f.
  for (SolverType solver : kSolvers) {
    SCOPED_TRACE(solverName(solver));
    World world(worldDef(solver, Vec2::Zero()));
    const BodyId anchor = addBox(world, "anchor", Vec2::Zero(), 0.1, 0.1, BodyType::Static);
    const BodyId mass = addCircle(world, "mass", Vec2(1.3, 0.0), 0.1, BodyType::Dynamic);
    JointDef joint = distanceDef(anchor, mass, Vec2::Zero());
    joint.length = 1.0;
    joint.frequency = 1.5;
    const JointId id = world.createJoint(joint);
    ASSERT_TRUE(id.valid());
    const double period =
        measurePeriod(world, 4.0, 1.0, [&] { return world.jointState(id).position; });
    EXPECT_NEAR(period, 1.0 / joint.frequency, 0.05 / joint.frequency);
  }
}

TEST(Distance, SpringLimitsHold) {
  for (SolverType solver : kSolvers) {
    SCOPED_TRACE(solverName(solver));
    // Hanging from a soft spring the mass would settle g / w^2 = 1 m below the rest length;
    // maxLength catches it.
    World world(worldDef(solver));
    const BodyId anchor = addBox(world, "anchor", Vec2::Zero(), 0.1, 0.1, BodyType::Static);
    const BodyId mass = addCircle(world, "mass", Vec2(0.0, -1.0), 0.1, BodyType::Dynamic);
    JointDef joint = distanceDef(anchor, mass, Vec2::Zero());
    joint.frequency = 0.5;
    joint.dampingRatio = 0.1;
    joint.minLength = 0.5;
    joint.maxLength = 1.2;
    const JointId id = world.createJoint(joint);
    ASSERT_TRUE(id.valid());
    double longest = 0.0;
    for (int i = 0; i < 300; ++i) {
      world.step();
      longest = std::max(longest, world.jointState(id).position);
    }
    EXPECT_LT(longest, 1.2 + 0.01);
    EXPECT_NEAR(world.jointState(id).position, 1.2, 0.01) << "resting on the limit";

    // Thrown at the anchor at 6 m/s: minLength stops it.
    world.settings().gravity = Vec2::Zero();
    world.setVelocity(mass, Vec2(0.0, 6.0), 0.0);
    double shortest = 10.0;
    for (int i = 0; i < 100; ++i) {
      world.step();
      shortest = std::min(shortest, world.jointState(id).position);
    }
    EXPECT_GT(shortest, 0.5 - 0.01);
    EXPECT_LT(shortest, 0.5 + 0.01) << "it reached the lower limit";
  }
}

// --- every type ---

TEST(JointTypes, TwoFreeBodiesKeepTheirMomentumAndTheirJoint) {
  // Joint impulses act equally and oppositely along each row's Jacobian; if a Jacobian were
  // derived wrongly (say, the prismatic's reaction on A taken at A's anchor instead of at B),
  // the pair would gain angular momentum. Baumgarte only: NGS moves bodies without momentum.
  for (JointType type : {JointType::Prismatic, JointType::Weld, JointType::Distance}) {
    SCOPED_TRACE(type == JointType::Prismatic ? "prismatic"
                 : type == JointType::Weld    ? "weld"
                                              : "distance");
    World world(worldDef(SolverType::Baumgarte, Vec2::Zero()));
    const BodyId a = addBox(world, "a", Vec2(-0.5, 0.2), 1.0, 0.6, BodyType::Dynamic, 2.0);
    const BodyId b = addBox(world, "b", Vec2(1.5, -0.1), 0.8, 0.4, BodyType::Dynamic, 1.0);
    JointDef joint;
    joint.type = type;
    joint.bodyA = a;
    joint.bodyB = b;
    joint.anchor = Vec2(0.5, 0.0);
    joint.axis = Vec2(1.0, 0.3);
    const JointId id = world.createJoint(joint);
    ASSERT_TRUE(id.valid());
    world.setVelocity(a, Vec2(0.3, -0.2), 2.0);
    world.setVelocity(b, Vec2(-0.5, 1.0), -1.0);
    const Momentum before = momentum(world);
    const JointState start = world.jointState(id);
    for (int i = 0; i < 200; ++i) world.step();
    const Momentum after = momentum(world);
    EXPECT_NEAR(after.linear.x(), before.linear.x(), 1e-9);
    EXPECT_NEAR(after.linear.y(), before.linear.y(), 1e-9);
    // The weld's point rows C = pB - pA are not invariant under a rotation of the whole pair
    // (the vector turns with it), so while the anchors are apart by a gap g an impulse P adds the
    // torque g x P: tiny, but not rounding. The prismatic's and distance's rows are invariant.
    EXPECT_NEAR(after.angular, before.angular, type == JointType::Weld ? 1e-5 : 1e-9);

    // And the joint still holds: 5 mm / 0.01 rad while the pair tumbles at ~2 rad/s.
    const JointState now = world.jointState(id);
    const double turn = world.body(b).angle - world.body(a).angle;
    const Vec2 axis = world.body(a).xf.q.apply(joint.axis.normalized());
    switch (type) {
      case JointType::Prismatic:
        EXPECT_LT(std::abs(cross(axis, Vec2(now.anchorB - now.anchorA))), 0.005);
        EXPECT_LT(std::abs(turn), 0.01);
        break;
      case JointType::Weld:
        EXPECT_LT((now.anchorB - now.anchorA).norm(), 0.005);
        EXPECT_LT(std::abs(turn), 0.01);
        break;
      default:
        EXPECT_NEAR(now.position, start.position, 0.005);
        break;
    }
  }
}

// --- validation ---

TEST(JointValidation, BadDefinitionsAreRefusedNamingTheKey) {
  World world;
  const BodyId a = addBox(world, "a", Vec2::Zero(), 1.0, 1.0, BodyType::Static);
  const BodyId b = addBox(world, "b", Vec2(2.0, 0.0), 1.0, 1.0, BodyType::Dynamic);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    const char* what;
    JointType type;
    void (*spoil)(JointDef&, double);
    const char* key;
  };
  const Case cases[] = {
      {"zero axis", JointType::Prismatic, [](JointDef& d, double) { d.axis = Vec2::Zero(); },
       "axis:"},
      {"nan axis", JointType::Prismatic, [](JointDef& d, double n) { d.axis.x() = n; }, "axis:"},
      {"prismatic limits reversed", JointType::Prismatic,
       [](JointDef& d, double) {
         d.enableLimit = true;
         d.lower = 1.0;
         d.upper = -1.0;
       },
       "lower:"},
      {"nan length", JointType::Distance, [](JointDef& d, double n) { d.length = n; }, "length:"},
      {"tiny length", JointType::Distance, [](JointDef& d, double) { d.length = 0.0005; },
       "length:"},
      {"length beyond max", JointType::Distance,
       [](JointDef& d, double) {
         d.length = 3.0;
         d.maxLength = 2.0;
       },
       "length:"},
      {"anchors together", JointType::Distance,
       [](JointDef& d, double) { d.anchor = Vec2(2.0, 0.0); }, "length:"},
      {"negative min", JointType::Distance, [](JointDef& d, double) { d.minLength = -1.0; },
       "min_length:"},
      {"min above max", JointType::Distance,
       [](JointDef& d, double) {
         d.minLength = 2.0;
         d.maxLength = 1.0;
       },
       "min_length:"},
      {"nan max", JointType::Distance, [](JointDef& d, double n) { d.maxLength = n; },
       "max_length:"},
      {"nan anchor_b", JointType::Distance,
       [](JointDef& d, double n) {
         d.useAnchorB = true;
         d.anchorB.y() = n;
       },
       "anchor_b:"},
      {"negative frequency", JointType::Weld, [](JointDef& d, double) { d.frequency = -1.0; },
       "frequency:"},
      {"infinite frequency", JointType::Distance,
       [](JointDef& d, double) { d.frequency = std::numeric_limits<double>::infinity(); },
       "frequency:"},
      {"negative damping", JointType::Weld, [](JointDef& d, double) { d.dampingRatio = -0.5; },
       "damping_ratio:"},
      {"nan damping", JointType::Distance, [](JointDef& d, double n) { d.dampingRatio = n; },
       "damping_ratio:"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    JointDef def;
    def.type = c.type;
    def.bodyA = a;
    def.bodyB = b;
    c.spoil(def, nan);
    std::string error;
    EXPECT_FALSE(world.createJoint(def, &error).valid());
    EXPECT_EQ(error.rfind(c.key, 0), 0u) << error;
  }
  EXPECT_EQ(world.jointCount(), 0u);

  // The unspoilt definitions of each type are accepted.
  for (JointType type : {JointType::Prismatic, JointType::Weld, JointType::Distance}) {
    JointDef def;
    def.type = type;
    def.bodyA = a;
    def.bodyB = b;
    std::string error;
    EXPECT_TRUE(world.createJoint(def, &error).valid()) << error;
  }
}

// --- bookkeeping ---

TEST(JointBookkeeping, CollideConnectedDecidesWhetherJointedBodiesTouch) {
  for (bool collide : {false, true}) {
    SCOPED_TRACE(collide ? "collide" : "no collide");
    World world(worldDef(SolverType::Baumgarte, Vec2::Zero()));
    const BodyId a = addBox(world, "a", Vec2::Zero(), 1.0, 1.0, BodyType::Dynamic);
    const BodyId b = addBox(world, "b", Vec2(0.5, 0.0), 1.0, 1.0, BodyType::Dynamic);
    JointDef joint;
    joint.type = JointType::Weld;
    joint.bodyA = a;
    joint.bodyB = b;
    joint.anchor = Vec2(0.25, 0.0);
    joint.collideConnected = collide;
    ASSERT_TRUE(world.createJoint(joint).valid());
    size_t most = 0;
    for (int i = 0; i < 20; ++i) {
      world.step();
      most = std::max(most, world.contactCount());
    }
    if (collide) {
      EXPECT_GT(most, 0u);
    } else {
      EXPECT_EQ(most, 0u);
    }
  }
}

TEST(JointBookkeeping, DestroyingABodyRemovesItsJointOfEveryType) {
  for (JointType type :
       {JointType::Revolute, JointType::Prismatic, JointType::Weld, JointType::Distance}) {
    for (bool destroyA : {false, true}) {
      World world;
      const BodyId a = addBox(world, "a", Vec2::Zero(), 1.0, 1.0, BodyType::Dynamic);
      const BodyId b = addBox(world, "b", Vec2(2.0, 0.0), 1.0, 1.0, BodyType::Dynamic);
      const BodyId other = addBox(world, "other", Vec2(5.0, 0.0), 1.0, 1.0, BodyType::Static);
      JointDef joint;
      joint.type = type;
      joint.bodyA = a;
      joint.bodyB = b;
      const JointId id = world.createJoint(joint);
      JointDef keep = joint;
      keep.anchor = Vec2(5.0, 0.0);
      keep.bodyA = other;
      keep.bodyB = destroyA ? b : a;  // the survivor keeps a joint to another body
      const JointId kept = world.createJoint(keep);
      ASSERT_TRUE(id.valid() && kept.valid());
      world.step();
      EXPECT_TRUE(world.destroyBody(destroyA ? a : b));
      EXPECT_FALSE(world.isValid(id));
      EXPECT_TRUE(world.isValid(kept));
      EXPECT_EQ(world.jointCount(), 1u);
      world.step();  // the survivor still steps
      EXPECT_TRUE(isFinite(world.body(destroyA ? b : a).xf.p));
    }
  }
}

// The sub-stepping solvers keep a step's joints in their own order for the next step
// (world_impl.hpp, heldJointOrder); a joint edited between steps must still be solved as edited,
// also when the edit leaves the same joints in the same order (a motor switched on, a joint
// replaced in the same slot).
TEST(JointBookkeeping, EditsBetweenStepsReachTheSolver) {
  for (SolverType solver : kSolvers) {
    SCOPED_TRACE(solverName(solver));
    {
      World world(worldDef(solver, Vec2::Zero()));
      const Rail rail = makeRail(world);
      for (int i = 0; i < 30; ++i) world.step();
      ASSERT_TRUE(world.setJointMotor(rail.joint, true, 2.0, 1000.0));
      for (int i = 0; i < 60; ++i) world.step();
      EXPECT_NEAR(world.body(rail.slider).linearVelocity.dot(rail.axis), 2.0, 0.02);
    }
    {
      World world(worldDef(solver));
      const BodyId ground = addBox(world, "ground", Vec2(0.0, 3.0), 0.2, 0.2, BodyType::Static);
      const BodyId bob = addBox(world, "bob", Vec2::Zero(), 0.5, 0.5, BodyType::Dynamic);
      JointDef joint;
      joint.type = JointType::Revolute;
      joint.bodyA = ground;
      joint.bodyB = bob;
      joint.anchor = Vec2(1.0, 0.0);  // level with the bob: it swings down
      const JointId first = world.createJoint(joint);
      for (int i = 0; i < 30; ++i) world.step();
      ASSERT_TRUE(world.destroyJoint(first));
      joint.anchor = world.body(bob).center + Vec2(0.0, 1.0);  // another pivot, same slot
      const JointId second = world.createJoint(joint);
      ASSERT_EQ(second.index, first.index);
      double widest = 0.0;
      for (int i = 0; i < 120; ++i) {
        world.step();
        const JointState state = world.jointState(second);
        widest = std::max(widest, (state.anchorB - state.anchorA).norm());
      }
      EXPECT_LT(widest, 0.01);  // m: the new pivot holds, not the old one
    }
  }
}

// The sub-steps keep their joints in held copies (world_impl.hpp, heldJointOrder) that are
// written back before anything else reads the joints' slots: a world switched between steps to a
// one-pass solver (which reads the slots) or to no warm starting (which drops the impulses kept
// there) steps exactly as one whose joints were written back after every step (here by a motor
// call that changes nothing).
TEST(JointBookkeeping, SettingsChangedBetweenStepsSeeTheLastStepsJoints) {
  const std::vector<std::pair<const char*, void (*)(WorldDef&)>> changes = {
      {"to baumgarte", [](WorldDef& d) { d.solver = SolverType::Baumgarte; }},
      {"to ngs", [](WorldDef& d) { d.solver = SolverType::NonlinearGaussSeidel; }},
      {"no warm starting", [](WorldDef& d) { d.warmStarting = false; }},
  };
  for (const auto& [name, change] : changes) {
    SCOPED_TRACE(name);
    uint64_t hashes[2] = {0, 0};
    for (const bool writtenBack : {false, true}) {
      WorldDef def = worldDef(SolverType::SubstepNgs);
      def.enableSleep = false;
      World world(def);
      BodyId above = addBox(world, "top", Vec2(0.0, 10.0), 0.2, 0.2, BodyType::Static);
      std::vector<JointId> chain;
      for (int i = 0; i < 10; ++i) {
        const BodyId link = addBox(world, "link" + std::to_string(i), Vec2(0.3 * i, 9.75 - 0.5 * i),
                                   0.1, 0.5, BodyType::Dynamic);
        JointDef joint;
        joint.type = JointType::Revolute;
        joint.bodyA = above;
        joint.bodyB = link;
        joint.anchor = Vec2(0.3 * i, 10.0 - 0.5 * i);
        chain.push_back(world.createJoint(joint));
        ASSERT_TRUE(chain.back().valid());
        above = link;
      }
      for (int i = 0; i < 70; ++i) {
        if (i == 60) change(world.settings());
        world.step();
        if (writtenBack) {
          ASSERT_TRUE(world.setJointMotor(chain[0], false, 0.0, 0.0));
        }
      }
      hashes[writtenBack] = world.hash();
    }
    EXPECT_EQ(hashes[0], hashes[1]);
  }
}

}  // namespace
}  // namespace impulse2d
