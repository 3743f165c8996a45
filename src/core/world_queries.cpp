// World's queries: ray casts and the bodies at a point or in a box. The AABB tree narrows the
// shapes down; ray_cast.cpp tests each candidate exactly; ray_fan.cpp casts fans.
#include "world_rays.hpp"

#include <algorithm>

namespace impulse2d {

RayHit castRay(const WorldImpl& w, const Vec2& from, const Vec2& to, const RayFilter& filter) {
  RayHit best;
  w.tree.rayCast(from, to, 1.0, [&](int proxy, double maxFraction) {
    const int slot = proxySlot(w.tree.userData(proxy)), shape = proxyShape(w.tree.userData(proxy));
    const Body& body = w.bodies.items[slot];
    if (filter.ignores(body.id)) return maxFraction;
    const ShapeRayHit hit = rayCastShape(body.shapes[shape], body.xf, from, to);
    if (!hit.hit() || hit.fraction > maxFraction || !nearerHit(hit.fraction, slot, shape, best)) {
      return maxFraction;
    }
    best.body = body.id;
    best.shape = shape;
    best.fraction = hit.fraction;
    best.normal = hit.normal;
    best.point = from + hit.fraction * (to - from);
    return hit.fraction;
  });
  return best;
}

namespace {

// The bodies of the shapes `accept` takes among those whose fat boxes overlap `box`, each once,
// in slot order.
template <class Accept>
std::vector<BodyId> bodiesIn(const WorldImpl& w, const Aabb& box, Accept&& accept) {
  std::vector<int> slots;
  w.tree.query(box, [&](int proxy) {
    const int slot = proxySlot(w.tree.userData(proxy));
    const Body& body = w.bodies.items[slot];
    if (accept(body.shapes[proxyShape(w.tree.userData(proxy))], body.xf)) slots.push_back(slot);
  });
  std::sort(slots.begin(), slots.end());
  slots.erase(std::unique(slots.begin(), slots.end()), slots.end());
  std::vector<BodyId> ids;
  ids.reserve(slots.size());
  for (const int slot : slots) ids.push_back(w.bodies.items[slot].id);
  return ids;
}

}  // namespace

RayHit World::rayCast(const Vec2& from, const Vec2& to, const RayFilter& filter) const {
  if (!isFinite(from) || !isFinite(to)) return RayHit();
  return castRay(*impl_, from, to, filter);
}

void World::rayCastFan(const Vec2& origin, const std::vector<Vec2>& ends, const RayFilter& filter,
                       std::vector<RayHit>* hits) const {
  if (!isFinite(origin)) {
    hits->assign(ends.size(), RayHit());
    return;
  }
  castFan(*impl_, origin, ends, filter, hits);
}

std::vector<BodyId> World::queryPoint(const Vec2& point) const {
  if (!isFinite(point)) return {};
  return bodiesIn(*impl_, Aabb{point, point}, [&](const Shape& shape, const Transform& xf) {
    return shapeContains(shape, xf, point);
  });
}

std::vector<BodyId> World::queryAabb(const Aabb& box) const {
  if (!isFinite(box.lower) || !isFinite(box.upper) || box.lower.x() > box.upper.x() ||
      box.lower.y() > box.upper.y()) {
    return {};
  }
  return bodiesIn(*impl_, box, [&](const Shape& shape, const Transform& xf) {
    return shapeOverlaps(shape, xf, box);
  });
}

}  // namespace impulse2d
