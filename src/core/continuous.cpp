// Continuous collision: a body that moved farther this step than the speculative margin is swept
// from its start pose to its end pose against what it must not pass through (static bodies, and
// every body for bullets); it is put back at the first time of impact and keeps its velocity, so
// the next step's speculative contact stops it at the surface.
#include <algorithm>

#include "distance.hpp"
#include "world_impl.hpp"

namespace impulse2d {
namespace {

// Samples of a sweep that starts in contact: a body turning this far in a step (up to a few
// radians for a spinning rod) is checked every eighth of it.
constexpr int kCloseSweepSamples = 8;
// Fast bodies per block of the parallel sweeps: a sweep that meets a static shape costs tens of
// microseconds, one that meets nothing well under one.
constexpr int kFastBodiesPerBlock = 32;

// The deepest overlap of the two shapes at those poses (0 when apart).
double overlapDepth(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB) {
  const Manifold m = collideShapes(a, xfA, b, xfB, 0.0);
  double deepest = 0.0;
  for (int i = 0; i < m.pointCount; ++i) deepest = std::max(deepest, -m.points[i].separation);
  return deepest;
}

// For a sweep that starts touching the other shape: the latest t before any part of the shape
// (not only the point in contact, which the speculative contact holds) has sunk deeper than
// `allowed`, or 1 when it never does. Overlap is measured along the axis of least penetration,
// which for a thin shape flips to its far side past the middle: `allowed` stays well below that.
double turnIntoContact(const Shape& shape, const Sweep& sweep, const Shape& other,
                       const Transform& otherXf, double allowed, double slop) {
  // A sweep that starts about as deep as `allowed` (a body resting a slop or two deep, turning)
  // may sink a slop deeper than its start: measured against `allowed` alone it would be put back
  // at its start pose every step, frozen with its velocity while the bodies jointed to it moved
  // on (a ragdoll's spinning forearm on the ground, v3_rain, opened its joints by 0.7 m).
  allowed = std::max(allowed, overlapDepth(shape, sweep.at(0.0), other, otherXf) + slop);
  double good = 0.0;
  for (int k = 1; k <= kCloseSweepSamples; ++k) {
    const double t = static_cast<double>(k) / kCloseSweepSamples;
    if (overlapDepth(shape, sweep.at(t), other, otherXf) <= allowed) {
      good = t;
      continue;
    }
    double bad = t;
    for (int i = 0; i < 10; ++i) {  // bisect down to 1/8000 of the step
      const double mid = 0.5 * (good + bad);
      (overlapDepth(shape, sweep.at(mid), other, otherXf) <= allowed ? good : bad) = mid;
    }
    return good;
  }
  return 1.0;
}

// A body where it stands now, as a sweep that does not move.
Sweep standingStill(const Body& body) {
  Sweep still;
  still.localCenter = body.localCenter;
  still.c0 = still.c1 = body.center;
  still.a0 = still.a1 = body.angle;
  return still;
}

}  // namespace

Sweep WorldImpl::sweepOf(const FastBody& fast) const {
  const Body& body = bodies.items[fast.slot];
  Sweep sweep;
  sweep.localCenter = body.localCenter;
  sweep.c0 = fast.startCenter;
  sweep.c1 = body.center;
  sweep.a0 = fast.startAngle;
  sweep.a1 = body.angle;
  return sweep;
}

double WorldImpl::firstImpact(const FastBody& fast, std::vector<int>& stack) const {
  const Body& body = bodies.items[fast.slot];
  const Sweep sweep = sweepOf(fast);
  const Transform start = sweep.at(0.0);
  Aabb swept = computeAabb(body.shapes[0], start).united(computeAabb(body.shapes[0], body.xf));
  for (size_t i = 1; i < body.shapes.size(); ++i) {
    swept = swept.united(computeAabb(body.shapes[i], start))
                .united(computeAabb(body.shapes[i], body.xf));
  }

  double impact = 1.0;  // the earliest over the candidates: the same in any order
  const DynamicTree& candidates = body.bullet ? tree : staticTree;
  candidates.query(swept.inflated(def.linearSlop), stack, [&](int proxy) {
    const int slot = proxySlot(candidates.userData(proxy));
    const int shapeIndex = proxyShape(candidates.userData(proxy));
    if (slot == fast.slot) return;
    const Body& other = bodies.items[slot];
    if (other.type != BodyType::Static && !body.bullet) return;
    if (!shouldCollide(std::min(slot, fast.slot), std::max(slot, fast.slot))) return;
    // Others are taken where they stand now: static ones do not move, and a bullet only needs
    // to not skip over a body, wherever that body went this step.
    const Sweep still = standingStill(other);
    const Shape& otherShape = other.shapes[shapeIndex];
    for (const Shape& shape : body.shapes) {
      if (!filtersAllowContact(shape.filter, otherShape.filter)) continue;
      const double gap = shapeDistance(shape, start, otherShape, other.xf).distance;
      if (gap >= def.speculativeDistance) {
        impact = std::min(impact, timeOfImpact(shape, sweep, otherShape, still, def.linearSlop));
      } else {
        // Close already: this step's speculative contact holds the point in contact, but a
        // turn or a glancing hit may still carry another part of the body in, and its centre
        // of mass must never pass into the other shape.
        const double enter = raycastShape(otherShape, other.xf, sweep.c0, sweep.c1);
        if (enter > 0.0 && enter <= 1.0) impact = std::min(impact, enter);
        const double allowed = std::max(2.0 * def.linearSlop,
                                        0.25 * std::min(innerRadius(otherShape), body.minExtent));
        impact = std::min(
            impact, turnIntoContact(shape, sweep, otherShape, other.xf, allowed, def.linearSlop));
      }
    }
  });
  return impact;
}

void WorldImpl::solveContinuous() {
  const StageClock clock(stage(&StepProfile::continuous));
  // In parallel: the impacts of the bodies that are not bullets. They sweep against static
  // shapes only, which nothing here moves, so no order changes them (v3_rain sweeps thousands of
  // falling ragdoll parts a step).
  std::vector<double>& impacts = scratch.fastImpacts;
  impacts.assign(fastBodies.size(), 1.0);
  const int count = static_cast<int>(fastBodies.size());
  scratch.queryStacks.resize(static_cast<size_t>(stepWorkers.threads()));
  stepWorkers.stage(
      (count + kFastBodiesPerBlock - 1) / kFastBodiesPerBlock, [&](int block, int worker) {
        const int end = std::min(count, (block + 1) * kFastBodiesPerBlock);
        for (int k = block * kFastBodiesPerBlock; k < end; ++k) {
          const FastBody& fast = fastBodies[static_cast<size_t>(k)];
          if (bodies.items[fast.slot].bullet) continue;
          impacts[static_cast<size_t>(k)] =
              firstImpact(fast, scratch.queryStacks[static_cast<size_t>(worker)].value);
        }
      });
  // In order: a bullet's impact, which sees the bodies before it where they were put back, and
  // each body put back at its first impact.
  for (size_t k = 0; k < fastBodies.size(); ++k) {
    const FastBody& fast = fastBodies[k];
    Body& body = bodies.items[fast.slot];
    const double impact =
        body.bullet ? firstImpact(fast, scratch.queryStacks[0].value) : impacts[k];
    if (fast.cluster >= 0) {
      double& first = fastClusters[fast.cluster].impact;
      first = std::min(first, impact);
      continue;
    }
    if (impact >= 1.0) continue;
    const Sweep sweep = sweepOf(fast);
    body.center = (1.0 - impact) * sweep.c0 + impact * sweep.c1;
    body.angle = (1.0 - impact) * sweep.a0 + impact * sweep.a1;
    syncTransform(body);
  }
  // A welded cluster stops whole at the first impact of any member: each member where the
  // cluster's rigid motion had carried it by then.
  for (const FastBody& fast : fastBodies) {
    if (fast.cluster < 0 || fastClusters[fast.cluster].impact >= 1.0) continue;
    const FastCluster& cluster = fastClusters[fast.cluster];
    const double t = cluster.impact;
    Body& body = bodies.items[fast.slot];
    body.center = cluster.pivot0 + t * cluster.move +
                  Rot(t * cluster.turn).apply(Vec2(fast.startCenter - cluster.pivot0));
    body.angle = fast.startAngle + t * cluster.turn;
    syncTransform(body);
  }
}

}  // namespace impulse2d
