// The SIMD kernels of the sub-stepping contact solver, on the bundles of contact_bundles.hpp.
// Highway compiles this file once per instruction set (a portable baseline, SSE4, AVX2, AVX-512)
// and the first call picks the widest the processor has: 2, 4 or 8 doubles a register.
//
// Every lane computes with the same IEEE operations in the same order on every instruction set
// (no fused multiply-add: the library builds with -ffp-contract=off), so the results are
// bit-identical whatever the width, and a lane-at-a-time run (the overflow's) is the scalar
// reference of a lane-parallel one.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "contact_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "body_lanes-inl.h"
#include "contact_bundles.hpp"
#include "two_point_block-inl.h"

#include <impulse2d/simd.hpp>

HWY_BEFORE_NAMESPACE();
namespace impulse2d {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// 1.0 in the lanes whose flags have `bit`, 0 elsewhere, as a mask (the rare lanes: a soft step,
// a degenerate pair).
template <class D>
HWY_INLINE auto laneMask(D d, const uint8_t* flags, uint8_t bit) {
  HWY_ALIGN double lanes[kBundleLanes];
  for (size_t i = 0; i < hn::Lanes(d); ++i) lanes[i] = (flags[i] & bit) ? 1.0 : 0.0;
  return hn::Gt(hn::Load(d, lanes), hn::Zero(d));
}

template <class D>
HWY_INLINE V<D> loadFloat(D d, const float* p) {
  const hn::Rebind<float, D> df;
  return hn::PromoteTo(d, hn::Load(df, p));
}

// What every row of a lane group needs: the normal and tangent t = perp(n), the masses, and
// half the bodies' relative move as it shifts the lever arms (contact_bundles.hpp).
template <class D>
struct Frame {
  V<D> nx, ny, tx, ty;
  V<D> mA, iA, mB, iB;
  V<D> moveX, moveY;          // dB - dA
  V<D> halfMoveN, halfMoveT;  // cross(dB - dA, n) / 2 and cross(dB - dA, t) / 2
};

template <class D>
HWY_INLINE Frame<D> frame(D d, const ContactBundle& c, size_t lane, const Bodies<D>& a,
                          const Bodies<D>& b) {
  Frame<D> f;
  f.nx = hn::Load(d, c.normalX + lane);
  f.ny = hn::Load(d, c.normalY + lane);
  f.tx = hn::Neg(f.ny);
  f.ty = f.nx;
  f.mA = hn::Load(d, c.invMassA + lane);
  f.iA = hn::Load(d, c.invInertiaA + lane);
  f.mB = hn::Load(d, c.invMassB + lane);
  f.iB = hn::Load(d, c.invInertiaB + lane);
  f.moveX = hn::Sub(b.dx, a.dx);
  f.moveY = hn::Sub(b.dy, a.dy);
  const V<D> half = hn::Set(d, 0.5);
  const V<D> limit = loadFloat(d, c.maxShift + lane), negLimit = hn::Neg(limit);
  f.halfMoveN = hn::Min(
      hn::Max(hn::Mul(half, hn::Sub(hn::Mul(f.moveX, f.ny), hn::Mul(f.moveY, f.nx))), negLimit),
      limit);
  f.halfMoveT = hn::Min(
      hn::Max(hn::Mul(half, hn::Sub(hn::Mul(f.moveX, f.ty), hn::Mul(f.moveY, f.tx))), negLimit),
      limit);
  return f;
}

// One point's lever arms cross(r, n) and cross(r, t) on each body, at the shared point.
template <class D>
struct Arms {
  V<D> normalA, normalB, tangentA, tangentB;
};

template <class D>
HWY_INLINE Arms<D> arms(D d, const BundlePoint& p, size_t lane, const Frame<D>& f) {
  const V<D> ax = hn::Load(d, p.anchorAx + lane), ay = hn::Load(d, p.anchorAy + lane);
  const V<D> bx = hn::Load(d, p.anchorBx + lane), by = hn::Load(d, p.anchorBy + lane);
  Arms<D> r;
  r.normalA = hn::Add(hn::Sub(hn::Mul(ax, f.ny), hn::Mul(ay, f.nx)), f.halfMoveN);
  r.normalB = hn::Sub(hn::Sub(hn::Mul(bx, f.ny), hn::Mul(by, f.nx)), f.halfMoveN);
  r.tangentA = hn::Add(hn::Sub(hn::Mul(ax, f.ty), hn::Mul(ay, f.tx)), f.halfMoveT);
  r.tangentB = hn::Sub(hn::Sub(hn::Mul(bx, f.ty), hn::Mul(by, f.tx)), f.halfMoveT);
  return r;
}

// A point's anchors (from each centre of mass, as the step began) and the same turned with their
// bodies since.
template <class D>
struct Anchors {
  V<D> ax, ay, bx, by;
  V<D> turnedAx, turnedAy, turnedBx, turnedBy;
};

template <class D>
HWY_INLINE Anchors<D> anchors(D d, const BundlePoint& p, size_t lane, const Bodies<D>& a,
                              const Bodies<D>& b) {
  Anchors<D> r;
  r.ax = hn::Load(d, p.anchorAx + lane);
  r.ay = hn::Load(d, p.anchorAy + lane);
  r.bx = hn::Load(d, p.anchorBx + lane);
  r.by = hn::Load(d, p.anchorBy + lane);
  r.turnedAx = hn::Sub(hn::Mul(a.qc, r.ax), hn::Mul(a.qs, r.ay));
  r.turnedAy = hn::Add(hn::Mul(a.qs, r.ax), hn::Mul(a.qc, r.ay));
  r.turnedBx = hn::Sub(hn::Mul(b.qc, r.bx), hn::Mul(b.qs, r.by));
  r.turnedBy = hn::Add(hn::Mul(b.qs, r.bx), hn::Mul(b.qc, r.by));
  return r;
}

// The separation now: the anchors turned with their bodies (contact_bundles.hpp).
template <class D>
HWY_INLINE V<D> separation(D d, const ContactBundle& c, int i, size_t lane, const Frame<D>& f,
                           const Anchors<D>& q) {
  const V<D> gapX = hn::Sub(hn::Add(f.moveX, q.turnedBx), q.turnedAx);
  const V<D> gapY = hn::Sub(hn::Add(f.moveY, q.turnedBy), q.turnedAy);
  return hn::Add(loadFloat(d, c.baseSeparation[i] + lane),
                 hn::Add(hn::Mul(f.nx, gapX), hn::Mul(f.ny, gapY)));
}

// The speed of B relative to A along (dx, dy) at a point with these arms.
template <class D>
HWY_INLINE V<D> rowSpeed(const Bodies<D>& a, const Bodies<D>& b, const V<D>& dx, const V<D>& dy,
                         const V<D>& armA, const V<D>& armB) {
  return hn::Sub(
      hn::Add(hn::Add(hn::Mul(dx, hn::Sub(b.vx, a.vx)), hn::Mul(dy, hn::Sub(b.vy, a.vy))),
              hn::Mul(b.w, armB)),
      hn::Mul(a.w, armA));
}

// The impulse `amount` along (dx, dy) on B at the point, and its reaction on A.
template <class D>
HWY_INLINE void applyRow(Bodies<D>* a, Bodies<D>* b, const Frame<D>& f, const V<D>& dx,
                         const V<D>& dy, const V<D>& armA, const V<D>& armB, const V<D>& amount) {
  const V<D> pa = hn::Mul(f.mA, amount), pb = hn::Mul(f.mB, amount);
  a->vx = hn::Sub(a->vx, hn::Mul(pa, dx));
  a->vy = hn::Sub(a->vy, hn::Mul(pa, dy));
  a->w = hn::Sub(a->w, hn::Mul(hn::Mul(f.iA, armA), amount));
  b->vx = hn::Add(b->vx, hn::Mul(pb, dx));
  b->vy = hn::Add(b->vy, hn::Mul(pb, dy));
  b->w = hn::Add(b->w, hn::Mul(hn::Mul(f.iB, armB), amount));
}

// Two impulses along the normal at the two points, at once.
template <class D>
HWY_INLINE void applyNormals(Bodies<D>* a, Bodies<D>* b, const Frame<D>& f, const Arms<D>& r1,
                             const Arms<D>& r2, const V<D>& amount1, const V<D>& amount2) {
  const V<D> sum = hn::Add(amount1, amount2);
  const V<D> pa = hn::Mul(f.mA, sum), pb = hn::Mul(f.mB, sum);
  a->vx = hn::Sub(a->vx, hn::Mul(pa, f.nx));
  a->vy = hn::Sub(a->vy, hn::Mul(pa, f.ny));
  a->w = hn::Sub(
      a->w, hn::Mul(f.iA, hn::Add(hn::Mul(r1.normalA, amount1), hn::Mul(r2.normalA, amount2))));
  b->vx = hn::Add(b->vx, hn::Mul(pb, f.nx));
  b->vy = hn::Add(b->vy, hn::Mul(pb, f.ny));
  b->w = hn::Add(
      b->w, hn::Mul(f.iB, hn::Add(hn::Mul(r1.normalB, amount1), hn::Mul(r2.normalB, amount2))));
}

// Friction rows of both points, clamped to the cone of their current normal impulses.
template <class D>
HWY_INLINE void solveFriction(D d, ContactBundle& c, BundleExtra& extra, size_t lane, bool relax,
                              const Frame<D>& f, const Arms<D> (&r)[2], Bodies<D>* a,
                              Bodies<D>* b) {
  const V<D> friction = loadFloat(d, c.friction + lane);
  for (int i = 0; i < 2; ++i) {
    BundlePoint& p = c.points[i];
    const V<D> vt = rowSpeed(*a, *b, f.tx, f.ty, r[i].tangentA, r[i].tangentB);
    const V<D> old = hn::Load(d, p.tangentImpulse + lane);
    const V<D> maxFriction = hn::Mul(friction, hn::Load(d, p.normalImpulse + lane));
    const V<D> total =
        hn::Min(hn::Max(hn::Sub(old, hn::Mul(loadFloat(d, c.tangentMass[i] + lane), vt)),
                        hn::Neg(maxFriction)),
                maxFriction);
    applyRow(a, b, f, f.tx, f.ty, r[i].tangentA, r[i].tangentB, hn::Sub(total, old));
    hn::Store(total, d, p.tangentImpulse + lane);
    if (relax) {
      double* sum = extra.totalTangentImpulse[i] + lane;
      hn::Store(hn::Add(hn::Load(d, sum), total), d, sum);
    }
  }
}

// Both normal rows. Not touching (s > 0): close the gap within the sub-step, no further (a
// target of -s / h). Touching: rigid, or in the soft step's biased pass a damped spring that
// pushes out at most maxPushVelocity. A spring row with accumulated impulse x satisfies
//   v + bias + gamma x >= 0,  gamma = K_ii s / m  (s, m: the feedback's impulse and mass scales),
// which is the one-row update of feedback.hpp solved exactly; for both rows it is the block
// with K + diag(gamma) and v + gamma x0.
template <class D>
HWY_INLINE void solveNormals(D d, const BundlePass& pass, ContactBundle& c, BundleExtra& extra,
                             size_t lane, const Frame<D>& f, const Arms<D> (&r)[2],
                             const V<D> (&s)[2], Bodies<D>* a, Bodies<D>* b) {
  const V<D> zero = hn::Zero(d), one = hn::Set(d, 1.0);
  const V<D> inverseH = hn::Set(d, pass.inverseH);
  BundlePoint& p1 = c.points[0];
  BundlePoint& p2 = c.points[1];
  const V<D> old1 = hn::Load(d, p1.normalImpulse + lane),
             old2 = hn::Load(d, p2.normalImpulse + lane);
  const V<D> linear =
      hn::Add(hn::Mul(f.nx, hn::Sub(b->vx, a->vx)), hn::Mul(f.ny, hn::Sub(b->vy, a->vy)));
  const V<D> vn[2] = {
      hn::Sub(hn::Add(linear, hn::Mul(b->w, r[0].normalB)), hn::Mul(a->w, r[0].normalA)),
      hn::Sub(hn::Add(linear, hn::Mul(b->w, r[1].normalB)), hn::Mul(a->w, r[1].normalA))};
  TwoPointBlock<SimdLanes<D>> k{
      loadFloat(d, c.k12 + lane),           loadFloat(d, c.inverse11 + lane),
      loadFloat(d, c.inverse12 + lane),     loadFloat(d, c.inverse22 + lane),
      loadFloat(d, c.normalMass[0] + lane), loadFloat(d, c.normalMass[1] + lane)};
  V<D> v[2];
  if (!pass.useBias) {
    for (int i = 0; i < 2; ++i) {
      v[i] = hn::Add(vn[i], hn::IfThenElseZero(hn::Gt(s[i], zero), hn::Mul(s[i], inverseH)));
    }
  } else {
    const auto stiffer = laneMask(d, c.laneFlags + lane, kAgainstStaticLane);
    const V<D> rate = hn::IfThenElse(stiffer, hn::Set(d, pass.staticSoft.rate),
                                     hn::Set(d, pass.dynamicSoft.rate));
    const V<D> spring = hn::IfThenElse(
        stiffer, hn::Set(d, pass.staticSoft.impulseScale / pass.staticSoft.massScale),
        hn::Set(d, pass.dynamicSoft.impulseScale / pass.dynamicSoft.massScale));
    const V<D> maxPush = hn::Set(d, -pass.maxPushVelocity);
    const V<D> olds[2] = {old1, old2};
    V<D> diagonal[2];  // K_ii + gamma_i
    for (int i = 0; i < 2; ++i) {
      const auto apart = hn::Gt(s[i], zero);
      const V<D> kii = hn::Load(d, extra.k[i] + lane);
      const V<D> gamma = hn::IfThenElseZero(hn::Not(apart), hn::Mul(kii, spring));
      V<D> bias =
          hn::IfThenElse(apart, hn::Mul(s[i], inverseH), hn::Max(hn::Mul(rate, s[i]), maxPush));
      // A crushed body's overlaps (crushed_bodies.hpp) are not pushed out. Their springs stay
      // soft: held rigid as well, the rows' impulses grew step after step (soak seed 365: to
      // 2,800 N s on a 0.2 x 1.4 m rod, which they flung at 170 m/s).
      if (c.anyNoPush) {
        const auto held = hn::AndNot(apart, laneMask(d, c.laneFlags + lane, kNoPushLane));
        bias = hn::IfThenZeroElse(held, bias);
      }
      v[i] = hn::Add(hn::Add(vn[i], bias), hn::Mul(gamma, olds[i]));
      diagonal[i] = hn::Add(kii, gamma);
    }
    // The softened block's inverse, here; one-point lanes (m2 = 0) keep only their first row.
    const auto twoPoints = hn::Gt(k.mass2, zero);
    const V<D> det = hn::IfThenElse(
        twoPoints, hn::Sub(hn::Mul(diagonal[0], diagonal[1]), hn::Mul(k.k12, k.k12)), one);
    const V<D> inverseDet = hn::Div(one, det);
    k.mass1 =
        hn::IfThenElseZero(hn::Gt(k.mass1, zero),
                           hn::Div(one, hn::IfThenElse(hn::Gt(k.mass1, zero), diagonal[0], one)));
    k.mass2 =
        hn::IfThenElseZero(twoPoints, hn::Div(one, hn::IfThenElse(twoPoints, diagonal[1], one)));
    k.inverse11 = hn::IfThenElse(twoPoints, hn::Mul(diagonal[1], inverseDet), k.mass1);
    k.inverse12 = hn::IfThenElseZero(twoPoints, hn::Neg(hn::Mul(k.k12, inverseDet)));
    k.inverse22 = hn::IfThenElseZero(twoPoints, hn::Mul(diagonal[0], inverseDet));
  }
  V<D> x1, x2;
  solveTwoPointBlock(SimdLanes<D>{d}, k, v[0], v[1], old1, old2, &x1, &x2);
  if (c.anySequential) {
    // Nearly coincident points, too ill-conditioned for the block: one row after the other,
    // the second seeing the first's impulse through the coupling K12.
    const auto sequential = laneMask(d, c.laneFlags + lane, kSequentialLane);
    const V<D> seq1 = hn::Max(hn::Sub(old1, hn::Mul(k.mass1, v[0])), zero);
    const V<D> v2After = hn::Add(v[1], hn::Mul(k.k12, hn::Sub(seq1, old1)));
    const V<D> seq2 = hn::Max(hn::Sub(old2, hn::Mul(k.mass2, v2After)), zero);
    x1 = hn::IfThenElse(sequential, seq1, x1);
    x2 = hn::IfThenElse(sequential, seq2, x2);
  }
  (void)one;
  applyNormals(a, b, f, r[0], r[1], hn::Sub(x1, old1), hn::Sub(x2, old2));
  hn::Store(x1, d, p1.normalImpulse + lane);
  hn::Store(x2, d, p2.normalImpulse + lane);
  if (pass.relax) {
    hn::Store(hn::Add(hn::Load(d, extra.totalNormalImpulse[0] + lane), x1), d,
              extra.totalNormalImpulse[0] + lane);
    hn::Store(hn::Add(hn::Load(d, extra.totalNormalImpulse[1] + lane), x2), d,
              extra.totalNormalImpulse[1] + lane);
  }
  if (c.anyRestitution) {
    hn::Store(hn::Max(hn::Load(d, extra.maxNormalImpulse[0] + lane), x1), d,
              extra.maxNormalImpulse[0] + lane);
    hn::Store(hn::Max(hn::Load(d, extra.maxNormalImpulse[1] + lane), x2), d,
              extra.maxNormalImpulse[1] + lane);
  }
}

template <class D>
HWY_INLINE void solveGroup(D d, const BundlePass& pass, ContactBundle& c, BundleExtra& extra,
                           size_t lane) {
  Bodies<D> a = loadBodies(d, pass.states, c.offsetA + lane);
  Bodies<D> b = loadBodies(d, pass.states, c.offsetB + lane);
  const Frame<D> f = frame(d, c, lane, a, b);
  const Arms<D> r[2] = {arms(d, c.points[0], lane, f), arms(d, c.points[1], lane, f)};
  const V<D> s[2] = {separation(d, c, 0, lane, f, anchors(d, c.points[0], lane, a, b)),
                     separation(d, c, 1, lane, f, anchors(d, c.points[1], lane, a, b))};
  // Friction first: non-penetration matters more, so the normal impulses get the last word.
  solveFriction(d, c, extra, lane, pass.relax, f, r, &a, &b);
  solveNormals(d, pass, c, extra, lane, f, r, s, &a, &b);
  storeVelocities(d, pass.states, c.offsetA + lane, pass.sinkOffset, a);
  storeVelocities(d, pass.states, c.offsetB + lane, pass.sinkOffset, b);
}

template <class D>
HWY_INLINE void warmStartGroup(D d, const BundlePass& pass, ContactBundle& c, size_t lane) {
  Bodies<D> a = loadBodies(d, pass.states, c.offsetA + lane);
  Bodies<D> b = loadBodies(d, pass.states, c.offsetB + lane);
  const Frame<D> f = frame(d, c, lane, a, b);
  // All impulses of the lane at once: P = sum over the points of (normal n + tangent t).
  V<D> normal = hn::Zero(d), tangent = hn::Zero(d), angularA = hn::Zero(d), angularB = hn::Zero(d);
  for (int i = 0; i < 2; ++i) {
    const BundlePoint& p = c.points[i];
    const Arms<D> r = arms(d, p, lane, f);
    const V<D> pn = hn::Load(d, p.normalImpulse + lane), pt = hn::Load(d, p.tangentImpulse + lane);
    normal = hn::Add(normal, pn);
    tangent = hn::Add(tangent, pt);
    angularA = hn::Add(angularA, hn::Add(hn::Mul(pn, r.normalA), hn::Mul(pt, r.tangentA)));
    angularB = hn::Add(angularB, hn::Add(hn::Mul(pn, r.normalB), hn::Mul(pt, r.tangentB)));
  }
  const V<D> px = hn::Sub(hn::Mul(normal, f.nx), hn::Mul(tangent, f.ny));
  const V<D> py = hn::Add(hn::Mul(normal, f.ny), hn::Mul(tangent, f.nx));
  a.vx = hn::Sub(a.vx, hn::Mul(f.mA, px));
  a.vy = hn::Sub(a.vy, hn::Mul(f.mA, py));
  a.w = hn::Sub(a.w, hn::Mul(f.iA, angularA));
  b.vx = hn::Add(b.vx, hn::Mul(f.mB, px));
  b.vy = hn::Add(b.vy, hn::Mul(f.mB, py));
  b.w = hn::Add(b.w, hn::Mul(f.iB, angularB));
  storeVelocities(d, pass.states, c.offsetA + lane, pass.sinkOffset, a);
  storeVelocities(d, pass.states, c.offsetB + lane, pass.sinkOffset, b);
}

// The speed the points meet at, for restitution: the lowest normal speed at the start of any
// sub-step, before the warm start. Read after the warm start (or during the solve), it would take
// in what the kept impulses throw a wedged body at, and the bounce would grow the impulses it is
// warm started with next step (core soak seed 1101: 16 m/s before the bounce, 77 after).
template <class D>
HWY_INLINE void approachGroup(D d, const BundlePass& pass, ContactBundle& c, BundleExtra& extra,
                              size_t lane) {
  const Bodies<D> a = loadBodies(d, pass.states, c.offsetA + lane);
  const Bodies<D> b = loadBodies(d, pass.states, c.offsetB + lane);
  const Frame<D> f = frame(d, c, lane, a, b);
  for (int i = 0; i < 2; ++i) {
    const Arms<D> r = arms(d, c.points[i], lane, f);
    double* approach = extra.approach[i] + lane;
    hn::Store(hn::Min(hn::Load(d, approach), rowSpeed(a, b, f.nx, f.ny, r.normalA, r.normalB)), d,
              approach);
  }
}

template <class D>
HWY_INLINE void restituteGroup(D d, const BundlePass& pass, ContactBundle& c, BundleExtra& extra,
                               size_t lane) {
  Bodies<D> a = loadBodies(d, pass.states, c.offsetA + lane);
  Bodies<D> b = loadBodies(d, pass.states, c.offsetB + lane);
  const Frame<D> f = frame(d, c, lane, a, b);
  const V<D> zero = hn::Zero(d);
  const V<D> restitution = hn::Load(d, extra.restitution + lane);
  for (int i = 0; i < 2; ++i) {
    BundlePoint& p = c.points[i];
    const Arms<D> r = arms(d, p, lane, f);
    const V<D> approach = hn::Load(d, extra.approach[i] + lane);
    const V<D> old = hn::Load(d, p.normalImpulse + lane);
    // Only points that pushed: a speculative point the bodies never reached does not bounce.
    const auto bounces =
        hn::And(hn::And(hn::Gt(restitution, zero),
                        hn::Lt(approach, hn::Set(d, -pass.restitutionThreshold))),
                hn::Gt(hn::Max(old, hn::Load(d, extra.maxNormalImpulse[i] + lane)), zero));
    const V<D> vn = rowSpeed(a, b, f.nx, f.ny, r.normalA, r.normalB);
    const V<D> target = hn::Neg(hn::Mul(restitution, approach));
    const V<D> total = hn::Max(
        hn::Sub(old, hn::Mul(loadFloat(d, c.normalMass[i] + lane), hn::Sub(vn, target))), zero);
    const V<D> delta = hn::IfThenElseZero(bounces, hn::Sub(total, old));
    hn::Store(hn::Add(old, delta), d, p.normalImpulse + lane);
    double* sum = extra.totalNormalImpulse[i] + lane;
    hn::Store(hn::Add(hn::Load(d, sum), delta), d, sum);
    applyRow(&a, &b, f, f.nx, f.ny, r.normalA, r.normalB, delta);
  }
  storeVelocities(d, pass.states, c.offsetA + lane, pass.sinkOffset, a);
  storeVelocities(d, pass.states, c.offsetB + lane, pass.sinkOffset, b);
}

// One NGS pass: each point's overlap beyond the slop is pushed out by moving both bodies along
// the normal at the shared point, both points of a lane together (their 2x2 block).
template <class D>
HWY_INLINE V<D> positionGroup(D d, const BundlePass& pass, ContactBundle& c, size_t lane) {
  Bodies<D> a = loadBodies(d, pass.states, c.offsetA + lane);
  Bodies<D> b = loadBodies(d, pass.states, c.offsetB + lane);
  const Frame<D> f = frame(d, c, lane, a, b);
  const V<D> zero = hn::Zero(d), half = hn::Set(d, 0.5);
  V<D> rnA[2], rnB[2], correction[2], deepest = zero;
  for (int i = 0; i < 2; ++i) {
    const Anchors<D> q = anchors(d, c.points[i], lane, a, b);
    const V<D>&ax = q.ax, &ay = q.ay, &bx = q.bx, &by = q.by;
    const V<D>&turnedAx = q.turnedAx, &turnedAy = q.turnedAy;
    const V<D>&turnedBx = q.turnedBx, &turnedBy = q.turnedBy;
    const V<D> s = separation(d, c, i, lane, f, q);
    const auto present = hn::Gt(loadFloat(d, c.normalMass[i] + lane), zero);
    deepest = hn::Min(deepest, hn::IfThenElseZero(present, s));
    // The shared point: midway between the two anchors now (pB - pA = move + turnedB - turnedA
    // + aA - aB).
    const V<D> gapX = hn::Add(hn::Sub(hn::Add(f.moveX, turnedBx), turnedAx), hn::Sub(ax, bx));
    const V<D> gapY = hn::Add(hn::Sub(hn::Add(f.moveY, turnedBy), turnedAy), hn::Sub(ay, by));
    const V<D> rAx = hn::Add(turnedAx, hn::Mul(half, gapX)),
               rAy = hn::Add(turnedAy, hn::Mul(half, gapY));
    const V<D> rBx = hn::Sub(turnedBx, hn::Mul(half, gapX)),
               rBy = hn::Sub(turnedBy, hn::Mul(half, gapY));
    rnA[i] = hn::Sub(hn::Mul(rAx, f.ny), hn::Mul(rAy, f.nx));
    rnB[i] = hn::Sub(hn::Mul(rBx, f.ny), hn::Mul(rBy, f.nx));
    correction[i] =
        hn::IfThenElseZero(present, positionCorrection(SimdLanes<D>{d}, s, pass.baumgarte,
                                                       pass.linearSlop, pass.maxLinearCorrection));
  }
  if (hn::AllTrue(d, hn::Eq(hn::Or(correction[0], correction[1]), zero))) {
    return deepest;  // every point within the slop
  }
  const auto twoPoints = hn::Gt(loadFloat(d, c.normalMass[1] + lane), zero);
  V<D> x1, x2;
  positionPushes(SimdLanes<D>{d}, hn::Add(f.mA, f.mB), f.iA, f.iB, rnA, rnB, correction, twoPoints,
                 &x1, &x2);
  const V<D> sum = hn::Add(x1, x2);
  a.dx = hn::Sub(a.dx, hn::Mul(hn::Mul(f.mA, sum), f.nx));
  a.dy = hn::Sub(a.dy, hn::Mul(hn::Mul(f.mA, sum), f.ny));
  b.dx = hn::Add(b.dx, hn::Mul(hn::Mul(f.mB, sum), f.nx));
  b.dy = hn::Add(b.dy, hn::Mul(hn::Mul(f.mB, sum), f.ny));
  const V<D> turnA = hn::Neg(hn::Mul(f.iA, hn::Add(hn::Mul(rnA[0], x1), hn::Mul(rnA[1], x2))));
  const V<D> turnB = hn::Mul(f.iB, hn::Add(hn::Mul(rnB[0], x1), hn::Mul(rnB[1], x2)));
  a.turned = hn::Add(a.turned, turnA);
  b.turned = hn::Add(b.turned, turnB);
  turn(d, turnA, &a.qc, &a.qs);
  turn(d, turnB, &b.qc, &b.qs);
  storePoses(d, pass.states, c.offsetA + lane, pass.sinkOffset, a);
  storePoses(d, pass.states, c.offsetB + lane, pass.sinkOffset, b);
  return deepest;
}

// A lane group's masses, as the step begins (fill leaves them to this, contact_bundles.cpp): each
// point's normal and tangent effective masses, the two-point block and its inverse, the lever
// arms' largest shift (shiftWithin there), the soft step's diagonal. The same operations in the
// same order as a lane at a time; lanes past the bundle's count stay empty (all zero).
template <class D>
HWY_INLINE void massGroup(D d, ContactBundle& c, BundleExtra& e, size_t lane, bool soft) {
  const V<D> zero = hn::Zero(d), one = hn::Set(d, 1.0), half = hn::Set(d, 0.5);
  const V<D> unbounded = hn::Set(d, static_cast<double>(std::numeric_limits<float>::max()));
  const V<D> nx = hn::Load(d, c.normalX + lane), ny = hn::Load(d, c.normalY + lane);
  const V<D> iA = hn::Load(d, c.invInertiaA + lane), iB = hn::Load(d, c.invInertiaB + lane);
  const V<D> mass = hn::Add(hn::Load(d, c.invMassA + lane), hn::Load(d, c.invMassB + lane));
  const V<D> inertiaSum = hn::Add(iA, iB);
  const auto turns = hn::Gt(inertiaSum, zero);
  const auto two = laneMask(d, c.laneFlags + lane, kTwoPointLane);
  const int count = c.laneCount;
  const auto used =
      hn::FirstN(d, count > static_cast<int>(lane) ? static_cast<size_t>(count) - lane : 0);
  // The largest |h| with K <= 1.5 k when the arms become armA + h and armB - h.
  auto shiftWithin = [&](V<D> k, V<D> armA, V<D> armB) {
    const V<D> lever = hn::Add(hn::Mul(iA, hn::Abs(armA)), hn::Mul(iB, hn::Abs(armB)));
    const V<D> root =
        hn::Sqrt(hn::Add(hn::Mul(lever, lever), hn::Mul(hn::Mul(half, inertiaSum), k)));
    return hn::IfThenElse(turns, hn::Div(hn::Sub(root, lever), inertiaSum), unbounded);
  };
  const hn::Rebind<float, D> df;
  V<D> normalArmA[2], normalArmB[2], normalK[2], maxShift = unbounded;
  for (int i = 0; i < 2; ++i) {
    const BundlePoint& p = c.points[i];
    const V<D> ax = hn::Load(d, p.anchorAx + lane), ay = hn::Load(d, p.anchorAy + lane);
    const V<D> bx = hn::Load(d, p.anchorBx + lane), by = hn::Load(d, p.anchorBy + lane);
    normalArmA[i] = hn::Sub(hn::Mul(ax, ny), hn::Mul(ay, nx));
    normalArmB[i] = hn::Sub(hn::Mul(bx, ny), hn::Mul(by, nx));
    const V<D> tangentArmA = hn::Add(hn::Mul(ax, nx), hn::Mul(ay, ny));
    const V<D> tangentArmB = hn::Add(hn::Mul(bx, nx), hn::Mul(by, ny));
    normalK[i] = hn::Add(hn::Add(mass, hn::Mul(hn::Mul(iA, normalArmA[i]), normalArmA[i])),
                         hn::Mul(hn::Mul(iB, normalArmB[i]), normalArmB[i]));
    const V<D> tangentK = hn::Add(hn::Add(mass, hn::Mul(hn::Mul(iA, tangentArmA), tangentArmA)),
                                  hn::Mul(hn::Mul(iB, tangentArmB), tangentArmB));
    const V<D> shift = hn::Min(shiftWithin(normalK[i], normalArmA[i], normalArmB[i]),
                               shiftWithin(tangentK, tangentArmA, tangentArmB));
    const auto present = i == 0 ? used : hn::And(used, two);
    maxShift = hn::IfThenElse(present, hn::Min(maxShift, shift), maxShift);
    const V<D> normalMass =
        hn::IfThenElseZero(hn::And(present, hn::Gt(normalK[i], zero)), hn::Div(one, normalK[i]));
    const V<D> tangentMass =
        hn::IfThenElseZero(hn::And(present, hn::Gt(tangentK, zero)), hn::Div(one, tangentK));
    hn::Store(hn::DemoteTo(df, normalMass), df, c.normalMass[i] + lane);
    hn::Store(hn::DemoteTo(df, tangentMass), df, c.tangentMass[i] + lane);
  }
  hn::Store(hn::DemoteTo(df, hn::IfThenElseZero(used, maxShift)), df, c.maxShift + lane);
  const V<D> k11 = normalK[0], k22 = hn::IfThenElseZero(two, normalK[1]);
  const V<D> k12 = hn::IfThenElseZero(
      two, hn::Add(hn::Add(mass, hn::Mul(hn::Mul(iA, normalArmA[0]), normalArmA[1])),
                   hn::Mul(hn::Mul(iB, normalArmB[0]), normalArmB[1])));
  if (soft) {
    hn::Store(k11, d, e.k[0] + lane);
    hn::Store(k22, d, e.k[1] + lane);
  }
  const V<D> det = hn::Sub(hn::Mul(k11, k22), hn::Mul(k12, k12));
  const auto block = hn::And(two, wellConditioned(SimdLanes<D>{d}, k11, det));
  const auto sequential = hn::AndNot(block, two);
  const V<D> single = hn::IfThenElseZero(hn::And(used, hn::Gt(k11, zero)), hn::Div(one, k11));
  V<D> inverse11, inverse12, inverse22;
  blockInverse(SimdLanes<D>{d}, k11, k12, k22, det, &inverse11, &inverse12, &inverse22);
  hn::Store(hn::DemoteTo(df, k12), df, c.k12 + lane);
  hn::Store(
      hn::DemoteTo(df, hn::IfThenElse(block, inverse11, hn::IfThenElseZero(hn::Not(two), single))),
      df, c.inverse11 + lane);
  hn::Store(hn::DemoteTo(df, hn::IfThenElseZero(block, inverse12)), df, c.inverse12 + lane);
  hn::Store(hn::DemoteTo(df, hn::IfThenElseZero(block, inverse22)), df, c.inverse22 + lane);
  HWY_ALIGN double flags[kBundleLanes];
  hn::Store(hn::IfThenElseZero(sequential, one), d, flags);
  for (size_t i = 0; i < hn::Lanes(d) && static_cast<int>(lane + i) < count; ++i) {
    if (flags[i] != 0.0) c.laneFlags[lane + i] |= kSequentialLane;
  }
}

// Runs `group` over the lane groups of the bundles [begin, end): as many lanes at once as the
// instruction set holds, or one at a time for the overflow, whose lanes may share bodies.
template <class Group>
HWY_INLINE void forEachGroup(const BundlePass& pass, int begin, int end, bool oneByOne,
                             const Group& group) {
  if (oneByOne) {
    const hn::CappedTag<double, 1> d1;
    for (int k = begin; k < end; ++k) {
      for (int lane = 0; lane < pass.bundles[k].laneCount; ++lane) group(d1, k, size_t(lane));
    }
    return;
  }
  const hn::CappedTag<double, kBundleLanes> d;
  const size_t n = hn::Lanes(d);
  for (int k = begin; k < end; ++k) {
    const size_t used = static_cast<size_t>(pass.bundles[k].laneCount);
    for (size_t lane = 0; lane < used; lane += n) group(d, k, lane);
  }
}

void WarmStartBundles(const BundlePass& pass, int begin, int end, bool oneByOne) {
  forEachGroup(pass, begin, end, oneByOne,
               [&](auto d, int k, size_t lane) { warmStartGroup(d, pass, pass.bundles[k], lane); });
}

void SolveBundles(const BundlePass& pass, int begin, int end, bool oneByOne) {
  forEachGroup(pass, begin, end, oneByOne, [&](auto d, int k, size_t lane) {
    solveGroup(d, pass, pass.bundles[k], pass.extras[k], lane);
  });
}

void NoteBundleApproaches(const BundlePass& pass, const int* bundles, int count) {
  // Reads the bodies and writes only the bundles' own fields: lane-parallel even in the overflow.
  const hn::CappedTag<double, kBundleLanes> d;
  for (int i = 0; i < count; ++i) {
    const int k = bundles[i];
    const size_t used = static_cast<size_t>(pass.bundles[k].laneCount);
    for (size_t lane = 0; lane < used; lane += hn::Lanes(d))
      approachGroup(d, pass, pass.bundles[k], pass.extras[k], lane);
  }
}

void RestituteBundles(const BundlePass& pass, int begin, int end, bool oneByOne) {
  forEachGroup(pass, begin, end, oneByOne, [&](auto d, int k, size_t lane) {
    if (pass.bundles[k].anyRestitution)
      restituteGroup(d, pass, pass.bundles[k], pass.extras[k], lane);
  });
}

double SolveBundlePositions(const BundlePass& pass, int begin, int end, bool oneByOne) {
  double deepest = 0.0;
  forEachGroup(pass, begin, end, oneByOne, [&](auto d, int k, size_t lane) {
    const auto groupDeepest = positionGroup(d, pass, pass.bundles[k], lane);
    deepest = std::min(deepest, hn::GetLane(hn::MinOfLanes(d, groupDeepest)));
  });
  return deepest;
}

void PrepareBundleMasses(ContactBundle* bundles, BundleExtra* extras, int begin, int end,
                         bool soft) {
  const hn::CappedTag<double, kBundleLanes> d;
  for (int k = begin; k < end; ++k) {
    for (size_t lane = 0; lane < static_cast<size_t>(bundles[k].laneCount); lane += hn::Lanes(d))
      massGroup(d, bundles[k], extras[k], lane, soft);
  }
}

const char* KernelTarget() { return hwy::TargetName(HWY_TARGET); }

}  // namespace HWY_NAMESPACE
}  // namespace impulse2d
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace impulse2d {

HWY_EXPORT(WarmStartBundles);
HWY_EXPORT(SolveBundles);
HWY_EXPORT(NoteBundleApproaches);
HWY_EXPORT(RestituteBundles);
HWY_EXPORT(SolveBundlePositions);
HWY_EXPORT(PrepareBundleMasses);
HWY_EXPORT(KernelTarget);

void warmStartBundles(const BundlePass& pass, int begin, int end, bool oneByOne) {
  HWY_DYNAMIC_DISPATCH(WarmStartBundles)(pass, begin, end, oneByOne);
}
void solveBundles(const BundlePass& pass, int begin, int end, bool oneByOne) {
  HWY_DYNAMIC_DISPATCH(SolveBundles)(pass, begin, end, oneByOne);
}
void noteBundleApproaches(const BundlePass& pass, const int* bundles, int count) {
  HWY_DYNAMIC_DISPATCH(NoteBundleApproaches)(pass, bundles, count);
}
void restituteBundles(const BundlePass& pass, int begin, int end, bool oneByOne) {
  HWY_DYNAMIC_DISPATCH(RestituteBundles)(pass, begin, end, oneByOne);
}
double solveBundlePositions(const BundlePass& pass, int begin, int end, bool oneByOne) {
  return HWY_DYNAMIC_DISPATCH(SolveBundlePositions)(pass, begin, end, oneByOne);
}
void prepareBundleMasses(ContactBundle* bundles, BundleExtra* extras, int begin, int end,
                         bool soft) {
  HWY_DYNAMIC_DISPATCH(PrepareBundleMasses)(bundles, extras, begin, end, soft);
}

namespace {

// Every target this build has and this processor runs, best first (read once).
const std::vector<int64_t>& availableTargets() {
  static const std::vector<int64_t> targets = hwy::SupportedAndGeneratedTargets();
  return targets;
}

}  // namespace

std::vector<std::string> simdTargets() {
  std::vector<std::string> names;
  for (const int64_t target : availableTargets()) names.emplace_back(hwy::TargetName(target));
  return names;
}

bool useSimdTarget(const std::string& name) {
  for (const int64_t target : availableTargets()) {
    if (!name.empty() && name != hwy::TargetName(target)) continue;
    // The dispatch takes the best target of the mask (with the scalar fallback): the one named,
    // or all this processor has. No test hook: DisableTargets and the mask are the production
    // interface.
    hwy::GetChosenTarget().Update(name.empty() ? hwy::SupportedTargets() : target);
    return true;
  }
  return false;
}

std::string simdTarget() { return HWY_DYNAMIC_DISPATCH(KernelTarget)(); }

std::string useSimdTargetFromEnvironment() {
  const char* name = std::getenv("IMPULSE2D_SIMD");
  if (name == nullptr || *name == '\0' || useSimdTarget(name)) return "";
  std::string known;
  for (const std::string& target : simdTargets()) known += " " + target;
  return std::string("IMPULSE2D_SIMD=") + name + " is not one of:" + known + "; using " +
         simdTarget();
}

}  // namespace impulse2d
#endif  // HWY_ONCE
