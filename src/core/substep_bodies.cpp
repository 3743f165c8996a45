#include "substep_bodies.hpp"

namespace impulse2d {

void SubstepBodies::gather(const std::vector<Body>& bodies, const std::vector<char>& alive,
                           const Vec2& gravity, double h, int workers) {
  bodies_ = &bodies;
  states_.clear();
  sims_.clear();
  entryOfSlot_.assign(bodies.size(), -1);
  for (const BodyType type : {BodyType::Dynamic, BodyType::Kinematic}) {
    for (size_t i = 0; i < bodies.size(); ++i) {
      const Body& body = bodies[i];
      if (!alive[i] || body.type != type || !body.awake) continue;
      entryOfSlot_[i] = static_cast<int>(states_.size());
      BodyState& state = states_.emplace_back();
      state.vx = body.linearVelocity.x();
      state.vy = body.linearVelocity.y();
      state.w = body.angularVelocity;
      BodySim& sim = sims_.emplace_back();
      sim.slot = static_cast<int>(i);
      sim.center0 = body.center;
      sim.angle0 = body.angle;
      sim.q0 = body.xf.q;
      sim.localCenter = body.localCenter;
      if (type == BodyType::Dynamic) {
        sim.invMass = body.invMass;
        sim.invInertia = body.invInertia;
        sim.dvx = h * (gravity.x() + body.invMass * body.force.x());
        sim.dvy = h * (gravity.y() + body.invMass * body.force.y());
        sim.dw = h * body.invInertia * body.torque;
        // Implicit damping: stable for any coefficient and sub-step.
        if (body.linearDamping > 0.0) sim.linearDamping = 1.0 / (1.0 + h * body.linearDamping);
        if (body.angularDamping > 0.0) sim.angularDamping = 1.0 / (1.0 + h * body.angularDamping);
      } else {
        sim.kinematicVelocity = body.linearVelocity;
        sim.kinematicAngularVelocity = body.angularVelocity;
      }
    }
    if (type == BodyType::Dynamic) dynamicCount_ = static_cast<int>(states_.size());
  }
  movingCount_ = static_cast<int>(states_.size());
  states_.resize(states_.size() + 1 + static_cast<size_t>(workers));  // identity and sinks
}

void SubstepBodies::integrateVelocities(int begin, int end) {
  const int last = std::min(end, dynamicCount_);
  for (int e = begin; e < last; ++e) {
    BodyState& s = states_[e];
    const BodySim& sim = sims_[e];
    s.vx = (s.vx + sim.dvx) * sim.linearDamping;
    s.vy = (s.vy + sim.dvy) * sim.linearDamping;
    s.w = (s.w + sim.dw) * sim.angularDamping;
  }
}

void SubstepBodies::integratePositions(int begin, int end, double h) {
  for (int e = begin; e < end; ++e) {
    BodyState& s = states_[e];
    if (e >= dynamicCount_) {  // impulses cannot change a kinematic velocity, nor may a NaN
      const BodySim& sim = sims_[e];
      s.vx = sim.kinematicVelocity.x();
      s.vy = sim.kinematicVelocity.y();
      s.w = sim.kinematicAngularVelocity;
    }
    s.dx += h * s.vx;
    s.dy += h * s.vy;
    const double turn = h * s.w;
    s.turned += turn;
    const Rot q = Rot::fromCosSin(s.qc, s.qs) * rotationBy(turn);
    s.qc = q.c;
    s.qs = q.s;
  }
}

SolverBody SubstepBodies::view(int slot) const {
  const int entry = entryOfSlot_[slot];
  if (entry < 0) {
    SolverBody e = solverView((*bodies_)[slot]);
    e.linearVelocity.setZero();
    e.angularVelocity = e.invMass = e.invInertia = 0.0;
    return e;
  }
  const BodyState& s = states_[entry];
  const BodySim& sim = sims_[entry];
  SolverBody e;
  e.linearVelocity = Vec2(s.vx, s.vy);
  e.angularVelocity = s.w;
  e.invMass = sim.invMass;
  e.invInertia = sim.invInertia;
  e.center = Vec2(sim.center0.x() + s.dx, sim.center0.y() + s.dy);
  e.angle = sim.angle0 + s.turned;
  e.q = sim.q0 * Rot::fromCosSin(s.qc, s.qs);
  e.localCenter = sim.localCenter;
  return e;
}

void SubstepBodies::store(int slot, const SolverBody& view, bool pose) {
  const int entry = entryOfSlot_[slot];
  if (entry < 0 || entry >= dynamicCount_) return;
  BodyState& s = states_[entry];
  s.vx = view.linearVelocity.x();
  s.vy = view.linearVelocity.y();
  s.w = view.angularVelocity;
  if (!pose) return;
  const BodySim& sim = sims_[entry];
  s.dx = view.center.x() - sim.center0.x();
  s.dy = view.center.y() - sim.center0.y();
  s.turned = view.angle - sim.angle0;
  const Rot q = sim.q0.inverseTimes(view.q);
  s.qc = q.c;
  s.qs = q.s;
}

void SubstepBodies::finish(std::vector<Body>& bodies) const {
  for (int e = 0; e < movingCount_; ++e) {
    const BodyState& s = states_[e];
    const BodySim& sim = sims_[e];
    Body& body = bodies[sim.slot];
    body.center = Vec2(sim.center0.x() + s.dx, sim.center0.y() + s.dy);
    body.angle = sim.angle0 + s.turned;
    body.xf.q = Rot(body.angle);
    body.xf.p = body.center - body.xf.q.apply(body.localCenter);
    if (e < dynamicCount_) {
      body.linearVelocity = Vec2(s.vx, s.vy);
      body.angularVelocity = s.w;
    }
  }
}

}  // namespace impulse2d
