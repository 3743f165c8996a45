// The revolute joint: a shared point (a 2x2 block, Box2D Lite's K matrix) plus an optional motor
// and angle limits on the relative rotation.
#include <algorithm>
#include <cmath>

#include "joint.hpp"

namespace impulse2d {
namespace {

// A pure torque impulse between the two bodies (motor and limit rows).
void applyAngular(BodyVelocity& a, BodyVelocity& b, double impulse) {
  applyJointImpulse(a, b, Vec2::Zero(), impulse, impulse);
}

// The anchors' arms from each centre of mass, rA = qA (localAnchorA - localCenterA) and likewise
// rB, and the gap between the anchors, (cB + rB) - (cA + rA), in scalars with the operations of
// the vector forms: as vectors, each was built from two scalars on the stack and read back as
// one, which stalls store forwarding (see solveRevoluteVelocity).
struct AnchorGap {
  double rAx, rAy, rBx, rBy, gapX, gapY;
};
AnchorGap anchorGap(const Joint& joint, const SolverBody& a, const SolverBody& b) {
  const Vec2 anchorA = joint.localAnchorA - a.localCenter;
  const Vec2 anchorB = joint.localAnchorB - b.localCenter;
  AnchorGap g;
  g.rAx = a.q.c * anchorA.x() - a.q.s * anchorA.y();
  g.rAy = a.q.s * anchorA.x() + a.q.c * anchorA.y();
  g.rBx = b.q.c * anchorB.x() - b.q.s * anchorB.y();
  g.rBy = b.q.s * anchorB.x() + b.q.c * anchorB.y();
  g.gapX = (b.center.x() + g.rBx) - (a.center.x() + g.rAx);
  g.gapY = (b.center.y() + g.rBy) - (a.center.y() + g.rAy);
  return g;
}

}  // namespace

void prepareRevolute(Joint& joint, SolverBody& a, SolverBody& b, const Feedback& fb, double dt) {
  const AnchorGap g = anchorGap(joint, a, b);
  joint.rA.x() = g.rAx;  // each coordinate on its own, as read (solveRevoluteVelocity)
  joint.rA.y() = g.rAy;
  joint.rB.x() = g.rBx;
  joint.rB.y() = g.rBy;
  invertPointMass(a, b, g.rAx, g.rAy, g.rBx, g.rBy, joint.pairMass);
  const double inertiaSum = a.invInertia + b.invInertia;
  joint.axialMass = inertiaSum > 0.0 ? 1.0 / inertiaSum : 0.0;
  joint.angle = b.angle - a.angle - joint.referenceAngle;
  pointBias(g.gapX, g.gapY, fb, joint.pairBias);
  if (joint.params.enableLimit) {  // the limit rows are read only then
    const double maxTurn = maxAngularPush(fb, anchorReach(joint.rA, joint.rB));
    joint.lowerBias =
        limitBias(joint.angle - joint.params.lower, fb, dt, &joint.lowerFeedback, maxTurn);
    joint.upperBias =
        limitBias(joint.params.upper - joint.angle, fb, dt, &joint.upperFeedback, maxTurn);
  } else {
    joint.lowerImpulse = joint.upperImpulse = 0.0;
  }
  if (!joint.params.enableMotor) joint.motorImpulse = 0.0;
}

void warmStartRevolute(Joint& joint, BodyVelocity& a, BodyVelocity& b) {
  const double px = joint.pairImpulse.x(), py = joint.pairImpulse.y();
  const double axial = joint.motorImpulse + joint.lowerImpulse - joint.upperImpulse;
  const Vec2& rA = joint.rA;
  const Vec2& rB = joint.rB;
  applyImpulse(a, b, px, py, (rA.x() * py - rA.y() * px) + axial,
               (rB.x() * py - rB.y() * px) + axial);
}

void solveRevoluteVelocity(Joint& joint, BodyVelocity& a, BodyVelocity& b, double dt) {
  const JointParams& params = joint.params;
  if (params.enableMotor) {
    const double cdot = b.angularVelocity - a.angularVelocity - params.motorSpeed;
    const double maxImpulse = params.maxMotorTorque * dt;
    const double total =
        std::clamp(joint.motorImpulse - joint.axialMass * cdot, -maxImpulse, maxImpulse);
    applyAngular(a, b, total - joint.motorImpulse);
    joint.motorImpulse = total;
  }
  if (params.enableLimit) {
    // Lower: angle - lower >= 0. Upper: upper - angle >= 0, so its impulse acts negatively.
    const double cdotLower = b.angularVelocity - a.angularVelocity;
    const double lower = solveOneSided(joint.lowerImpulse, joint.axialMass,
                                       cdotLower + joint.lowerBias, joint.lowerFeedback);
    applyAngular(a, b, lower - joint.lowerImpulse);
    joint.lowerImpulse = lower;

    const double cdotUpper = a.angularVelocity - b.angularVelocity;
    const double upper = solveOneSided(joint.upperImpulse, joint.axialMass,
                                       cdotUpper + joint.upperBias, joint.upperFeedback);
    applyAngular(a, b, -(upper - joint.upperImpulse));
    joint.upperImpulse = upper;
  }
  // The pair, in scalars with the operations of the vector form
  //   cdot = vB + wB x rB - vA - wA x rA,
  //   P = massScale K^-1 (bias - cdot) - impulseScale accumulated:
  // as vectors, each cross product was built from two scalars and read back as one 16-byte
  // vector, which stalls store forwarding (see Transform::apply); `perf` put a third of this
  // function's samples on one such load.
  const Vec2& rA = joint.rA;
  const Vec2& rB = joint.rB;
  const double wA = a.angularVelocity, wB = b.angularVelocity;
  const double cdotX = b.linearVelocity.x() + -wB * rB.y() - a.linearVelocity.x() - -wA * rA.y();
  const double cdotY = b.linearVelocity.y() + wB * rB.x() - a.linearVelocity.y() - wA * rA.x();
  const double errorX = joint.pairBias.x() - cdotX, errorY = joint.pairBias.y() - cdotY;
  const Eigen::Matrix2d& k = joint.pairMass;
  const Feedback& fb = joint.feedback;
  const double ms = fb.massScale;  // Eigen folds it into K: (ms K) (bias - cdot)
  const double px =
      (ms * k(0, 0)) * errorX + (ms * k(0, 1)) * errorY - fb.impulseScale * joint.pairImpulse.x();
  const double py =
      (ms * k(1, 0)) * errorX + (ms * k(1, 1)) * errorY - fb.impulseScale * joint.pairImpulse.y();
  joint.pairImpulse.x() += px;
  joint.pairImpulse.y() += py;
  applyImpulse(a, b, px, py, rA.x() * py - rA.y() * px, rB.x() * py - rB.y() * px);
}

// The limit's angular error (rad) at these poses: none without a limit or when the bodies cannot
// turn against each other.
double revoluteLimitError(const Joint& joint, const SolverBody& a, const SolverBody& b) {
  if (!joint.params.enableLimit || !(joint.axialMass > 0.0)) return 0.0;
  return beyondLimits(b.angle - a.angle - joint.referenceAngle, joint.params);
}

PositionError solveRevolutePosition(Joint& joint, SolverBody& a, SolverBody& b) {
  double angularError = 0.0;
  if (joint.params.enableLimit && joint.axialMass > 0.0) {
    double c = revoluteLimitError(joint, a, b);
    angularError = std::abs(c);
    c = std::clamp(c, -kMaxAngularCorrection, kMaxAngularCorrection);
    const double impulse = -joint.axialMass * c;
    applyJointCorrection(a, b, Vec2::Zero(), impulse, impulse);
  }
  const AnchorGap g = anchorGap(joint, a, b);
  double cx = g.gapX, cy = g.gapY;
  const double linearError = std::sqrt(cx * cx + cy * cy);
  if (linearError > kMaxLinearCorrection) {
    const double shrink = kMaxLinearCorrection / linearError;
    cx *= shrink;
    cy *= shrink;
  }
  Eigen::Matrix2d k;
  invertPointMass(a, b, g.rAx, g.rAy, g.rBx, g.rBy, k);
  const double px = -(k(0, 0) * cx + k(0, 1) * cy);
  const double py = -(k(1, 0) * cx + k(1, 1) * cy);
  applyJointCorrection(a, b, px, py, g.rAx * py - g.rAy * px, g.rBx * py - g.rBy * px);
  return {linearError, angularError};
}

PositionError revolutePositionError(const Joint& joint, const SolverBody& a, const SolverBody& b) {
  const AnchorGap g = anchorGap(joint, a, b);
  return {std::sqrt(g.gapX * g.gapX + g.gapY * g.gapY), std::abs(revoluteLimitError(joint, a, b))};
}

}  // namespace impulse2d
