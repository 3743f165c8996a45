// World::step, top to bottom as the algorithm, and the stages it calls.
#include "world_impl.hpp"

#include <impulse2d/limits.hpp>

#include "motion_limits.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace impulse2d {

void World::step() {
  WorldImpl& w = *impl_;
  const double dt = w.def.timeStep;
  w.stepWorkers.setThreads(w.def.threads);
  w.stepWorkers.session([&] {  // the step's threads, for each stage that has parallel blocks
    w.updateBroadPhase();      // 1. refit the fat boxes of bodies that left them
    w.findNewContacts();       // 2. newly overlapping pairs become arbiters
    w.updateContacts();        // 3. narrow phase; keep the impulses of matching contact ids
    if (usesSubsteps(w.def.solver)) {
      w.solveSubsteps(dt);  // 4-6 in sub-steps, and 8 (world_substeps.cpp)
    } else {
      w.solverBodies.gather(w.bodies.items, w.bodies.alive);  // 4-6 work on the solver's copy
      w.integrateVelocities(dt);                              // 4. gravity, applied forces, damping
      w.solve(dt);               // 5. pre-step, warm start, velocity iterations, restitution
      w.integratePositions(dt);  // 6. move with the solved velocities
      w.solverBodies.storeMotion(w.bodies.items);
    }
    w.solveContinuous();    // 7. fast bodies stop at their first impact instead of tunnelling
    w.correctPositions();   // 8. ngs: push remaining overlaps apart
    w.updateSleep(dt);      // 9. islands still for long enough fall asleep
    removeEscapedBodies();  // 10. bodies that left the world are removed; lost ones reported
    w.clearForces();
  });
  w.time += dt;
  ++w.steps;
}

namespace {

// Whether no point of the body has moved as far as the fat boxes' margin since they were placed:
// at most the shift of its origin plus the chord its farthest point turned through,
// reach * 2 sin(turn / 2) = reach * sqrt(2 - 2 cos(turn)).
bool movedLessThanMargin(const Body& body) {
  const double dx = body.xf.p.x() - body.proxyXf.p.x(), dy = body.xf.p.y() - body.proxyXf.p.y();
  const double cosTurn = body.proxyXf.q.c * body.xf.q.c + body.proxyXf.q.s * body.xf.q.s;
  const double reach = body.maxExtent + body.localCenter.norm();
  const double chord = reach * std::sqrt(std::max(0.0, 2.0 - 2.0 * cosTurn));
  return std::sqrt(dx * dx + dy * dy) + chord < 0.5 * kAabbMargin;
}

}  // namespace

void WorldImpl::updateBroadPhase() {
  // In parallel: the shapes of moving bodies that left their fat boxes (most move less than the
  // margin and need nothing). Then in slot order, one thread: the tree moves them.
  const int slots = static_cast<int>(bodies.items.size());
  const int blocks = (slots + kBodiesPerBlock - 1) / kBodiesPerBlock;
  refits.resize(static_cast<size_t>(blocks));
  stepWorkers.stage(blocks, [&](int block, int) {
    std::vector<std::pair<int, Aabb>>& out = refits[block];
    out.clear();
    for (int i = block * kBodiesPerBlock; i < std::min(slots, (block + 1) * kBodiesPerBlock); ++i) {
      Body& body = bodies.items[i];
      if (!bodies.alive[i] || body.type == BodyType::Static || !body.awake) continue;
      if (movedLessThanMargin(body)) continue;
      const size_t before = out.size();
      for (size_t k = 0; k < body.shapes.size(); ++k) {
        const Aabb box = computeAabb(body.shapes[k], body.xf);
        if (!tree.fatAabb(body.proxies[k]).contains(box)) out.emplace_back(body.proxies[k], box);
      }
      if (out.size() - before == body.shapes.size()) body.proxyXf = body.xf;  // all placed anew
    }
  });
  for (const std::vector<std::pair<int, Aabb>>& block : refits) {
    for (const auto& [proxy, box] : block) {
      tree.moveProxy(proxy, box.inflated(kAabbMargin));
      markMoved(proxy);
    }
  }
}

void WorldImpl::findNewContacts() {
  std::vector<std::pair<int, int>>& pairs = newPairs;  // reused: no allocation once warm
  pairs.clear();
  for (const int proxy : movedProxies) {
    if (!proxyMoved[proxy]) continue;  // destroyed since it moved
    tree.query(tree.fatAabb(proxy), [&](int other) {
      // A pair of two moved proxies is reported by the lower one only.
      if (other == proxy || (proxyMoved[other] && other < proxy)) return;
      pairs.emplace_back(std::min(proxy, other), std::max(proxy, other));
    });
  }
  // proxyMoved stays set until the narrow phase has checked the contacts of the moved proxies.

  std::vector<Contact>& fresh = newContacts;
  fresh.clear();
  for (const auto& [p, q] : pairs) {
    int slotA = static_cast<int>(tree.userData(p) >> 8), shapeA = tree.userData(p) & 0xff;
    int slotB = static_cast<int>(tree.userData(q) >> 8), shapeB = tree.userData(q) & 0xff;
    if (slotA == slotB) continue;
    if (slotA > slotB) {
      std::swap(slotA, slotB);
      std::swap(shapeA, shapeB);
    }
    const uint64_t key = contactKey(slotA, shapeA, slotB, shapeB);
    if (contactKeys.count(key) || !shouldCollide(slotA, slotB)) continue;
    Contact contact;
    contact.key = key;
    contact.bodyA = slotA;
    contact.bodyB = slotB;
    contact.shapeA = shapeA;
    contact.shapeB = shapeB;
    contact.proxyA = slotA == static_cast<int>(tree.userData(p) >> 8) ? p : q;
    contact.proxyB = contact.proxyA == p ? q : p;
    const Shape& sa = bodies.items[slotA].shapes[shapeA];
    const Shape& sb = bodies.items[slotB].shapes[shapeB];
    contact.friction = mixFriction(sa.friction, sb.friction);
    contact.restitution = mixRestitution(sa.restitution, sb.restitution);
    contactKeys.insert(key);
    fresh.push_back(contact);
  }
  // The tree's shape depends on history; sorting by key makes the solve order depend only on
  // which pairs exist.
  std::sort(fresh.begin(), fresh.end(),
            [](const Contact& x, const Contact& y) { return x.key < y.key; });
  contacts.insert(contacts.end(), fresh.begin(), fresh.end());
}

void WorldImpl::updateContacts() {
  // In parallel: each contact's new manifold, or its mark to go (its fat boxes parted). Which
  // bodies move is read as the step found them, so the result does not depend on the order.
  enum : uint8_t { kKeep = 0, kDrop = 1, kWakeA = 2, kWakeB = 4 };
  std::vector<uint8_t>& contactFate = contactFates;
  contactFate.resize(contacts.size());
  const int blocks =
      static_cast<int>((contacts.size() + kContactsPerBlock - 1) / kContactsPerBlock);
  stepWorkers.stage(blocks, [&](int block, int) {
    const size_t first = static_cast<size_t>(block) * kContactsPerBlock;
    const size_t last = std::min(contacts.size(), first + kContactsPerBlock);
    for (size_t i = first; i < last; ++i) {
      Contact& contact = contacts[i];
      const Body& a = bodies.items[contact.bodyA];
      const Body& b = bodies.items[contact.bodyB];
      uint8_t fate = kKeep;
      // Fat boxes can only have parted if one of them moved this step.
      const bool moved = movedThisStep(contact.proxyA) || movedThisStep(contact.proxyB);
      if (moved && !tree.fatAabb(contact.proxyA).overlaps(tree.fatAabb(contact.proxyB))) {
        fate = kDrop;
      } else if (isMoving(a) || isMoving(b)) {
        // Two bodies that cannot move relative to each other keep last step's manifold.
        updateContact(contact, a, b, def.speculativeDistance, def.timeStep, def.warmStarting);
        // Something moving now touches a sleeper: it wakes before the solver runs.
        if (contact.manifold.pointCount > 0) {
          if (isMoving(a) && b.type == BodyType::Dynamic && !b.awake) fate |= kWakeB;
          if (isMoving(b) && a.type == BodyType::Dynamic && !a.awake) fate |= kWakeA;
        }
      }
      contactFate[i] = fate;
    }
  });
  // In order: drop what went, wake what was touched.
  size_t write = 0;
  for (size_t read = 0; read < contacts.size(); ++read) {
    const uint8_t fate = contactFate[read];
    if (fate & kDrop) {
      contactKeys.erase(contacts[read].key);
      continue;
    }
    if (fate & kWakeA) wakeBody(bodies.items[contacts[read].bodyA]);
    if (fate & kWakeB) wakeBody(bodies.items[contacts[read].bodyB]);
    if (write != read) contacts[write] = contacts[read];
    ++write;
  }
  contacts.resize(write);
  for (const int proxy : movedProxies) proxyMoved[proxy] = 0;
  movedProxies.clear();
}

void WorldImpl::integrateVelocities(double dt) {
  const MotionLimits limits = MotionLimits::of(def, dt);
  for (int e = 0; e < solverBodies.dynamicCount(); ++e) {
    SolverBody& body = solverBodies[e];
    if (body.invMass == 0.0) continue;  // overflowed earlier in this step (below)
    const SolverBodyLoad& load = solverBodies.load(e);
    body.linearVelocity += dt * (def.gravity + body.invMass * load.force);
    body.angularVelocity += dt * body.invInertia * load.torque;
    // Implicit damping: stable for any damping coefficient and time step.
    if (load.linearDamping > 0.0) body.linearVelocity *= 1.0 / (1.0 + dt * load.linearDamping);
    if (load.angularDamping > 0.0) body.angularVelocity *= 1.0 / (1.0 + dt * load.angularDamping);
    limits.apply(body.linearVelocity, body.angularVelocity);
    // The last guard against non-finite impulses: 0 x inf is NaN in the static and sleeping
    // bodies' read-only entries, which every other body touching them reads. A body whose
    // velocity is not finite stands still, with infinite mass, for the rest of the step, and is
    // removed at its end (world_bounds.cpp).
    if (!(isFinite(body.linearVelocity) && std::isfinite(body.angularVelocity))) {
      body.linearVelocity.setZero();
      body.angularVelocity = body.invMass = body.invInertia = 0.0;
      overflowedBodies.push_back(solverBodies.slotOf(e));
    }
  }
}

void WorldImpl::collectActiveJoints() {
  activeJoints.clear();
  for (size_t j = 0; j < joints.items.size(); ++j) {
    if (!joints.alive[j]) continue;
    Joint& joint = joints.items[j];
    if (!solverBodies.isActive(joint.bodyA) && !solverBodies.isActive(joint.bodyB)) continue;
    activeJoints.push_back(static_cast<int>(j));
    joint.entryA = solverBodies.entryOf(joint.bodyA);
    joint.entryB = solverBodies.entryOf(joint.bodyB);
    if (!def.warmStarting) {
      joint.pointImpulse.setZero();
      joint.motorImpulse = joint.lowerImpulse = joint.upperImpulse = 0.0;
    }
  }
}

void WorldImpl::prepareJoints(const Feedback& fb, double dt) {
  for (const int j : activeJoints) {
    Joint& joint = joints.items[j];
    prepareJoint(joint, solverBodies[joint.entryA], solverBodies[joint.entryB], def, fb, dt);
  }
}

void WorldImpl::warmStartJoints() {
  const MotionLimits limits = MotionLimits::of(def, def.timeStep);
  for (const int j : activeJoints) {
    Joint& joint = joints.items[j];
    warmStartJoint(joint, solverBodies[joint.entryA], solverBodies[joint.entryB], limits);
  }
}

void WorldImpl::solveJointVelocities(double dt) {
  for (const int j : activeJoints) {
    Joint& joint = joints.items[j];
    solveJointVelocity(joint, solverBodies[joint.entryA], solverBodies[joint.entryB], dt);
  }
}

void WorldImpl::solve(double dt) {
  collectActiveJoints();
  contactSolver.prepare(contacts, solverBodies, def, dt);
  Feedback fb;  // NGS: no bias, its position pass corrects the drift
  if (def.solver == SolverType::Baumgarte) fb.rate = def.baumgarte / dt;
  prepareJoints(fb, dt);

  // Warm start: apply last step's impulses first, so the iterations only refine them.
  warmStartJoints();
  contactSolver.warmStart();

  for (int iteration = 0; iteration < def.velocityIterations; ++iteration) {
    solveJointVelocities(dt);
    contactSolver.solveVelocities();
  }
  contactSolver.applyRestitution(def.restitutionThreshold);
  contactSolver.storeImpulses();
}

void WorldImpl::integratePositions(double dt) {
  solverBodies.holdKinematicVelocities();
  fastBodies.clear();
  const MotionLimits limits = MotionLimits::of(def, dt);
  for (int e = 0; e < solverBodies.movingCount(); ++e) {
    SolverBody& body = solverBodies[e];
    if (solverBodies.isDynamic(e)) limits.apply(body.linearVelocity, body.angularVelocity);
    const Vec2 move = dt * body.linearVelocity;
    const double turn = dt * body.angularVelocity;
    if (solverBodies.isDynamic(e)) {
      // A body that moves less than a quarter of its own thickness in a step cannot skip past
      // anything as thick as itself, and its speculative contacts catch it before it sinks
      // deep; faster ones get the continuous pass.
      const Body& shape = bodies.items[solverBodies.slotOf(e)];
      const double reach = move.norm() + std::abs(turn) * shape.maxExtent;
      if (reach > std::max(def.speculativeDistance, 0.25 * shape.minExtent)) {
        fastBodies.push_back({solverBodies.slotOf(e), body.center, body.angle});
      }
    }
    body.center += move;
    turnBy(body, turn);
  }
}

void WorldImpl::correctPositions() {
  if (def.solver != SolverType::NonlinearGaussSeidel) return;
  solverBodies.loadPoses(bodies.items);  // continuous collision may have moved some
  for (int iteration = 0; iteration < def.positionIterations; ++iteration) {
    bool jointsOk = true;
    for (const int j : activeJoints) {
      Joint& joint = joints.items[j];
      jointsOk &=
          solveJointPosition(joint, solverBodies[joint.entryA], solverBodies[joint.entryB], def);
    }
    const bool contactsOk = contactSolver.solvePositions(def);
    if (jointsOk && contactsOk) break;
  }
  solverBodies.storeDynamicPoses(bodies.items);
}

void WorldImpl::clearForces() {
  for (size_t i = 0; i < bodies.items.size(); ++i) {
    if (!bodies.alive[i]) continue;
    bodies.items[i].force.setZero();
    bodies.items[i].torque = 0.0;
  }
}

}  // namespace impulse2d
