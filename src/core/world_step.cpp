// World::step, top to bottom as the algorithm, and the stages it calls.
#include "world_impl.hpp"

#include <impulse2d/limits.hpp>

#include "motion_limits.hpp"
#include "position_pass.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace impulse2d {

void World::step() {
  WorldImpl& w = *impl_;
  const double dt = w.def.timeStep;
  if (w.profiling) w.profile = StepProfile();
  const StageClock wholeStep(w.stage(&StepProfile::total));
  w.stepWorkers.setThreads(w.def.threads);
  w.dropDeadContacts();        // of the bodies destroyed since the last step
  w.stepWorkers.session([&] {  // the step's threads, for each stage that has parallel blocks
    w.updateBroadPhase();      // 1. refit the fat boxes of bodies that left them
    w.findNewContacts();       // 2. newly overlapping pairs become arbiters
    w.updateContacts();        // 3. narrow phase; keep the impulses of matching contact ids
    w.wakeJointedSleepers();   //    sleepers jointed to a moving body wake to move with it
    if (usesSubsteps(w.def.solver)) {
      w.solveSubsteps(dt);  // 4-7 in sub-steps (world_substeps.cpp)
    } else {
      w.gatherSolverBodies();     // 4-7 on a copy, each welded cluster one body
      w.integrateVelocities(dt);  // 4. gravity, applied forces, damping
      w.solve(dt);                // 5. pre-step, warm start, velocity iterations, restitution
      w.integratePositions(dt);   // 6. move with the solved velocities
      w.correctPositions();       // 7. ngs: push remaining overlaps and joint gaps apart
      w.storeMotion();
      w.findOnePassFastBodies();
    }
    w.solveContinuous();    // 8. fast bodies stop at their first impact instead of tunnelling
    w.keepOutOfStatic();    // 9. what a joint or a push drove deep into a static body comes out
    w.dropMotionUndone();   //    bodies of joints left far open keep only the motion they made
    w.updateSleep(dt);      // 10. islands still for long enough fall asleep
    removeEscapedBodies();  // 11. bodies that left the world are removed; lost ones reported
    w.clearForces();
  });
  w.time += dt;
  ++w.steps;
}

namespace {

// Whether no point of the body has moved as far as the fat boxes' margin since they were placed:
// at most the shift of its origin plus the chord its farthest point turned through,
// reach * 2 sin(turn / 2) = reach * sqrt(2 - 2 cos(turn)).
bool movedLessThanMargin(const Body& body, const Transform& placed) {
  const double dx = body.xf.p.x() - placed.p.x(), dy = body.xf.p.y() - placed.p.y();
  const double cosTurn = placed.q.c * body.xf.q.c + placed.q.s * body.xf.q.s;
  const double reach = body.maxExtent + body.localCenter.norm();
  const double chord = reach * std::sqrt(std::max(0.0, 2.0 - 2.0 * cosTurn));
  return std::sqrt(dx * dx + dy * dy) + chord < 0.5 * kAabbMargin;
}

}  // namespace

void WorldImpl::updateBroadPhase() {
  const StageClock clock(stage(&StepProfile::broadPhase));
  // In parallel: the shapes of moving bodies that left their fat boxes (most move less than the
  // margin and need nothing). Then in slot order, one thread: the tree moves them.
  const int movables = static_cast<int>(movableSlots.size());
  const int blocks = (movables + kBodiesPerBlock - 1) / kBodiesPerBlock;
  scratch.refits.resize(static_cast<size_t>(blocks));
  stepWorkers.stage(blocks, [&](int block, int) {
    std::vector<std::pair<int, Aabb>>& out = scratch.refits[block].value;
    out.clear();
    const int end = std::min(movables, (block + 1) * kBodiesPerBlock);
    for (int k = block * kBodiesPerBlock; k < end; ++k) {
      const Body& body = bodies.items[movableSlots[k]];
      BodyBookkeeping& book = bookkeeping[movableSlots[k]];
      if (!body.awake || movedLessThanMargin(body, book.proxyXf)) continue;
      const size_t before = out.size();
      for (size_t k = 0; k < body.shapes.size(); ++k) {
        const Aabb box = computeAabb(body.shapes[k], body.xf);
        if (!tree.fatAabb(book.proxies[k]).contains(box)) out.emplace_back(book.proxies[k], box);
      }
      if (out.size() - before == body.shapes.size()) book.proxyXf = body.xf;  // all placed anew
    }
  });
  size_t moved = 0;
  for (const auto& block : scratch.refits) moved += block.value.size();
  // Many proxies moved (a smashed wall, a shower of parts): their new boxes in place and the tree
  // built anew, instead of each taken out and put back in turn.
  const bool rebuild = moved >= 64 && 8 * moved >= static_cast<size_t>(tree.proxyCount());
  for (const auto& block : scratch.refits) {
    for (const auto& [proxy, box] : block.value) {
      if (rebuild) {
        tree.setFatAabb(proxy, box.inflated(kAabbMargin));
      } else {
        tree.moveProxy(proxy, box.inflated(kAabbMargin));
      }
      markMoved(proxy);
    }
  }
  if (rebuild) {
    tree.rebuild([this](int count, const std::function<void(int)>& task) {
      stepWorkers.stage(count, [&task](int block, int) { task(block); });
    });
  }
}

void WorldImpl::findNewContacts() {
  const StageClock clock(stage(&StepProfile::broadPhase));
  // In parallel, by blocks of moved proxies: the pairs their queries meet that have no contact
  // yet and may touch (reading only the tree, the keys and the bodies). Most of what a query
  // meets are old neighbours: ten thousand lookups a step in v3_tumbler.
  const int moved = static_cast<int>(movedProxies.size());
  const int blocks = (moved + kProxiesPerBlock - 1) / kProxiesPerBlock;
  scratch.newPairs.resize(static_cast<size_t>(blocks));
  scratch.queryStacks.resize(static_cast<size_t>(stepWorkers.threads()));
  stepWorkers.stage(blocks, [&](int block, int worker) {
    std::vector<NewPair>& out = scratch.newPairs[block].value;
    out.clear();
    const int end = std::min(moved, (block + 1) * kProxiesPerBlock);
    for (int k = block * kProxiesPerBlock; k < end; ++k) {
      const int proxy = movedProxies[k];
      if (!proxyMoved[proxy]) continue;  // destroyed since it moved
      tree.query(tree.fatAabb(proxy), scratch.queryStacks[worker].value, [&](int other) {
        // A pair of two moved proxies is reported by the lower one only; one whose filters refuse
        // it, by neither (world_impl.hpp, ProxyFilter).
        if (other == proxy || (proxyMoved[other] && other < proxy)) return;
        if (filtersRefuse(proxy, other)) return;
        out.push_back(NewPair{0, 0, 0, proxy, 0, 0, other});
      });
    }
    // Then the keys, after the queries: the tree's nodes and the key table stay apart in cache.
    // Each lookup misses the cache (a key's slot is anywhere in the table), so all keys are
    // made first and each slot asked for eight lookups ahead.
    size_t kept = 0;
    for (NewPair& pair : out) {
      pair.slotA = proxySlot(tree.userData(pair.proxyA));
      pair.shapeA = proxyShape(tree.userData(pair.proxyA));
      pair.slotB = proxySlot(tree.userData(pair.proxyB));
      pair.shapeB = proxyShape(tree.userData(pair.proxyB));
      if (pair.slotA > pair.slotB) {
        std::swap(pair.slotA, pair.slotB);
        std::swap(pair.shapeA, pair.shapeB);
        std::swap(pair.proxyA, pair.proxyB);
      }
      pair.key = contactKey(pair.slotA, pair.shapeA, pair.slotB, pair.shapeB);
    }
    constexpr size_t kKeysAhead = 8;
    for (size_t k = 0; k < out.size(); ++k) {
      if (k + kKeysAhead < out.size()) contactKeys.prefetch(out[k + kKeysAhead].key);
      const NewPair& pair = out[k];
      if (pair.slotA == pair.slotB) continue;
      if (contactKeys.contains(pair.key) || !shouldCollide(pair.slotA, pair.slotB)) continue;
      out[kept++] = pair;
    }
    out.resize(kept);
  });
  // proxyMoved stays set until the narrow phase has checked the contacts of the moved proxies.

  // The tree's shape depends on history; sorting by key makes the solve order depend only on
  // which pairs exist. The small pairs are sorted, and each contact is made once, in place.
  std::vector<NewPair>& fresh = scratch.freshPairs;
  fresh.clear();
  for (const auto& block : scratch.newPairs) {
    for (const NewPair& pair : block.value) {
      if (contactKeys.insert(pair.key)) fresh.push_back(pair);  // each pair is met once; a guard
    }
  }
  std::sort(fresh.begin(), fresh.end(),
            [](const NewPair& x, const NewPair& y) { return x.key < y.key; });
  for (const NewPair& pair : fresh) {
    Contact& contact = contacts.emplace_back();
    contact.key = pair.key;
    contact.bodyA = pair.slotA;
    contact.bodyB = pair.slotB;
    contact.shapeA = pair.shapeA;
    contact.shapeB = pair.shapeB;
    contact.proxyA = pair.proxyA;
    contact.proxyB = pair.proxyB;
    const Shape& sa = bodies.items[pair.slotA].shapes[pair.shapeA];
    const Shape& sb = bodies.items[pair.slotB].shapes[pair.shapeB];
    contact.friction = mixFriction(sa.friction, sb.friction);
    contact.restitution = mixRestitution(sa.restitution, sb.restitution);
  }
}

// The narrow phase waits on memory: a contact's two bodies and their shapes lie anywhere. So
// while it works on contact i, the bodies of contact i + 16 and the shapes of contact i + 8 are
// asked for (their bodies arrived by then); hints only, nothing computed changes.
void WorldImpl::prefetchPairAhead(size_t i, size_t last) const {
  constexpr size_t kBodiesAhead = 16, kShapesAhead = 8;
  if (i + kBodiesAhead < last) {
    const Contact& c = contacts[i + kBodiesAhead];
    const char* a = reinterpret_cast<const char*>(&bodies.items[c.bodyA]);
    const char* b = reinterpret_cast<const char*>(&bodies.items[c.bodyB]);
    __builtin_prefetch(a);
    __builtin_prefetch(a + 64);
    __builtin_prefetch(a + 128);
    __builtin_prefetch(b);
    __builtin_prefetch(b + 64);
    __builtin_prefetch(b + 128);
  }
  if (i + kShapesAhead < last) {
    const Contact& c = contacts[i + kShapesAhead];
    for (const auto& [slot, index] : {std::pair(c.bodyA, c.shapeA), std::pair(c.bodyB, c.shapeB)}) {
      const Shape* shape = bodies.items[slot].shapes.data() + index;
      const char* bytes = reinterpret_cast<const char*>(shape);
      __builtin_prefetch(bytes);
      __builtin_prefetch(bytes + 64);
      __builtin_prefetch(&shape->polygon.normals[0]);
      __builtin_prefetch(&shape->polygon.normals[3]);
      __builtin_prefetch(&shape->filter);
    }
  }
}

void WorldImpl::updateContacts() {
  const StageClock clock(stage(&StepProfile::narrowPhase));
  // In parallel: each contact's new manifold, or its mark to go (its fat boxes parted). Which
  // bodies move is read as the step found them, so the result does not depend on the order.
  enum : uint8_t { kKeep = 0, kDrop = 1, kWakeA = 2, kWakeB = 4 };
  std::vector<uint8_t>& contactFate = contactFates;
  contactFate.resize(contacts.size());
  stepWorkers.forRanges(
      static_cast<int>(contacts.size()), kContactsPerBlock, [&](int begin, int end, int) {
        const size_t last = static_cast<size_t>(end);
        for (size_t i = static_cast<size_t>(begin); i < last; ++i) {
          prefetchPairAhead(i, last);
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
  const StageClock clock(stage(&StepProfile::integrate));
  const MotionLimits limits = MotionLimits::of(def, dt);
  for (int e = 0; e < solverBodies.dynamicCount(); ++e) {
    SolverBody& body = solverBodies[e];
    if (body.invMass == 0.0) continue;  // overflowed earlier in this step (below)
    const SolverBodyLoad& load = solverBodies.load(e);
    double vx = body.linearVelocity.x(), vy = body.linearVelocity.y();
    applyLoad(loadOver(dt, def.gravity, body.invMass, body.invInertia, load.force, load.torque,
                       load.linearDamping, load.angularDamping),
              vx, vy, body.angularVelocity);
    body.linearVelocity = Vec2(vx, vy);
    limits.apply(body.linearVelocity, body.angularVelocity);
    // The last guard (body_load.hpp, isFiniteMotion): held still with infinite mass.
    if (!isFiniteMotion(body.linearVelocity.x(), body.linearVelocity.y(), body.angularVelocity)) {
      body.linearVelocity.setZero();
      body.angularVelocity = body.invMass = body.invInertia = 0.0;
      overflowedBodies.push_back(solverBodies.slotOf(e));
    }
  }
}

template <class Op>
void WorldImpl::onActiveJoints(Op op, bool pose) {
  for (const int j : activeJoints) {
    Joint& joint = joints.items[j];
    SolverBody a = solverBodies.view(joint.bodyA), b = solverBodies.view(joint.bodyB);
    op(joint, a, b);
    solverBodies.store(joint.bodyA, a, pose);
    solverBodies.store(joint.bodyB, b, pose);
  }
}

void WorldImpl::prepareJoints(const Feedback& fb, double dt) {
  const Feedback rigid;
  onActiveJoints(
      [&](Joint& j, SolverBody& a, SolverBody& b) {
        prepareJoint(j, a, b, def, j.feedbackWithheld ? rigid : fb, dt);
      },
      false);
}

void WorldImpl::warmStartJoints() {
  const MotionLimits limits = MotionLimits::of(def, def.timeStep);
  onActiveJoints([&](Joint& j, SolverBody& a, SolverBody& b) { warmStartJoint(j, a, b, limits); },
                 false);
}

void WorldImpl::solveJointVelocities(double dt) {
  onActiveJoints([&](Joint& j, SolverBody& a, SolverBody& b) { solveJointVelocity(j, a, b, dt); },
                 false);
}

void WorldImpl::solve(double dt) {
  StageLaps laps(profiled());
  syncJoints();  // a world switched from a sub-stepping solver (settings().solver)
  collectActiveJoints([&](int slot) { return solverBodies.isActive(slot); });
  Feedback fb;  // NGS: no bias, its position pass corrects the drift
  if (def.solver == SolverType::Baumgarte) fb.rate = def.baumgarte / dt;
  fb.maxPush = def.maxPushVelocity;
  if (def.solver == SolverType::Baumgarte) splitStressedJoints();
  prepareJoints(fb, dt);
  for (const int j : scratch.splitJoints) joints.items[j].feedbackWithheld = false;  // spent
  scratch.guardedJoints.clear();
  for (const int j : activeJoints) scratch.guardedJoints.push_back(&joints.items[j]);
  warmStartGuard.run(
      scratch.guardedJoints, contacts, solverBodies.dynamicCount(),
      [&](int slot) {
        const int entry = solverBodies.movingEntryOf(slot);
        return entry >= 0 && solverBodies.isDynamic(entry) ? entry : -1;
      },
      [&](int slot) { return solverBodies.view(slot); }, nullptr, nullptr, nullptr,
      def.gravity.norm() * dt, def.maxLinearSpeed, true);
  contactSolver.prepare(contacts, solverBodies, def, dt);
  laps.lap(&StepProfile::prepare);

  // Warm start: apply last step's impulses first, so the iterations only refine them.
  warmStartJoints();
  contactSolver.warmStart();
  laps.lap(&StepProfile::warmStart);

  for (int iteration = 0; iteration < def.velocityIterations; ++iteration) {
    solveJointVelocities(dt);
    contactSolver.solveVelocities();
  }
  laps.lap(&StepProfile::solve);
  contactSolver.applyRestitution(def.restitutionThreshold);
  contactSolver.storeImpulses();
  laps.lap(&StepProfile::restitution);
}

void WorldImpl::gatherSolverBodies() {
  const StageClock clock(stage(&StepProfile::prepare));
  weldClusters.find(bodies.items, movableSlots, joints.items, joints.alive, rigidWelds);
  solverBodies.gather(bodies.items, movableSlots, weldClusters);
}

void WorldImpl::storeMotion() {
  const StageClock clock(stage(&StepProfile::integrate));
  solverBodies.storeMotion(bodies.items);
}

void WorldImpl::integratePositions(double dt) {
  const StageClock clock(stage(&StepProfile::integrate));
  solverBodies.holdKinematicVelocities();
  const MotionLimits limits = MotionLimits::of(def, dt);
  capTurnsByJointReach(
      scratch.turnCaps, solverBodies.dynamicCount(), limits,
      [&](int slot) {
        const int entry = solverBodies.movingEntryOf(slot);
        return entry >= 0 && solverBodies.isDynamic(entry) ? entry : -1;
      },
      [&](int entry) { return solverBodies[entry].center; });
  scratch.onePassStarts.resize(static_cast<size_t>(solverBodies.dynamicCount()));
  for (int e = 0; e < solverBodies.movingCount(); ++e) {
    SolverBody& body = solverBodies[e];
    if (solverBodies.isDynamic(e)) {
      limits.apply(body.linearVelocity, body.angularVelocity, scratch.turnCaps.rate(e, limits));
      scratch.onePassStarts[e] = {body.center, body.angle};
    }
    body.center += dt * body.linearVelocity;
    turnBy(body, dt * body.angularVelocity);
  }
}

bool WorldImpl::isFast(const Body& body, const Vec2& move, double turn, double arm) const {
  // A body that moves less than a quarter of its own thickness in a step cannot skip past
  // anything as thick as itself, and its speculative contacts catch it before it sinks deep;
  // faster ones get the continuous pass.
  const double reach = move.norm() + std::abs(turn) * (arm + body.maxExtent);
  return reach > std::max(def.speculativeDistance, 0.25 * body.minExtent);
}

void WorldImpl::findOnePassFastBodies() {
  const StageClock clock(stage(&StepProfile::continuous));
  fastBodies.clear();
  fastClusters.clear();
  for (int e = 0; e < solverBodies.dynamicCount(); ++e) {
    const SolverBody& entry = solverBodies[e];
    const auto& [center0, angle0] = scratch.onePassStarts[e];
    noteIfFast(solverBodies.clusterRows(), e, solverBodies.slotOf(e), center0, angle0,
               entry.center - center0, entry.angle - angle0);
  }
}

void WorldImpl::noteIfFast(const ClusterRows& rows, int row, int slot, const Vec2& center0,
                           double angle0, const Vec2& move, double turn) {
  const auto [first, last] = rows.ofRow(row);
  if (first == last) {
    if (isFast(bodies.items[slot], move, turn, 0.0))
      fastBodies.push_back({slot, center0, angle0, -1});
    return;
  }
  bool fast = false;  // a welded cluster is swept whole when any member moved fast
  for (int k = first; k < last && !fast; ++k) {
    const MemberStart& m = rows.member(k);
    fast = isFast(bodies.items[m.slot], move, turn, m.offset.norm());
  }
  if (!fast) return;
  const int cluster = static_cast<int>(fastClusters.size());
  fastClusters.push_back({center0, move, turn, 1.0});
  for (int k = first; k < last; ++k) {
    const MemberStart& m = rows.member(k);
    fastBodies.push_back({m.slot, center0 + m.offset, m.angle0, cluster});
  }
}

void WorldImpl::correctPositions() {
  const StageClock clock(stage(&StepProfile::positions));
  if (def.solver == SolverType::Baumgarte) {  // only its far-open groups (splitStressedJoints)
    PositionPasses split;
    split.guarded = true;
    split.contacts = split.forgetImpulses = false;  // kept: see position_guard.hpp
    if (!scratch.splitJoints.empty()) {
      runPositionPasses(scratch.splitJoints, split);
      noteHeldOpen(scratch.splitJoints, 0.0);
    }
    return;
  }
  if (def.solver != SolverType::NonlinearGaussSeidel) return;
  PositionPasses all;
  all.guarded = positionGuard.armed();  // position_guard.hpp
  const double widest = runPositionPasses(activeJoints, all);
  if (widest > PositionGuard::kJudgedError) noteHeldOpen(activeJoints, PositionGuard::kJudgedError);
  positionGuard.settle(widest);
}

// A joint left far open (position_guard.hpp) holds its bodies by passes that their velocity does
// not see: a box on a soft weld open 9 m beside a wall, turned about its own anchor by the weld's
// angle spring, was pulled into the wall by the weld's pass and put back out by keepOutOfStatic,
// every step, its pose all but still while the spring sped it up (the core soak's ngs seed 159:
// 0.13 m/s more each step; by hand, 57 J of spring gave the box 460 J). So the bodies of a joint
// still open wider than `open` after the passes (0: every one) are noted with their start, and
// once nothing else moves them this step (dropMotionUndone) they keep, along their velocity and
// their turn, no more than the step moved them. Only speed is taken, never given.
void WorldImpl::noteHeldOpen(const std::vector<int>& slots, double open) {
  noteHeldOpenBodies(
      slots, open, [&](int slot) { return solverBodies.view(slot); },
      [&](int slot) {
        const int e = solverBodies.movingEntryOf(slot);
        // A welded cluster is left alone: its entry's start is the cluster's, not a member's.
        if (e < 0 || !solverBodies.isDynamic(e)) return;
        const auto [first, last] = solverBodies.clusterRows().ofRow(e);
        if (first != last) return;
        const auto& [center0, angle0] = scratch.onePassStarts[e];
        scratch.heldOpen.push_back({slot, center0, angle0});
      });
}

void WorldImpl::dropMotionUndone() {
  const double dt = def.timeStep;
  for (const StepScratch::HeldOpen& held : scratch.heldOpen) {
    Body& body = bodies.items[held.slot];
    const double speedSquared = body.linearVelocity.squaredNorm();
    if (speedSquared > 0.0) {
      const double share =
          (body.center - held.center0).dot(body.linearVelocity) / (speedSquared * dt);
      if (share < 1.0) body.linearVelocity *= std::max(0.0, share);
    }
    const double w = body.angularVelocity;
    if (w != 0.0) {
      const double share = (body.angle - held.angle0) / (w * dt);
      if (share < 1.0) body.angularVelocity = w * std::max(0.0, share);
    }
  }
  scratch.heldOpen.clear();
}

double WorldImpl::runPositionPasses(const std::vector<int>& slots, const PositionPasses& passes) {
  const auto visitJoints = [&](const auto& note) { visitOnePassJointErrors(slots, note); };
  double widest = 0.0;    // the widest joint error the last pass met
  noteOnePassFarReach();  // world_substeps.cpp, noteFarReach
  int passCount = 0;
  for (int iteration = 0; iteration < def.positionIterations; ++iteration) {
    ++passCount;
    bool jointsOk = true;
    widest = 0.0;
    const auto moveJoints = [&] {
      for (const int j : slots) {
        Joint& joint = joints.items[j];
        SolverBody a = solverBodies.view(joint.bodyA), b = solverBodies.view(joint.bodyB);
        const PositionError error = solveJointPosition(joint, a, b);
        widest = std::max({widest, error.linear, error.angular});
        jointsOk = jointsOk && error.within(def.linearSlop);
        solverBodies.store(joint.bodyA, a, true);
        solverBodies.store(joint.bodyB, b, true);
      }
    };
    if (passes.guarded) {  // the joints' part of the pass is kept only where it closed them
      positionGuard.guardPass(
          solverBodies.dynamicCount(), visitJoints, iteration == 0,
          [&] {
            scratch.guardedBodies.assign(solverBodies.data(),
                                         solverBodies.data() + solverBodies.dynamicCount());
          },
          moveJoints, [&](int entry) { solverBodies[entry] = scratch.guardedBodies[entry]; },
          [&](size_t k) {
            if (passes.forgetImpulses) scaleJointImpulses(joints.items[slots[k]], 0.0);
          });
    } else {
      moveJoints();
    }
    const bool contactsOk = !passes.contacts || contactSolver.solvePositions(def);
    if (jointsOk && contactsOk) break;
  }
  boundOnePassFarReach(passCount);
  return widest;
}

void WorldImpl::noteOnePassFarReach() {
  scratch.onePassFarReaching.clear();
  for (int e = 0; e < solverBodies.dynamicCount() && def.positionIterations > 0; ++e) {
    const double reach = reachOf(solverBodies.clusterRows(), e, solverBodies.slotOf(e));
    if (reach > kLongestFreeReach)
      scratch.onePassFarReaching.push_back({e, reach, solverBodies[e]});
  }
}

void WorldImpl::boundOnePassFarReach(int passes) {
  for (const StepScratch::OnePassFarReach& far : scratch.onePassFarReaching) {
    SolverBody& body = solverBodies[far.entry];
    const SolverBody& before = far.before;
    const Vec2 move = body.center - before.center;
    const double turn = body.angle - before.angle;
    const double share = farReachShare(move.norm(), turn, far.reach, passes);
    if (share >= 1.0) continue;
    body.center = before.center + share * move;
    body.angle = before.angle + share * turn;
    body.q = Rot(body.angle);
  }
}

// Baumgarte's bias is momentum: a group of joints that cannot all hold, pushed by it, flew (a
// pinned chain given random joints, 2,460 m from its pin at up to 400 m/s). A group far open at
// the step's start is solved as ngs solves it instead (position_guard.hpp).
void WorldImpl::splitStressedJoints() {
  std::vector<int>& split = scratch.splitJoints;
  split.clear();
  positionGuard.measureStepStart(
      solverBodies.dynamicCount(), [&](const auto& note) { visitJointErrors(note); }, false);
  if (!positionGuard.armed()) return;
  positionGuard.forEachJudgedJoint([&](size_t j) {
    Joint& joint = joints.items[activeJoints[j]];
    joint.feedbackWithheld = true;
    split.push_back(activeJoints[j]);
    for (const int slot : {joint.bodyA, joint.bodyB}) {
      if (solverBodies.isActive(slot)) contactSolver.withholdPush(slot);
    }
  });
}

void WorldImpl::clearForces() {
  for (const int i : movableSlots) {  // a static body never gathers a force
    bodies.items[i].force.setZero();
    bodies.items[i].torque = 0.0;
  }
}

}  // namespace impulse2d
