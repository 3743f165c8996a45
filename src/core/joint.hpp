// Joints as the solver sees them. Each type keeps its anchors in the bodies' frames and its
// accumulated impulses between steps (warm starting), like contacts do. joint.cpp dispatches on
// the type; each type's constraint rows live in joint_<type>.cpp.
#pragma once

#include <impulse2d/body.hpp>
#include <impulse2d/defs.hpp>
#include <impulse2d/world.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

#include "feedback.hpp"
#include "motion_limits.hpp"
#include "position_pass.hpp"
#include "solver_body.hpp"

namespace impulse2d {

/// The numbers of a joint's definition that the solver reads: JointDef without its name, its
/// bodies and its creation-time geometry, so that a Joint copies without allocating (the
/// sub-stepping solvers lay a colour's joints side by side each step). The world keeps the
/// whole definition apart (WorldImpl::jointDefs).
struct JointParams {
  JointType type = JointType::Revolute;
  bool enableLimit = false, enableMotor = false, collideConnected = false;
  double lower = 0.0, upper = 0.0;
  double motorSpeed = 0.0, maxMotorTorque = 0.0;
  double frequency = 0.0, dampingRatio = 0.0;
  double minLength = 0.0, maxLength = std::numeric_limits<double>::infinity();
};
JointParams paramsOf(const JointDef& def);

struct Joint {
  // First what every velocity pass of a revolute or weld joint reads (bodies, type and switches,
  // the pair's rows, the feedback), in the first four of its ten cache lines: a pass over the
  // 19,800 joints of v3_joint_grid reads them from L3, and the passes prefetch those lines
  // (world_substeps.cpp); spread over the struct they took a line more each.
  int bodyA = -1, bodyB = -1;  // slot indices
  JointId id;
  JointParams params;  // the definition's numbers the solver reads
  // Accumulated impulses, kept across steps. Every type's limits are lowerImpulse and
  // upperImpulse (revolute: the angle; prismatic: the slide; distance: the length).
  //
  // The pair: two equality rows solved together as one 2x2 block, with pairMass the block's
  // inverse and pairBias its target rates. Revolute and weld: the anchors' gap, x and y;
  // prismatic: across the rail and the angle.
  Vec2 pairImpulse = Vec2::Zero();
  // Pre-step scratch.
  Vec2 rA = Vec2::Zero(), rB = Vec2::Zero();           // from each centre of mass to the anchor
  Eigen::Matrix2d pairMass = Eigen::Matrix2d::Zero();  // the pair's (see pairImpulse)
  Vec2 pairBias = Vec2::Zero();
  // The feedback of this pass for the equality rows (each limit's is lowerFeedback and
  // upperFeedback below: a limit not yet reached is approached speculatively, always rigid).
  Feedback feedback;
  // The other rows' accumulated impulses, kept across steps like pairImpulse.
  double motorImpulse = 0.0;
  double lowerImpulse = 0.0, upperImpulse = 0.0;
  double angularImpulse = 0.0;  // weld angle row
  double lengthImpulse = 0.0;   // distance length row (rigid or spring)
  // Pre-step scratch of the other rows.
  double axialMass = 0.0;
  double angle = 0.0;                       // current joint angle relative to the reference
  double lowerBias = 0.0, upperBias = 0.0;  // target rates of the limit constraints
  Feedback lowerFeedback, upperFeedback;
  // Prismatic and distance: the axial row's direction (unit, world) and its lever arms
  // cross(r, axis) on each body; the prismatic also its perpendicular row's.
  Vec2 axis = Vec2::Zero(), normal = Vec2::Zero();
  double axisArmA = 0.0, axisArmB = 0.0, normalArmA = 0.0, normalArmB = 0.0;
  double axialPosition = 0.0;  // prismatic translation or distance length now (m)
  // Equality rows' target rates (Baumgarte or spring), like pairBias.
  double angularBias = 0.0, lengthBias = 0.0;
  // Weld: the inverse of the 3x3 block (point + angle) when rigid.
  Eigen::Matrix3d blockMass = Eigen::Matrix3d::Zero();
  // Spring rows (weld angle, distance length): softened effective mass and the softness gamma.
  double springMass = 0.0, springGamma = 0.0;

  // The geometry, set at creation (read by the preparing passes and the position passes).
  Vec2 localAnchorA = Vec2::Zero(), localAnchorB = Vec2::Zero();  // body frames (origin based)
  double referenceAngle = 0.0;                                    // angle B - angle A at creation
  Vec2 localAxisA = Vec2(1.0, 0.0);  // prismatic: unit slide direction in A's frame
  double restLength = 0.0;           // distance: the length the joint keeps (m)
  // This step solves the joint without bias (position_guard.hpp): soft, its group having opened
  // wider under the last step's; baumgarte, its group being far open (read only by prepare).
  bool feedbackWithheld = false;
};

/// Initialises the parameters, anchors and reference angle from a validated definition.
void initJoint(Joint& joint, const JointDef& def, const Body& a, const Body& b);

/// Computes the rows of this pass at the bodies' current poses; dt is the pass's time step (the
/// sub-step for the soft step).
void prepareJoint(Joint& joint, SolverBody& a, SolverBody& b, const WorldDef& def,
                  const Feedback& fb, double dt);
/// Applies the impulses kept from the last step (warm_start_guard.hpp keeps them from growing
/// without bound). Reads the joint only.
void applyJointWarmStart(Joint& joint, BodyVelocity& a, BodyVelocity& b);
/// applyJointWarmStart, scaled down when it would change a body's velocity by more than the
/// motion limits of this pass allow.
void warmStartJoint(Joint& joint, BodyVelocity& a, BodyVelocity& b, const MotionLimits& limits);
/// Scales every accumulated impulse of the joint.
void scaleJointImpulses(Joint& joint, double scale);
void solveJointVelocity(Joint& joint, BodyVelocity& a, BodyVelocity& b, double dt);
/// How far a joint is from holding: its linear error (m) and its angular one (rad), each the
/// largest of its rows'.
struct PositionError {
  double linear = 0.0, angular = 0.0;
  bool within(double linearSlop) const { return linear <= linearSlop && angular <= kAngularSlop; }
  /// One number for a sum over joints (m^2): a radian weighs as a metre.
  double squared() const { return linear * linear + angular * angular; }
};
/// One NGS position pass; returns the error it found (before its correction).
PositionError solveJointPosition(Joint& joint, SolverBody& a, SolverBody& b);
/// The error the pass would find at these poses, with nothing moved.
PositionError jointPositionError(const Joint& joint, const SolverBody& a, const SolverBody& b);
JointState measureJoint(const Joint& joint, const Body& a, const Body& b);

// --- shared by the joint types ---

/// K = [mA + mB + iA rA.y^2 + iB rB.y^2,   -iA rA.x rA.y - iB rB.x rB.y ]
///     [-iA rA.x rA.y - iB rB.x rB.y,      mA + mB + iA rA.x^2 + iB rB.x^2]
/// maps an impulse at a shared point to the change of the relative velocity there. Its entries
/// (symmetric: k10 = k01), in scalars.
/// (Inline, as safeInverse: every revolute and weld joint calls both several times a step.)
struct PointMass {
  double k00, k01, k11;
};
inline PointMass pointMass(const BodyVelocity& a, const BodyVelocity& b, double rAx, double rAy,
                           double rBx, double rBy) {
  const double mA = a.invMass, mB = b.invMass, iA = a.invInertia, iB = b.invInertia;
  return PointMass{mA + mB + iA * rAy * rAy + iB * rBy * rBy, -iA * rAx * rAy - iB * rBx * rBy,
                   mA + mB + iA * rAx * rAx + iB * rBx * rBx};
}
inline Eigen::Matrix2d pointMassMatrix(const SolverBody& a, const SolverBody& b, const Vec2& rA,
                                       const Vec2& rB) {
  const PointMass m = pointMass(a, b, rA.x(), rA.y(), rB.x(), rB.y());
  Eigen::Matrix2d k;
  k << m.k00, m.k01, m.k01, m.k11;
  return k;
}
/// The inverse of [k00 k01; k10 k11] with Eigen's operations (1 / det times the adjugate), or
/// zero when it is singular (two bodies that cannot move); each entry written on its own.
inline void safeInverse(double k00, double k01, double k10, double k11, Eigen::Matrix2d& inverse) {
  const double det = k00 * k11 - k10 * k01;
  if (det == 0.0) {
    inverse(0, 0) = inverse(0, 1) = inverse(1, 0) = inverse(1, 1) = 0.0;
    return;
  }
  const double invDet = 1.0 / det;
  inverse(0, 0) = k11 * invDet;
  inverse(1, 0) = -k10 * invDet;
  inverse(0, 1) = -k01 * invDet;
  inverse(1, 1) = k00 * invDet;
}
inline Eigen::Matrix2d safeInverse(const Eigen::Matrix2d& k) {
  Eigen::Matrix2d inverse;
  safeInverse(k(0, 0), k(0, 1), k(1, 0), k(1, 1), inverse);
  return inverse;
}
/// safeInverse(pointMassMatrix(a, b, rA, rB)) in scalars (prepareRevolute: a matrix returned
/// through the stack was stored as scalars and read back as vectors, stalling store forwarding).
inline void invertPointMass(const SolverBody& a, const SolverBody& b, double rAx, double rAy,
                            double rBx, double rBy, Eigen::Matrix2d& inverse) {
  const PointMass m = pointMass(a, b, rAx, rAy, rBx, rBy);
  safeInverse(m.k00, m.k01, m.k01, m.k11, inverse);
}

/// Applies the impulse p at the joint, plus the angular impulses; A takes the reaction:
///   vA -= mA p, wA -= iA angularA, vB += mB p, wB += iB angularB.
/// (Inline: the joints' rows call it several times each, in every pass of every sub-step.)
inline void applyJointImpulse(BodyVelocity& a, BodyVelocity& b, const Vec2& p, double angularA,
                              double angularB) {
  applyImpulse(a, b, p.x(), p.y(), angularA, angularB);  // solver_body.hpp
}
/// How fast the bodies move apart along a row through the joint: the unit `axis` with lever arms
/// armA = cross(rA, axis) and armB = cross(rB, axis) (a distance joint's rod, a prismatic one's
/// rail).
inline double rateAlong(const Vec2& axis, double armA, double armB, const BodyVelocity& a,
                        const BodyVelocity& b) {
  return axis.dot(b.linearVelocity - a.linearVelocity) + armB * b.angularVelocity -
         armA * a.angularVelocity;
}
/// The same as a position correction (NGS): moves and turns both bodies.
void applyJointCorrection(SolverBody& a, SolverBody& b, const Vec2& p, double angularA,
                          double angularB);
/// The same with p as two scalars, each coordinate of a centre written on its own.
void applyJointCorrection(SolverBody& a, SolverBody& b, double px, double py, double angularA,
                          double angularB);
/// Target rate of a one-sided limit row whose position error is c (>= 0 means within): a limit
/// not yet reached may be approached within the step (speculative, rigid); one already passed is
/// pushed back with the pass's feedback (none with NGS: its position pass does it), at most at
/// maxRate. `rowFb` receives the feedback the row uses.
double limitBias(double c, const Feedback& fb, double dt, Feedback* rowFb, double maxRate);
/// How far x lies beyond the joint's limits [lower, upper] (< 0 below, > 0 above, 0 within).
inline double beyondLimits(double x, const JointParams& params) {
  if (x < params.lower) return x - params.lower;
  if (x > params.upper) return x - params.upper;
  return 0.0;
}

/// The target rate of an equality row with linear position error c (m): -rate c, at most
/// fb.maxPush either way.
inline double linearBias(double c, const Feedback& fb) {
  if (!(fb.rate > 0.0)) return 0.0;
  return std::clamp(-fb.rate * c, -fb.maxPush, fb.maxPush);
}
/// The target rate of a point's error (a gap between two anchors): at most fb.maxPush long. In
/// scalars, each coordinate written on its own (prepareRevolute: a Vec2 returned from two scalars
/// was stored so and read back as one vector, which stalls store forwarding).
inline void pointBias(double gapX, double gapY, const Feedback& fb, Vec2& bias) {
  if (!(fb.rate > 0.0)) {
    bias.x() = bias.y() = 0.0;
    return;
  }
  double x = -fb.rate * gapX, y = -fb.rate * gapY;
  const double speed = std::sqrt(x * x + y * y);
  if (speed > fb.maxPush) {
    const double shrink = fb.maxPush / speed;
    x *= shrink;
    y *= shrink;
  }
  bias.x() = x;
  bias.y() = y;
}
/// The same as a vector.
inline Vec2 pointBias(const Vec2& gap, const Feedback& fb) {
  Vec2 bias;
  pointBias(gap.x(), gap.y(), fb, bias);
  return bias;
}
/// The fastest an angular row's feedback turns the bodies (rad/s): a point `reach` from the
/// centre of mass then moves at most fb.maxPush, and nothing turns faster than pi rad/s.
inline double maxAngularPush(const Feedback& fb, double reach) {
  return std::min(kPi, fb.maxPush / std::max(reach, 1e-9));
}
/// The target rate of an angular equality row with error c (rad).
inline double angularBias(double c, const Feedback& fb, double reach) {
  if (!(fb.rate > 0.0)) return 0.0;
  const double cap = maxAngularPush(fb, reach);
  return std::clamp(-fb.rate * c, -cap, cap);
}
/// How far the joint's anchors lie from their bodies' centres of mass (the larger).
inline double anchorReach(const Vec2& rA, const Vec2& rB) { return std::max(rA.norm(), rB.norm()); }

/// A soft (spring) row. With effective mass m, stiffness k = m w^2 and damping c = 2 m zeta w
/// (w = 2 pi frequency), implicit Euler over one step asks the impulse L to satisfy
///   L = -dt (k (C + dt Cdot') + c Cdot'),  Cdot' = Cdot + L / m,
/// which rearranges to Cdot + biasRate C + gamma L = -L / m with
///   gamma = 1 / (dt (c + dt k)),  biasRate = dt k gamma.
/// gamma = 0 and biasRate = 0 when there is no spring (frequency 0 or m 0).
struct Softness {
  double gamma = 0.0;
  double biasRate = 0.0;  // 1/s
};
Softness softness(double frequency, double dampingRatio, double effectiveMass, double dt);

// --- per type ---
void prepareRevolute(Joint& joint, SolverBody& a, SolverBody& b, const Feedback& fb, double dt);
void warmStartRevolute(Joint& joint, BodyVelocity& a, BodyVelocity& b);
void solveRevoluteVelocity(Joint& joint, BodyVelocity& a, BodyVelocity& b, double dt);
PositionError solveRevolutePosition(Joint& joint, SolverBody& a, SolverBody& b);
PositionError revolutePositionError(const Joint& joint, const SolverBody& a, const SolverBody& b);

void preparePrismatic(Joint& joint, SolverBody& a, SolverBody& b, const Feedback& fb, double dt);
void warmStartPrismatic(Joint& joint, BodyVelocity& a, BodyVelocity& b);
void solvePrismaticVelocity(Joint& joint, BodyVelocity& a, BodyVelocity& b, double dt);
PositionError solvePrismaticPosition(Joint& joint, SolverBody& a, SolverBody& b);
PositionError prismaticPositionError(const Joint& joint, const SolverBody& a, const SolverBody& b);
/// Position and velocity along the rail (the anchors are measureJoint's).
JointState measurePrismatic(const Joint& joint, const SolverBody& a, const SolverBody& b);

void prepareWeld(Joint& joint, SolverBody& a, SolverBody& b, const Feedback& fb, double dt);
void warmStartWeld(Joint& joint, BodyVelocity& a, BodyVelocity& b);
void solveWeldVelocity(Joint& joint, BodyVelocity& a, BodyVelocity& b, double dt);
PositionError solveWeldPosition(Joint& joint, SolverBody& a, SolverBody& b);
PositionError weldPositionError(const Joint& joint, const SolverBody& a, const SolverBody& b);

void prepareDistance(Joint& joint, SolverBody& a, SolverBody& b, const Feedback& fb, double dt);
void warmStartDistance(Joint& joint, BodyVelocity& a, BodyVelocity& b);
void solveDistanceVelocity(Joint& joint, BodyVelocity& a, BodyVelocity& b, double dt);
PositionError solveDistancePosition(Joint& joint, SolverBody& a, SolverBody& b);
PositionError distancePositionError(const Joint& joint, const SolverBody& a, const SolverBody& b);
/// Length and its rate (the anchors are measureJoint's).
JointState measureDistance(const Joint& joint, const SolverBody& a, const SolverBody& b);

}  // namespace impulse2d
