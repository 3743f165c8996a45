// The revolute joint: a shared point (a 2x2 block, Box2D Lite's K matrix) plus an optional motor
// and angle limits on the relative rotation.
#include <algorithm>
#include <cmath>

#include "joint.hpp"

namespace impulse2d {
namespace {

// A pure torque impulse between the two bodies (motor and limit rows).
void applyAngular(SolverBody& a, SolverBody& b, double impulse) {
  applyJointImpulse(a, b, Vec2::Zero(), impulse, impulse);
}

}  // namespace

void prepareRevolute(Joint& joint, SolverBody& a, SolverBody& b, const Feedback& fb, double dt) {
  joint.rA = a.q.apply(joint.localAnchorA - a.localCenter);
  joint.rB = b.q.apply(joint.localAnchorB - b.localCenter);
  joint.pairMass = safeInverse(pointMassMatrix(a, b, joint.rA, joint.rB));
  const double inertiaSum = a.invInertia + b.invInertia;
  joint.axialMass = inertiaSum > 0.0 ? 1.0 / inertiaSum : 0.0;
  joint.angle = b.angle - a.angle - joint.referenceAngle;

  const Vec2 gap = (b.center + joint.rB) - (a.center + joint.rA);
  joint.pairBias = pointBias(gap, fb);
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

void warmStartRevolute(Joint& joint, SolverBody& a, SolverBody& b) {
  const Vec2& p = joint.pairImpulse;
  const double axial = joint.motorImpulse + joint.lowerImpulse - joint.upperImpulse;
  applyJointImpulse(a, b, p, cross(joint.rA, p) + axial, cross(joint.rB, p) + axial);
}

void solveRevoluteVelocity(Joint& joint, SolverBody& a, SolverBody& b, double dt) {
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
  const Vec2 cdot = b.linearVelocity + cross(b.angularVelocity, joint.rB) - a.linearVelocity -
                    cross(a.angularVelocity, joint.rA);
  const Feedback& fb = joint.feedback;
  const Vec2 impulse = fb.massScale * (joint.pairMass * (joint.pairBias - cdot)) -
                       fb.impulseScale * joint.pairImpulse;
  joint.pairImpulse += impulse;
  applyJointImpulse(a, b, impulse, cross(joint.rA, impulse), cross(joint.rB, impulse));
}

bool solveRevolutePosition(Joint& joint, SolverBody& a, SolverBody& b, const WorldDef& def) {
  double angularError = 0.0;
  if (joint.params.enableLimit && joint.axialMass > 0.0) {
    const double angle = b.angle - a.angle - joint.referenceAngle;
    double c = 0.0;
    if (angle < joint.params.lower) c = angle - joint.params.lower;
    if (angle > joint.params.upper) c = angle - joint.params.upper;
    angularError = std::abs(c);
    c = std::clamp(c, -kMaxAngularCorrection, kMaxAngularCorrection);
    const double impulse = -joint.axialMass * c;
    applyJointCorrection(a, b, Vec2::Zero(), impulse, impulse);
  }
  const Vec2 rA = a.q.apply(joint.localAnchorA - a.localCenter);
  const Vec2 rB = b.q.apply(joint.localAnchorB - b.localCenter);
  Vec2 c = (b.center + rB) - (a.center + rA);
  const double linearError = c.norm();
  if (linearError > kMaxLinearCorrection) c *= kMaxLinearCorrection / linearError;
  const Vec2 impulse = -(safeInverse(pointMassMatrix(a, b, rA, rB)) * c);
  applyJointCorrection(a, b, impulse, cross(rA, impulse), cross(rB, impulse));
  return linearError <= def.linearSlop && angularError <= kAngularSlop;
}

}  // namespace impulse2d
