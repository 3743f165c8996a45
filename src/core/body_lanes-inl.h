// Moving bodies between their 64-byte BodyState rows (substep_bodies.hpp) and SIMD lanes, one
// body a lane, for the contact kernels (contact_kernels.cpp). Included once per instruction set.
//
// A gather instruction per field is the portable way, and costs most of a kernel: 8 fields of 2
// bodies a group. Where a row fills one register (AVX-512: 8 doubles) or two (AVX2: 4), the rows
// are loaded whole and transposed in registers instead, which is how Box2D v3 does it in float:
//
//   rows  r0 = [vx vy w t dx dy qc qs]_0        lanes  vx = [vx_0 vx_1 ... vx_7]
//         r1 = [vx vy w t dx dy qc qs]_1   ->          vy = [vy_0 vy_1 ... vy_7]
//         ...                                          ...
//
// A lane whose offset is stored as ~offset reads its row but must not write it (a static or
// kinematic body, an empty lane): its write goes to the worker's sink row instead.
#if defined(IMPULSE2D_BODY_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef IMPULSE2D_BODY_LANES_INL_H_
#undef IMPULSE2D_BODY_LANES_INL_H_
#else
#define IMPULSE2D_BODY_LANES_INL_H_
#endif

#include <hwy/highway.h>

#include <cstdint>

#include "substep_bodies.hpp"

HWY_BEFORE_NAMESPACE();
namespace impulse2d {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

template <class D>
using V = hn::Vec<D>;

// The bodies of a group of lanes: every field of their rows.
template <class D>
struct Bodies {
  V<D> vx, vy, w, turned, dx, dy, qc, qs;
};

inline int32_t readOffset(int32_t stored) { return stored < 0 ? ~stored : stored; }
inline int32_t writeOffset(int32_t stored, int32_t sink) { return stored < 0 ? sink : stored; }

// The offsets of a group of lanes, widened to the lanes of D.
template <class D>
HWY_INLINE hn::Vec<hn::RebindToSigned<D>> loadOffsets(D /*d*/, const int32_t* stored) {
  const hn::RebindToSigned<D> di;
  const hn::Rebind<int32_t, D> d32;
  return hn::PromoteTo(di, hn::Load(d32, stored));
}

// Turns (qc, qs) by `angle`: a Taylor series while every lane's turn is small, as rotationBy.
template <class D>
HWY_INLINE void turn(D d, const V<D>& angle, V<D>* qc, V<D>* qs) {
  V<D> c, s;
  if (hn::AllTrue(d, hn::Lt(hn::Abs(angle), hn::Set(d, kSmallTurn)))) {
    const V<D> a2 = hn::Mul(angle, angle);
    const V<D> one = hn::Set(d, 1.0);
    c = hn::Sub(one,
                hn::Mul(a2, hn::Sub(hn::Set(d, 1.0 / 2.0),
                                    hn::Mul(a2, hn::Sub(hn::Set(d, 1.0 / 24.0),
                                                        hn::Mul(a2, hn::Set(d, 1.0 / 720.0)))))));
    s = hn::Mul(
        angle,
        hn::Sub(one,
                hn::Mul(a2, hn::Sub(hn::Set(d, 1.0 / 6.0),
                                    hn::Mul(a2, hn::Sub(hn::Set(d, 1.0 / 120.0),
                                                        hn::Mul(a2, hn::Set(d, 1.0 / 5040.0))))))));
  } else {
    HWY_ALIGN double lanes[8], cs[8], ss[8];  // at most 8 doubles a vector
    hn::Store(angle, d, lanes);
    for (size_t i = 0; i < hn::Lanes(d); ++i) {
      const Rot r = rotationBy(lanes[i]);
      cs[i] = r.c;
      ss[i] = r.s;
    }
    c = hn::Load(d, cs);
    s = hn::Load(d, ss);
  }
  const V<D> newC = hn::Sub(hn::Mul(*qc, c), hn::Mul(*qs, s));
  const V<D> newS = hn::Add(hn::Mul(*qs, c), hn::Mul(*qc, s));
  *qc = newC;
  *qs = newS;
}

// --- any instruction set: a gather or scatter per field ---

template <class D>
HWY_INLINE Bodies<D> loadBodies(D d, const double* states, const int32_t* stored) {
  const auto o = loadOffsets(d, stored);
  const auto read = hn::Max(o, hn::Not(o));  // ~o for the negative ones
  Bodies<D> b;
  b.vx = hn::GatherIndex(d, states + kVx, read);
  b.vy = hn::GatherIndex(d, states + kVy, read);
  b.w = hn::GatherIndex(d, states + kW, read);
  b.turned = hn::GatherIndex(d, states + kTurned, read);
  b.dx = hn::GatherIndex(d, states + kDx, read);
  b.dy = hn::GatherIndex(d, states + kDy, read);
  b.qc = hn::GatherIndex(d, states + kQc, read);
  b.qs = hn::GatherIndex(d, states + kQs, read);
  return b;
}

template <class D>
HWY_INLINE hn::Vec<hn::RebindToSigned<D>> writeOffsets(D d, const int32_t* stored, int32_t sink) {
  const hn::RebindToSigned<D> di;
  const auto o = loadOffsets(d, stored);
  return hn::IfThenElse(hn::Lt(o, hn::Zero(di)), hn::Set(di, sink), o);
}

/// Writes velocities back (the velocity kernels change nothing else).
template <class D>
HWY_INLINE void storeVelocities(D d, double* states, const int32_t* stored, int32_t sink,
                                const Bodies<D>& b) {
  const auto write = writeOffsets(d, stored, sink);
  hn::ScatterIndex(b.vx, d, states + kVx, write);
  hn::ScatterIndex(b.vy, d, states + kVy, write);
  hn::ScatterIndex(b.w, d, states + kW, write);
}

/// Writes poses back (the position pass changes nothing else).
template <class D>
HWY_INLINE void storePoses(D d, double* states, const int32_t* stored, int32_t sink,
                           const Bodies<D>& b) {
  const auto write = writeOffsets(d, stored, sink);
  hn::ScatterIndex(b.turned, d, states + kTurned, write);
  hn::ScatterIndex(b.dx, d, states + kDx, write);
  hn::ScatterIndex(b.dy, d, states + kDy, write);
  hn::ScatterIndex(b.qc, d, states + kQc, write);
  hn::ScatterIndex(b.qs, d, states + kQs, write);
}

// --- one lane (the overflow, whose lanes go one by one): plain loads and stores ---
// In a stack the overflow's next contact reads the body the last one wrote. A gather after a
// scatter to the same row waits for the scatter to reach the cache; a plain load takes the
// value from the store in flight. Same values, so the same results (stack20 spent two thirds
// of its step in the one-lane solve, with the gathers and scatters).

using D1 = hn::Simd<double, 1, 0>;

HWY_INLINE Bodies<D1> loadBodies(D1 d, const double* states, const int32_t* stored) {
  const double* row = states + readOffset(stored[0]);
  return {hn::Set(d, row[kVx]),     hn::Set(d, row[kVy]), hn::Set(d, row[kW]),
          hn::Set(d, row[kTurned]), hn::Set(d, row[kDx]), hn::Set(d, row[kDy]),
          hn::Set(d, row[kQc]),     hn::Set(d, row[kQs])};
}

HWY_INLINE void storeVelocities(D1 /*d*/, double* states, const int32_t* stored, int32_t sink,
                                const Bodies<D1>& b) {
  double* row = states + writeOffset(stored[0], sink);
  row[kVx] = hn::GetLane(b.vx);
  row[kVy] = hn::GetLane(b.vy);
  row[kW] = hn::GetLane(b.w);
}

HWY_INLINE void storePoses(D1 /*d*/, double* states, const int32_t* stored, int32_t sink,
                           const Bodies<D1>& b) {
  double* row = states + writeOffset(stored[0], sink);
  row[kTurned] = hn::GetLane(b.turned);
  row[kDx] = hn::GetLane(b.dx);
  row[kDy] = hn::GetLane(b.dy);
  row[kQc] = hn::GetLane(b.qc);
  row[kQs] = hn::GetLane(b.qs);
}

#if HWY_TARGET == HWY_AVX3 || HWY_TARGET == HWY_AVX3_DL
// --- AVX-512: a row is one register; an 8x8 transpose in three rounds of shuffles ---

using D8 = hn::Simd<double, 8, 0>;

// r[i] holds row i; afterwards r[f] holds field f of every row.
HWY_INLINE void transpose8(__m512d (&r)[8]) {
  __m512d t[8], u[8];
  for (int i = 0; i < 4; ++i) {  // pairs of rows: fields (0, 2, 4, 6) and (1, 3, 5, 7)
    t[2 * i] = _mm512_unpacklo_pd(r[2 * i], r[2 * i + 1]);
    t[2 * i + 1] = _mm512_unpackhi_pd(r[2 * i], r[2 * i + 1]);
  }
  for (int i = 0; i < 2; ++i) {  // 128-bit blocks: rows 0-3 (4-7) of fields (0 4), (2 6), ...
    u[4 * i + 0] = _mm512_shuffle_f64x2(t[4 * i + 0], t[4 * i + 2], 0x88);
    u[4 * i + 1] = _mm512_shuffle_f64x2(t[4 * i + 0], t[4 * i + 2], 0xDD);
    u[4 * i + 2] = _mm512_shuffle_f64x2(t[4 * i + 1], t[4 * i + 3], 0x88);
    u[4 * i + 3] = _mm512_shuffle_f64x2(t[4 * i + 1], t[4 * i + 3], 0xDD);
  }
  r[0] = _mm512_shuffle_f64x2(u[0], u[4], 0x88);
  r[4] = _mm512_shuffle_f64x2(u[0], u[4], 0xDD);
  r[2] = _mm512_shuffle_f64x2(u[1], u[5], 0x88);
  r[6] = _mm512_shuffle_f64x2(u[1], u[5], 0xDD);
  r[1] = _mm512_shuffle_f64x2(u[2], u[6], 0x88);
  r[5] = _mm512_shuffle_f64x2(u[2], u[6], 0xDD);
  r[3] = _mm512_shuffle_f64x2(u[3], u[7], 0x88);
  r[7] = _mm512_shuffle_f64x2(u[3], u[7], 0xDD);
}

HWY_INLINE Bodies<D8> loadBodies(D8 /*d*/, const double* states, const int32_t* stored) {
  __m512d r[8];
  for (int i = 0; i < 8; ++i) r[i] = _mm512_load_pd(states + readOffset(stored[i]));
  transpose8(r);
  return {{r[kVx]}, {r[kVy]}, {r[kW]}, {r[kTurned]}, {r[kDx]}, {r[kDy]}, {r[kQc]}, {r[kQs]}};
}

HWY_INLINE void storeRows(double* states, const int32_t* stored, int32_t sink, __m512d (&r)[8]) {
  transpose8(r);  // its own inverse
  for (int i = 0; i < 8; ++i) _mm512_store_pd(states + writeOffset(stored[i], sink), r[i]);
}

HWY_INLINE void storeVelocities(D8 /*d*/, double* states, const int32_t* stored, int32_t sink,
                                const Bodies<D8>& b) {
  __m512d r[8] = {b.vx.raw, b.vy.raw, b.w.raw,  b.turned.raw,
                  b.dx.raw, b.dy.raw, b.qc.raw, b.qs.raw};
  storeRows(states, stored, sink, r);
}

HWY_INLINE void storePoses(D8 d, double* states, const int32_t* stored, int32_t sink,
                           const Bodies<D8>& b) {
  storeVelocities(d, states, stored, sink, b);  // whole rows: the velocities as they were read
}

#elif HWY_TARGET == HWY_AVX2
// --- AVX2: a row is two registers; two 4x4 transposes ---

using D4 = hn::Simd<double, 4, 0>;

HWY_INLINE void transpose4(__m256d& a, __m256d& b, __m256d& c, __m256d& d) {
  const __m256d t0 = _mm256_unpacklo_pd(a, b), t1 = _mm256_unpackhi_pd(a, b);
  const __m256d t2 = _mm256_unpacklo_pd(c, d), t3 = _mm256_unpackhi_pd(c, d);
  a = _mm256_permute2f128_pd(t0, t2, 0x20);
  b = _mm256_permute2f128_pd(t1, t3, 0x20);
  c = _mm256_permute2f128_pd(t0, t2, 0x31);
  d = _mm256_permute2f128_pd(t1, t3, 0x31);
}

HWY_INLINE Bodies<D4> loadBodies(D4 /*d*/, const double* states, const int32_t* stored) {
  __m256d lo[4], hi[4];
  for (int i = 0; i < 4; ++i) {
    const double* row = states + readOffset(stored[i]);
    lo[i] = _mm256_load_pd(row);
    hi[i] = _mm256_load_pd(row + 4);
  }
  transpose4(lo[0], lo[1], lo[2], lo[3]);
  transpose4(hi[0], hi[1], hi[2], hi[3]);
  return {{lo[0]}, {lo[1]}, {lo[2]}, {lo[3]}, {hi[0]}, {hi[1]}, {hi[2]}, {hi[3]}};
}

HWY_INLINE void storeVelocities(D4 /*d*/, double* states, const int32_t* stored, int32_t sink,
                                const Bodies<D4>& b) {
  __m256d r0 = b.vx.raw, r1 = b.vy.raw, r2 = b.w.raw, r3 = b.turned.raw;
  transpose4(r0, r1, r2, r3);
  const __m256d rows[4] = {r0, r1, r2, r3};
  for (int i = 0; i < 4; ++i) _mm256_store_pd(states + writeOffset(stored[i], sink), rows[i]);
}

HWY_INLINE void storePoses(D4 /*d*/, double* states, const int32_t* stored, int32_t sink,
                           const Bodies<D4>& b) {
  __m256d lo[4] = {b.vx.raw, b.vy.raw, b.w.raw, b.turned.raw};
  __m256d hi[4] = {b.dx.raw, b.dy.raw, b.qc.raw, b.qs.raw};
  transpose4(lo[0], lo[1], lo[2], lo[3]);
  transpose4(hi[0], hi[1], hi[2], hi[3]);
  for (int i = 0; i < 4; ++i) {
    double* row = states + writeOffset(stored[i], sink);
    _mm256_store_pd(row, lo[i]);
    _mm256_store_pd(row + 4, hi[i]);
  }
}
#endif

}  // namespace HWY_NAMESPACE
}  // namespace impulse2d
HWY_AFTER_NAMESPACE();

#endif  // IMPULSE2D_BODY_LANES_INL_H_
