#include "metrics.hpp"

#include <impulse2d/collision.hpp>

#include <algorithm>
#include <cmath>

namespace impulse2d_bench {
namespace {

using impulse2d::Aabb;
using impulse2d::Rot;
using impulse2d::Transform;

// Every body's origin is its centre of mass (centreOnMass), which is what engines report.
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
  double totalMass = 0.0, lowest = INFINITY, highest = -INFINITY, kinetic = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const BenchBody& body = scene.bodies[i];
    for (const BenchShape& shape : body.shapes) {
      shapes_[i].emplace_back();
      impulse2d::makeShape(toShapeDef(shape), &shapes_[i].back());
    }
    initial_[i].position = body.position;
    initial_[i].angle = body.angle;
    initial_[i].velocity = body.velocity;
    initial_[i].alive = body.group < 0;
    if (body.isDriven()) continue;
    nominalMass(body, &mass_[i], &inertia_[i]);
    if (body.group >= 0) continue;
    totalMass += mass_[i];
    kinetic += 0.5 * mass_[i] * body.velocity.squaredNorm();
    lowest = std::min(lowest, body.position.y());
    highest = std::max(highest, body.position.y());
  }
  // The scene's energy range: a drift of 1 means energy enough to lift everything by the scene's
  // height appeared (or, negative, vanished), plus what it started moving with (smash).
  energyScale_ = totalMass * scene.gravity.norm() * std::max(1.0, highest - lowest) + kinetic;
  startEnergy_ = energy(initial_);
  startMomentum_ = momentum(initial_);
  figures_.energyMeaningful = scene.events.empty();
  figures_.energyMeaningful &= !scene.hasMovingKinematic();  // it does work
  for (const BenchJoint& joint : scene.joints) {
    figures_.energyMeaningful &= !joint.enableMotor;  // a motor adds energy; friction takes it
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
    if (!states[i].alive) continue;
    e += mass_[i] *
             (-scene_.gravity.dot(states[i].position) + 0.5 * states[i].velocity.squaredNorm()) +
         0.5 * inertia_[i] * states[i].angularVelocity * states[i].angularVelocity;
  }
  return e;
}

Vec2 ErrorMeter::momentum(const std::vector<BodyState>& states) const {
  Vec2 p = Vec2::Zero();
  for (size_t i = 0; i < states.size(); ++i) {
    if (states[i].alive) p += mass_[i] * states[i].velocity;
  }
  return p;
}

bool ErrorMeter::inside(const std::vector<BodyState>& states, size_t body) const {
  const Container& c = scene_.container;
  const Vec2& p = states[body].position;
  switch (c.kind) {
    case Container::Kind::Box:
      return p.x() > c.lower.x() && p.x() < c.upper.x() && p.y() > c.lower.y() &&
             p.y() < c.upper.y();
    case Container::Kind::Disc:
      return (p - c.center).norm() < c.radius;
    case Container::Kind::BodyBox: {
      if (static_cast<int>(body) == c.body) return true;
      const Vec2 local = poseOf(states[c.body]).applyInverse(p);
      return local.x() > c.lower.x() && local.x() < c.upper.x() && local.y() > c.lower.y() &&
             local.y() < c.upper.y();
    }
  }
  return true;
}

void ErrorMeter::sample(const std::vector<BodyState>& states) {
  const size_t n = states.size();
  for (const BodyState& s : states) figures_.finite &= !s.alive || finiteState(s);
  if (!figures_.finite) return;

  // Sweep and prune on x over the bodies' boxes, then the narrow phase on the scene geometry.
  boxes_.resize(n);
  order_.clear();
  for (size_t i = 0; i < n; ++i) {
    if (!states[i].alive || shapes_[i].empty()) continue;
    const Transform pose = poseOf(states[i]);
    boxes_[i] = impulse2d::computeAabb(shapes_[i][0], pose);
    for (size_t k = 1; k < shapes_[i].size(); ++k) {
      boxes_[i] = boxes_[i].united(impulse2d::computeAabb(shapes_[i][k], pose));
    }
    order_.push_back(static_cast<int>(i));
  }
  std::sort(order_.begin(), order_.end(),
            [&](int x, int y) { return boxes_[x].lower.x() < boxes_[y].lower.x(); });
  for (size_t k = 0; k < order_.size(); ++k) {
    const int i = order_[k];
    for (size_t m = k + 1; m < order_.size() && boxes_[order_[m]].lower.x() <= boxes_[i].upper.x();
         ++m) {
      const int j = order_[m];
      if (scene_.bodies[i].isDriven() && scene_.bodies[j].isDriven()) continue;
      if (!boxes_[i].overlaps(boxes_[j])) continue;
      const std::pair<int, int> pair(std::min(i, j), std::max(i, j));
      if (std::binary_search(jointPairs_.begin(), jointPairs_.end(), pair)) continue;
      const Transform poseI = poseOf(states[i]), poseJ = poseOf(states[j]);
      for (const impulse2d::Shape& a : shapes_[i]) {
        for (const impulse2d::Shape& b : shapes_[j]) {
          if (!impulse2d::filtersAllowContact(a.filter, b.filter)) continue;
          const impulse2d::Manifold manifold = impulse2d::collideShapes(a, poseI, b, poseJ, 0.0);
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
    }
  }

  for (size_t k = 0; k < scene_.joints.size(); ++k) {
    const BenchJoint& joint = scene_.joints[k];
    if (!states[joint.bodyA].alive || !states[joint.bodyB].alive) continue;
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
  const double startMomentum = startMomentum_.norm();
  out.momentumDrift =
      startMomentum > 0.0 ? (momentum(finalStates) - startMomentum_).norm() / startMomentum : 0.0;
  for (size_t i = 0; i < finalStates.size(); ++i) {
    if (scene_.bodies[i].isDriven() || !finalStates[i].alive) continue;
    const Vec2 move = finalStates[i].position - initial_[i].position;
    out.driftMax = std::max(out.driftMax, std::abs(move.x()));
    out.sinkMax = std::max(out.sinkMax, -move.y());
    if (scene_.kind == SceneKind::Contained && !inside(finalStates, i)) ++out.escaped;
  }
  switch (scene_.kind) {
    case SceneKind::Resting:
      out.stood = out.driftMax < scene_.tolerance;
      break;
    case SceneKind::Jointed:
      out.stood = out.jointGapMax < scene_.tolerance;
      break;
    case SceneKind::Contained:
      out.stood = out.escaped == 0;
      break;
    case SceneKind::Impact:
      out.stood = out.momentumDrift < scene_.tolerance;
      break;
  }
  return out;
}

}  // namespace impulse2d_bench
