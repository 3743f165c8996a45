// Small pieces of contact maths for the one-pass solvers (contact_solver.cpp): a row's mass, its
// speed and its impulse. (The two-point block both solver paths share is two_point_block-inl.h.)
// A row along the unit direction d at a point r_A, r_B from the centres of mass is described by
// its lever arms armA = cross(rA, d) and armB = cross(rB, d).
//
// The iterations are written on scalars: a Vec2 built from two scalars and then used in packed
// (SSE2) arithmetic is stored as two halves and loaded as one, which the CPU cannot forward
// from its store buffer (in the sub-step solver, before it went to SIMD lanes, that stall was
// half of its time).
#pragma once

#include "solver_body.hpp"

namespace impulse2d {

/// 1 / (J M^-1 J^T) of a row, or 0 when neither body can move along it.
inline double rowMass(const SolverBody& a, const SolverBody& b, double armA, double armB) {
  const double k = a.invMass + b.invMass + a.invInertia * armA * armA + b.invInertia * armB * armB;
  return k > 0.0 ? 1.0 / k : 0.0;
}

/// The speed of B relative to A along (dx, dy) at the point.
inline double rowSpeed(const SolverBody& a, const SolverBody& b, double dx, double dy, double armA,
                       double armB) {
  return dx * (b.linearVelocity.x() - a.linearVelocity.x()) +
         dy * (b.linearVelocity.y() - a.linearVelocity.y()) + b.angularVelocity * armB -
         a.angularVelocity * armA;
}

/// The impulse `amount` along (dx, dy) at the point on B, and its reaction on A.
inline void applyRowImpulse(SolverBody& a, SolverBody& b, double dx, double dy, double armA,
                            double armB, double amount) {
  const double pa = a.invMass * amount, pb = b.invMass * amount;
  a.linearVelocity.x() -= pa * dx;
  a.linearVelocity.y() -= pa * dy;
  a.angularVelocity -= a.invInertia * armA * amount;
  b.linearVelocity.x() += pb * dx;
  b.linearVelocity.y() += pb * dy;
  b.angularVelocity += b.invInertia * armB * amount;
}

/// Two impulses along the same (dx, dy) at two points of one manifold, applied at once.
inline void applyTwoRowImpulses(SolverBody& a, SolverBody& b, double dx, double dy, double armA1,
                                double armB1, double amount1, double armA2, double armB2,
                                double amount2) {
  const double sum = amount1 + amount2;
  const double pa = a.invMass * sum, pb = b.invMass * sum;
  a.linearVelocity.x() -= pa * dx;
  a.linearVelocity.y() -= pa * dy;
  a.angularVelocity -= a.invInertia * (armA1 * amount1 + armA2 * amount2);
  b.linearVelocity.x() += pb * dx;
  b.linearVelocity.y() += pb * dy;
  b.angularVelocity += b.invInertia * (armB1 * amount1 + armB2 * amount2);
}

}  // namespace impulse2d
