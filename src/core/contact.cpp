#include "contact.hpp"

#include <cmath>

namespace impulse2d {

double mixFriction(double a, double b) { return std::sqrt(a * b); }
double mixRestitution(double a, double b) { return a > b ? a : b; }

void updateContact(Contact& contact, const Body& a, const Body& b, double speculativeDistance,
                   bool warmStarting) {
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
}

}  // namespace impulse2d
