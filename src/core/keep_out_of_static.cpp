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
#include <utility>
#include <vector>

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
  const StageClock clock(stage(&StepProfile::continuous));
  // The deep ones first, found in parallel blocks of contacts (nothing moves yet), then by body
  // (in slot order, then contact order: deterministic).
  const int count = static_cast<int>(contacts.size());
  scratch.deepStaticOfBlock.resize(static_cast<size_t>(count + kContactsPerBlock - 1) /
                                   kContactsPerBlock);
  stepWorkers.forRanges(count, kContactsPerBlock, [&](int begin, int end, int) {
    std::vector<DeepStatic>& found =
        scratch.deepStaticOfBlock[static_cast<size_t>(begin / kContactsPerBlock)].value;
    found.clear();
    for (size_t i = static_cast<size_t>(begin); i < static_cast<size_t>(end); ++i) {
      const Contact& contact = contacts[i];
      // Static is told by movableIndex (a contact's bodies are alive): most contacts of a pile
      // are between two dynamic bodies, and are passed over without reading the bodies.
      const bool staticA = !isMovable(contact.bodyA), staticB = !isMovable(contact.bodyB);
      if (staticA == staticB || contact.manifold.pointCount == 0) continue;
      const int slot = staticA ? contact.bodyB : contact.bodyA;
      if (!isActive(bodies.items[slot])) continue;
      // The manifold's normal points from A to B.
      const Vec2 n = staticA ? contact.manifold.normal : Vec2(-contact.manifold.normal);
      if (staticDepth(contact, n) > allowedDepth(contact)) {
        found.push_back({slot, static_cast<int>(i), n});
      }
    }
  });
  std::vector<DeepStatic>& deep = scratch.deepStatic;
  deep.clear();
  for (const auto& block : scratch.deepStaticOfBlock) {
    deep.insert(deep.end(), block.value.begin(), block.value.end());
  }
  scratch.clusterPush.assign(static_cast<size_t>(weldClusters.count()), Vec2::Zero());
  std::sort(deep.begin(), deep.end(), [](const DeepStatic& x, const DeepStatic& y) {
    return x.slot != y.slot ? x.slot < y.slot : x.contact < y.contact;
  });
  for (size_t first = 0; first < deep.size();) {
    size_t end = first + 1;
    while (end < deep.size() && deep[end].slot == deep[first].slot) ++end;
    if (!escapeSeam(deep.data() + first, deep.data() + end)) {
      // One push per contact, each measured where the last one left the body.
      for (size_t k = first; k < end; ++k) {
        const Contact& contact = contacts[static_cast<size_t>(deep[k].contact)];
        const double depth = staticDepth(contact, deep[k].n);
        if (depth > allowedDepth(contact)) {
          pushOut(deep[k].slot, (depth - def.linearSlop) * deep[k].n, deep[k].n);
        }
      }
    }
    first = end;
  }
}

// The static shape's and the body's shape of a contact between a static and a dynamic body.
std::pair<const Shape*, const Shape*> WorldImpl::staticPair(const Contact& contact) const {
  const bool staticA = bodies.items[contact.bodyA].type == BodyType::Static;
  const Body& wall = bodies.items[staticA ? contact.bodyA : contact.bodyB];
  const Body& body = bodies.items[staticA ? contact.bodyB : contact.bodyA];
  return {&wall.shapes[staticA ? contact.shapeA : contact.shapeB],
          &body.shapes[staticA ? contact.shapeB : contact.shapeA]};
}

double WorldImpl::staticDepth(const Contact& contact, const Vec2& n) const {
  const bool staticA = bodies.items[contact.bodyA].type == BodyType::Static;
  const Body& wall = bodies.items[staticA ? contact.bodyA : contact.bodyB];
  const Body& body = bodies.items[staticA ? contact.bodyB : contact.bodyA];
  const auto [wallShape, shape] = staticPair(contact);
  return reachAlong(*wallShape, wall.xf, n) + reachAlong(*shape, body.xf, -n);
}

double WorldImpl::allowedDepth(const Contact& contact) const {
  const bool staticA = bodies.items[contact.bodyA].type == BodyType::Static;
  const Body& body = bodies.items[staticA ? contact.bodyB : contact.bodyA];
  return std::max(2.0 * def.linearSlop,
                  0.25 * std::min(innerRadius(*staticPair(contact).first), body.minExtent));
}

void WorldImpl::pushOut(int slot, const Vec2& push, const Vec2& n) {
  const int cluster = weldClusters.clusterOf(slot);
  // A welded cluster moves whole, unless this step already pushed it the other way: then it is
  // jammed (a rigid assembly taller or wider than the space it is in, between the ground and
  // the ceiling), and the member alone goes out. That opens its weld, which leaves the cluster
  // until it closes again (weld_clusters.cpp) and is solved as a joint meanwhile: the welds give,
  // not the walls.
  if (cluster >= 0) {
    if (scratch.clusterPush.size() < static_cast<size_t>(weldClusters.count())) {
      scratch.clusterPush.resize(static_cast<size_t>(weldClusters.count()), Vec2::Zero());
    }
    Vec2& first = scratch.clusterPush[static_cast<size_t>(cluster)];
    if (first.isZero()) first = n;
    if (first.dot(n) >= -0.3) {
      moveOut(bodies.items, weldClusters.membersBegin(cluster), weldClusters.membersEnd(cluster),
              push, n);
      return;
    }
  }
  moveOut(bodies.items, &slot, &slot + 1, push, n);
}

// Where two static boxes meet (a wall standing on the ground), their faces inside the union
// point at each other:
//
//      | wall |
//      |      |                 a body pushed into the corner below the wall's foot is told
//      |  [#] |  <- n = down    "up" by the ground and "down" by the wall: pushed along each
//   ===|==[#]=|============     in turn it stays, and creeps along the seam, out of the far
//      ground    n = up         side. Out of the seam it goes along the seam instead, the
//                               shorter way out of one of the two.
//
// Returns false (nothing done) when the body is in no seam, or when the way out along it is
// longer than twice its size (a long rigid assembly jammed between two walls far apart:
// then the pushes along the normals are the best there is).
bool WorldImpl::escapeSeam(const DeepStatic* begin, const DeepStatic* end) {
  for (const DeepStatic* i = begin; i != end; ++i) {
    for (const DeepStatic* j = i + 1; j != end; ++j) {
      if (!(i->n.dot(j->n) < -0.9)) continue;  // faces that meet (not a corner's vertex)
      const Contact& ci = contacts[static_cast<size_t>(i->contact)];
      const Contact& cj = contacts[static_cast<size_t>(j->contact)];
      const Vec2 along = perp(i->n);
      double best = std::numeric_limits<double>::infinity();
      Vec2 way = Vec2::Zero();
      for (const Vec2& d : {along, Vec2(-along)}) {
        const double out = std::min(staticDepth(ci, d), staticDepth(cj, d));
        if (out < best) best = out, way = d;
      }
      const Body& body = bodies.items[i->slot];
      if (!(best <= std::max(2.0 * body.maxExtent, 0.25))) return false;
      pushOut(i->slot, (best + def.linearSlop) * way, way);
      return true;
    }
  }
  return false;
}

}  // namespace impulse2d
