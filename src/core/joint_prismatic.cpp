// The prismatic joint: body B slides along a rail fixed in body A and keeps its angle to A.
//
//                 n = perp(u)
//                 ^
//        A        |            B
//   =====pA-------+---------->pB=====> u  (the rail, fixed in A's frame)
//        \___________ d _____/
//
//   C_perp  = n . d                         = 0   \  solved together as a 2x2 block, so
//   C_angle = angle_B - angle_A - reference = 0   /  neither row undoes the other's work
//   x       = u . d  in [lower, upper] (speculative limits), motor on dx/dt
//
// Jacobians, with pA = cA + rA, pB = cB + rB, d = pB - pA and the rail turning with A
// (dn/dt = wA x n, and (wA x n) . d = wA cross(n, d) = -wA cross(d, n)):
//   d/dt (n . d) = -n.vA - wA cross(rA + d, n) + n.vB + wB cross(rB, n)
// and the same with u for the axial row. A's lever arm is rA + d: A feels the reaction where B
// actually is on the rail, not at A's anchor. The effective masses follow as J M^-1 J^T:
//   K = [mA + mB + iA sA^2 + iB sB^2,  iA sA + iB sB]    sA = cross(rA + d, n)
//       [iA sA + iB sB,                iA + iB      ]    sB = cross(rB, n)
//   axial: mA + mB + iA aA^2 + iB aB^2                   aA = cross(rA + d, u), aB = cross(rB, u)
// Impulses: pairImpulse = (perpendicular, angular); the axial one is motor + lower - upper.
#include "joint.hpp"

#include <algorithm>
#include <cmath>

namespace impulse2d {
namespace {

// Applies impulses on the perpendicular, angular and axial rows (J^T lambda).
void applyRows(const Joint& j, BodyVelocity& a, BodyVelocity& b, double perpendicular,
               double angular, double axial) {
  const Vec2 p = perpendicular * j.normal + axial * j.axis;
  applyJointImpulse(a, b, p, j.normalArmA * perpendicular + angular + j.axisArmA * axial,
                    j.normalArmB * perpendicular + angular + j.axisArmB * axial);
}

double axialRate(const Joint& j, const BodyVelocity& a, const BodyVelocity& b) {
  return rateAlong(j.axis, j.axisArmA, j.axisArmB, a, b);
}

// The rail at the bodies' current positions: the part of prepare that the position pass repeats
// after every correction and that measurePrismatic needs.
struct Rail {
  Vec2 rA, rB, d, axis, normal;
  double axisArmA, axisArmB, normalArmA, normalArmB;
};

Rail railOf(const Joint& j, const SolverBody& a, const SolverBody& b) {
  Rail r;
  r.rA = a.q.apply(j.localAnchorA - a.localCenter);
  r.rB = b.q.apply(j.localAnchorB - b.localCenter);
  r.d = (b.center + r.rB) - (a.center + r.rA);
  r.axis = a.q.apply(j.localAxisA);
  r.normal = perp(r.axis);
  const Vec2 armA = r.rA + r.d;
  r.axisArmA = cross(armA, r.axis);
  r.axisArmB = cross(r.rB, r.axis);
  r.normalArmA = cross(armA, r.normal);
  r.normalArmB = cross(r.rB, r.normal);
  return r;
}

void storeRail(Joint& j, const Rail& r, const SolverBody& a, const SolverBody& b) {
  j.rA = r.rA;
  j.rB = r.rB;
  j.axis = r.axis;
  j.normal = r.normal;
  j.axisArmA = r.axisArmA;
  j.axisArmB = r.axisArmB;
  j.normalArmA = r.normalArmA;
  j.normalArmB = r.normalArmB;
  j.axialPosition = r.axis.dot(r.d);
  j.angle = b.angle - a.angle - j.referenceAngle;
}

Eigen::Matrix2d blockMatrix(const Joint& j, const SolverBody& a, const SolverBody& b) {
  const double mA = a.invMass, mB = b.invMass, iA = a.invInertia, iB = b.invInertia;
  Eigen::Matrix2d k;
  k(0, 0) = mA + mB + iA * j.normalArmA * j.normalArmA + iB * j.normalArmB * j.normalArmB;
  k(0, 1) = k(1, 0) = iA * j.normalArmA + iB * j.normalArmB;
  // Two bodies that cannot turn: the angle row is moot, and a unit entry keeps K invertible
  // (its off-diagonal is then zero too) so the perpendicular row still works.
  k(1, 1) = iA + iB > 0.0 ? iA + iB : 1.0;
  return k;
}

double axialMassOf(const Joint& j, const SolverBody& a, const SolverBody& b) {
  const double k = a.invMass + b.invMass + a.invInertia * j.axisArmA * j.axisArmA +
                   b.invInertia * j.axisArmB * j.axisArmB;
  return k > 0.0 ? 1.0 / k : 0.0;
}

}  // namespace

void preparePrismatic(Joint& joint, SolverBody& a, SolverBody& b, const Feedback& fb, double dt) {
  const Rail rail = railOf(joint, a, b);
  storeRail(joint, rail, a, b);
  joint.pairMass = safeInverse(blockMatrix(joint, a, b));
  joint.axialMass = axialMassOf(joint, a, b);
  const Vec2 error(rail.normal.dot(rail.d), joint.angle);
  joint.pairBias =
      Vec2(linearBias(error.x(), fb), angularBias(error.y(), fb, anchorReach(joint.rA, joint.rB)));
  joint.lowerBias =
      limitBias(joint.axialPosition - joint.params.lower, fb, dt, &joint.lowerFeedback, fb.maxPush);
  joint.upperBias =
      limitBias(joint.params.upper - joint.axialPosition, fb, dt, &joint.upperFeedback, fb.maxPush);
  if (!joint.params.enableMotor) joint.motorImpulse = 0.0;
  if (!joint.params.enableLimit) joint.lowerImpulse = joint.upperImpulse = 0.0;
}

void warmStartPrismatic(Joint& joint, BodyVelocity& a, BodyVelocity& b) {
  applyRows(joint, a, b, joint.pairImpulse.x(), joint.pairImpulse.y(),
            joint.motorImpulse + joint.lowerImpulse - joint.upperImpulse);
}

void solvePrismaticVelocity(Joint& joint, BodyVelocity& a, BodyVelocity& b, double dt) {
  const JointParams& params = joint.params;
  if (params.enableMotor) {
    const double maxImpulse = params.maxMotorTorque * dt;  // a force (N) for this joint
    const double total = std::clamp(
        joint.motorImpulse - joint.axialMass * (axialRate(joint, a, b) - params.motorSpeed),
        -maxImpulse, maxImpulse);
    applyRows(joint, a, b, 0.0, 0.0, total - joint.motorImpulse);
    joint.motorImpulse = total;
  }
  if (params.enableLimit) {
    // Lower: x - lower >= 0. Upper: upper - x >= 0, whose impulse pushes along -u.
    const double lower =
        solveOneSided(joint.lowerImpulse, joint.axialMass, axialRate(joint, a, b) + joint.lowerBias,
                      joint.lowerFeedback);
    applyRows(joint, a, b, 0.0, 0.0, lower - joint.lowerImpulse);
    joint.lowerImpulse = lower;

    const double upper =
        solveOneSided(joint.upperImpulse, joint.axialMass,
                      -axialRate(joint, a, b) + joint.upperBias, joint.upperFeedback);
    applyRows(joint, a, b, 0.0, 0.0, -(upper - joint.upperImpulse));
    joint.upperImpulse = upper;
  }
  // Last, so the rail itself is the row best satisfied when the iterations stop.
  const Vec2 cdot(joint.normal.dot(b.linearVelocity - a.linearVelocity) +
                      joint.normalArmB * b.angularVelocity - joint.normalArmA * a.angularVelocity,
                  b.angularVelocity - a.angularVelocity);
  const Feedback& fb = joint.feedback;
  const Vec2 impulse = fb.massScale * (joint.pairMass * (joint.pairBias - cdot)) -
                       fb.impulseScale * joint.pairImpulse;
  joint.pairImpulse += impulse;
  applyRows(joint, a, b, impulse.x(), impulse.y(), 0.0);
}

PositionError solvePrismaticPosition(Joint& joint, SolverBody& a, SolverBody& b) {
  storeRail(joint, railOf(joint, a, b), a, b);
  double limitError = 0.0;
  if (joint.params.enableLimit) {
    double c = beyondLimits(joint.axialPosition, joint.params);
    limitError = std::abs(c);
    if (c != 0.0) {
      c = std::clamp(c, -kMaxLinearCorrection, kMaxLinearCorrection);
      const double impulse = -axialMassOf(joint, a, b) * c;
      applyJointCorrection(a, b, impulse * joint.axis, joint.axisArmA * impulse,
                           joint.axisArmB * impulse);
    }
  }
  const Rail rail = railOf(joint, a, b);
  storeRail(joint, rail, a, b);
  const double perpendicular = rail.normal.dot(rail.d);
  const double linearError = std::max(limitError, std::abs(perpendicular));
  const double angularError = std::abs(joint.angle);
  const Vec2 c(std::clamp(perpendicular, -kMaxLinearCorrection, kMaxLinearCorrection),
               std::clamp(joint.angle, -kMaxAngularCorrection, kMaxAngularCorrection));
  const Vec2 impulse = -(safeInverse(blockMatrix(joint, a, b)) * c);
  applyJointCorrection(a, b, impulse.x() * joint.normal,
                       joint.normalArmA * impulse.x() + impulse.y(),
                       joint.normalArmB * impulse.x() + impulse.y());
  return {linearError, angularError};
}

PositionError prismaticPositionError(const Joint& joint, const SolverBody& a, const SolverBody& b) {
  const Rail rail = railOf(joint, a, b);
  const double limit =
      joint.params.enableLimit ? beyondLimits(rail.axis.dot(rail.d), joint.params) : 0.0;
  return {std::max(std::abs(limit), std::abs(rail.normal.dot(rail.d))),
          std::abs(b.angle - a.angle - joint.referenceAngle)};
}

JointState measurePrismatic(const Joint& joint, const SolverBody& a, const SolverBody& b) {
  const Rail rail = railOf(joint, a, b);
  JointState state;
  state.position = rail.axis.dot(rail.d);
  state.velocity = rateAlong(rail.axis, rail.axisArmA, rail.axisArmB, a, b);
  return state;
}

}  // namespace impulse2d
