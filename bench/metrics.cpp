#include "metrics.hpp"

#include <impulse2d/collision.hpp>

#include <algorithm>
#include <cmath>

namespace impulse2d_bench {
namespace {

using impulse2d::Aabb;
using impulse2d::Rot;
using impulse2d::Transform;

constexpr double kGravity = 9.81;

Transform poseOf(const BodyState& s) { return Transform(s.position, Rot(s.angle)); }

bool finiteState(const BodyState& s) {
  return std::isfinite(s.position.x()) && std::isfinite(s.position.y()) && std::isfinite(s.angle) &&
         std::isfinite(s.velocity.x()) && std::isfinite(s.velocity.y()) &&
         std::isfinite(s.angularVelocity);
}

}  // namespace

ErrorMeter::ErrorMeter(const SceneSpec& scene) : scene_(scene) {
  const size_t n = scene.bodies.size();
  shapes_.resize(n);
  mass_.assign(n, 0.0);
  inertia_.assign(n, 0.0);
  initial_.resize(n);
  double totalMass = 0.0, lowest = INFINITY, highest = -INFINITY;
  for (size_t i = 0; i < n; ++i) {
    const BenchBody& body = scene.bodies[i];
    impulse2d::makeShape(toShapeDef(body.shape), &shapes_[i]);
    initial_[i].position = body.position;
    initial_[i].angle = body.angle;
    if (body.isStatic) continue;
    nominalMass(body.shape, &mass_[i], &inertia_[i]);
    totalMass += mass_[i];
    lowest = std::min(lowest, body.position.y());
    highest = std::max(highest, body.position.y());
  }
  // The scene's potential energy range: a drift of 1 means energy enough to lift everything by
  // the scene's height appeared (or, negative, vanished).
  energyScale_ = totalMass * kGravity * std::max(1.0, highest - lowest);
  startEnergy_ = energy(initial_);
  for (const BenchJoint& joint : scene.joints) {
    const BodyState& a = initial_[joint.bodyA];
    const BodyState& b = initial_[joint.bodyB];
    localAnchorA_.push_back(poseOf(a).applyInverse(joint.anchor));
    localAnchorB_.push_back(poseOf(b).applyInverse(joint.anchor));
    jointPairs_.emplace_back(std::min(joint.bodyA, joint.bodyB),
                             std::max(joint.bodyA, joint.bodyB));
  }
  std::sort(jointPairs_.begin(), jointPairs_.end());
}

double ErrorMeter::energy(const std::vector<BodyState>& states) const {
  double e = 0.0;
  for (size_t i = 0; i < states.size(); ++i) {
    e += mass_[i] * (kGravity * states[i].position.y() + 0.5 * states[i].velocity.squaredNorm()) +
         0.5 * inertia_[i] * states[i].angularVelocity * states[i].angularVelocity;
  }
  return e;
}

void ErrorMeter::sample(const std::vector<BodyState>& states) {
  const size_t n = states.size();
  for (const BodyState& s : states) figures_.finite &= finiteState(s);
  if (!figures_.finite) return;

  // Sweep and prune on x over the shapes' boxes, then the narrow phase on the scene geometry.
  boxes_.resize(n);
  order_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    boxes_[i] = impulse2d::computeAabb(shapes_[i], poseOf(states[i]));
    order_[i] = static_cast<int>(i);
  }
  std::sort(order_.begin(), order_.end(),
            [&](int x, int y) { return boxes_[x].lower.x() < boxes_[y].lower.x(); });
  for (size_t k = 0; k < n; ++k) {
    const int i = order_[k];
    for (size_t m = k + 1; m < n && boxes_[order_[m]].lower.x() <= boxes_[i].upper.x(); ++m) {
      const int j = order_[m];
      if (scene_.bodies[i].isStatic && scene_.bodies[j].isStatic) continue;
      if (!boxes_[i].overlaps(boxes_[j])) continue;
      const std::pair<int, int> pair(std::min(i, j), std::max(i, j));
      if (std::binary_search(jointPairs_.begin(), jointPairs_.end(), pair)) continue;
      const impulse2d::Manifold manifold = impulse2d::collideShapes(
          shapes_[i], poseOf(states[i]), shapes_[j], poseOf(states[j]), 0.0);
      for (int p = 0; p < manifold.pointCount; ++p) {
        const double depth = -manifold.points[p].separation;
        if (depth <= 0.0) continue;
        const double beyond = std::max(0.0, depth - kPenetrationSlop);
        penetrationSum_ += beyond;
        ++penetrationCount_;
        figures_.penetrationMax = std::max(figures_.penetrationMax, beyond);
      }
    }
  }

  for (size_t k = 0; k < scene_.joints.size(); ++k) {
    const BenchJoint& joint = scene_.joints[k];
    const Vec2 a = poseOf(states[joint.bodyA]).apply(localAnchorA_[k]);
    const Vec2 b = poseOf(states[joint.bodyB]).apply(localAnchorB_[k]);
    const double gap = (a - b).norm();
    gapSum_ += gap;
    ++gapCount_;
    figures_.jointGapMax = std::max(figures_.jointGapMax, gap);
  }
}

ErrorFigures ErrorMeter::finish(const std::vector<BodyState>& finalStates) {
  sample(finalStates);
  ErrorFigures out = figures_;
  if (!out.finite) {
    out.stood = false;
    return out;
  }
  out.penetrationMean = penetrationCount_ ? penetrationSum_ / penetrationCount_ : 0.0;
  out.jointGapMean = gapCount_ ? gapSum_ / gapCount_ : 0.0;
  out.energyDrift = (energy(finalStates) - startEnergy_) / energyScale_;
  bool inside = true;
  for (size_t i = 0; i < finalStates.size(); ++i) {
    if (scene_.bodies[i].isStatic) continue;
    const Vec2 move = finalStates[i].position - initial_[i].position;
    out.driftMax = std::max(out.driftMax, std::abs(move.x()));
    out.sinkMax = std::max(out.sinkMax, -move.y());
    const Vec2& p = finalStates[i].position;
    inside &= p.x() > scene_.boxLower.x() && p.x() < scene_.boxUpper.x() &&
              p.y() > scene_.boxLower.y() && p.y() < scene_.boxUpper.y();
  }
  switch (scene_.kind) {
    case SceneKind::Resting:
      out.stood = out.driftMax < scene_.tolerance;
      break;
    case SceneKind::Jointed:
      out.stood = out.jointGapMax < scene_.tolerance;
      break;
    case SceneKind::Falling:
      out.stood = inside;
      break;
  }
  return out;
}

}  // namespace impulse2d_bench
