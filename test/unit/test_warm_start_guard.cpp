// The warm-start guard (warm_start_guard.hpp) on a hand-made joint and contact: balanced impulses
// grown past what would move their group at the speed limit shrink to that; a load's balanced
// impulses, however heavy the load, are left alone.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "contact.hpp"
#include "joint.hpp"
#include "warm_start_guard.hpp"

namespace impulse2d {
namespace {

constexpr double kMaxSpeed = 400.0;  // m/s, WorldDef::maxLinearSpeed's default

// A box of `mass` (slot 1, row 0) pinned at its centre to a still body (slot 0) whose joint
// pulls it with `impulse` along +x into a static wall (slot 2), whose contact at the same centre
// pushes it back as hard: the two cancel, so a warm start gives the box no velocity at all.
struct Standoff {
  SolverBody box;
  Joint pin;
  std::vector<Contact> contacts;

  Standoff(double mass, double impulse) {
    box.invMass = 1.0 / mass;
    box.invInertia = 6.0 / mass;  // a 1 m box's 1 / (m / 6)
    pin.bodyA = 0;
    pin.bodyB = 1;
    pin.params.type = JointType::Revolute;
    pin.pairImpulse = Vec2(impulse, 0.0);
    Contact& wall = contacts.emplace_back();
    wall.bodyA = 1;
    wall.bodyB = 2;
    wall.manifold.normal = Vec2(1.0, 0.0);  // from the box into the wall
    wall.manifold.pointCount = 1;
    wall.normalImpulse[0] = impulse;  // pushes the box along -x
  }
  // Runs the guard as a step would; the box's joint impulse after it.
  double guarded() {
    WarmStartGuard guard;
    std::vector<Joint*> joints = {&pin};
    guard.run(
        joints, contacts, 1, [](int slot) { return slot == 1 ? 0 : -1; }, [&](int) { return box; },
        nullptr, nullptr, nullptr, 0.0, kMaxSpeed, true);
    return pin.pairImpulse.x();
  }
};

// Found by the core soak (baumgarte seed 434): a 0.43 kg welded pair pulled into the arena's wall
// by a prismatic joint to a stopped kinematic body; the joint's and the wall's impulses grew 7 %
// a step, at rest, to 118,000 N m s and 9,000 N s, and flung the pair at 232 m/s when a box
// drifted into it. Each impulse alone would give the box (m/2) v^2 with v = p / m; both at most
// what moves it at the speed limit: p = m v_max / sqrt(2).
TEST(WarmStartGuard, BalancedImpulsesGrownPastTheSpeedLimitShrink) {
  const double mass = 0.43;
  Standoff standoff(mass, 9000.0);
  const double held = standoff.guarded();
  EXPECT_NEAR(held, mass * kMaxSpeed / std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(standoff.contacts[0].normalImpulse[0], held, 1e-9)
      << "the same scale: still balanced";
}

// A 1 kg link holding 1,000 kg against gravity for a 60 Hz step: 163.5 N s each way, far below.
TEST(WarmStartGuard, AHeavyLoadsBalancedImpulsesAreLeftAlone) {
  const double load = 1000.0 * 9.81 / 60.0;
  Standoff link(1.0, load);
  EXPECT_EQ(link.guarded(), load);
  EXPECT_EQ(link.contacts[0].normalImpulse[0], load);
}

// A small box (slot 1) hinged to a still body (slot 0) at `reach` m from its centre, the hinge
// open by `gap` m, with a kept impulse far too small for the energy checks above to touch.
double keptImpulseOfAnOpenHinge(double reach, double gap) {
  SolverBody still, box;
  box.invMass = 1.0 / 0.05;
  box.invInertia = 6.0 / 0.05;
  box.linearVelocity = Vec2(10.0, 0.0);  // 2.5 J: a 0.007 J warm start is nothing to it
  Joint hinge;
  hinge.bodyA = 0;
  hinge.bodyB = 1;
  hinge.params.type = JointType::Revolute;
  hinge.localAnchorA = Vec2(0.0, reach - gap);
  hinge.localAnchorB = Vec2(0.0, reach);
  hinge.rB = hinge.localAnchorB;  // its last pass's arm
  hinge.pairImpulse = Vec2(1e-3, 0.0);
  std::vector<Contact> contacts;
  std::vector<Joint*> joints = {&hinge};
  WarmStartGuard guard;
  guard.run(
      joints, contacts, 1, [](int slot) { return slot == 1 ? 0 : -1; },
      [&](int slot) { return slot == 1 ? box : still; }, nullptr, nullptr, nullptr, 0.0, kMaxSpeed,
      true);
  return hinge.pairImpulse.x();
}

// Core soak seeds 224, 469, 514, 671 (substep): hinges anchored 5-15 m out on small bodies and
// held open 0.1-0.3 m handed their kept impulses on step after step, and the bodies gained
// energy until they shook at 17-38 m/s. Such a joint starts its step from zero; a hinge anchored
// near, or one that holds, keeps its impulse.
TEST(WarmStartGuard, AFarAnchoredJointHeldOpenStartsFromZero) {
  EXPECT_EQ(keptImpulseOfAnOpenHinge(11.0, 0.2), 0.0);
  EXPECT_EQ(keptImpulseOfAnOpenHinge(11.0, 0.001), 1e-3) << "far, but it holds";
  EXPECT_EQ(keptImpulseOfAnOpenHinge(1.0, 0.2), 1e-3) << "open, but anchored near";
}

}  // namespace
}  // namespace impulse2d
