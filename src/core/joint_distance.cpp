// The distance joint: keeps the anchors on A and B a rest length apart, rigidly (a rod) or
// as a spring with hard limits [minLength, maxLength].
//
//     A                    B
//    [pA]o--------------o[pB]      u = (pB - pA) / |pB - pA|
//         <--- length --->         C = |pB - pA| - restLength
//
// Jacobian: d/dt |d| = u . d/dt d = u.(vB + wB perp(rB) - vA - wA perp(rA))
//                    = -u.vA - wA cross(rA, u) + u.vB + wB cross(rB, u),
// effective mass 1 / (mA + mB + iA cross(rA, u)^2 + iB cross(rB, u)^2).
// Rigid (frequency 0): one equality row with the Baumgarte bias or, with NGS, a position pass;
// min/max are not used. Spring (frequency > 0): the row is soft (see Softness in joint.hpp) and
// min/max are one-sided rows like the revolute's limits (speculative before they are reached,
// accumulated impulse >= 0). The length row and the min limit share the axis, so they cannot
// be solved as one block; the limits come last, so they win when the spring pulls past them.
#include "joint.hpp"

#include <algorithm>
#include <cmath>

namespace impulse2d {
namespace {

// Below this the direction of the rod is noise; the rows are then left out for the step.
constexpr double kMinDirectionLength = 1e-9;

bool isSpring(const Joint& joint) { return joint.params.frequency > 0.0; }

struct Rod {
  Vec2 rA, rB, axis;
  double length, armA, armB;
};

Rod rodOf(const Joint& j, const SolverBody& a, const SolverBody& b) {
  Rod r;
  r.rA = a.q.apply(j.localAnchorA - a.localCenter);
  r.rB = b.q.apply(j.localAnchorB - b.localCenter);
  const Vec2 d = (b.center + r.rB) - (a.center + r.rA);
  r.length = d.norm();
  r.axis = r.length > kMinDirectionLength ? Vec2(d / r.length) : Vec2::Zero();
  r.armA = cross(r.rA, r.axis);
  r.armB = cross(r.rB, r.axis);
  return r;
}

double inverseMassOf(const Rod& r, const SolverBody& a, const SolverBody& b) {
  return a.invMass + b.invMass + a.invInertia * r.armA * r.armA + b.invInertia * r.armB * r.armB;
}

void applyAxial(const Joint& j, BodyVelocity& a, BodyVelocity& b, double impulse) {
  applyJointImpulse(a, b, impulse * j.axis, j.axisArmA * impulse, j.axisArmB * impulse);
}

}  // namespace

void prepareDistance(Joint& joint, SolverBody& a, SolverBody& b, const Feedback& fb, double dt) {
  const Rod rod = rodOf(joint, a, b);
  joint.rA = rod.rA;
  joint.rB = rod.rB;
  joint.axis = rod.axis;
  joint.axisArmA = rod.armA;
  joint.axisArmB = rod.armB;
  joint.axialPosition = rod.length;
  const double k = rod.axis.isZero() ? 0.0 : inverseMassOf(rod, a, b);
  joint.axialMass = k > 0.0 ? 1.0 / k : 0.0;
  const double c = rod.length - joint.restLength;

  if (isSpring(joint)) {
    const Softness soft =
        softness(joint.params.frequency, joint.params.dampingRatio, joint.axialMass, dt);
    joint.springGamma = soft.gamma;
    joint.springMass = k + soft.gamma > 0.0 ? 1.0 / (k + soft.gamma) : 0.0;
    joint.lengthBias = -soft.biasRate * c;
    joint.lowerBias =
        limitBias(rod.length - joint.params.minLength, fb, dt, &joint.lowerFeedback, fb.maxPush);
    // An infinite maxLength never binds: its row is skipped, and inf never enters a bias.
    joint.upperBias = std::isfinite(joint.params.maxLength)
                          ? limitBias(joint.params.maxLength - rod.length, fb, dt,
                                      &joint.upperFeedback, fb.maxPush)
                          : 0.0;
  } else {
    joint.lengthBias = linearBias(c, fb);
    joint.lowerImpulse = joint.upperImpulse = 0.0;
  }
}

void warmStartDistance(Joint& joint, BodyVelocity& a, BodyVelocity& b) {
  applyAxial(joint, a, b, joint.lengthImpulse + joint.lowerImpulse - joint.upperImpulse);
}

void solveDistanceVelocity(Joint& joint, BodyVelocity& a, BodyVelocity& b, double /*dt*/) {
  auto rate = [&] { return rateAlong(joint.axis, joint.axisArmA, joint.axisArmB, a, b); };
  if (!isSpring(joint)) {
    const Feedback& fb = joint.feedback;
    const double impulse = fb.massScale * joint.axialMass * (joint.lengthBias - rate()) -
                           fb.impulseScale * joint.lengthImpulse;
    joint.lengthImpulse += impulse;
    applyAxial(joint, a, b, impulse);
    return;
  }
  // Cdot + biasRate C + gamma L = -dL / m, with L the accumulated spring impulse.
  const double spring =
      joint.springMass * (joint.lengthBias - rate() - joint.springGamma * joint.lengthImpulse);
  joint.lengthImpulse += spring;
  applyAxial(joint, a, b, spring);

  if (joint.params.minLength > 0.0) {  // length - min >= 0
    const double lower = solveOneSided(joint.lowerImpulse, joint.axialMass,
                                       rate() + joint.lowerBias, joint.lowerFeedback);
    applyAxial(joint, a, b, lower - joint.lowerImpulse);
    joint.lowerImpulse = lower;
  }
  if (std::isfinite(joint.params.maxLength)) {  // max - length >= 0, pushing along -u
    const double upper = solveOneSided(joint.upperImpulse, joint.axialMass,
                                       -rate() + joint.upperBias, joint.upperFeedback);
    applyAxial(joint, a, b, -(upper - joint.upperImpulse));
    joint.upperImpulse = upper;
  }
}

// How much longer the rod is than the joint allows (< 0: shorter): a rigid joint holds its rest
// length, a spring only its limits.
double lengthError(const Joint& joint, const Rod& rod) {
  if (!isSpring(joint)) return rod.length - joint.restLength;
  if (rod.length < joint.params.minLength) return rod.length - joint.params.minLength;
  if (rod.length > joint.params.maxLength) return rod.length - joint.params.maxLength;
  return 0.0;
}

PositionError solveDistancePosition(Joint& joint, SolverBody& a, SolverBody& b) {
  const Rod rod = rodOf(joint, a, b);
  const double c = lengthError(joint, rod);
  const double k = rod.axis.isZero() ? 0.0 : inverseMassOf(rod, a, b);
  if (c != 0.0 && k > 0.0) {
    const double impulse = -std::clamp(c, -kMaxLinearCorrection, kMaxLinearCorrection) / k;
    applyJointCorrection(a, b, impulse * rod.axis, rod.armA * impulse, rod.armB * impulse);
  }
  return {std::abs(c), 0.0};
}

PositionError distancePositionError(const Joint& joint, const SolverBody& a, const SolverBody& b) {
  return {std::abs(lengthError(joint, rodOf(joint, a, b))), 0.0};
}

JointState measureDistance(const Joint& joint, const SolverBody& a, const SolverBody& b) {
  const Rod rod = rodOf(joint, a, b);
  JointState state;
  state.position = rod.length;
  state.velocity = rateAlong(rod.axis, rod.armA, rod.armB, a, b);
  return state;
}

}  // namespace impulse2d
