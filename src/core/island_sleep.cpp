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
  const StageClock clock(stage(&StepProfile::sleep));
  const int slotCount = static_cast<int>(bodies.items.size());
  if (!def.enableSleep) {
    // Nothing may sleep, so no islands are needed. Bodies put to sleep before sleeping was
    // switched off wake up, and stillness counts from zero once it is switched back on.
    for (int i = 0; i < slotCount; ++i) {
      if (bodies.alive[i] && bodies.items[i].type == BodyType::Dynamic) wakeBody(bodies.items[i]);
    }
    return;
  }
  const double linTol2 = def.sleepLinearTolerance * def.sleepLinearTolerance;
  const double angTol2 = def.sleepAngularTolerance * def.sleepAngularTolerance;

  // Contacts per body as a compressed adjacency list (counts, then offsets), rebuilt each step
  // into reused buffers.
  adjacencyStart.assign(slotCount + 1, 0);
  for (const Contact& c : contacts) {
    if (!isTouching(c)) continue;
    ++adjacencyStart[c.bodyA + 1];
    ++adjacencyStart[c.bodyB + 1];
  }
  for (int i = 0; i < slotCount; ++i) adjacencyStart[i + 1] += adjacencyStart[i];
  adjacency.resize(adjacencyStart[slotCount]);
  adjacencyFill.assign(adjacencyStart.begin(), adjacencyStart.end() - 1);
  for (const Contact& c : contacts) {
    if (!isTouching(c)) continue;
    adjacency[adjacencyFill[c.bodyA]++] = c.bodyB;
    adjacency[adjacencyFill[c.bodyB]++] = c.bodyA;
  }

  for (int i = 0; i < slotCount; ++i) {
    if (!movable[i]) continue;  // static bodies are never flagged: only dynamic ones join islands
    Body& body = bodies.items[i];
    body.islandFlag = 0;
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
  for (int seed = 0; seed < slotCount; ++seed) {
    if (!movable[seed]) continue;
    Body& start = bodies.items[seed];
    if (start.type != BodyType::Dynamic || !start.awake || start.islandFlag) {
      continue;
    }
    island.clear();
    islandStack.clear();
    islandStack.push_back(seed);
    start.islandFlag = 1;
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
        if (next.type != BodyType::Dynamic || next.islandFlag) return;
        next.islandFlag = 1;
        islandStack.push_back(other);
      };
      for (int k = adjacencyStart[index]; k < adjacencyStart[index + 1]; ++k) visit(adjacency[k]);
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
