// Small pieces of contact maths for the one-pass solvers (contact_solver.cpp): a row's mass and
// the two-point block's LCP. The sub-stepping solvers' SIMD kernels (contact_kernels.cpp) follow
// the same formulas in lanes (the block's cases in this order, kMaxBlockCondition). A row along
// the unit direction d at a point r_A, r_B from the centres of mass is described by its lever
// arms armA = cross(rA, d) and armB = cross(rB, d).
//
// The iterations are written on scalars: a Vec2 built from two scalars and then used in packed
// (SSE2) arithmetic is stored as two halves and loaded as one, which the CPU cannot forward
// from its store buffer (in the sub-step solver, before it went to SIMD lanes, that stall was
// half of its time).
#pragma once

#include "solver_body.hpp"

namespace impulse2d {

// Two-point manifolds are solved as a block only while their 2x2 matrix is this well conditioned;
// nearly coincident points would make it singular, and then the points are solved one by one.
constexpr double kMaxBlockCondition = 1000.0;

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

// The 2x2 linear complementarity problem  w = K x + b,  x >= 0,  w >= 0,  x_i w_i = 0  has few
// enough cases to try them all: both rows active, only the first, only the second, neither.
// `inverse` is K^-1 (symmetric) and mass1, mass2 are 1 / K11, 1 / K22. Returns false when none
// fits (round-off on a nearly degenerate pair).
inline bool solveTwoPointLcp(double k12, double inverse11, double inverse12, double inverse22,
                             double mass1, double mass2, double b1, double b2, double* x1,
                             double* x2) {
  double y1 = -(inverse11 * b1 + inverse12 * b2);
  double y2 = -(inverse12 * b1 + inverse22 * b2);
  if (!(y1 >= 0.0 && y2 >= 0.0)) {
    y1 = -b1 * mass1;
    y2 = 0.0;
    if (!(y1 >= 0.0 && k12 * y1 + b2 >= 0.0)) {
      y1 = 0.0;
      y2 = -b2 * mass2;
      if (!(y2 >= 0.0 && k12 * y2 + b1 >= 0.0)) {
        y1 = y2 = 0.0;
        if (!(b1 >= 0.0 && b2 >= 0.0)) return false;
      }
    }
  }
  *x1 = y1;
  *x2 = y2;
  return true;
}

/// The same for a K known only now (the soft step's springs add to its diagonal).
inline bool solveTwoPointLcp(double k11, double k12, double k22, double b1, double b2, double* x1,
                             double* x2) {
  const double det = k11 * k22 - k12 * k12;  // > 0: only well-conditioned pairs come here
  return solveTwoPointLcp(k12, k22 / det, -k12 / det, k11 / det, 1.0 / k11, 1.0 / k22, b1, b2, x1,
                          x2);
}

inline bool wellConditioned(double k11, double k12, double k22) {
  return k11 * k11 < kMaxBlockCondition * (k11 * k22 - k12 * k12);
}

}  // namespace impulse2d
