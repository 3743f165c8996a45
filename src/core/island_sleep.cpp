// Sleeping: bodies connected by touching contacts or joints form an island; when every body of an
// island has been still for timeToSleep, the whole island sleeps. Sleeping bodies are neither
// integrated, nor refitted in the broad phase, nor solved, so a settled pile costs nothing.
// Static bodies join no island: a box on the ground sleeps on its own, not with everything else
// that happens to rest on the same ground.
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

}  // namespace

void WorldImpl::updateSleep(double dt) {
  std::vector<int>& adjacencyStart = scratch.adjacencyStart;
  std::vector<int>& adjacencyFill = scratch.adjacencyFill;
  std::vector<int>& adjacency = scratch.adjacency;
  std::vector<int>& island = scratch.island;
  std::vector<int>& islandStack = scratch.islandStack;
  const StageClock clock(stage(&StepProfile::sleep));
  if (!def.enableSleep) {
    // Nothing may sleep, so no islands are needed. Bodies put to sleep before sleeping was
    // switched off wake up, and stillness counts from zero once it is switched back on.
    for (const int i : movableSlots) {
      if (bodies.items[i].type == BodyType::Dynamic) wakeBody(bodies.items[i]);
    }
    return;
  }
  const double linTol2 = def.sleepLinearTolerance * def.sleepLinearTolerance;
  const double angTol2 = def.sleepAngularTolerance * def.sleepAngularTolerance;

  // Contacts per body that moves, as a compressed adjacency list (counts, then offsets) by its
  // place in movableSlots, rebuilt each step into reused buffers. Static bodies have none: the
  // flood fill below never goes on from one, so theirs would never be read.
  const int movableCount = static_cast<int>(movableSlots.size());
  adjacencyStart.assign(movableCount + 1, 0);
  for (const Contact& c : contacts) {
    if (!isTouching(c)) continue;
    if (isMovable(c.bodyA)) ++adjacencyStart[movableIndex[c.bodyA] + 1];
    if (isMovable(c.bodyB)) ++adjacencyStart[movableIndex[c.bodyB] + 1];
  }
  for (int k = 0; k < movableCount; ++k) adjacencyStart[k + 1] += adjacencyStart[k];
  adjacency.resize(adjacencyStart[movableCount]);
  adjacencyFill.assign(adjacencyStart.begin(), adjacencyStart.end() - 1);
  for (const Contact& c : contacts) {
    if (!isTouching(c)) continue;
    if (isMovable(c.bodyA)) adjacency[adjacencyFill[movableIndex[c.bodyA]]++] = c.bodyB;
    if (isMovable(c.bodyB)) adjacency[adjacencyFill[movableIndex[c.bodyB]]++] = c.bodyA;
  }

  // Static bodies are never flagged: only dynamic ones join islands.
  for (const int i : movableSlots) {
    Body& body = bodies.items[i];
    bookkeeping[i].islandFlag = 0;
    if (body.type != BodyType::Dynamic || !body.awake) continue;
    const bool still = body.linearVelocity.squaredNorm() <= linTol2 &&
                       body.angularVelocity * body.angularVelocity <= angTol2;
    body.sleepTime = still ? body.sleepTime + dt : 0.0;
  }
  // The NGS pass moves overlapping bodies apart without giving them velocity: a body still being
  // pushed out of an overlap is not at rest.
  for (const Contact& c : contacts) {
    for (int i = 0; i < c.manifold.pointCount; ++i) {
      if (c.manifold.points[i].separation < -2.0 * def.linearSlop) {
        bodies.items[c.bodyA].sleepTime = 0.0;
        bodies.items[c.bodyB].sleepTime = 0.0;
      }
    }
  }

  // Flood fill from each awake dynamic body. A sleeping body reached from an awake one is woken:
  // something touches it.
  for (const int seed : movableSlots) {
    Body& start = bodies.items[seed];
    if (start.type != BodyType::Dynamic || !start.awake || bookkeeping[seed].islandFlag) {
      continue;
    }
    island.clear();
    islandStack.clear();
    islandStack.push_back(seed);
    bookkeeping[seed].islandFlag = 1;
    double minSleepTime = std::numeric_limits<double>::infinity();
    while (!islandStack.empty()) {
      const int index = islandStack.back();
      islandStack.pop_back();
      Body& body = bodies.items[index];
      island.push_back(index);
      if (!body.awake) wakeBody(body);
      minSleepTime = std::min(minSleepTime, body.sleepTime);
      auto visit = [&](int other) {
        Body& next = bodies.items[other];
        if (next.type == BodyType::Kinematic &&
            (next.linearVelocity.squaredNorm() > 0.0 || next.angularVelocity != 0.0)) {
          minSleepTime = 0.0;  // a moving kinematic body keeps what it touches awake
        }
        int& flag = bookkeeping[other].islandFlag;
        if (next.type != BodyType::Dynamic || flag) return;
        flag = 1;
        islandStack.push_back(other);
      };
      const int place = movableIndex[index];
      for (int k = adjacencyStart[place]; k < adjacencyStart[place + 1]; ++k) visit(adjacency[k]);
      for (const int j : jointsOfBody[index]) {
        const Joint& joint = joints.items[j];
        visit(joint.bodyA == index ? joint.bodyB : joint.bodyA);
      }
    }
    if (minSleepTime < def.timeToSleep) continue;
    for (const int index : island) {
      Body& body = bodies.items[index];
      body.awake = false;
      body.linearVelocity.setZero();
      body.angularVelocity = 0.0;
    }
  }
}

}  // namespace impulse2d
