#include "contact.hpp"

#include <cmath>

namespace impulse2d {

double mixFriction(double a, double b) { return std::sqrt(a * b); }
double mixRestitution(double a, double b) { return a > b ? a : b; }

namespace {

// B's frame seen from A's.
Transform relativeOf(const Body& a, const Body& b) { return a.xf.inverseTimes(b.xf); }

// Whether B has moved less than kFollowDistance at any of its points, relative to A, since
// `base`: by |dp| plus the turn times B's reach from its origin.
bool barelyMoved(const Transform& now, const Transform& base, const Body& b) {
  const double dx = now.p.x() - base.p.x(), dy = now.p.y() - base.p.y();
  const double turn = std::abs(base.q.c * now.q.s - base.q.s * now.q.c);  // sin of the turn
  const double reach = b.maxExtent + b.localCenter.norm();
  return std::sqrt(dx * dx + dy * dy) + turn * reach <= kFollowDistance;
}

// Keeps the computed manifold in the bodies' frames: each point's two ends on the surfaces.
void remember(Contact& contact, const Body& a, const Body& b) {
  const Manifold& m = contact.manifold;
  contact.following = true;
  contact.baseRelative = relativeOf(a, b);
  contact.localNormal = a.xf.q.applyInverse(m.normal);
  for (int i = 0; i < m.pointCount; ++i) {
    const ManifoldPoint& p = m.points[i];
    const double hx = 0.5 * p.separation * m.normal.x(), hy = 0.5 * p.separation * m.normal.y();
    contact.localA[i] = a.xf.applyInverse(Vec2(p.point.x() - hx, p.point.y() - hy));
    contact.localB[i] = b.xf.applyInverse(Vec2(p.point.x() + hx, p.point.y() + hy));
  }
}

// The remembered points where the bodies are now.
void follow(Contact& contact, const Body& a, const Body& b) {
  Manifold& m = contact.manifold;
  m.normal = a.xf.q.apply(contact.localNormal);
  const double nx = m.normal.x(), ny = m.normal.y();
  for (int i = 0; i < m.pointCount; ++i) {
    const Vec2 onA = a.xf.apply(contact.localA[i]), onB = b.xf.apply(contact.localB[i]);
    const double ax = onA.x(), ay = onA.y(), bx = onB.x(), by = onB.y();
    m.points[i].separation = nx * (bx - ax) + ny * (by - ay);
    m.points[i].point = Vec2(0.5 * (ax + bx), 0.5 * (ay + by));
  }
}

}  // namespace

void updateContact(Contact& contact, const Body& a, const Body& b, double speculativeDistance,
                   double timeStep, bool warmStarting) {
  if (contact.following && barelyMoved(relativeOf(a, b), contact.baseRelative, b)) {
    follow(contact, a, b);  // the same points: the impulses stay theirs
    return;
  }
  const double closing = (b.linearVelocity - a.linearVelocity).norm() +
                         std::abs(a.angularVelocity) * a.maxExtent +
                         std::abs(b.angularVelocity) * b.maxExtent;
  speculativeDistance += timeStep * closing;
  const Manifold old = contact.manifold;
  const double oldNormal[2] = {contact.normalImpulse[0], contact.normalImpulse[1]};
  const double oldTangent[2] = {contact.tangentImpulse[0], contact.tangentImpulse[1]};

  const Shape& shapeA = a.shapes[contact.shapeA];
  const Shape& shapeB = b.shapes[contact.shapeB];
  // A filtered pair of shapes on two bodies that may otherwise touch never gets a point.
  contact.manifold = filtersAllowContact(shapeA.filter, shapeB.filter)
                         ? collideShapes(shapeA, a.xf, shapeB, b.xf, speculativeDistance)
                         : Manifold();
  for (int i = 0; i < contact.manifold.pointCount; ++i) {
    contact.normalImpulse[i] = 0.0;
    contact.tangentImpulse[i] = 0.0;
    if (!warmStarting) continue;
    for (int j = 0; j < old.pointCount; ++j) {
      if (old.points[j].id == contact.manifold.points[i].id) {
        contact.normalImpulse[i] = oldNormal[j];
        contact.tangentImpulse[i] = oldTangent[j];
        break;
      }
    }
  }
  for (int i = contact.manifold.pointCount; i < 2; ++i) {
    contact.normalImpulse[i] = 0.0;
    contact.tangentImpulse[i] = 0.0;
  }
  remember(contact, a, b);
}

}  // namespace impulse2d
