// The two-point block of a manifold's normal rows, written once for both solver paths: the
// one-pass solvers (contact_solver.cpp) run it on doubles (`ScalarLanes`), the sub-stepping
// kernels (contact_kernels.cpp) on SIMD lanes (`SimdLanes`). The same operations in the same
// order in both, so a lane computes what the scalar path computes, to the bit. Included once per
// instruction set (Highway's -inl.h convention), as the kernels' code must be compiled for each.
//
// Two points of one manifold share the bodies, so their normal rows are coupled through
//
//   K = | K11 K12 |,  K_ij = 1/mA + 1/mB + cross(rA_i, n) cross(rA_j, n) / IA
//       | K12 K22 |                      + cross(rB_i, n) cross(rB_j, n) / IB
//
// Solving the pair exactly removes the left-right bias of one-by-one Gauss-Seidel that makes
// stacks lean. Nearly coincident points make K singular; such pairs are told by the condition
// test and solved another way by the callers.
#if defined(IMPULSE2D_TWO_POINT_BLOCK_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef IMPULSE2D_TWO_POINT_BLOCK_INL_H_
#undef IMPULSE2D_TWO_POINT_BLOCK_INL_H_
#else
#define IMPULSE2D_TWO_POINT_BLOCK_INL_H_
#endif

#include <hwy/highway.h>

#include <type_traits>

HWY_BEFORE_NAMESPACE();
namespace impulse2d {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Two-point manifolds are solved as a block only while their 2x2 matrix is this well conditioned;
// nearly coincident points would make it singular, and then the points are solved one by one.
constexpr double kMaxBlockCondition = 1000.0;

/// The lane operations the block needs, on one double. Max and Min return the second operand
/// when the first is not larger (smaller) or either is NaN, as the SIMD instructions do.
struct ScalarLanes {
  using V = double;
  using M = bool;
  static constexpr bool kOneLane = true;
  static V Set(double x) { return x; }
  static V Zero() { return 0.0; }
  static V Add(V a, V b) { return a + b; }
  static V Sub(V a, V b) { return a - b; }
  static V Mul(V a, V b) { return a * b; }
  static V Div(V a, V b) { return a / b; }
  static V Neg(V a) { return -a; }
  static V Max(V a, V b) { return a > b ? a : b; }
  static V Min(V a, V b) { return a < b ? a : b; }
  static M Ge(V a, V b) { return a >= b; }
  static M Gt(V a, V b) { return a > b; }
  static M Lt(V a, V b) { return a < b; }
  static M Le(V a, V b) { return a <= b; }
  static M And(M a, M b) { return a && b; }
  static M Or(M a, M b) { return a || b; }
  static M AndNot(M notA, M b) { return !notA && b; }
  static M Not(M a) { return !a; }
  static bool AllTrue(M a) { return a; }
  static V IfThenElse(M m, V yes, V no) { return m ? yes : no; }
  static V IfThenElseZero(M m, V yes) { return m ? yes : 0.0; }
};

/// The same on the lanes of a SIMD descriptor `D`: one lane (the overflow) or a vector of them.
template <class D>
struct SimdLanes {
  using V = hn::Vec<D>;
  using M = hn::Mask<D>;
  static constexpr bool kOneLane = std::is_same_v<D, hn::Simd<double, 1, 0>>;
  D d;
  V Set(double x) const { return hn::Set(d, x); }
  V Zero() const { return hn::Zero(d); }
  static V Add(V a, V b) { return hn::Add(a, b); }
  static V Sub(V a, V b) { return hn::Sub(a, b); }
  static V Mul(V a, V b) { return hn::Mul(a, b); }
  static V Div(V a, V b) { return hn::Div(a, b); }
  static V Neg(V a) { return hn::Neg(a); }
  static V Max(V a, V b) { return hn::Max(a, b); }
  static V Min(V a, V b) { return hn::Min(a, b); }
  static M Ge(V a, V b) { return hn::Ge(a, b); }
  static M Gt(V a, V b) { return hn::Gt(a, b); }
  static M Lt(V a, V b) { return hn::Lt(a, b); }
  static M Le(V a, V b) { return hn::Le(a, b); }
  static M And(M a, M b) { return hn::And(a, b); }
  static M Or(M a, M b) { return hn::Or(a, b); }
  static M AndNot(M notA, M b) { return hn::AndNot(notA, b); }
  static M Not(M a) { return hn::Not(a); }
  bool AllTrue(M a) const { return hn::AllTrue(d, a); }
  static V IfThenElse(M m, V yes, V no) { return hn::IfThenElse(m, yes, no); }
  static V IfThenElseZero(M m, V yes) { return hn::IfThenElseZero(m, yes); }
};

template <class L>
using VOf = typename L::V;
template <class L>
using MOf = typename L::M;

/// Whether a pair's K (its first diagonal entry and determinant) is well conditioned enough for
/// the block: K11^2 < kMaxBlockCondition det.
template <class L>
HWY_INLINE MOf<L> wellConditioned(const L& l, VOf<L> k11, VOf<L> det) {
  return l.Lt(l.Mul(k11, k11), l.Mul(l.Set(kMaxBlockCondition), det));
}

/// K^-1 of a well-conditioned pair from K's entries and determinant: K22 / det, -K12 / det,
/// K11 / det (the step's prepare; a position pass, which solves each pair once, multiplies by
/// 1 / det instead).
template <class L>
HWY_INLINE void blockInverse(const L& l, VOf<L> k11, VOf<L> k12, VOf<L> k22, VOf<L> det,
                             VOf<L>* inverse11, VOf<L>* inverse12, VOf<L>* inverse22) {
  *inverse11 = l.Div(k22, det);
  *inverse12 = l.Div(l.Neg(k12), det);
  *inverse22 = l.Div(k11, det);
}

/// What the block solve reads of K: K12, K^-1 (symmetric) and m_i = 1 / K_ii.
template <class L>
struct TwoPointBlock {
  VOf<L> k12, inverse11, inverse12, inverse22, mass1, mass2;
};

/// Both normal rows at once: the 2x2 linear complementarity problem of the accumulated impulses
/// x (old: x0),
///   w = v + K (x - x0) >= 0,  x >= 0,  x_i w_i = 0,
/// where v is each row's speed (less its target) now. It has few enough cases to try them all:
/// both rows push, only the first, only the second, neither. Only K12, K^-1 and m_i enter: "w_i
/// >= 0" is tested as m_i w_i >= 0 (m_i > 0), so the diagonal of K is not kept. A one-point lane
/// has m2 = K12 = 0, and its second row stays 0. Where no case fits (round-off on a degenerate
/// pair) x keeps x0; the returned mask tells where one did.
template <class L>
HWY_INLINE MOf<L> solveTwoPointBlock(const L& l, const TwoPointBlock<L>& k, VOf<L> v1, VOf<L> v2,
                                     VOf<L> old1, VOf<L> old2, VOf<L>* x1, VOf<L>* x2) {
  using V = VOf<L>;
  const V zero = l.Zero();
  const V both1 = l.Sub(old1, l.Add(l.Mul(k.inverse11, v1), l.Mul(k.inverse12, v2)));
  const V both2 = l.Sub(old2, l.Add(l.Mul(k.inverse12, v1), l.Mul(k.inverse22, v2)));
  const auto both = l.And(l.Ge(both1, zero), l.Ge(both2, zero));
  // One lane at a time (the scalar path, the overflow's contacts one after the other), the
  // common case of a resting pair is taken on a branch, so the next contact need not wait for
  // the other cases' tests (stack20: a tenth of its step). Lanes side by side keep the selects:
  // there a mispredicted branch costs more than the tests.
  if constexpr (L::kOneLane) {
    if (l.AllTrue(both)) {
      *x1 = both1;
      *x2 = both2;
      return both;
    }
  }
  // Only the first: x2 = 0.
  const V first = l.Sub(old1, l.Mul(k.mass1, l.Sub(v1, l.Mul(k.k12, old2))));
  const V w2 = l.Sub(l.Mul(k.mass2, l.Add(v2, l.Mul(k.k12, l.Sub(first, old1)))), old2);
  const auto onlyFirst = l.And(l.Ge(first, zero), l.Ge(w2, zero));
  // Only the second: x1 = 0.
  const V second = l.Sub(old2, l.Mul(k.mass2, l.Sub(v2, l.Mul(k.k12, old1))));
  const V w1 = l.Sub(l.Mul(k.mass1, l.Add(v1, l.Mul(k.k12, l.Sub(second, old2)))), old1);
  const auto onlySecond = l.And(l.Ge(second, zero), l.Ge(w1, zero));
  // Neither.
  const V rest1 = l.Sub(l.Mul(k.mass1, l.Sub(v1, l.Mul(k.k12, old2))), old1);
  const V rest2 = l.Sub(l.Mul(k.mass2, l.Sub(v2, l.Mul(k.k12, old1))), old2);
  const auto none = l.And(l.Ge(rest1, zero), l.Ge(rest2, zero));
  const auto fits = l.Or(l.Or(both, onlyFirst), l.Or(onlySecond, none));
  const V new1 = l.IfThenElse(both, both1, l.IfThenElseZero(onlyFirst, first));
  const V new2 =
      l.IfThenElse(both, both2, l.IfThenElseZero(l.AndNot(onlyFirst, onlySecond), second));
  *x1 = l.IfThenElse(fits, new1, old1);
  *x2 = l.IfThenElse(fits, new2, old2);
  return fits;
}

/// One point's overlap beyond the slop as an NGS pass corrects it: baumgarte (s + slop), at most
/// maxCorrection deep, 0 when the point is within the slop (s: its separation, m).
template <class L>
HWY_INLINE VOf<L> positionCorrection(const L& l, VOf<L> s, double baumgarte, double linearSlop,
                                     double maxCorrection) {
  return l.Min(l.Max(l.Mul(l.Set(baumgarte), l.Add(s, l.Set(linearSlop))), l.Set(-maxCorrection)),
               l.Zero());
}

/// An NGS position pass's pushes x1, x2 >= 0 (impulses of position, kg m) along the normal for a
/// manifold's corrections c (positionCorrection), from the bodies' masses (invMass: 1/mA + 1/mB;
/// iA, iB: inverse inertias) and the points' normal arms cross(r, n) on each body:
/// K x + c >= 0, complementary, the block solved from no push at all. One point, or a pair too
/// degenerate for the block: the deeper point alone.
template <class L>
HWY_INLINE void positionPushes(const L& l, VOf<L> invMass, VOf<L> iA, VOf<L> iB,
                               const VOf<L> (&armA)[2], const VOf<L> (&armB)[2],
                               const VOf<L> (&correction)[2], MOf<L> twoPoints, VOf<L>* x1,
                               VOf<L>* x2) {
  using V = VOf<L>;
  const V zero = l.Zero(), one = l.Set(1.0);
  const V k11 =
      l.Add(invMass, l.Add(l.Mul(iA, l.Mul(armA[0], armA[0])), l.Mul(iB, l.Mul(armB[0], armB[0]))));
  const V k22 =
      l.Add(invMass, l.Add(l.Mul(iA, l.Mul(armA[1], armA[1])), l.Mul(iB, l.Mul(armB[1], armB[1]))));
  const V k12 =
      l.Add(invMass, l.Add(l.Mul(iA, l.Mul(armA[0], armA[1])), l.Mul(iB, l.Mul(armB[0], armB[1]))));
  const auto positive1 = l.Gt(k11, zero), positive2 = l.Gt(k22, zero);
  const V mass1 = l.IfThenElseZero(positive1, l.Div(one, l.IfThenElse(positive1, k11, one)));
  const V mass2 = l.IfThenElseZero(positive2, l.Div(one, l.IfThenElse(positive2, k22, one)));
  const V det = l.Sub(l.Mul(k11, k22), l.Mul(k12, k12));
  const auto block = l.And(twoPoints, wellConditioned(l, k11, det));
  const V inverseDet = l.Div(one, l.IfThenElse(block, det, one));
  solveTwoPointBlock(l,
                     TwoPointBlock<L>{k12, l.Mul(k22, inverseDet), l.Neg(l.Mul(k12, inverseDet)),
                                      l.Mul(k11, inverseDet), mass1, mass2},
                     correction[0], correction[1], zero, zero, x1, x2);
  const auto deeper1 = l.Le(correction[0], correction[1]);
  const V alone1 =
      l.IfThenElseZero(l.Or(l.Not(twoPoints), deeper1), l.Neg(l.Mul(correction[0], mass1)));
  const V alone2 =
      l.IfThenElseZero(l.AndNot(deeper1, twoPoints), l.Neg(l.Mul(correction[1], mass2)));
  *x1 = l.IfThenElse(block, *x1, alone1);
  *x2 = l.IfThenElse(block, *x2, alone2);
}

}  // namespace HWY_NAMESPACE
}  // namespace impulse2d
HWY_AFTER_NAMESPACE();

#endif  // IMPULSE2D_TWO_POINT_BLOCK_INL_H_
