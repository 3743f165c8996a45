// The hard-case suite, part two: things that move. Closed forms for the pendulum and the bounce,
// joint gaps for the chain and the bridge. Each case prints a "hard-case:" line per solver.
#include "hard_case_helpers.hpp"

#include <vector>

namespace impulse2d {
namespace {

using namespace hard_case;

/// The largest distance between the two anchors of any joint, over the whole run.
double largestJointGap(World& world, double seconds) {
  double widest = 0.0;
  while (world.time() < seconds - 1e-9) {
    world.step();
    for (JointId id : world.joints()) {
      const JointState s = world.jointState(id);
      widest = std::max(widest, (s.anchorA - s.anchorB).norm());
    }
  }
  return widest;
}

// A 40-link chain released horizontally whips its tip past 45 m/s; the top joints then carry
// many times the chain's weight. Held to 1 cm by the default solver; the others are reported.
TEST(HardCase, ChainOfFortyKeepsItsJointsClosed) {
  for (SolverType solver : kSolvers) {
    World world;
    load("chain40.yaml", solver, world);
    const double gap = largestJointGap(world, 10.0);
    ASSERT_TRUE(allFinite(world));
    report("chain40.yaml", solver, figures("largest_joint_gap=%.4f m", gap));
    if (solver == WorldDef().solver) {
      EXPECT_LT(gap, 0.01);
    }
  }
}

// Twenty planks spanning exactly the gap between two posts, a load of ten planks in the middle:
// the bridge can only sag by stretching its joints, so the gaps measure how rigid they are.
TEST(HardCase, BridgeOfTwentyPlanksCarriesItsLoad) {
  for (SolverType solver : kSolvers) {
    World world;
    load("bridge20.yaml", solver, world);
    const double gap = largestJointGap(world, 10.0);
    ASSERT_TRUE(allFinite(world));
    const Body& load = world.body(world.findBody("load"));
    report("bridge20.yaml", solver,
           figures("largest_joint_gap=%.4f m load_height=%.3f m", gap, load.xf.p.y()));
    EXPECT_GT(load.xf.p.y(), 0.0) << solverName(solver);  // still on the bridge, not the ground
    if (solver == WorldDef().solver) {
      EXPECT_LT(gap, 0.01);
    }
  }
}

// A ball with e = 0.5 dropped from h = 2 m (bottom to floor) rises to e^2 h = 0.5 m. One-pass
// solvers bounce it from wherever the speculative contact caught it, up to one step's travel
// above the floor (6 cm at 6.3 m/s and 100 Hz); sub-steps catch it within a sub-step.
TEST(HardCase, BallReboundsToRestitutionSquaredTimesHeight) {
  for (SolverType solver : kSolvers) {
    World world;
    load("bounce.yaml", solver, world);
    const BodyId ball = world.findBody("ball");
    const double radius = 0.25, expected = 0.25 * 2.0;
    double lowest = 1e9, apex = -1e9;
    bool bounced = false;
    while (world.time() < 1.5) {
      world.step();
      const Body& b = world.body(ball);
      lowest = std::min(lowest, b.xf.p.y());
      if (b.linearVelocity.y() > 0.0) bounced = true;
      if (bounced) apex = std::max(apex, b.xf.p.y() - radius);
    }
    ASSERT_TRUE(bounced) << solverName(solver);
    report("bounce.yaml", solver,
           figures("rebound=%.4f m expected=%.4f m error=%.2f%%", apex, expected,
                   100.0 * (apex - expected) / expected));
    EXPECT_GE(lowest, radius - world.settings().linearSlop) << solverName(solver);
    if (holdsLargeCases(solver)) {
      EXPECT_NEAR(apex, expected, 0.02 * expected);
    }
  }
}

TEST(HardCase, PendulumKeepsItsPeriodAndAmplitude) {
  for (SolverType solver : kSolvers) {
    World world;
    load("pendulum.yaml", solver, world);
    const Body& bob = world.body(world.findBody("bob"));
    // Physical pendulum about the pivot: T = 2 pi sqrt(I / (m g L)).
    const double length = 2.0;
    const double inertia = bob.inertia + bob.mass * length * length;
    const double expected = 2.0 * kPi * std::sqrt(inertia / (bob.mass * 9.81 * length));
    std::vector<double> crossings;
    double previous = bob.xf.p.x(), firstPeak = 0.0, lastPeak = 0.0;
    while (world.time() < 20.0) {
      world.step();
      const double x = bob.xf.p.x();
      if (world.time() < 2.0) firstPeak = std::max(firstPeak, std::abs(x));
      if (world.time() > 18.0) lastPeak = std::max(lastPeak, std::abs(x));
      if (previous < 0.0 && x >= 0.0) {
        crossings.push_back(world.time() - world.settings().timeStep * x / (x - previous));
      }
      previous = x;
    }
    ASSERT_GE(crossings.size(), 3u);
    const double period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
    report("pendulum.yaml", solver,
           figures("period_error=%.4f%% amplitude_change=%.3f%%",
                   100.0 * (period - expected) / expected,
                   100.0 * (lastPeak - firstPeak) / firstPeak));
    EXPECT_NEAR(period, expected, 0.01 * expected) << solverName(solver);
    EXPECT_NEAR(lastPeak, firstPeak, 0.1 * firstPeak) << solverName(solver);
  }
}

}  // namespace
}  // namespace impulse2d
