#include "substep_bodies.hpp"

#include <algorithm>
#include <cmath>

namespace impulse2d {

void SubstepBodies::gather(const std::vector<Body>& bodies, const std::vector<int>& movableSlots,
                           const Vec2& gravity, double h, const MotionLimits& limits,
                           const WeldClusters& clusters, StepWorkers& workers) {
  bodies_ = &bodies;
  limits_ = limits;
  turnCaps_.clear();
  // Blocks of the moving bodies' slots (static bodies have no row and cost nothing here).
  const int movables = static_cast<int>(movableSlots.size());
  const int blocks = (movables + kSlotsPerBlock - 1) / kSlotsPerBlock;
  auto rowOf = [&](int i) {  // 0: none, 1: a dynamic row, 2: a kinematic one
    const Body& body = bodies[i];
    if (!body.awake) return 0;
    const int cluster = clusters.clusterOf(i);
    if (cluster >= 0 && clusters.root(cluster) != i) return 0;  // the root's row moves it
    return body.type == BodyType::Dynamic ? 1 : 2;
  };
  // Count each block's rows, so that every block knows where its own go: dynamic rows first,
  // then kinematic ones, each in slot order, as if one thread had gone through the slots.
  blockFirst_.assign(2 * static_cast<size_t>(blocks) + 2, 0);
  workers.stage(blocks, [&](int block, int) {
    const int end = std::min(movables, (block + 1) * kSlotsPerBlock);
    for (int k = block * kSlotsPerBlock; k < end; ++k) {
      const int kind = rowOf(movableSlots[k]);
      if (kind != 0) ++blockFirst_[2 * (block + 1) + (kind - 1)];
    }
  });
  for (int block = 1; block <= blocks; ++block) {
    blockFirst_[2 * block] += blockFirst_[2 * (block - 1)];
    blockFirst_[2 * block + 1] += blockFirst_[2 * (block - 1) + 1];
  }
  dynamicCount_ = blockFirst_[2 * blocks];
  movingCount_ = dynamicCount_ + blockFirst_[2 * blocks + 1];
  states_.resize(static_cast<size_t>(movingCount_) + 1 + static_cast<size_t>(workers.threads()));
  sims_.resize(static_cast<size_t>(movingCount_));
  starts_.resize(static_cast<size_t>(movingCount_));
  loads_.resize(static_cast<size_t>(dynamicCount_));
  entryOfSlot_.assign(bodies.size(), -1);
  overflowedOfBlock_.resize(static_cast<size_t>(blocks));
  workers.stage(blocks, [&](int block, int) {
    int next[2] = {blockFirst_[2 * block], dynamicCount_ + blockFirst_[2 * block + 1]};
    overflowedOfBlock_[block].clear();
    const int end = std::min(movables, (block + 1) * kSlotsPerBlock);
    for (int k = block * kSlotsPerBlock; k < end; ++k) {
      const int i = movableSlots[k];
      const int kind = rowOf(i);
      entryOfSlot_[i] = kind == 0 ? -1 : next[kind - 1]++;
      if (kind != 0 && !add(bodies[i], i, entryOfSlot_[i], gravity, h)) {
        overflowedOfBlock_[block].push_back(i);
      }
    }
  });
  overflowed_.clear();
  for (const std::vector<int>& list : overflowedOfBlock_) {
    overflowed_.insert(overflowed_.end(), list.begin(), list.end());
  }
  clusterRows_.reset(clusters, bodies.size(), static_cast<size_t>(movingCount_));
  for (int c = 0; c < clusters.count(); ++c) addCluster(clusters, c, gravity, h);
  // The identity row and the sinks.
  std::fill(states_.begin() + movingCount_, states_.end(), BodyState());
}

bool SubstepBodies::add(const Body& body, int slot, int entry, const Vec2& gravity, double h) {
  BodyState& state = states_[entry];
  state = BodyState();
  state.vx = body.linearVelocity.x();
  state.vy = body.linearVelocity.y();
  state.w = body.angularVelocity;
  BodySim& sim = sims_[entry];
  sim = BodySim();
  sim.center0 = body.center;
  BodyStart& start = starts_[entry];
  start = BodyStart();
  start.slot = slot;
  start.angle0 = body.angle;
  start.q0 = body.xf.q;
  start.localCenter = body.localCenter;
  if (body.type == BodyType::Dynamic) {
    sim.invMass = body.invMass;
    sim.invInertia = body.invInertia;
    BodyLoad& load = loads_[entry];
    load = loadOver(h, gravity, body.invMass, body.invInertia, body.force, body.torque,
                    body.linearDamping, body.angularDamping);
    // The last guard (body_load.hpp, isFiniteMotion): held still with infinite mass.
    if (!isFiniteMotion(state.vx, state.vy, state.w) ||
        !isFiniteMotion(load.dvx, load.dvy, load.dw)) {
      state.vx = state.vy = state.w = 0.0;
      sim.invMass = sim.invInertia = 0.0;
      load = BodyLoad();
      return false;
    }
  } else {
    start.kinematicVelocity = body.linearVelocity;
    start.kinematicAngularVelocity = body.angularVelocity;
  }
  return true;
}

void SubstepBodies::addCluster(const WeldClusters& clusters, int cluster, const Vec2& gravity,
                               double h) {
  const std::vector<Body>& bodies = *bodies_;
  const int root = clusters.root(cluster);
  const int entry = entryOfSlot_[root];
  const RigidCluster r = clusters.combine(cluster, bodies);
  BodyState& state = states_[entry];
  state = BodyState();
  state.vx = r.velocity.x();
  state.vy = r.velocity.y();
  state.w = r.angularVelocity;
  BodySim& sim = sims_[entry];
  sim.center0 = r.center;
  sim.invMass = 1.0 / r.mass;
  sim.invInertia = 1.0 / r.inertia;
  BodyStart& start = starts_[entry];
  start = BodyStart();  // the cluster's frame: at its centre of mass, angle 0
  start.slot = root;
  BodyLoad& load = loads_[entry];
  load = loadOver(h, gravity, sim.invMass, sim.invInertia, r.force, r.torque, r.linearDamping,
                  r.angularDamping);
  clusterRows_.add(clusters, cluster, bodies, r.center, entry, entryOfSlot_);
  const bool finite = isFiniteMotion(state.vx, state.vy, state.w) &&
                      isFiniteMotion(load.dvx, load.dvy, load.dw) &&
                      std::isfinite(sim.invMass + sim.invInertia) && isFinite(sim.center0);
  if (!finite) {  // as add(): held still, and every member removed at the end of the step
    state = BodyState();
    sim.invMass = sim.invInertia = 0.0;
    sim.center0 = bodies[root].center;
    load = BodyLoad();
    for (const int* m = clusters.membersBegin(cluster); m != clusters.membersEnd(cluster); ++m) {
      overflowed_.push_back(*m);
    }
  }
}

void SubstepBodies::integrateVelocities(int begin, int end) {
  const int last = std::min(end, dynamicCount_);
  for (int e = begin; e < last; ++e) {
    BodyState& s = states_[e];
    applyLoad(loads_[e], s.vx, s.vy, s.w);
    limits_.apply(s.vx, s.vy, s.w, turnCaps_.rate(e, limits_));
  }
}

void SubstepBodies::integratePositions(int begin, int end, double h) {
  // In chunks, the turns' rotations in a loop of their own: rotationBy's series is a long chain
  // of dependent operations, and a loop of nothing else lets the processor run the chunk's
  // bodies side by side (this stage took 8.5 % of the 5050-box pyramid's step as one loop).
  // The same operations in the same order as rotationBy, so the same results.
  constexpr int kChunk = 16;
  double turn[kChunk], turnC[kChunk], turnS[kChunk];
  for (int first = begin; first < end; first += kChunk) {
    const int n = std::min(kChunk, end - first);
    for (int i = 0; i < n; ++i) {
      const int e = first + i;
      BodyState& s = states_[e];
      if (e >= dynamicCount_) {  // impulses cannot change a kinematic velocity, nor may a NaN
        const BodyStart& start = starts_[e];
        s.vx = start.kinematicVelocity.x();
        s.vy = start.kinematicVelocity.y();
        s.w = start.kinematicAngularVelocity;
      } else {
        limits_.apply(s.vx, s.vy, s.w, turnCaps_.rate(e, limits_));
      }
      s.dx += h * s.vx;
      s.dy += h * s.vy;
      turn[i] = h * s.w;
      s.turned += turn[i];
    }
    for (int i = 0; i < n; ++i) {
      const double a2 = turn[i] * turn[i];
      turnC[i] = 1.0 - a2 * (1.0 / 2.0 - a2 * (1.0 / 24.0 - a2 * (1.0 / 720.0)));
      turnS[i] = turn[i] * (1.0 - a2 * (1.0 / 6.0 - a2 * (1.0 / 120.0 - a2 * (1.0 / 5040.0))));
    }
    for (int i = 0; i < n; ++i) {
      BodyState& s = states_[first + i];
      const Rot r = std::abs(turn[i]) < kSmallTurn ? Rot::fromCosSin(turnC[i], turnS[i])
                                                   : rotationBy(turn[i]);
      const Rot q = Rot::fromCosSin(s.qc, s.qs) * r;
      s.qc = q.c;
      s.qs = q.s;
    }
  }
}

void SubstepBodies::finishMember(std::vector<Body>& bodies, int entry, const MemberStart& m) const {
  const BodyState& s = states_[entry];
  const Vec2 center = sims_[entry].center0 + Vec2(s.dx, s.dy);
  Body& body = bodies[m.slot];
  body.center = center + Rot::fromCosSin(s.qc, s.qs).apply(m.offset);
  body.angle = m.angle0 + s.turned;
  body.xf.q = Rot(body.angle);
  body.xf.p = body.center - body.xf.q.apply(body.localCenter);
  double vx = s.vx, vy = s.vy, w = s.w;
  limits_.apply(vx, vy, w, turnCaps_.rate(entry, limits_));
  body.linearVelocity = Vec2(vx, vy) + cross(w, Vec2(body.center - center));
  body.angularVelocity = w;
}

void SubstepBodies::finish(std::vector<Body>& bodies, int begin, int end) const {
  for (int e = begin; e < std::min(end, movingCount_); ++e) {
    const auto [first, last] = clusterRows_.ofRow(e);
    if (first < last) {
      for (int k = first; k < last; ++k) finishMember(bodies, e, clusterRows_.member(k));
      continue;
    }
    const BodyState& s = states_[e];
    const BodySim& sim = sims_[e];
    const BodyStart& start = starts_[e];
    Body& body = bodies[start.slot];
    // In scalars, with the operations of p = c - q.apply(localCenter): the centre stored as two
    // scalars and read back as one vector stalled store forwarding.
    const double cx = sim.center0.x() + s.dx, cy = sim.center0.y() + s.dy;
    body.center.x() = cx;
    body.center.y() = cy;
    body.angle = start.angle0 + s.turned;
    const Rot q(body.angle);
    body.xf.q = q;
    const double lx = body.localCenter.x(), ly = body.localCenter.y();
    body.xf.p.x() = cx - (q.c * lx - q.s * ly);
    body.xf.p.y() = cy - (q.s * lx + q.c * ly);
    if (e < dynamicCount_) {
      double vx = s.vx, vy = s.vy, w = s.w;
      // Restitution and the relax pass come after the last move.
      limits_.apply(vx, vy, w, turnCaps_.rate(e, limits_));
      body.linearVelocity = Vec2(vx, vy);
      body.angularVelocity = w;
    }
  }
}

}  // namespace impulse2d
