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

inline uint64_t contactKey(int bodyA, int shapeA, int bodyB, int shapeB) {
  return (static_cast<uint64_t>(bodyA) << 40) | (static_cast<uint64_t>(shapeA) << 32) |
         (static_cast<uint64_t>(bodyB) << 8) | static_cast<uint64_t>(shapeB);
}

struct Contact {
  uint64_t key = 0;
  int bodyA = -1, bodyB = -1;             // slot indices, bodyA < bodyB
  int shapeA = -1, shapeB = -1;           // shape index within each body
  Manifold manifold;                      // normal from A to B
  double normalImpulse[2] = {0.0, 0.0};   // accumulated, N s
  double tangentImpulse[2] = {0.0, 0.0};  // accumulated, N s
  double friction = 0.0;
  double restitution = 0.0;
};

/// Friction mixes by geometric mean (a frictionless surface makes the pair frictionless);
/// restitution by maximum (a bouncy ball bounces on any floor).
double mixFriction(double a, double b);
double mixRestitution(double a, double b);

/// Recomputes the manifold from the bodies' current poses and carries over the impulses of points
/// whose feature ids match the last step's.
void updateContact(Contact& contact, const Body& a, const Body& b, double speculativeDistance,
                   bool warmStarting);

}  // namespace impulse2d
