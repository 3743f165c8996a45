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

void SolverBodies::gather(const std::vector<Body>& bodies, const std::vector<char>& alive) {
  bodies_ = &bodies;
  entries_.clear();
  loads_.clear();
  slots_.clear();
  indexOfSlot_.assign(bodies.size(), kNone);
  for (const BodyType type : {BodyType::Dynamic, BodyType::Kinematic}) {
    for (size_t i = 0; i < bodies.size(); ++i) {
      if (alive[i] && bodies[i].type == type && bodies[i].awake) {
        add(bodies[i], static_cast<int>(i), false);
      }
    }
    if (type == BodyType::Dynamic) dynamicCount_ = static_cast<int>(entries_.size());
  }
  movingCount_ = static_cast<int>(entries_.size());
}

int SolverBodies::entryOf(int slot) {
  if (indexOfSlot_[slot] == kNone) add((*bodies_)[slot], slot, true);
  return indexOfSlot_[slot];
}

void SolverBodies::holdKinematicVelocities() {
  for (int e = dynamicCount_; e < movingCount_; ++e) {
    entries_[e].linearVelocity = loads_[e].linearVelocity;
    entries_[e].angularVelocity = loads_[e].angularVelocity;
  }
}

void SolverBodies::storeMotion(std::vector<Body>& bodies) const {
  storePoses(bodies, movingCount_);
  for (int e = 0; e < dynamicCount_; ++e) {
    Body& body = bodies[slots_[e]];
    body.linearVelocity = entries_[e].linearVelocity;
    body.angularVelocity = entries_[e].angularVelocity;
  }
}

void SolverBodies::loadPoses(const std::vector<Body>& bodies) {
  for (int e = 0; e < movingCount_; ++e) {
    const Body& body = bodies[slots_[e]];
    entries_[e].center = body.center;
    entries_[e].angle = body.angle;
    entries_[e].q = body.xf.q;
  }
}

void SolverBodies::storePoses(std::vector<Body>& bodies, int count) const {
  for (int e = 0; e < count; ++e) {
    Body& body = bodies[slots_[e]];
    body.center = entries_[e].center;
    body.angle = entries_[e].angle;
    body.xf.q = Rot(body.angle);
    body.xf.p = body.center - body.xf.q.apply(body.localCenter);
  }
}

}  // namespace impulse2d
