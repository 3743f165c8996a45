// Small 2D math vocabulary on top of Eigen: vectors, rotations, rigid transforms.
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace impulse2d {

using Vec2 = Eigen::Vector2d;

constexpr double kPi = 3.14159265358979323846;

/// 2D cross product: the z component of (a, 0) x (b, 0).
inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
/// (0, 0, s) x (v, 0): the velocity of point v about an angular rate s.
inline Vec2 cross(double s, const Vec2& v) { return Vec2(-s * v.y(), s * v.x()); }
/// (v, 0) x (0, 0, s).
inline Vec2 cross(const Vec2& v, double s) { return Vec2(s * v.y(), -s * v.x()); }
/// The left-hand perpendicular (rotated +90 degrees).
inline Vec2 perp(const Vec2& v) { return Vec2(-v.y(), v.x()); }

/// A rotation stored as cosine and sine, so composing and applying it costs no trig.
struct Rot {
  double c = 1.0;
  double s = 0.0;

  Rot() = default;
  explicit Rot(double angle) : c(std::cos(angle)), s(std::sin(angle)) {}
  static Rot fromCosSin(double cosine, double sine) {
    Rot r;
    r.c = cosine;
    r.s = sine;
    return r;
  }
  double angle() const { return std::atan2(s, c); }
  Vec2 apply(const Vec2& v) const { return Vec2(c * v.x() - s * v.y(), s * v.x() + c * v.y()); }
  Vec2 applyInverse(const Vec2& v) const {
    return Vec2(c * v.x() + s * v.y(), -s * v.x() + c * v.y());
  }
  Rot operator*(const Rot& r) const {  // this then r, i.e. angle() + r.angle()
    Rot out;
    out.c = c * r.c - s * r.s;
    out.s = s * r.c + c * r.s;
    return out;
  }
  Rot inverseTimes(const Rot& r) const {  // r.angle() - angle()
    Rot out;
    out.c = c * r.c + s * r.s;
    out.s = c * r.s - s * r.c;
    return out;
  }
};

/// A rigid transform: p + q * v maps a local point v into the parent frame.
struct Transform {
  Vec2 p = Vec2::Zero();
  Rot q;

  Transform() = default;
  Transform(const Vec2& position, const Rot& rotation) : p(position), q(rotation) {}
  // Written in scalars, with the same operations in the same order as p + q.apply(v): a Vec2
  // built from two scalars and read back at once as one 16-byte vector (as in p + ...) stalls
  // the processor's store forwarding, which cost more than the transform itself
  // (docs/benchmarks.md, "Profile and optimisations").
  Vec2 apply(const Vec2& v) const {
    return Vec2(p.x() + (q.c * v.x() - q.s * v.y()), p.y() + (q.s * v.x() + q.c * v.y()));
  }
  Vec2 applyInverse(const Vec2& v) const {
    const double dx = v.x() - p.x(), dy = v.y() - p.y();
    return Vec2(q.c * dx + q.s * dy, -q.s * dx + q.c * dy);
  }
  /// inverse(this) * other: `other` expressed in this frame.
  Transform inverseTimes(const Transform& other) const {
    return Transform(applyInverse(other.p), q.inverseTimes(other.q));
  }
};

/// An axis-aligned bounding box.
struct Aabb {
  Vec2 lower = Vec2::Zero();
  Vec2 upper = Vec2::Zero();

  bool overlaps(const Aabb& o) const {
    return !(o.lower.x() > upper.x() || o.lower.y() > upper.y() || lower.x() > o.upper.x() ||
             lower.y() > o.upper.y());
  }
  bool contains(const Aabb& o) const {
    return lower.x() <= o.lower.x() && lower.y() <= o.lower.y() && o.upper.x() <= upper.x() &&
           o.upper.y() <= upper.y();
  }
  Aabb united(const Aabb& o) const {
    return Aabb{lower.cwiseMin(o.lower), upper.cwiseMax(o.upper)};
  }
  double perimeter() const { return 2.0 * ((upper.x() - lower.x()) + (upper.y() - lower.y())); }
  Aabb inflated(double margin) const {
    return Aabb{lower - Vec2::Constant(margin), upper + Vec2::Constant(margin)};
  }
};

inline bool isFinite(const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

}  // namespace impulse2d
