// Arbiters: one per pair of shapes whose fat boxes overlap. An arbiter lives as long as the pair
// stays close, and carries the accumulated impulses of its points from step to step so the solver
// can warm start from them.
#pragma once

#include <impulse2d/body.hpp>
#include <impulse2d/collision.hpp>

#include <cstdint>

namespace impulse2d {

/// Bodies ordered by slot index (never by address), so the same pair gets the same key and the
/// same orientation in every run: key = indexA:24 | shapeA:8 | indexB:24 | shapeB:8.
constexpr int kMaxBodySlots = 1 << 24;
constexpr int kMaxShapesPerBodyForKey = 1 << 8;

/// m: how far any point of B may have moved relative to A since a contact's manifold was
/// computed for the narrow phase to follow its points instead of computing it again. Following
/// errs by the square of the motion over the shapes' size (a point clipped on B's edge slides
/// along it; a normal kept on the other body turns): well under a micrometre here, against the
/// 5 mm linear slop. A resting pile's pairs move far less than this a step.
constexpr double kFollowDistance = 2.5e-4;

inline uint64_t contactKey(int bodyA, int shapeA, int bodyB, int shapeB) {
  return (static_cast<uint64_t>(bodyA) << 40) | (static_cast<uint64_t>(shapeA) << 32) |
         (static_cast<uint64_t>(bodyB) << 8) | static_cast<uint64_t>(shapeB);
}

struct Contact {
  uint64_t key = 0;
  int bodyA = -1, bodyB = -1;             // slot indices, bodyA < bodyB
  int shapeA = -1, shapeB = -1;           // shape index within each body
  int proxyA = -1, proxyB = -1;           // the shapes' broad-phase proxies
  Manifold manifold;                      // normal from A to B
  double normalImpulse[2] = {0.0, 0.0};   // accumulated, N s
  double tangentImpulse[2] = {0.0, 0.0};  // accumulated, N s
  double friction = 0.0;
  double restitution = 0.0;
  // The manifold as last computed by the narrow phase, in the bodies' frames, so that while the
  // pair barely moves it can be followed instead of computed again (updateContact).
  bool following = false;                         // the fields below describe `manifold`
  Transform baseRelative;                         // B's frame seen from A's when it was computed
  Vec2 localNormal = Vec2::Zero();                // in A's frame
  Vec2 localA[2] = {Vec2::Zero(), Vec2::Zero()};  // each point's end on A, A's frame
  Vec2 localB[2] = {Vec2::Zero(), Vec2::Zero()};  // and on B, B's frame
};

/// Friction mixes by geometric mean (a frictionless surface makes the pair frictionless);
/// restitution by maximum (a bouncy ball bounces on any floor).
double mixFriction(double a, double b);
double mixRestitution(double a, double b);

/// Recomputes the manifold from the bodies' current poses and carries over the impulses of points
/// whose feature ids match the last step's; or, while B has moved less than kFollowDistance
/// relative to A since the manifold was computed, follows its points with the bodies instead.
/// The manifold keeps points up to `speculativeDistance` apart, plus, when `timeStep` > 0, as far
/// as the two bodies can close in one step at their current speeds: a body fast enough to cross
/// the margin in a step is caught at the surface instead of a step's travel inside it.
void updateContact(Contact& contact, const Body& a, const Body& b, double speculativeDistance,
                   double timeStep, bool warmStarting);

}  // namespace impulse2d
