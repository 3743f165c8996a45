// Small pieces of contact maths shared by the one-pass solvers (contact_solver.cpp) and the
// sub-stepping solvers (contact_solver_substeps.cpp).
#pragma once

#include "solver_body.hpp"

namespace impulse2d {

// Two-point manifolds are solved as a block only while their 2x2 matrix is this well conditioned;
// nearly coincident points would make it singular, and then the points are solved one by one.
constexpr double kMaxBlockCondition = 1000.0;

inline double effectiveMass(const SolverBody& a, const SolverBody& b, const Vec2& rA,
                            const Vec2& rB, const Vec2& dir) {
  const double rnA = cross(rA, dir), rnB = cross(rB, dir);
  const double k = a.invMass + b.invMass + a.invInertia * rnA * rnA + b.invInertia * rnB * rnB;
  return k > 0.0 ? 1.0 / k : 0.0;
}

inline Vec2 relativeVelocity(const SolverBody& a, const SolverBody& b, const Vec2& rA,
                             const Vec2& rB) {
  return b.linearVelocity + cross(b.angularVelocity, rB) - a.linearVelocity -
         cross(a.angularVelocity, rA);
}

inline void applyImpulse(SolverBody& a, SolverBody& b, const Vec2& rA, const Vec2& rB,
                         const Vec2& impulse) {
  a.linearVelocity -= a.invMass * impulse;
  a.angularVelocity -= a.invInertia * cross(rA, impulse);
  b.linearVelocity += b.invMass * impulse;
  b.angularVelocity += b.invInertia * cross(rB, impulse);
}

// The 2x2 linear complementarity problem  w = K x + b,  x >= 0,  w >= 0,  x_i w_i = 0  has few
// enough cases to try them all: both rows active, only the first, only the second, neither.
// Returns false when none fits (round-off on a nearly degenerate pair).
inline bool solveTwoPointLcp(double k11, double k12, double k22, double b1, double b2, double* x1,
                             double* x2) {
  const double det = k11 * k22 - k12 * k12;  // > 0: only well-conditioned pairs come here
  double y1 = -(k22 * b1 - k12 * b2) / det;
  double y2 = -(k11 * b2 - k12 * b1) / det;
  if (!(y1 >= 0.0 && y2 >= 0.0)) {
    y1 = -b1 / k11;
    y2 = 0.0;
    if (!(y1 >= 0.0 && k12 * y1 + b2 >= 0.0)) {
      y1 = 0.0;
      y2 = -b2 / k22;
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

inline bool wellConditioned(double k11, double k12, double k22) {
  return k11 * k11 < kMaxBlockCondition * (k11 * k22 - k12 * k12);
}

}  // namespace impulse2d
