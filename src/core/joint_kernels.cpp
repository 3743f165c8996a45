// The SIMD kernels of the revolute joints in lanes (joint_lanes.hpp). Highway compiles this file
// once per instruction set, as contact_kernels.cpp; each lane repeats the scalar path's operations
// in its order (cited by function below), so the bits match it on every instruction set.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "joint_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <type_traits>

#include "body_lanes-inl.h"
#include "joint_lanes.hpp"
#include "position_pass.hpp"

HWY_BEFORE_NAMESPACE();
namespace impulse2d {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// A lane group's prepared rows.
template <class D>
struct Rows {
  V<D> rAx, rAy, rBx, rBy, mass00, mass01, mass11;
};

template <class D>
HWY_INLINE Rows<D> loadRows(D d, const JointBundle& j, size_t lane) {
  return {hn::Load(d, j.rAx + lane),   hn::Load(d, j.rAy + lane),    hn::Load(d, j.rBx + lane),
          hn::Load(d, j.rBy + lane),   hn::Load(d, j.mass00 + lane), hn::Load(d, j.mass01 + lane),
          hn::Load(d, j.mass11 + lane)};
}

// One body's view (SubstepBodies::view) in a lane group: its rotation q = q0 * Rot(qc, qs), and
// for the position passes its centre center0 + (dx, dy) and angle angle0 + turned; for a body that
// does not move, q0, center0 and angle0 themselves.
template <class D>
struct View {
  V<D> c, s, x, y, angle;
};

template <class D>
HWY_INLINE View<D> viewOf(D d, const double* q0c, const double* q0s, const double* turns,
                          size_t lane, const Bodies<D>& body) {
  View<D> v;
  const V<D> c0 = hn::Load(d, q0c + lane), s0 = hn::Load(d, q0s + lane);
  const auto moves = hn::Gt(hn::Load(d, turns + lane), hn::Zero(d));
  v.c = hn::IfThenElse(moves, hn::Sub(hn::Mul(c0, body.qc), hn::Mul(s0, body.qs)), c0);
  v.s = hn::IfThenElse(moves, hn::Add(hn::Mul(s0, body.qc), hn::Mul(c0, body.qs)), s0);
  return v;
}

template <class D>
HWY_INLINE View<D> poseOf(D d, const double* q0c, const double* q0s, const double* turns,
                          const double* center0X, const double* center0Y, const double* angle0,
                          size_t lane, const Bodies<D>& body) {
  View<D> v = viewOf(d, q0c, q0s, turns, lane, body);
  const auto moves = hn::Gt(hn::Load(d, turns + lane), hn::Zero(d));
  const V<D> x0 = hn::Load(d, center0X + lane), y0 = hn::Load(d, center0Y + lane);
  const V<D> a0 = hn::Load(d, angle0 + lane);
  v.x = hn::IfThenElse(moves, hn::Add(x0, body.dx), x0);
  v.y = hn::IfThenElse(moves, hn::Add(y0, body.dy), y0);
  v.angle = hn::IfThenElse(moves, hn::Add(a0, body.turned), a0);
  return v;
}

// The arm q * anchor (anchorGap, joint_revolute.cpp).
template <class D>
HWY_INLINE void arm(D d, const View<D>& v, const double* anchorX, const double* anchorY,
                    size_t lane, V<D>* rx, V<D>* ry) {
  const V<D> ax = hn::Load(d, anchorX + lane), ay = hn::Load(d, anchorY + lane);
  *rx = hn::Sub(hn::Mul(v.c, ax), hn::Mul(v.s, ay));
  *ry = hn::Add(hn::Mul(v.s, ax), hn::Mul(v.c, ay));
}

// K^-1 at these arms: pointMass, then safeInverse (zero where K is singular, det == 0 as it asks
// it: false for a NaN on every instruction set, which Ne is not).
template <class D>
HWY_INLINE void invertPointMass(D d, const JointBundle& j, size_t lane, const V<D>& rAx,
                                const V<D>& rAy, const V<D>& rBx, const V<D>& rBy, V<D>* mass00,
                                V<D>* mass01, V<D>* mass11) {
  const V<D> mA = hn::Load(d, j.invMassA + lane), mB = hn::Load(d, j.invMassB + lane);
  const V<D> iA = hn::Load(d, j.invInertiaA + lane), iB = hn::Load(d, j.invInertiaB + lane);
  const V<D> m = hn::Add(mA, mB);
  const V<D> k00 =
      hn::Add(hn::Add(m, hn::Mul(hn::Mul(iA, rAy), rAy)), hn::Mul(hn::Mul(iB, rBy), rBy));
  const V<D> k01 = hn::Sub(hn::Mul(hn::Mul(hn::Neg(iA), rAx), rAy), hn::Mul(hn::Mul(iB, rBx), rBy));
  const V<D> k11 =
      hn::Add(hn::Add(m, hn::Mul(hn::Mul(iA, rAx), rAx)), hn::Mul(hn::Mul(iB, rBx), rBx));
  const V<D> det = hn::Sub(hn::Mul(k00, k11), hn::Mul(k01, k01));
  const auto singular = hn::Eq(det, hn::Zero(d));
  const V<D> invDet = hn::Div(hn::Set(d, 1.0), det);
  *mass00 = hn::IfThenZeroElse(singular, hn::Mul(k11, invDet));
  *mass01 = hn::IfThenZeroElse(singular, hn::Mul(hn::Neg(k01), invDet));
  *mass11 = hn::IfThenZeroElse(singular, hn::Mul(k00, invDet));
}

// std::max(a, b) and std::clamp(v, lo, hi), NaN and all.
template <class D>
HWY_INLINE V<D> maxOf(const V<D>& a, const V<D>& b) {
  return hn::IfThenElse(hn::Lt(a, b), b, a);
}
template <class D>
HWY_INLINE V<D> clampOf(const V<D>& v, const V<D>& lo, const V<D>& hi) {
  return hn::IfThenElse(hn::Lt(v, lo), lo, hn::IfThenElse(hn::Lt(hi, v), hi, v));
}

// The limit rows' targets (prepareRevolute's limitBias with rigid feedback, whose largest turn
// rate is pi): an angle c within a limit may close at c / h; one past it gets max(0 c, -pi).
template <class D>
HWY_INLINE void limitBiases(D d, JointBundle& j, size_t lane, double step, const Bodies<D>& a,
                            const Bodies<D>& b) {
  auto angleOf = [&](const double* angle0, const double* turns, const Bodies<D>& body) {
    const V<D> start = hn::Load(d, angle0 + lane);
    const auto moves = hn::Gt(hn::Load(d, turns + lane), hn::Zero(d));
    return hn::IfThenElse(moves, hn::Add(start, body.turned), start);
  };
  const V<D> angle =
      hn::Sub(hn::Sub(angleOf(j.angle0B, j.turnsB, b), angleOf(j.angle0A, j.turnsA, a)),
              hn::Load(d, j.referenceAngle + lane));
  const V<D> h = hn::Set(d, step), zero = hn::Zero(d), fastestBack = hn::Set(d, -kPi);
  auto bias = [&](const V<D>& c) {
    return hn::IfThenElse(hn::Gt(c, zero), hn::Div(c, h), maxOf<D>(hn::Mul(zero, c), fastestBack));
  };
  hn::Store(bias(hn::Sub(angle, hn::Load(d, j.lower + lane))), d, j.lowerBias + lane);
  hn::Store(bias(hn::Sub(hn::Load(d, j.upper + lane), angle)), d, j.upperBias + lane);
}

// prepareRevolute with rigid feedback: the arms and K^-1.
template <class D>
HWY_INLINE Rows<D> prepare(D d, JointBundle& j, size_t lane, double h, const Bodies<D>& a,
                           const Bodies<D>& b) {
  Rows<D> r;
  arm(d, viewOf(d, j.q0cA, j.q0sA, j.turnsA, lane, a), j.anchorAx, j.anchorAy, lane, &r.rAx,
      &r.rAy);
  arm(d, viewOf(d, j.q0cB, j.q0sB, j.turnsB, lane, b), j.anchorBx, j.anchorBy, lane, &r.rBx,
      &r.rBy);
  invertPointMass(d, j, lane, r.rAx, r.rAy, r.rBx, r.rBy, &r.mass00, &r.mass01, &r.mass11);
  hn::Store(r.rAx, d, j.rAx + lane);
  hn::Store(r.rAy, d, j.rAy + lane);
  hn::Store(r.rBx, d, j.rBx + lane);
  hn::Store(r.rBy, d, j.rBy + lane);
  hn::Store(r.mass00, d, j.mass00 + lane);
  hn::Store(r.mass01, d, j.mass01 + lane);
  hn::Store(r.mass11, d, j.mass11 + lane);
  if (j.anyLimit) limitBiases(d, j, lane, h, a, b);
  return r;
}

// applyImpulse (solver_body.hpp).
template <class D>
HWY_INLINE void apply(const JointBundle& j, size_t lane, D d, const V<D>& px, const V<D>& py,
                      const V<D>& angularA, const V<D>& angularB, Bodies<D>* a, Bodies<D>* b) {
  const V<D> mA = hn::Load(d, j.invMassA + lane), mB = hn::Load(d, j.invMassB + lane);
  a->vx = hn::Sub(a->vx, hn::Mul(mA, px));
  a->vy = hn::Sub(a->vy, hn::Mul(mA, py));
  a->w = hn::Sub(a->w, hn::Mul(hn::Load(d, j.invInertiaA + lane), angularA));
  b->vx = hn::Add(b->vx, hn::Mul(mB, px));
  b->vy = hn::Add(b->vy, hn::Mul(mB, py));
  b->w = hn::Add(b->w, hn::Mul(hn::Load(d, j.invInertiaB + lane), angularB));
}

// The velocities of `changed` in the lanes of `mask`, `body`'s own elsewhere.
template <class D, class M>
HWY_INLINE void takeWhere(const M& mask, const Bodies<D>& changed, Bodies<D>* body) {
  body->vx = hn::IfThenElse(mask, changed.vx, body->vx);
  body->vy = hn::IfThenElse(mask, changed.vy, body->vy);
  body->w = hn::IfThenElse(mask, changed.w, body->w);
}

// warmStartJoint over warmStartRevolute (a bundle without motors and limits has an axial impulse
// of +0, as (0 + 0) - 0). Lanes whose change would break the motion limits keep their bodies'
// velocities and are marked for the scalar path, which rescales the impulses as warmStartJoint
// does.
template <class D>
HWY_INLINE void warmStart(D d, const JointLaneArgs& args, JointBundle& j, size_t lane,
                          const Rows<D>& r, Bodies<D>* a, Bodies<D>* b) {
  const V<D> px = hn::Load(d, j.impulseX + lane), py = hn::Load(d, j.impulseY + lane);
  const V<D> axial =
      j.anyMotor || j.anyLimit
          ? hn::Sub(hn::Add(hn::Load(d, j.motorImpulse + lane), hn::Load(d, j.lowerImpulse + lane)),
                    hn::Load(d, j.upperImpulse + lane))
          : hn::Zero(d);
  Bodies<D> a1 = *a, b1 = *b;
  apply(j, lane, d, px, py, hn::Add(hn::Sub(hn::Mul(r.rAx, py), hn::Mul(r.rAy, px)), axial),
        hn::Add(hn::Sub(hn::Mul(r.rBx, py), hn::Mul(r.rBy, px)), axial), &a1, &b1);
  // warmStartJoint's clearlyWithin.
  const V<D> maxSpeedSquared = hn::Set(d, args.limits.maxSpeedSquared);
  const V<D> halfMaxTurnRate = hn::Set(d, 0.5 * args.limits.maxTurnRate);
  const bool limited = args.limits.maxSpeedSquared > 0.0;
  auto within = [&](const Bodies<D>& before, const Bodies<D>& after) {
    const V<D> dvx = hn::Sub(after.vx, before.vx), dvy = hn::Sub(after.vy, before.vy);
    const V<D> speedSquared = hn::Add(hn::Mul(dvx, dvx), hn::Mul(dvy, dvy));
    return hn::And(hn::Le(speedSquared, maxSpeedSquared),
                   hn::Le(hn::Abs(hn::Sub(after.w, before.w)), halfMaxTurnRate));
  };
  const auto ok = hn::And(within(*a, a1), within(*b, b1));
  if (limited && hn::AllTrue(d, ok)) {  // nearly always: a branch the next joint need not wait on
    *a = a1;
    *b = b1;
    return;
  }
  HWY_ALIGN double okLanes[kJointLanes];
  hn::Store(hn::IfThenElseZero(ok, hn::Set(d, 1.0)), d, okLanes);
  for (size_t i = 0; i < hn::Lanes(d); ++i) {
    if (lane + i < static_cast<size_t>(j.laneCount) && (!limited || okLanes[i] == 0.0))
      j.scalarLanes = static_cast<uint8_t>(j.scalarLanes | (1u << (lane + i)));
  }
  const auto keep = limited ? ok : hn::FirstN(d, 0);
  takeWhere(keep, a1, a);
  takeWhere(keep, b1, b);
}

// applyAngular (joint_revolute.cpp): a pure torque impulse, through applyImpulse with p = 0, in
// the lanes of `mask` only.
template <class D, class M>
HWY_INLINE void applyAngular(D d, const JointBundle& j, size_t lane, const M& mask,
                             const V<D>& impulse, Bodies<D>* a, Bodies<D>* b) {
  const V<D> zero = hn::Zero(d);
  Bodies<D> a1 = *a, b1 = *b;
  apply(j, lane, d, zero, zero, impulse, impulse, &a1, &b1);
  takeWhere(mask, a1, a);
  takeWhere(mask, b1, b);
}

// solveRevoluteVelocity's motor and limit rows, in the lanes that have them.
template <class D>
HWY_INLINE void solveAngular(D d, JointBundle& j, size_t lane, Bodies<D>* a, Bodies<D>* b) {
  const V<D> zero = hn::Zero(d), mass = hn::Load(d, j.axialMass + lane);
  if (j.anyMotor) {
    const auto motor = hn::Gt(hn::Load(d, j.hasMotor + lane), zero);
    const V<D> cdot = hn::Sub(hn::Sub(b->w, a->w), hn::Load(d, j.motorSpeed + lane));
    const V<D> maxImpulse = hn::Load(d, j.maxMotorImpulse + lane);
    const V<D> old = hn::Load(d, j.motorImpulse + lane);
    const V<D> total =
        clampOf<D>(hn::Sub(old, hn::Mul(mass, cdot)), hn::Neg(maxImpulse), maxImpulse);
    applyAngular(d, j, lane, motor, hn::Sub(total, old), a, b);
    hn::Store(hn::IfThenElse(motor, total, old), d, j.motorImpulse + lane);
  }
  if (j.anyLimit) {
    // solveOneSided with rigid feedback: max(x - 1 m rate - 0 x, 0).
    const auto limit = hn::Gt(hn::Load(d, j.hasLimit + lane), zero);
    const V<D> one = hn::Set(d, 1.0);
    auto oneSided = [&](const V<D>& old, const V<D>& rate) {
      return maxOf<D>(hn::Sub(hn::Sub(old, hn::Mul(hn::Mul(one, mass), rate)), hn::Mul(zero, old)),
                      zero);
    };
    const V<D> oldLower = hn::Load(d, j.lowerImpulse + lane);
    const V<D> lower =
        oneSided(oldLower, hn::Add(hn::Sub(b->w, a->w), hn::Load(d, j.lowerBias + lane)));
    applyAngular(d, j, lane, limit, hn::Sub(lower, oldLower), a, b);
    hn::Store(hn::IfThenElse(limit, lower, oldLower), d, j.lowerImpulse + lane);
    const V<D> oldUpper = hn::Load(d, j.upperImpulse + lane);
    const V<D> upper =
        oneSided(oldUpper, hn::Add(hn::Sub(a->w, b->w), hn::Load(d, j.upperBias + lane)));
    applyAngular(d, j, lane, limit, hn::Neg(hn::Sub(upper, oldUpper)), a, b);
    hn::Store(hn::IfThenElse(limit, upper, oldUpper), d, j.upperImpulse + lane);
  }
}

// solveRevoluteVelocity with rigid feedback (bias 0, massScale 1, impulseScale 0): the motor and
// limits, then the pair.
template <class D>
HWY_INLINE void solve(D d, JointBundle& j, size_t lane, const Rows<D>& r, Bodies<D>* a,
                      Bodies<D>* b) {
  if (j.anyMotor || j.anyLimit) solveAngular(d, j, lane, a, b);
  const V<D> zero = hn::Zero(d), massScale = hn::Set(d, 1.0), impulseScale = zero;
  const V<D> cdotX = hn::Sub(hn::Sub(hn::Add(b->vx, hn::Mul(hn::Neg(b->w), r.rBy)), a->vx),
                             hn::Mul(hn::Neg(a->w), r.rAy));
  const V<D> cdotY =
      hn::Sub(hn::Sub(hn::Add(b->vy, hn::Mul(b->w, r.rBx)), a->vy), hn::Mul(a->w, r.rAx));
  const V<D> errorX = hn::Sub(zero, cdotX), errorY = hn::Sub(zero, cdotY);
  const V<D> oldX = hn::Load(d, j.impulseX + lane), oldY = hn::Load(d, j.impulseY + lane);
  const V<D> px = hn::Sub(hn::Add(hn::Mul(hn::Mul(massScale, r.mass00), errorX),
                                  hn::Mul(hn::Mul(massScale, r.mass01), errorY)),
                          hn::Mul(impulseScale, oldX));
  const V<D> py = hn::Sub(hn::Add(hn::Mul(hn::Mul(massScale, r.mass01), errorX),
                                  hn::Mul(hn::Mul(massScale, r.mass11), errorY)),
                          hn::Mul(impulseScale, oldY));
  hn::Store(hn::Add(oldX, px), d, j.impulseX + lane);
  hn::Store(hn::Add(oldY, py), d, j.impulseY + lane);
  apply(j, lane, d, px, py, hn::Sub(hn::Mul(r.rAx, py), hn::Mul(r.rAy, px)),
        hn::Sub(hn::Mul(r.rBx, py), hn::Mul(r.rBy, px)), a, b);
}

template <class D>
HWY_INLINE void group(D d, const JointLaneArgs& args, JointLanePass pass, JointBundle& j,
                      size_t lane) {
  Bodies<D> a = loadBodies(d, args.states, j.offsetA + lane);
  Bodies<D> b = loadBodies(d, args.states, j.offsetB + lane);
  const Rows<D> r = prepares(pass) ? prepare(d, j, lane, args.h, a, b) : loadRows(d, j, lane);
  if (warmsStart(pass)) {
    warmStart(d, args, j, lane, r, &a, &b);
  } else {
    solve(d, j, lane, r, &a, &b);
  }
  storeVelocities(d, args.states, j.offsetA + lane, args.sinkOffset, a);
  storeVelocities(d, args.states, j.offsetB + lane, args.sinkOffset, b);
}

// A body moved and turned by a position correction (applyJointCorrection's turnBy), then written
// back as SubstepBodies::store does: the motion since the step began from the pose, which is not
// always the motion it was read as, to the last bit.
template <class D, class M>
HWY_INLINE void moveAndStore(D d, const JointLaneArgs& args, const int32_t* offset,
                             const double* q0c, const double* q0s, const double* center0X,
                             const double* center0Y, const double* angle0, size_t lane,
                             const M& corrects, View<D> v, const V<D>& moveX, const V<D>& moveY,
                             const V<D>& turnAngle, Bodies<D> body) {
  View<D> moved = v;
  moved.x = hn::Add(v.x, moveX);
  moved.y = hn::Add(v.y, moveY);
  moved.angle = hn::Add(v.angle, turnAngle);
  turn(d, turnAngle, &moved.c, &moved.s);
  v.x = hn::IfThenElse(corrects, moved.x, v.x);
  v.y = hn::IfThenElse(corrects, moved.y, v.y);
  v.angle = hn::IfThenElse(corrects, moved.angle, v.angle);
  v.c = hn::IfThenElse(corrects, moved.c, v.c);
  v.s = hn::IfThenElse(corrects, moved.s, v.s);
  const V<D> c0 = hn::Load(d, q0c + lane), s0 = hn::Load(d, q0s + lane);
  body.dx = hn::Sub(v.x, hn::Load(d, center0X + lane));
  body.dy = hn::Sub(v.y, hn::Load(d, center0Y + lane));
  body.turned = hn::Sub(v.angle, hn::Load(d, angle0 + lane));
  body.qc = hn::Add(hn::Mul(c0, v.c), hn::Mul(s0, v.s));  // q0.inverseTimes(q)
  body.qs = hn::Sub(hn::Mul(c0, v.s), hn::Mul(s0, v.c));
  storePoses(d, args.states, offset + lane, args.sinkOffset, body);
}

// Whether any lane of `mask` holds, where that matters: one lane at a time (the overflow, one
// joint after the other), a test that nearly never holds is taken on a branch, so the next joint
// need not wait for it; lanes side by side always take the select.
template <class D, class M>
HWY_INLINE bool mayNeed(D d, const M& mask) {
  return !std::is_same_v<D, D1> || !hn::AllFalse(d, mask);
}

// solveRevolutePosition without limits, then applyJointCorrection: the gap between the anchors,
// its correction K^-1 C (C at most kMaxLinearCorrection long), shrunk until neither body moves
// more than kMaxLinearCorrection nor turns more than kMaxAngularCorrection; none where that is
// not finite. Returns each lane's gap before the correction.
template <class D>
HWY_INLINE V<D> positionGroup(D d, const JointLaneArgs& args, const JointBundle& j, size_t lane) {
  const Bodies<D> a = loadBodies(d, args.states, j.offsetA + lane);
  const Bodies<D> b = loadBodies(d, args.states, j.offsetB + lane);
  const View<D> va =
      poseOf(d, j.q0cA, j.q0sA, j.turnsA, j.center0Ax, j.center0Ay, j.angle0A, lane, a);
  const View<D> vb =
      poseOf(d, j.q0cB, j.q0sB, j.turnsB, j.center0Bx, j.center0By, j.angle0B, lane, b);
  V<D> rAx, rAy, rBx, rBy;
  arm(d, va, j.anchorAx, j.anchorAy, lane, &rAx, &rAy);
  arm(d, vb, j.anchorBx, j.anchorBy, lane, &rBx, &rBy);
  V<D> cx = hn::Sub(hn::Add(vb.x, rBx), hn::Add(va.x, rAx));
  V<D> cy = hn::Sub(hn::Add(vb.y, rBy), hn::Add(va.y, rAy));
  const V<D> error = hn::Sqrt(hn::Add(hn::Mul(cx, cx), hn::Mul(cy, cy)));
  const V<D> maxLinear = hn::Set(d, kMaxLinearCorrection);
  const auto far = hn::Gt(error, maxLinear);
  if (mayNeed(d, far)) {
    const V<D> shrink = hn::Div(maxLinear, error);
    cx = hn::IfThenElse(far, hn::Mul(cx, shrink), cx);
    cy = hn::IfThenElse(far, hn::Mul(cy, shrink), cy);
  }
  V<D> m00, m01, m11;
  invertPointMass(d, j, lane, rAx, rAy, rBx, rBy, &m00, &m01, &m11);
  const V<D> px = hn::Neg(hn::Add(hn::Mul(m00, cx), hn::Mul(m01, cy)));
  const V<D> py = hn::Neg(hn::Add(hn::Mul(m01, cx), hn::Mul(m11, cy)));
  const V<D> angularA = hn::Sub(hn::Mul(rAx, py), hn::Mul(rAy, px));
  const V<D> angularB = hn::Sub(hn::Mul(rBx, py), hn::Mul(rBy, px));
  // applyJointCorrection.
  const V<D> mA = hn::Load(d, j.invMassA + lane), mB = hn::Load(d, j.invMassB + lane);
  const V<D> iA = hn::Load(d, j.invInertiaA + lane), iB = hn::Load(d, j.invInertiaB + lane);
  const V<D> moved = hn::Mul(maxOf<D>(mA, mB), hn::Sqrt(hn::Add(hn::Mul(px, px), hn::Mul(py, py))));
  const V<D> turned = maxOf<D>(hn::Abs(hn::Mul(iA, angularA)), hn::Abs(hn::Mul(iB, angularB)));
  const V<D> maxAngular = hn::Set(d, kMaxAngularCorrection);
  V<D> scale = hn::Set(d, 1.0);
  const auto tooFar = hn::Gt(moved, maxLinear);
  if (mayNeed(d, tooFar)) scale = hn::IfThenElse(tooFar, hn::Div(maxLinear, moved), scale);
  const auto tooTurned = hn::Gt(hn::Mul(turned, scale), maxAngular);
  if (mayNeed(d, tooTurned)) {
    scale = hn::IfThenElse(tooTurned, hn::Div(maxAngular, turned), scale);
  }
  const auto corrects = hn::IsFinite(hn::Add(moved, turned));
  const V<D> moveA = hn::Mul(scale, mA), moveB = hn::Mul(scale, mB);
  const auto store = [&](const auto& where) {
    moveAndStore(d, args, j.offsetA, j.q0cA, j.q0sA, j.center0Ax, j.center0Ay, j.angle0A, lane,
                 where, va, hn::Neg(hn::Mul(moveA, px)), hn::Neg(hn::Mul(moveA, py)),
                 hn::Mul(hn::Mul(hn::Neg(scale), iA), angularA), a);
    moveAndStore(d, args, j.offsetB, j.q0cB, j.q0sB, j.center0Bx, j.center0By, j.angle0B, lane,
                 where, vb, hn::Mul(moveB, px), hn::Mul(moveB, py),
                 hn::Mul(hn::Mul(scale, iB), angularB), b);
  };
  if (mayNeed(d, hn::Not(corrects))) {
    store(corrects);
  } else {
    store(hn::FirstN(d, 1));  // one lane, finite
  }
  return error;
}

// Raises *widest to the largest of the first `count` errors and clears *within where one exceeds
// linearSlop.
template <class D>
HWY_INLINE void noteErrors(D d, const V<D>& errors, int count, double linearSlop, double* widest,
                           bool* within) {
  HWY_ALIGN double lanes[kJointLanes];
  hn::Store(errors, d, lanes);
  for (int i = 0; i < count; ++i) {
    if (*widest < lanes[i]) *widest = lanes[i];  // std::max({widest, error, 0})
    if (!(lanes[i] <= linearSlop)) *within = false;
  }
}

int PositionJointOverflow(const JointLaneArgs& args, int firstLane, int count, double linearSlop,
                          double* widest, bool* within) {
  const hn::CappedTag<double, 1> d1;
  for (int i = 0; i < count; ++i) {
    const int lane = firstLane + i;
    const JointBundle& j = args.bundles[lane / kJointLanes];
    if (j.anyLimit) return i;  // the limits' position rows are the scalar path's
    noteErrors(d1, positionGroup(d1, args, j, static_cast<size_t>(lane % kJointLanes)), 1,
               linearSlop, widest, within);
  }
  return count;
}

// Runs fn(d, bundle, lane) over the lane groups of the bundles [begin, end): as many lanes at once
// as the instruction set holds.
template <class Fn>
HWY_INLINE void forEachLaneGroup(const JointLaneArgs& args, int begin, int end, const Fn& fn) {
  const hn::CappedTag<double, kJointLanes> d;
  for (int k = begin; k < end; ++k) {
    JointBundle& j = args.bundles[k];
    for (size_t lane = 0; lane < static_cast<size_t>(j.laneCount); lane += hn::Lanes(d)) {
      fn(d, j, lane);
    }
  }
}

void PositionJointLanes(const JointLaneArgs& args, int begin, int end, double linearSlop,
                        double* widest, bool* within) {
  forEachLaneGroup(args, begin, end, [&](auto d, JointBundle& j, size_t first) {
    const size_t used = std::min(hn::Lanes(d), static_cast<size_t>(j.laneCount) - first);
    noteErrors(d, positionGroup(d, args, j, first), static_cast<int>(used), linearSlop, widest,
               within);
  });
}

void RunJointLanes(const JointLaneArgs& args, JointLanePass pass, int begin, int end) {
  forEachLaneGroup(args, begin, end,
                   [&](auto d, JointBundle& j, size_t lane) { group(d, args, pass, j, lane); });
}

void PrepareJointLanes(const JointLaneArgs& args, int begin, int end) {
  forEachLaneGroup(args, begin, end, [&](auto d, JointBundle& j, size_t lane) {
    prepare(d, j, lane, args.h, loadBodies(d, args.states, j.offsetA + lane),
            loadBodies(d, args.states, j.offsetB + lane));
  });
}

int RunJointOverflow(const JointLaneArgs& args, JointLanePass pass, int firstLane, int count) {
  const hn::CappedTag<double, 1> d1;
  for (int i = 0; i < count; ++i) {
    const int lane = firstLane + i;
    JointBundle& j = args.bundles[lane / kJointLanes];
    group(d1, args, pass, j, static_cast<size_t>(lane % kJointLanes));
    if (warmsStart(pass) && j.scalarLanes != 0) return i + 1;  // the scalar path's turn first
  }
  return count;
}

}  // namespace HWY_NAMESPACE
}  // namespace impulse2d
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace impulse2d {

HWY_EXPORT(RunJointLanes);
HWY_EXPORT(RunJointOverflow);
HWY_EXPORT(PrepareJointLanes);
HWY_EXPORT(PositionJointLanes);
HWY_EXPORT(PositionJointOverflow);

void runJointLanes(const JointLaneArgs& args, JointLanePass pass, int begin, int end) {
  HWY_DYNAMIC_DISPATCH(RunJointLanes)(args, pass, begin, end);
}
void prepareJointLanes(const JointLaneArgs& args, int begin, int end) {
  HWY_DYNAMIC_DISPATCH(PrepareJointLanes)(args, begin, end);
}
int runJointOverflow(const JointLaneArgs& args, JointLanePass pass, int firstLane, int count) {
  return HWY_DYNAMIC_DISPATCH(RunJointOverflow)(args, pass, firstLane, count);
}
void positionJointLanes(const JointLaneArgs& args, int begin, int end, double linearSlop,
                        double* widest, bool* within) {
  HWY_DYNAMIC_DISPATCH(PositionJointLanes)(args, begin, end, linearSlop, widest, within);
}
int positionJointOverflow(const JointLaneArgs& args, int firstLane, int count, double linearSlop,
                          double* widest, bool* within) {
  return HWY_DYNAMIC_DISPATCH(PositionJointOverflow)(args, firstLane, count, linearSlop, widest,
                                                     within);
}

}  // namespace impulse2d
#endif  // HWY_ONCE
