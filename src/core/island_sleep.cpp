// Sleeping: bodies connected by touching contacts or joints form an island; when every body of an
// island has been still for timeToSleep, the whole island sleeps. Sleeping bodies are neither
// integrated, nor refitted in the broad phase, nor solved, so a settled pile costs nothing.
// Static bodies join no island: a box on the ground sleeps on its own, not with everything else
// that happens to rest on the same ground. Kinematic bodies join none either, but a moving one
// keeps what touches it awake.
//
// The islands are found anew each step by union-find over the dynamic bodies' places in
// movableSlots: one pass over the contacts and joints links bodies, then each island is read at
// its root. An island with an awake body wakes its sleepers (something touches them); islands
// of sleepers only are left as they are.
#include <limits>

#include "world_impl.hpp"

namespace impulse2d {
namespace {

bool isTouching(const Contact& contact) {
  for (int i = 0; i < contact.manifold.pointCount; ++i) {
    if (contact.manifold.points[i].separation <= 0.0 || contact.normalImpulse[i] > 0.0) return true;
  }
  return false;
}

bool isMovingKinematic(const Body& body) {
  return body.type == BodyType::Kinematic && isMoving(body);
}

// What a link to a movable body does: a dynamic body joins the island; a moving kinematic one
// holds the dynamic body it touches awake; a kinematic one at rest does neither.
enum : uint8_t { kJoinsIsland, kHoldsIsland, kNoLink };

// The root of place k's island; halves the path on the way, so chains stay short.
int rootOf(std::vector<int>& parent, int k) {
  while (parent[k] != k) {
    parent[k] = parent[parent[k]];
    k = parent[k];
  }
  return k;
}

}  // namespace

// A sleeping body jointed to a moving one wakes before the solver runs, and so does everything
// jointed to it. Asleep, it would hold its joints like a static anchor: a force on one of two
// roped boxes at rest was taken up by the rope for a whole step, and lost. (Contacts wake what
// moving bodies touch in the narrow phase; updateSleep wakes the rest of the island after.)
void WorldImpl::wakeJointedSleepers() {
  if (joints.count() == 0) return;
  const StageClock clock(stage(&StepProfile::sleep));
  // With no body asleep there is nothing to wake: the common case of a busy world, checked
  // before walking every joint (v3_joint_grid's 20,000 joints cost 2.8 ms a step for nothing).
  bool anyAsleep = false;
  for (const int slot : movableSlots) {
    const Body& body = bodies.items[slot];
    if (body.type == BodyType::Dynamic && !body.awake) {
      anyAsleep = true;
      break;
    }
  }
  if (!anyAsleep) return;
  std::vector<int>& stack = scratch.wakeStack;
  stack.clear();
  for (size_t j = 0; j < joints.items.size(); ++j) {  // by joint: a step's cost follows them
    if (!joints.alive[j]) continue;
    for (const int slot : {jointBodies[j].first, jointBodies[j].second}) {
      if (isMoving(bodies.items[slot])) stack.push_back(slot);
    }
  }
  while (!stack.empty()) {
    const int slot = stack.back();
    stack.pop_back();
    for (const int j : jointsOfBody[slot]) {
      const auto [bodyA, bodyB] = jointBodies[j];
      const int other = bodyA == slot ? bodyB : bodyA;
      Body& body = bodies.items[other];
      if (body.type != BodyType::Dynamic || body.awake) continue;
      wakeBody(body);
      stack.push_back(other);
    }
  }
}

void WorldImpl::updateSleep(double dt) {
  const StageClock clock(stage(&StepProfile::sleep));
  if (!def.enableSleep) {
    // Nothing may sleep, so no islands are needed. Bodies put to sleep before sleeping was
    // switched off wake up, and stillness counts from zero once it is switched back on. In
    // parallel blocks: a write to every body, each its own.
    stepWorkers.forRanges(static_cast<int>(movableSlots.size()), kBodiesPerBlock,
                          [&](int begin, int end, int) {
                            for (int k = begin; k < end; ++k) {
                              Body& body = bodies.items[movableSlots[static_cast<size_t>(k)]];
                              if (body.type == BodyType::Dynamic) wakeBody(body);
                            }
                          });
    return;
  }
  const double linTol2 = def.sleepLinearTolerance * def.sleepLinearTolerance;
  const double angTol2 = def.sleepAngularTolerance * def.sleepAngularTolerance;

  // By movable place, what a link to the body does (kJoinsIsland, ...): read here, with the bodies,
  // so that the links need not read them again.
  const int movableCount = static_cast<int>(movableSlots.size());
  std::vector<uint8_t>& kind = scratch.islandKind;
  kind.resize(static_cast<size_t>(movableCount));
  bool anyAwake = false, anyAsleep = false;
  bool mayBeStill = false;  // before the deep overlaps' resets, which only make bodies less still
  for (int k = 0; k < movableCount; ++k) {
    Body& body = bodies.items[movableSlots[k]];
    kind[k] = body.type == BodyType::Dynamic ? kJoinsIsland
              : isMovingKinematic(body)      ? kHoldsIsland
                                             : kNoLink;
    if (isActive(body)) {
      anyAwake = true;
      const bool still = body.linearVelocity.squaredNorm() <= linTol2 &&
                         body.angularVelocity * body.angularVelocity <= angTol2;
      body.sleepTime = still ? body.sleepTime + dt : 0.0;
      mayBeStill = mayBeStill || body.sleepTime >= def.timeToSleep;
    } else if (body.type == BodyType::Dynamic) {
      anyAsleep = true;
    }
  }
  // The islands are needed only where one may wake or fall asleep (below): a busy world collects
  // no links.
  const bool mayLink = anyAwake && (anyAsleep || mayBeStill);
  // One parallel pass over the contacts (a pile's contacts outnumber its bodies five to one, and
  // reading them twice on one thread was most of this stage): the overlaps too deep to rest, and
  // the touching pairs of movable bodies (places), which the islands link. The NGS pass moves
  // overlapping bodies apart without giving them velocity: a body still being pushed out of an
  // overlap is not at rest.
  const int contactCount = static_cast<int>(contacts.size());
  auto& ofBlock = scratch.sleepContactsOfBlock;
  ofBlock.resize(static_cast<size_t>(contactCount + kContactsPerBlock - 1) / kContactsPerBlock);
  stepWorkers.forRanges(contactCount, kContactsPerBlock, [&](int begin, int end, int) {
    StepScratch::SleepContacts& found =
        ofBlock[static_cast<size_t>(begin / kContactsPerBlock)].value;
    found.deep.clear();
    found.links.clear();
    for (size_t i = static_cast<size_t>(begin); i < static_cast<size_t>(end); ++i) {
      const Contact& c = contacts[i];
      for (int k = 0; k < c.manifold.pointCount; ++k) {
        if (c.manifold.points[k].separation < -2.0 * def.linearSlop) {
          found.deep.emplace_back(c.bodyA, c.bodyB);
          break;  // both bodies are reset once
        }
      }
      // Static bodies join no island (movableIndex tells them without reading the bodies).
      if (mayLink && isMovable(c.bodyA) && isMovable(c.bodyB) && isTouching(c)) {
        found.links.emplace_back(movableIndex[c.bodyA], movableIndex[c.bodyB]);
      }
    }
  });
  for (const auto& block : ofBlock) {
    for (const auto& [slotA, slotB] : block.value.deep) {
      bodies.items[slotA].sleepTime = 0.0;
      bodies.items[slotB].sleepTime = 0.0;
    }
  }
  if (!anyAwake) return;  // no island has a body awake: none wakes, none falls asleep
  bool anyStill = false;
  for (const int i : movableSlots) {
    const Body& body = bodies.items[i];
    anyStill = anyStill || (isActive(body) && body.sleepTime >= def.timeToSleep);
  }
  // No awake body has been still long enough, so no island can fall asleep; and with no sleeper
  // there is nothing to wake. The common case of a busy world.
  if (!anyStill && !anyAsleep) return;

  // Link the dynamic bodies that touch or are jointed; mark those a moving kinematic body
  // touches or holds.
  std::vector<int>& parent = scratch.islandParent;
  std::vector<uint8_t>& held = scratch.islandHeld;
  parent.resize(static_cast<size_t>(movableCount));
  for (int k = 0; k < movableCount; ++k) parent[k] = k;
  held.assign(static_cast<size_t>(movableCount), 0);
  auto link = [&](int placeA, int placeB) {
    if (kind[placeA] == kJoinsIsland && kind[placeB] == kJoinsIsland) {
      const int rootA = rootOf(parent, placeA);
      const int rootB = rootOf(parent, placeB);
      if (rootA < rootB) parent[rootB] = rootA;
      if (rootB < rootA) parent[rootA] = rootB;
    } else if (kind[placeA] == kJoinsIsland && kind[placeB] == kHoldsIsland) {
      held[placeA] = 1;
    } else if (kind[placeB] == kJoinsIsland && kind[placeA] == kHoldsIsland) {
      held[placeB] = 1;
    }
  };
  for (const auto& block : ofBlock) {
    for (const auto& [placeA, placeB] : block.value.links) link(placeA, placeB);
  }
  // Every joint once, in slot order (its bodies' lists would be a cache miss each): a root is
  // always its island's lowest index, whatever the order of the links.
  for (size_t j = 0; j < jointBodies.size(); ++j) {
    const auto [slotA, slotB] = jointBodies[j];
    if (joints.alive[j] && isMovable(slotA) && isMovable(slotB)) {
      link(movableIndex[slotA], movableIndex[slotB]);
    }
  }

  // Each island at its root: whether a body of it is awake, then (its sleepers woken) the least
  // time any of its bodies has been still, 0 when a moving kinematic body holds one.
  std::vector<uint8_t>& awakeIsland = scratch.islandAwake;
  std::vector<double>& stillFor = scratch.islandStillFor;
  awakeIsland.assign(static_cast<size_t>(movableCount), 0);
  stillFor.assign(static_cast<size_t>(movableCount), std::numeric_limits<double>::infinity());
  for (int k = 0; k < movableCount; ++k) {
    const Body& body = bodies.items[movableSlots[k]];
    if (body.type == BodyType::Dynamic && body.awake) awakeIsland[rootOf(parent, k)] = 1;
  }
  for (int k = 0; k < movableCount; ++k) {
    Body& body = bodies.items[movableSlots[k]];
    if (body.type != BodyType::Dynamic) continue;
    const int root = rootOf(parent, k);
    if (!awakeIsland[root]) continue;
    if (!body.awake) wakeBody(body);
    stillFor[root] = std::min(stillFor[root], held[k] ? 0.0 : body.sleepTime);
  }
  for (int k = 0; k < movableCount; ++k) {
    Body& body = bodies.items[movableSlots[k]];
    if (body.type != BodyType::Dynamic) continue;
    const int root = rootOf(parent, k);
    if (!awakeIsland[root] || stillFor[root] < def.timeToSleep) continue;
    body.awake = false;
    body.linearVelocity.setZero();
    body.angularVelocity = 0.0;
  }
}

}  // namespace impulse2d
