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

// In scalars, as contact_math.hpp explains.
double currentSeparation(const ContactConstraintPoint& p, const Vec2& normal, const SolverBody& a,
                         const SolverBody& b) {
  const double ax = a.center.x() + a.q.c * p.anchorA.x() - a.q.s * p.anchorA.y();
  const double ay = a.center.y() + a.q.s * p.anchorA.x() + a.q.c * p.anchorA.y();
  const double bx = b.center.x() + b.q.c * p.anchorB.x() - b.q.s * p.anchorB.y();
  const double by = b.center.y() + b.q.s * p.anchorB.x() + b.q.c * p.anchorB.y();
  return normal.x() * (bx - ax) + normal.y() * (by - ay) + p.separation;
}

}  // namespace

void ContactSolver::prepareSubsteps(const WorldDef& def, int substeps, double h) {
  substeps_ = substeps;
  const double hertz = std::min(def.contactHertz, kMaxContactHertzPerSubstepRate / h);
  dynamicSoft_ = springFeedback(hertz, def.contactDampingRatio, h);
  staticSoft_ = springFeedback(2.0 * hertz, def.contactDampingRatio, h);
  for (ContactConstraint& c : constraints_) {
    for (int i = 0; i < c.pointCount; ++i) {
      ContactConstraintPoint& p = c.points[i];
      p.normalImpulse /= substeps;
      p.tangentImpulse /= substeps;
      p.maxNormalImpulse = 0.0;
      p.totalNormalImpulse = p.totalTangentImpulse = 0.0;
    }
  }
}

void ContactSolver::solveSubstep(double h, bool useBias, bool relax, double maxPushVelocity) {
  SolverBody* bodies = bodies_->data();
  const double inverseH = 1.0 / h;
  for (size_t k = 0; k < constraints_.size(); ++k) {
    ContactConstraint& c = constraints_[k];
    SolverBody& a = bodies[c.a];
    SolverBody& b = bodies[c.b];
    solveFriction(c, a, b);
    // Each total summed right after its own row, not both together afterwards: GCC's vectoriser
    // pairs those two sums into one 16-byte load of impulses just stored as scalars, which stalls
    // store forwarding (math.hpp).
    if (relax) {
      for (int i = 0; i < c.pointCount; ++i)
        c.points[i].totalTangentImpulse += c.points[i].tangentImpulse;
    }

    // Not touching: close the gap within the sub-step, no further (a bias of s / h). Touching:
    // no bias, or the soft step's push.
    double bias[2] = {0.0, 0.0};
    bool soft = false;
    for (int i = 0; i < c.pointCount; ++i) {
      const double s = currentSeparation(c.points[i], c.normal, a, b);
      if (s > 0.0) {
        bias[i] = s * inverseH;
      } else if (useBias) {
        bias[i] = std::max(softness(c).rate * s, -maxPushVelocity);
        soft = true;
      }
    }
    if (c.restitution > 0.0) {
      // Gravity keeps speeding the bodies up until the sub-step they meet in: the bounce must
      // return that speed, not the slower one the step began with.
      for (int i = 0; i < c.pointCount; ++i) {
        const ContactConstraintPoint& p = c.points[i];
        double& approach = extras_[k].approachVelocity[i];
        approach = std::min(approach,
                            rowSpeed(a, b, c.normal.x(), c.normal.y(), p.normalArmA, p.normalArmB));
      }
    }
    if (c.blockSolve && !soft) {
      solveNormalBlock(c, a, b, -bias[0], -bias[1]);
    } else if (c.blockSolve) {
      solveSoftNormalBlock(c, a, b, bias);
    } else {
      for (int i = 0; i < c.pointCount; ++i) {
        ContactConstraintPoint& p = c.points[i];
        const bool pushes = useBias && bias[i] <= 0.0;
        const double vn = rowSpeed(a, b, c.normal.x(), c.normal.y(), p.normalArmA, p.normalArmB);
        const double total = solveOneSided(p.normalImpulse, p.normalMass, vn + bias[i],
                                           pushes ? softness(c) : Feedback());
        applyRowImpulse(a, b, c.normal.x(), c.normal.y(), p.normalArmA, p.normalArmB,
                        total - p.normalImpulse);
        p.normalImpulse = total;
      }
    }
    if (c.restitution > 0.0) {
      for (int i = 0; i < c.pointCount; ++i) {
        ContactConstraintPoint& p = c.points[i];
        p.maxNormalImpulse = std::max(p.maxNormalImpulse, p.normalImpulse);
      }
    }
    if (relax) {
      for (int i = 0; i < c.pointCount; ++i)
        c.points[i].totalNormalImpulse += c.points[i].normalImpulse;
    }
  }
}

// The two normal rows together. A soft row i with accumulated impulse x_i satisfies
//   v_i + bias_i + gamma_i x_i >= 0  (complementary to x_i >= 0),  gamma_i = K_ii s_i / m_i
// (s = impulseScale, m = massScale), which is the one-row update of feedback.hpp solved
// exactly; with v = v_now + K (x - x_old) it is the 2x2 LCP  w = (K + diag(gamma)) x + b.
void ContactSolver::solveSoftNormalBlock(ContactConstraint& c, SolverBody& a, SolverBody& b,
                                         const double bias[2]) const {
  ContactConstraintPoint& p1 = c.points[0];
  ContactConstraintPoint& p2 = c.points[1];
  const double x1Old = p1.normalImpulse, x2Old = p2.normalImpulse;
  // A point not touching (bias > 0) is rigid: no spring.
  const Feedback& fb = softness(c);
  const double spring = fb.impulseScale / fb.massScale;
  const double gamma1 = bias[0] > 0.0 ? 0.0 : c.k11 * spring;
  const double gamma2 = bias[1] > 0.0 ? 0.0 : c.k22 * spring;
  const double b1 = rowSpeed(a, b, c.normal.x(), c.normal.y(), p1.normalArmA, p1.normalArmB) +
                    bias[0] - (c.k11 * x1Old + c.k12 * x2Old);
  const double b2 = rowSpeed(a, b, c.normal.x(), c.normal.y(), p2.normalArmA, p2.normalArmB) +
                    bias[1] - (c.k12 * x1Old + c.k22 * x2Old);
  double x1 = 0.0, x2 = 0.0;
  if (!solveTwoPointLcp(c.k11 + gamma1, c.k12, c.k22 + gamma2, b1, b2, &x1, &x2)) return;
  applyRowImpulse(a, b, c.normal.x(), c.normal.y(), p1.normalArmA, p1.normalArmB, x1 - x1Old);
  applyRowImpulse(a, b, c.normal.x(), c.normal.y(), p2.normalArmA, p2.normalArmB, x2 - x2Old);
  p1.normalImpulse = x1;
  p2.normalImpulse = x2;
}

}  // namespace impulse2d
