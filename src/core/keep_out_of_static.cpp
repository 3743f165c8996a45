// Stage 9 of World::step, the last to move bodies: what the solve drove deep into a static body
// comes back out.
//
//           n (the contact's normal when the step began, out of the static body)
//           ^
//        +--|--+
//   =====|=====|=======  static surface: its farthest point along n
//        |#####| depth   the body's nearest point along n is this far below it
//        +-----+
//
// Contacts and the position passes hold a body against a static one when they can; a joint set
// that cannot be met (a loop that does not close, a pin dragged by a kinematic body) or a body
// squeezed by others may still push it in, a little more every step, until it comes out on the
// far side (issue 26: a welded loop carried through a 2 m ground to y = -650 m). So a body deeper
// than a quarter of the thinner of the two shapes, measured along the normal the contact had as
// the step began (a body past the middle of a thin wall is still on its first side), is moved
// back out to one slop deep, and stops moving into the wall. A welded cluster moves whole. No
// energy is added: the move is a projection, and only the velocity into the wall is removed.
#include <impulse2d/shape.hpp>

#include <algorithm>
#include <limits>

#include "world_impl.hpp"

namespace impulse2d {
namespace {

// The farthest any point of the shape at xf reaches along d.
double reachAlong(const Shape& shape, const Transform& xf, const Vec2& d) {
  if (shape.type == ShapeType::Circle) {
    return d.dot(xf.apply(shape.circle.center)) + shape.circle.radius;
  }
  double farthest = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < shape.polygon.count; ++i) {
    farthest = std::max(farthest, d.dot(xf.apply(shape.polygon.vertices[i])));
  }
  return farthest;
}

// Moves the bodies by `push` and takes from each the velocity their common centre of mass has
// into the wall (along -n): the same for each, so a welded cluster keeps moving rigidly.
void moveOut(std::vector<Body>& bodies, const int* begin, const int* end, const Vec2& push,
             const Vec2& n) {
  double mass = 0.0, into = 0.0;
  for (const int* slot = begin; slot != end; ++slot) {
    Body& body = bodies[*slot];
    body.center += push;
    syncTransform(body);
    mass += body.mass;
    into += body.mass * body.linearVelocity.dot(n);
  }
  into /= mass;
  if (!(into < 0.0)) return;
  for (const int* slot = begin; slot != end; ++slot) bodies[*slot].linearVelocity -= into * n;
}

}  // namespace

void WorldImpl::keepOutOfStatic() {
  for (const Contact& contact : contacts) {
    if (contact.manifold.pointCount == 0) continue;
    const bool staticA = bodies.items[contact.bodyA].type == BodyType::Static;
    const bool staticB = bodies.items[contact.bodyB].type == BodyType::Static;
    if (staticA == staticB) continue;
    const int slot = staticA ? contact.bodyB : contact.bodyA;
    Body& body = bodies.items[slot];
    if (!isActive(body)) continue;
    const Body& wall = bodies.items[staticA ? contact.bodyA : contact.bodyB];
    const Shape& wallShape = wall.shapes[staticA ? contact.shapeA : contact.shapeB];
    const Shape& shape = body.shapes[staticA ? contact.shapeB : contact.shapeA];
    // The manifold's normal points from A to B.
    const Vec2 n = staticA ? contact.manifold.normal : Vec2(-contact.manifold.normal);
    const double depth = reachAlong(wallShape, wall.xf, n) + reachAlong(shape, body.xf, -n);
    const double allowed =
        std::max(2.0 * def.linearSlop, 0.25 * std::min(innerRadius(wallShape), body.minExtent));
    if (!(depth > allowed)) continue;
    const Vec2 push = (depth - def.linearSlop) * n;
    const int cluster = weldClusters.clusterOf(slot);
    if (cluster < 0) {
      moveOut(bodies.items, &slot, &slot + 1, push, n);
    } else {
      moveOut(bodies.items, weldClusters.membersBegin(cluster), weldClusters.membersEnd(cluster),
              push, n);
    }
  }
}

}  // namespace impulse2d
