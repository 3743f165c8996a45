// Joint set-up and the dispatch from the world's solver loop to each joint type (kKinds).
#include "joint.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace impulse2d {
namespace {

// What each joint type does at each stage of the solvers (joint_<type>.cpp), by JointType.
struct JointKind {
  void (*prepare)(Joint&, SolverBody&, SolverBody&, const Feedback&, double dt);
  void (*warmStart)(Joint&, BodyVelocity&, BodyVelocity&);
  void (*solveVelocity)(Joint&, BodyVelocity&, BodyVelocity&, double dt);
  PositionError (*solvePosition)(Joint&, SolverBody&, SolverBody&);
  PositionError (*positionError)(const Joint&, const SolverBody&, const SolverBody&);
};

constexpr JointKind kKinds[] = {
    {prepareRevolute, warmStartRevolute, solveRevoluteVelocity, solveRevolutePosition,
     revolutePositionError},
    {preparePrismatic, warmStartPrismatic, solvePrismaticVelocity, solvePrismaticPosition,
     prismaticPositionError},
    {prepareWeld, warmStartWeld, solveWeldVelocity, solveWeldPosition, weldPositionError},
    {prepareDistance, warmStartDistance, solveDistanceVelocity, solveDistancePosition,
     distancePositionError},
};
static_assert(static_cast<int>(JointType::Revolute) == 0 &&
                  static_cast<int>(JointType::Prismatic) == 1 &&
                  static_cast<int>(JointType::Weld) == 2 &&
                  static_cast<int>(JointType::Distance) == 3 && std::size(kKinds) == 4,
              "kKinds is in JointType's order");

const JointKind& kindOf(const Joint& joint) { return kKinds[static_cast<int>(joint.params.type)]; }

}  // namespace

void applyJointCorrection(SolverBody& a, SolverBody& b, const Vec2& p, double angularA,
                          double angularB) {
  applyJointCorrection(a, b, p.x(), p.y(), angularA, angularB);
}

void applyJointCorrection(SolverBody& a, SolverBody& b, double px, double py, double angularA,
                          double angularB) {
  // Each row's error is clamped, but the correction that removes it is K^-1 times it, and an
  // ill-conditioned K (anchors far out on light bodies, a long rail) made it move a body
  // kilometres in one pass. So the whole correction shrinks until neither body moves more than
  // kMaxLinearCorrection nor turns more than kMaxAngularCorrection.
  const double moved = std::max(a.invMass, b.invMass) * std::sqrt(px * px + py * py);
  const double turned =
      std::max(std::abs(a.invInertia * angularA), std::abs(b.invInertia * angularB));
  double scale = 1.0;
  if (moved > kMaxLinearCorrection) scale = kMaxLinearCorrection / moved;
  if (turned * scale > kMaxAngularCorrection) scale = kMaxAngularCorrection / turned;
  if (!std::isfinite(moved + turned)) return;
  // Each coordinate on its own (see applyImpulse, solver_body.hpp).
  const double moveA = scale * a.invMass, moveB = scale * b.invMass;
  a.center.x() -= moveA * px;
  a.center.y() -= moveA * py;
  turnBy(a, -scale * a.invInertia * angularA);
  b.center.x() += moveB * px;
  b.center.y() += moveB * py;
  turnBy(b, scale * b.invInertia * angularB);
}

double limitBias(double c, const Feedback& fb, double dt, Feedback* rowFb, double maxRate) {
  if (c > 0.0) {
    *rowFb = Feedback();
    return c / dt;
  }
  *rowFb = fb;
  return std::max(fb.rate * c, -maxRate);
}

Softness softness(double frequency, double dampingRatio, double effectiveMass, double dt) {
  Softness soft;
  if (!(frequency > 0.0) || !(effectiveMass > 0.0)) return soft;
  const double omega = 2.0 * kPi * frequency;
  const double k = effectiveMass * omega * omega;
  const double c = 2.0 * effectiveMass * dampingRatio * omega;
  soft.gamma = 1.0 / (dt * (c + dt * k));
  soft.biasRate = dt * k * soft.gamma;
  return soft;
}

JointParams paramsOf(const JointDef& def) {
  JointParams p;
  p.type = def.type;
  p.enableLimit = def.enableLimit;
  p.enableMotor = def.enableMotor;
  p.collideConnected = def.collideConnected;
  p.lower = def.lower;
  p.upper = def.upper;
  p.motorSpeed = def.motorSpeed;
  p.maxMotorTorque = def.maxMotorTorque;
  p.frequency = def.frequency;
  p.dampingRatio = def.dampingRatio;
  p.minLength = def.minLength;
  p.maxLength = def.maxLength;
  return p;
}

void initJoint(Joint& joint, const JointDef& def, const Body& a, const Body& b) {
  joint.params = paramsOf(def);
  joint.localAnchorA = a.xf.applyInverse(def.anchor);
  joint.localAnchorB = b.xf.applyInverse(def.anchor);
  joint.referenceAngle = b.angle - a.angle;
  if (def.type == JointType::Prismatic) {
    // Kept in A's frame so the rail turns with A.
    joint.localAxisA = a.xf.q.applyInverse(def.axis.normalized());
  } else if (def.type == JointType::Distance) {
    joint.localAnchorB = def.useAnchorB ? b.xf.applyInverse(def.anchorB) : Vec2::Zero();
    const double current = (b.xf.apply(joint.localAnchorB) - def.anchor).norm();
    joint.restLength =
        def.length > 0.0 ? def.length : std::clamp(current, def.minLength, def.maxLength);
  }
}

void prepareJoint(Joint& joint, SolverBody& a, SolverBody& b, const WorldDef& def,
                  const Feedback& fb, double dt) {
  joint.feedback = fb;
  if (!def.warmStarting) {  // the world resets only the impulses every type shares
    joint.angularImpulse = joint.lengthImpulse = 0.0;
  }
  kindOf(joint).prepare(joint, a, b, fb, dt);
}

void applyJointWarmStart(Joint& joint, BodyVelocity& a, BodyVelocity& b) {
  kindOf(joint).warmStart(joint, a, b);
}

void warmStartJoint(Joint& joint, BodyVelocity& a, BodyVelocity& b, const MotionLimits& limits) {
  const Vec2 va = a.linearVelocity, vb = b.linearVelocity;
  const double wa = a.angularVelocity, wb = b.angularVelocity;
  applyJointWarmStart(joint, a, b);
  // How much either body's velocity changed: the square of its linear change and its turn rate's
  // change. Read as scalars: a joint type may have written them so (applyImpulse).
  struct Change {
    double speedSquared, turnRate;
  };
  auto changeOf = [](const BodyVelocity& body, const Vec2& v, double w) {
    const double dvx = body.linearVelocity.x() - v.x(), dvy = body.linearVelocity.y() - v.y();
    return Change{dvx * dvx + dvy * dvy, body.angularVelocity - w};
  };
  const Change changeA = changeOf(a, va, wa), changeB = changeOf(b, vb, wb);
  // Within the limits without a division (`perf` put a fifth of this function's samples in the
  // joint grid just after its four divisions): dv^2 <= maxSpeed^2 gives dv^2 / maxSpeed^2 <= 1
  // after rounding too, and a turn of at most half the limit a squared ratio of at most 1/4, so
  // `worst` below would be at most 1 (a limit squared to 0 would make it 0 / 0 instead).
  auto clearlyWithin = [&](const Change& c) {
    return c.speedSquared <= limits.maxSpeedSquared && limits.maxSpeedSquared > 0.0 &&
           std::abs(c.turnRate) <= 0.5 * limits.maxTurnRate;
  };
  if (clearlyWithin(changeA) && clearlyWithin(changeB)) return;
  // How far past the motion limits the change goes (squared).
  auto excess = [&](const Change& c) {
    const double turn = c.turnRate / limits.maxTurnRate;
    return std::max(c.speedSquared / limits.maxSpeedSquared, turn * turn);
  };
  const double worst = std::max(excess(changeA), excess(changeB));
  if (worst <= 1.0) return;
  // Last step's impulse would change a body's velocity by more than the fastest it may move:
  // a joint that cannot be met whose impulse grew from sub-step to sub-step while the motion
  // limits ate its effect. Warm started whole, it would grow on without bound; so it starts
  // from what the limits allow.
  a.linearVelocity = va;
  a.angularVelocity = wa;
  b.linearVelocity = vb;
  b.angularVelocity = wb;
  scaleJointImpulses(joint, std::isfinite(worst) ? 1.0 / std::sqrt(worst) : 0.0);
  applyJointWarmStart(joint, a, b);
}

void scaleJointImpulses(Joint& joint, double scale) {
  joint.pairImpulse *= scale;
  joint.motorImpulse *= scale;
  joint.lowerImpulse *= scale;
  joint.upperImpulse *= scale;
  joint.angularImpulse *= scale;
  joint.lengthImpulse *= scale;
}

void solveJointVelocity(Joint& joint, BodyVelocity& a, BodyVelocity& b, double dt) {
  kindOf(joint).solveVelocity(joint, a, b, dt);
}

PositionError solveJointPosition(Joint& joint, SolverBody& a, SolverBody& b) {
  return kindOf(joint).solvePosition(joint, a, b);
}

PositionError jointPositionError(const Joint& joint, const SolverBody& a, const SolverBody& b) {
  return kindOf(joint).positionError(joint, a, b);
}

JointState measureJoint(const Joint& joint, const Body& a, const Body& b) {
  const SolverBody viewA = solverView(a), viewB = solverView(b);
  JointState state;
  if (joint.params.type == JointType::Prismatic) {
    state = measurePrismatic(joint, viewA, viewB);
  } else if (joint.params.type == JointType::Distance) {
    state = measureDistance(joint, viewA, viewB);
  } else {  // revolute and weld: the relative angle
    state.position = b.angle - a.angle - joint.referenceAngle;
    state.velocity = b.angularVelocity - a.angularVelocity;
  }
  state.anchorA = a.xf.apply(joint.localAnchorA);
  state.anchorB = b.xf.apply(joint.localAnchorB);
  return state;
}

}  // namespace impulse2d
