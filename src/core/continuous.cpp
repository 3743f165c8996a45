// Continuous collision: a body that moved farther this step than the speculative margin is swept
// from its start pose to its end pose against what it must not pass through (static bodies, and
// every body for bullets); it is put back at the first time of impact and keeps its velocity, so
// the next step's speculative contact stops it at the surface.
#include <algorithm>

#include "distance.hpp"
#include "world_impl.hpp"

namespace impulse2d {

void WorldImpl::solveContinuous() {
  for (const FastBody& fast : fastBodies) {
    Body& body = bodies.items[fast.slot];
    Sweep sweep;
    sweep.localCenter = body.localCenter;
    sweep.c0 = fast.startCenter;
    sweep.c1 = body.center;
    sweep.a0 = fast.startAngle;
    sweep.a1 = body.angle;
    const Transform start = sweep.at(0.0);
    Aabb swept = computeAabb(body.shapes[0], start).united(computeAabb(body.shapes[0], body.xf));
    for (size_t i = 1; i < body.shapes.size(); ++i) {
      swept = swept.united(computeAabb(body.shapes[i], start))
                  .united(computeAabb(body.shapes[i], body.xf));
    }

    double impact = 1.0;
    tree.query(swept.inflated(def.linearSlop), [&](int proxy) {
      const int slot = static_cast<int>(tree.userData(proxy) >> 8);
      const int shapeIndex = static_cast<int>(tree.userData(proxy) & 0xff);
      if (slot == fast.slot) return;
      const Body& other = bodies.items[slot];
      if (other.type != BodyType::Static && !body.bullet) return;
      if (!shouldCollide(std::min(slot, fast.slot), std::max(slot, fast.slot))) return;
      // Others are taken where they stand now: static ones do not move, and a bullet only needs
      // to not skip over a body, wherever that body went this step.
      Sweep still;
      still.localCenter = other.localCenter;
      still.c0 = still.c1 = other.center;
      still.a0 = still.a1 = other.angle;
      const Shape& otherShape = other.shapes[shapeIndex];
      for (const Shape& shape : body.shapes) {
        const double gap = shapeDistance(shape, start, otherShape, other.xf).distance;
        if (gap >= def.speculativeDistance) {
          impact = std::min(impact, timeOfImpact(shape, sweep, otherShape, still, def.linearSlop));
        } else {
          // Close already: this step's speculative contact stops the surfaces meeting, but a
          // turn or a glancing hit may still carry the body in. At least its centre of mass
          // must not pass into the other shape.
          const double enter = raycastShape(otherShape, other.xf, sweep.c0, sweep.c1);
          if (enter > 0.0 && enter <= 1.0) impact = std::min(impact, enter);
        }
      }
    });
    if (impact >= 1.0) continue;
    body.center = (1.0 - impact) * sweep.c0 + impact * sweep.c1;
    body.angle = (1.0 - impact) * sweep.a0 + impact * sweep.a1;
    syncTransform(body);
  }
}

}  // namespace impulse2d
