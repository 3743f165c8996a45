// The SIMD kernels of the revolute joints in lanes (joint_lanes.hpp). Highway compiles this file
// once per instruction set, as contact_kernels.cpp; each lane repeats the scalar path's operations
// in its order (cited by function below), so the bits match it on every instruction set.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "joint_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "body_lanes-inl.h"
#include "joint_lanes.hpp"

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

// One body's arm at its pose now: its view's q = q0 * Rot(qc, qs) (SubstepBodies::view; q0 itself
// for a body that does not move), times the anchor (anchorGap, joint_revolute.cpp).
template <class D>
HWY_INLINE void arm(D d, const double* q0c, const double* q0s, const double* turns,
                    const double* anchorX, const double* anchorY, size_t lane, const V<D>& qc,
                    const V<D>& qs, V<D>* rx, V<D>* ry) {
  const V<D> c0 = hn::Load(d, q0c + lane), s0 = hn::Load(d, q0s + lane);
  const auto moves = hn::Gt(hn::Load(d, turns + lane), hn::Zero(d));
  const V<D> c = hn::IfThenElse(moves, hn::Sub(hn::Mul(c0, qc), hn::Mul(s0, qs)), c0);
  const V<D> s = hn::IfThenElse(moves, hn::Add(hn::Mul(s0, qc), hn::Mul(c0, qs)), s0);
  const V<D> ax = hn::Load(d, anchorX + lane), ay = hn::Load(d, anchorY + lane);
  *rx = hn::Sub(hn::Mul(c, ax), hn::Mul(s, ay));
  *ry = hn::Add(hn::Mul(s, ax), hn::Mul(c, ay));
}

// prepareRevolute with rigid feedback: the arms, and K^-1 (pointMass, then safeInverse: zero
// where K is singular).
template <class D>
HWY_INLINE Rows<D> prepare(D d, JointBundle& j, size_t lane, const Bodies<D>& a,
                           const Bodies<D>& b) {
  Rows<D> r;
  arm(d, j.q0cA, j.q0sA, j.turnsA, j.anchorAx, j.anchorAy, lane, a.qc, a.qs, &r.rAx, &r.rAy);
  arm(d, j.q0cB, j.q0sB, j.turnsB, j.anchorBx, j.anchorBy, lane, b.qc, b.qs, &r.rBx, &r.rBy);
  const V<D> mA = hn::Load(d, j.invMassA + lane), mB = hn::Load(d, j.invMassB + lane);
  const V<D> iA = hn::Load(d, j.invInertiaA + lane), iB = hn::Load(d, j.invInertiaB + lane);
  const V<D> m = hn::Add(mA, mB);
  const V<D> k00 =
      hn::Add(hn::Add(m, hn::Mul(hn::Mul(iA, r.rAy), r.rAy)), hn::Mul(hn::Mul(iB, r.rBy), r.rBy));
  const V<D> k01 =
      hn::Sub(hn::Mul(hn::Mul(hn::Neg(iA), r.rAx), r.rAy), hn::Mul(hn::Mul(iB, r.rBx), r.rBy));
  const V<D> k11 =
      hn::Add(hn::Add(m, hn::Mul(hn::Mul(iA, r.rAx), r.rAx)), hn::Mul(hn::Mul(iB, r.rBx), r.rBx));
  const V<D> det = hn::Sub(hn::Mul(k00, k11), hn::Mul(k01, k01));
  const auto invertible = hn::Ne(det, hn::Zero(d));
  const V<D> invDet = hn::Div(hn::Set(d, 1.0), det);
  r.mass00 = hn::IfThenElseZero(invertible, hn::Mul(k11, invDet));
  r.mass01 = hn::IfThenElseZero(invertible, hn::Mul(hn::Neg(k01), invDet));
  r.mass11 = hn::IfThenElseZero(invertible, hn::Mul(k00, invDet));
  hn::Store(r.rAx, d, j.rAx + lane);
  hn::Store(r.rAy, d, j.rAy + lane);
  hn::Store(r.rBx, d, j.rBx + lane);
  hn::Store(r.rBy, d, j.rBy + lane);
  hn::Store(r.mass00, d, j.mass00 + lane);
  hn::Store(r.mass01, d, j.mass01 + lane);
  hn::Store(r.mass11, d, j.mass11 + lane);
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

// warmStartJoint over warmStartRevolute (no motor, no limits: the axial impulse is +0). Lanes
// whose change would break the motion limits keep their bodies' velocities and are marked for
// the scalar path, which rescales the impulse as warmStartJoint does.
template <class D>
HWY_INLINE void warmStart(D d, const JointLaneArgs& args, JointBundle& j, size_t lane,
                          const Rows<D>& r, Bodies<D>* a, Bodies<D>* b) {
  const V<D> px = hn::Load(d, j.impulseX + lane), py = hn::Load(d, j.impulseY + lane);
  const V<D> axial = hn::Zero(d);
  Bodies<D> a1 = *a, b1 = *b;
  apply(j, lane, d, px, py, hn::Add(hn::Sub(hn::Mul(r.rAx, py), hn::Mul(r.rAy, px)), axial),
        hn::Add(hn::Sub(hn::Mul(r.rBx, py), hn::Mul(r.rBy, px)), axial), &a1, &b1);
  const V<D> maxSpeedSquared = hn::Set(d, args.maxSpeedSquared);
  const V<D> halfMaxTurnRate = hn::Set(d, args.halfMaxTurnRate);
  const bool limited = args.maxSpeedSquared > 0.0;
  auto within = [&](const Bodies<D>& before, const Bodies<D>& after) {
    const V<D> dvx = hn::Sub(after.vx, before.vx), dvy = hn::Sub(after.vy, before.vy);
    const V<D> speedSquared = hn::Add(hn::Mul(dvx, dvx), hn::Mul(dvy, dvy));
    return hn::And(hn::Le(speedSquared, maxSpeedSquared),
                   hn::Le(hn::Abs(hn::Sub(after.w, before.w)), halfMaxTurnRate));
  };
  const auto ok = hn::And(within(*a, a1), within(*b, b1));
  HWY_ALIGN double okLanes[kJointLanes];
  hn::Store(hn::IfThenElseZero(ok, hn::Set(d, 1.0)), d, okLanes);
  for (size_t i = 0; i < hn::Lanes(d); ++i) {
    if (lane + i < static_cast<size_t>(j.laneCount) && (!limited || okLanes[i] == 0.0))
      j.scalarLanes = static_cast<uint8_t>(j.scalarLanes | (1u << (lane + i)));
  }
  const auto keep = limited ? ok : hn::FirstN(d, 0);
  a->vx = hn::IfThenElse(keep, a1.vx, a->vx);
  a->vy = hn::IfThenElse(keep, a1.vy, a->vy);
  a->w = hn::IfThenElse(keep, a1.w, a->w);
  b->vx = hn::IfThenElse(keep, b1.vx, b->vx);
  b->vy = hn::IfThenElse(keep, b1.vy, b->vy);
  b->w = hn::IfThenElse(keep, b1.w, b->w);
}

// solveRevoluteVelocity without motor and limits, with rigid feedback (bias 0, massScale 1,
// impulseScale 0).
template <class D>
HWY_INLINE void solve(D d, JointBundle& j, size_t lane, const Rows<D>& r, Bodies<D>* a,
                      Bodies<D>* b) {
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
  const bool prepares =
      pass == JointLanePass::PrepareAndWarmStart || pass == JointLanePass::PrepareAndSolve;
  const Rows<D> r = prepares ? prepare(d, j, lane, a, b) : loadRows(d, j, lane);
  if (pass == JointLanePass::PrepareAndWarmStart || pass == JointLanePass::WarmStart) {
    warmStart(d, args, j, lane, r, &a, &b);
  } else {
    solve(d, j, lane, r, &a, &b);
  }
  storeVelocities(d, args.states, j.offsetA + lane, args.sinkOffset, a);
  storeVelocities(d, args.states, j.offsetB + lane, args.sinkOffset, b);
}

void RunJointLanes(const JointLaneArgs& args, JointLanePass pass, int begin, int end) {
  const hn::CappedTag<double, kJointLanes> d;
  const size_t n = hn::Lanes(d);
  for (int k = begin; k < end; ++k) {
    JointBundle& j = args.bundles[k];
    for (size_t lane = 0; lane < static_cast<size_t>(j.laneCount); lane += n)
      group(d, args, pass, j, lane);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace impulse2d
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace impulse2d {

HWY_EXPORT(RunJointLanes);

void runJointLanes(const JointLaneArgs& args, JointLanePass pass, int begin, int end) {
  HWY_DYNAMIC_DISPATCH(RunJointLanes)(args, pass, begin, end);
}

}  // namespace impulse2d
#endif  // HWY_ONCE
