// The contact part of the sub-stepping solvers (world_substeps.cpp): each sub-step of h = dt / n
// solves every contact at the poses the sub-step has reached, with the soft step's push out of
// overlaps or without it. The narrow phase runs once per step; within it a contact point is
// followed as two points fixed in the bodies, and the normal stays fixed:
//
//        A's point, fixed in A         separation now = n . (pB - pA) + separation at prepare
//              pA  *                   (pA = pB at prepare: the manifold's point)
//                   \  n
//                    v
//              pB  *   B's point, fixed in B
#include "contact_math.hpp"
#include "contact_solver.hpp"

#include <algorithm>
#include <cmath>

namespace impulse2d {
namespace {

// Contact springs stiffer than this fraction of the sub-step rate were measured to shake the
// 5050-box pyramid apart (0.19 sways, 0.25 collapses; 0.15 holds it within 3 cm).
constexpr double kMaxContactHertzPerSubstepRate = 0.15;

double currentSeparation(const ContactConstraint& c, const ContactConstraintPoint& p,
                         const SolverBody& a, const SolverBody& b) {
  const Vec2 pointA = a.center + a.q.apply(p.anchorA);
  const Vec2 pointB = b.center + b.q.apply(p.anchorB);
  return c.normal.dot(pointB - pointA) + p.separation;
}

}  // namespace

void ContactSolver::prepareSubsteps(const WorldDef& def, int substeps, double h) {
  substeps_ = substeps;
  const double hertz = std::min(def.contactHertz, kMaxContactHertzPerSubstepRate / h);
  const Feedback dynamicSoft = springFeedback(hertz, def.contactDampingRatio, h);
  const Feedback staticSoft = springFeedback(2.0 * hertz, def.contactDampingRatio, h);
  SolverBody* bodies = bodies_->data();
  for (ContactConstraint& c : constraints_) {
    const SolverBody& a = bodies[c.a];
    const SolverBody& b = bodies[c.b];
    const bool bothMove = a.invMass > 0.0 && b.invMass > 0.0;
    c.soft = bothMove ? dynamicSoft : staticSoft;
    for (int i = 0; i < c.pointCount; ++i) {
      ContactConstraintPoint& p = c.points[i];
      // prepare() measured the separation with both points at the manifold point.
      p.anchorA = a.q.applyInverse(p.rA);
      p.anchorB = b.q.applyInverse(p.rB);
      p.normalImpulse /= substeps;
      p.tangentImpulse /= substeps;
      p.maxNormalImpulse = 0.0;
      p.totalNormalImpulse = p.totalTangentImpulse = 0.0;
    }
  }
}

void ContactSolver::solveSubstep(double h, bool useBias, double maxPushVelocity) {
  SolverBody* bodies = bodies_->data();
  for (ContactConstraint& c : constraints_) {
    SolverBody& a = bodies[c.a];
    SolverBody& b = bodies[c.b];
    solveFriction(c, a, b);

    double bias[2] = {0.0, 0.0};
    Feedback fb[2];
    for (int i = 0; i < c.pointCount; ++i) {
      const double s = currentSeparation(c, c.points[i], a, b);
      if (s > 0.0) {
        bias[i] = s / h;  // not touching: close the gap within the sub-step, no further
      } else if (useBias) {
        bias[i] = std::max(c.soft.rate * s, -maxPushVelocity);
        fb[i] = c.soft;
      }
    }
    if (c.restitution > 0.0) {
      // Gravity keeps speeding the bodies up until the sub-step they meet in: the bounce must
      // return that speed, not the slower one the step began with.
      for (int i = 0; i < c.pointCount; ++i) {
        ContactConstraintPoint& p = c.points[i];
        p.approachVelocity =
            std::min(p.approachVelocity, relativeVelocity(a, b, p.rA, p.rB).dot(c.normal));
      }
    }
    if (c.blockSolve) {
      solveSoftNormalBlock(c, a, b, bias, fb);
    } else {
      for (int i = 0; i < c.pointCount; ++i) {
        ContactConstraintPoint& p = c.points[i];
        const double vn = relativeVelocity(a, b, p.rA, p.rB).dot(c.normal);
        const double total = solveOneSided(p.normalImpulse, p.normalMass, vn + bias[i], fb[i]);
        applyImpulse(a, b, p.rA, p.rB, (total - p.normalImpulse) * c.normal);
        p.normalImpulse = total;
      }
    }
    for (int i = 0; i < c.pointCount; ++i) {
      ContactConstraintPoint& p = c.points[i];
      p.maxNormalImpulse = std::max(p.maxNormalImpulse, p.normalImpulse);
    }
  }
}

// The two normal rows together. A soft row i with accumulated impulse x_i satisfies
//   v_i + bias_i + gamma_i x_i >= 0  (complementary to x_i >= 0),  gamma_i = K_ii s_i / m_i
// (s = impulseScale, m = massScale), which is the one-row update of feedback.hpp solved
// exactly; with v = v_now + K (x - x_old) it is the 2x2 LCP  w = (K + diag(gamma)) x + b.
void ContactSolver::solveSoftNormalBlock(ContactConstraint& c, SolverBody& a, SolverBody& b,
                                         const double bias[2], const Feedback fb[2]) {
  ContactConstraintPoint& p1 = c.points[0];
  ContactConstraintPoint& p2 = c.points[1];
  const double x1Old = p1.normalImpulse, x2Old = p2.normalImpulse;
  const double gamma1 = c.k11 * fb[0].impulseScale / fb[0].massScale;
  const double gamma2 = c.k22 * fb[1].impulseScale / fb[1].massScale;
  const double b1 = relativeVelocity(a, b, p1.rA, p1.rB).dot(c.normal) + bias[0] -
                    (c.k11 * x1Old + c.k12 * x2Old);
  const double b2 = relativeVelocity(a, b, p2.rA, p2.rB).dot(c.normal) + bias[1] -
                    (c.k12 * x1Old + c.k22 * x2Old);
  double x1 = 0.0, x2 = 0.0;
  if (!solveTwoPointLcp(c.k11 + gamma1, c.k12, c.k22 + gamma2, b1, b2, &x1, &x2)) return;
  applyImpulse(a, b, p1.rA, p1.rB, (x1 - x1Old) * c.normal);
  applyImpulse(a, b, p2.rA, p2.rB, (x2 - x2Old) * c.normal);
  p1.normalImpulse = x1;
  p2.normalImpulse = x2;
}

void ContactSolver::addSubstepImpulses() {
  for (ContactConstraint& c : constraints_) {
    for (int i = 0; i < c.pointCount; ++i) {
      ContactConstraintPoint& p = c.points[i];
      p.totalNormalImpulse += p.normalImpulse;
      p.totalTangentImpulse += p.tangentImpulse;
    }
  }
}

}  // namespace impulse2d
