#include "solver_body.hpp"

namespace impulse2d {

void SolverBodies::add(const Body& body, int slot, bool readOnly) {
  indexOfSlot_[slot] = static_cast<int>(entries_.size());
  SolverBody e = solverView(body);
  if (readOnly) {  // it does not move this step, whatever pushes it
    e.linearVelocity.setZero();
    e.angularVelocity = e.invMass = e.invInertia = 0.0;
  }
  entries_.push_back(e);
  slots_.push_back(slot);
  SolverBodyLoad load;
  if (!readOnly) {
    load = {body.force,          body.torque,         body.linearDamping,
            body.angularDamping, body.linearVelocity, body.angularVelocity};
  }
  loads_.push_back(load);
}

void SolverBodies::addCluster(const WeldClusters& clusters, int cluster) {
  const std::vector<Body>& bodies = *bodies_;
  const int entry = indexOfSlot_[clusters.root(cluster)];
  const RigidCluster r = clusters.combine(cluster, bodies);
  SolverBody& e = entries_[entry];
  e = SolverBody();  // the cluster's frame: at its centre of mass, angle 0
  e.linearVelocity = r.velocity;
  e.angularVelocity = r.angularVelocity;
  e.invMass = 1.0 / r.mass;
  e.invInertia = 1.0 / r.inertia;
  e.center = r.center;
  loads_[entry] = {r.force,          r.torque,   r.linearDamping,
                   r.angularDamping, r.velocity, r.angularVelocity};
  clusterRows_.add(clusters, cluster, bodies, r.center, entry, indexOfSlot_);
}

void SolverBodies::gather(const std::vector<Body>& bodies, const std::vector<int>& movableSlots,
                          const WeldClusters& clusters) {
  bodies_ = &bodies;
  entries_.clear();
  loads_.clear();
  slots_.clear();
  indexOfSlot_.assign(bodies.size(), kNone);
  // Through the living bodies that are not static, in ascending slots: static ones cost nothing.
  for (const BodyType type : {BodyType::Dynamic, BodyType::Kinematic}) {
    for (const int i : movableSlots) {
      if (bodies[i].type != type || !bodies[i].awake) continue;
      const int cluster = clusters.clusterOf(i);
      if (cluster >= 0 && clusters.root(cluster) != i) continue;
      add(bodies[i], i, false);
    }
    if (type == BodyType::Dynamic) dynamicCount_ = static_cast<int>(entries_.size());
  }
  movingCount_ = static_cast<int>(entries_.size());
  clusterRows_.reset(clusters, bodies.size(), static_cast<size_t>(dynamicCount_));
  for (int c = 0; c < clusters.count(); ++c) addCluster(clusters, c);
}

int SolverBodies::ensureEntryOf(int slot) {
  if (indexOfSlot_[slot] == kNone) add((*bodies_)[slot], slot, true);
  return indexOfSlot_[slot];
}

SolverBody SolverBodies::view(int slot) {
  SolverBody e = entries_[ensureEntryOf(slot)];
  if (const MemberStart* m = clusterRows_.ofSlot(slot)) {
    e.q = m->q0 * e.q;  // the cluster's entry turns from 0
    e.angle += m->angle0;
    e.localCenter = m->viewLocalCenter;
  }
  return e;
}

void SolverBodies::store(int slot, const SolverBody& view, bool pose) {
  const int entry = indexOfSlot_[slot];
  if (entry >= dynamicCount_) return;  // kinematic or read-only: nothing moves them
  SolverBody& e = entries_[entry];
  e.linearVelocity = view.linearVelocity;
  e.angularVelocity = view.angularVelocity;
  if (!pose) return;
  e.center = view.center;
  e.angle = view.angle;
  e.q = view.q;
  if (const MemberStart* m = clusterRows_.ofSlot(slot)) {
    e.angle -= m->angle0;
    e.q = m->q0.inverseTimes(view.q);
  }
}

void SolverBodies::holdKinematicVelocities() {
  for (int e = dynamicCount_; e < movingCount_; ++e) {
    entries_[e].linearVelocity = loads_[e].linearVelocity;
    entries_[e].angularVelocity = loads_[e].angularVelocity;
  }
}

void SolverBodies::storeMotion(std::vector<Body>& bodies) const {
  for (int e = 0; e < movingCount_; ++e) {
    const SolverBody& entry = entries_[e];
    const auto [first, last] = clusterRows_.ofRow(e);
    for (int k = first; k < last; ++k) {  // a cluster: its members, rigidly
      const MemberStart& m = clusterRows_.member(k);
      Body& body = bodies[m.slot];
      body.center = entry.center + entry.q.apply(m.offset);
      body.angle = m.angle0 + entry.angle;
      body.xf.q = Rot(body.angle);
      body.xf.p = body.center - body.xf.q.apply(body.localCenter);
      body.linearVelocity =
          entry.linearVelocity + cross(entry.angularVelocity, Vec2(body.center - entry.center));
      body.angularVelocity = entry.angularVelocity;
    }
    if (first < last) continue;
    Body& body = bodies[slots_[e]];
    body.center = entry.center;
    body.angle = entry.angle;
    body.xf.q = Rot(body.angle);
    body.xf.p = body.center - body.xf.q.apply(body.localCenter);
    if (e < dynamicCount_) {
      body.linearVelocity = entry.linearVelocity;
      body.angularVelocity = entry.angularVelocity;
    }
  }
}

}  // namespace impulse2d
