// The weld joint: no relative translation at the anchor and no relative rotation.
//
//      A           B
//   +-----+-----------+
//   |     X  anchor   |   C_point = pB - pA                            = 0  (2 rows)
//   +-----+-----------+   C_angle = angle_B - angle_A - reference     = 0
//
// Jacobians: d/dt (pB - pA) = vB + wB perp(rB) - vA - wA perp(rA), perp(r) = (-r.y, r.x), and
// d/dt C_angle = wB - wA. Their effective mass J M^-1 J^T is the 3x3
//   K = [ pointMassMatrix (2x2)       | -iA rA.y - iB rB.y ]
//       [                             |  iA rA.x + iB rB.x ]
//       [ -iA rA.y - iB rB.y, iA rA.x + iB rB.x | iA + iB  ]
// Rigid (frequency 0): the three rows are solved as one block, so a long cantilever does not
// sag while sequential rows trade errors. Soft (frequency > 0): the angle row is a torsional
// spring (see Softness in joint.hpp, with the angle row's own effective mass 1 / (iA + iB)),
// solved first, then the point rows as a rigid 2x2 block; the spring gets no position pass.
#include "joint.hpp"

#include <algorithm>
#include <cmath>

namespace impulse2d {
namespace {

bool isSoft(const Joint& joint) { return joint.params.frequency > 0.0; }

Eigen::Matrix3d blockMatrix(const SolverBody& a, const SolverBody& b, const Vec2& rA,
                            const Vec2& rB) {
  const double iA = a.invInertia, iB = b.invInertia;
  Eigen::Matrix3d k;
  k.topLeftCorner<2, 2>() = pointMassMatrix(a, b, rA, rB);
  k(0, 2) = k(2, 0) = -iA * rA.y() - iB * rB.y();
  k(1, 2) = k(2, 1) = iA * rA.x() + iB * rB.x();
  // Two bodies that cannot turn: the angle row is moot; a unit entry (its off-diagonals are
  // zero then) keeps K invertible for the point rows.
  k(2, 2) = iA + iB > 0.0 ? iA + iB : 1.0;
  return k;
}

Eigen::Matrix3d safeInverse3(const Eigen::Matrix3d& k) {
  const double det = k.determinant();
  return det != 0.0 ? Eigen::Matrix3d(k.inverse()) : Eigen::Matrix3d::Zero();
}

void applyPointAndAngle(const Joint& j, BodyVelocity& a, BodyVelocity& b, const Vec2& p,
                        double angular) {
  applyJointImpulse(a, b, p, cross(j.rA, p) + angular, cross(j.rB, p) + angular);
}

Vec2 pointRate(const Joint& j, const BodyVelocity& a, const BodyVelocity& b) {
  return b.linearVelocity + cross(b.angularVelocity, j.rB) - a.linearVelocity -
         cross(a.angularVelocity, j.rA);
}

}  // namespace

void prepareWeld(Joint& joint, SolverBody& a, SolverBody& b, const Feedback& fb, double dt) {
  joint.rA = a.q.apply(joint.localAnchorA - a.localCenter);
  joint.rB = b.q.apply(joint.localAnchorB - b.localCenter);
  joint.angle = b.angle - a.angle - joint.referenceAngle;
  const Eigen::Matrix3d k = blockMatrix(a, b, joint.rA, joint.rB);
  const Vec2 gap = (b.center + joint.rB) - (a.center + joint.rA);
  joint.pairBias = pointBias(gap, fb);

  if (isSoft(joint)) {
    joint.pairMass = safeInverse(k.topLeftCorner<2, 2>());
    const double inertiaSum = a.invInertia + b.invInertia;
    const Softness soft = softness(joint.params.frequency, joint.params.dampingRatio,
                                   inertiaSum > 0.0 ? 1.0 / inertiaSum : 0.0, dt);
    joint.springGamma = soft.gamma;
    joint.springMass = inertiaSum + soft.gamma > 0.0 ? 1.0 / (inertiaSum + soft.gamma) : 0.0;
    // The spring acts in both solvers: it is the physics, not an error correction.
    joint.angularBias = -soft.biasRate * joint.angle;
  } else {
    joint.blockMass = safeInverse3(k);
    joint.angularBias = angularBias(joint.angle, fb, anchorReach(joint.rA, joint.rB));
  }
}

void warmStartWeld(Joint& joint, BodyVelocity& a, BodyVelocity& b) {
  applyPointAndAngle(joint, a, b, joint.pairImpulse, joint.angularImpulse);
}

void solveWeldVelocity(Joint& joint, BodyVelocity& a, BodyVelocity& b, double /*dt*/) {
  if (isSoft(joint)) {
    // Cdot + biasRate C + gamma L = -dL / m, with L the accumulated spring impulse.
    const double cdot = b.angularVelocity - a.angularVelocity;
    const double impulse =
        joint.springMass * (joint.angularBias - cdot - joint.springGamma * joint.angularImpulse);
    joint.angularImpulse += impulse;
    applyPointAndAngle(joint, a, b, Vec2::Zero(), impulse);

    const Feedback& fb = joint.feedback;
    const Vec2 point = fb.massScale * (joint.pairMass * (joint.pairBias - pointRate(joint, a, b))) -
                       fb.impulseScale * joint.pairImpulse;
    joint.pairImpulse += point;
    applyPointAndAngle(joint, a, b, point, 0.0);
    return;
  }
  const Vec2 rate = pointRate(joint, a, b);
  const Eigen::Vector3d cdot(rate.x(), rate.y(), b.angularVelocity - a.angularVelocity);
  const Eigen::Vector3d bias(joint.pairBias.x(), joint.pairBias.y(), joint.angularBias);
  const Eigen::Vector3d accumulated(joint.pairImpulse.x(), joint.pairImpulse.y(),
                                    joint.angularImpulse);
  const Feedback& fb = joint.feedback;
  const Eigen::Vector3d impulse =
      fb.massScale * (joint.blockMass * (bias - cdot)) - fb.impulseScale * accumulated;
  const Vec2 point = impulse.head<2>();
  joint.pairImpulse += point;
  joint.angularImpulse += impulse.z();
  applyPointAndAngle(joint, a, b, point, impulse.z());
}

// The arms from each centre of mass to the anchor and the gap between the anchors.
struct WeldGap {
  Vec2 rA, rB, gap;
};
WeldGap weldGap(const Joint& joint, const SolverBody& a, const SolverBody& b) {
  const Vec2 rA = a.q.apply(joint.localAnchorA - a.localCenter);
  const Vec2 rB = b.q.apply(joint.localAnchorB - b.localCenter);
  return {rA, rB, (b.center + rB) - (a.center + rA)};
}

PositionError solveWeldPosition(Joint& joint, SolverBody& a, SolverBody& b) {
  const WeldGap w = weldGap(joint, a, b);
  const Vec2& rA = w.rA;
  const Vec2& rB = w.rB;
  Vec2 gap = w.gap;
  const double linearError = gap.norm();
  if (linearError > kMaxLinearCorrection) gap *= kMaxLinearCorrection / linearError;
  const Eigen::Matrix3d k = blockMatrix(a, b, rA, rB);

  Vec2 p;
  double angular = 0.0, angularError = 0.0;
  if (isSoft(joint)) {
    p = -(safeInverse(k.topLeftCorner<2, 2>()) * gap);
  } else {
    const double angle = b.angle - a.angle - joint.referenceAngle;
    angularError = std::abs(angle);
    const Eigen::Vector3d c(gap.x(), gap.y(),
                            std::clamp(angle, -kMaxAngularCorrection, kMaxAngularCorrection));
    const Eigen::Vector3d impulse = -(safeInverse3(k) * c);
    p = impulse.head<2>();
    angular = impulse.z();
  }
  applyJointCorrection(a, b, p, cross(rA, p) + angular, cross(rB, p) + angular);
  return {linearError, angularError};
}

PositionError weldPositionError(const Joint& joint, const SolverBody& a, const SolverBody& b) {
  // A soft weld's angle is a spring's: the pass leaves it alone.
  const double angle = isSoft(joint) ? 0.0 : b.angle - a.angle - joint.referenceAngle;
  return {weldGap(joint, a, b).gap.norm(), std::abs(angle)};
}

}  // namespace impulse2d
