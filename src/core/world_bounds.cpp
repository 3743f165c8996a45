// The step stage that keeps the world finite and says what it lost. A body that flew beyond
// kWorldExtent, or whose velocity stopped being finite (integrateVelocities froze it), is removed
// with its joints and contacts and reported, rather than left to poison the broad phase and its
// neighbours with non-finite numbers. A body that fell below every static body, with nothing
// left that could stop it, is reported as lost for good, and removed then if the world says so.
#include "world_impl.hpp"

#include <impulse2d/limits.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace impulse2d {
namespace {

// Reports kept between two take...() calls; a caller that never asks cannot make the lists grow
// without bound.
constexpr size_t kMaxReports = 1024;

// Null while the body may stay, else why it goes.
const char* escapeReason(const Body& body, RemovalCause* cause) {
  const bool finite = isFinite(body.center) && isFinite(body.xf.p) && std::isfinite(body.angle) &&
                      isFinite(body.linearVelocity) && std::isfinite(body.angularVelocity);
  if (!finite) {
    *cause = RemovalCause::Overflow;
    return "its state stopped being finite";
  }
  if (std::abs(body.center.x()) > kWorldExtent || std::abs(body.center.y()) > kWorldExtent) {
    *cause = RemovalCause::LeftWorldExtent;
    return "it left the world extent of 1e7 m";
  }
  return nullptr;
}

std::string metres(double m) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.4g m", m);
  return text;
}

// Where "down" is (along gravity, whatever its direction) and how deep the static bodies reach:
//
//      -----------------------   <- shallowest static point   }
//        | static bodies |                                     } height
//      -----------------------   <- deepest static point      }
//                  :                                           } height
//   - - - - - - - - - - - - - - - - - - - - - - - - - - - - -  <- deepest + height
//              [ ]  a body whose top is below this line, not rising: lost for good
//
// Measured on the static bodies' bounding box, kept until they change: along a slanted gravity
// its corners reach a little deeper than the shapes do, which only makes the line lower.
struct Floor {
  Vec2 down = Vec2::Zero();
  double deepest = 0.0;
  double height = 0.0;

  double top(const Body& body) const { return down.dot(body.center) - body.maxExtent; }
  double bottom(const Body& body) const { return down.dot(body.center) + body.maxExtent; }
};

// How far the box reaches along d: the largest dot(p, d) over its corners.
double deepestCorner(const Aabb& box, const Vec2& d) {
  return std::max(box.lower.x() * d.x(), box.upper.x() * d.x()) +
         std::max(box.lower.y() * d.y(), box.upper.y() * d.y());
}

}  // namespace

void WorldImpl::refreshStaticBounds() {
  if (!staticBoundsStale) return;
  staticBoundsStale = false;
  hasStaticBodies = false;
  for (size_t i = 0; i < bodies.items.size(); ++i) {
    const Body& body = bodies.items[i];
    if (!bodies.alive[i] || body.type != BodyType::Static) continue;
    for (const Shape& shape : body.shapes) {
      const Aabb box = computeAabb(shape, body.xf);
      staticBounds = hasStaticBodies ? staticBounds.united(box) : box;
      hasStaticBodies = true;
    }
  }
}

void WorldImpl::findLostBodies(std::vector<RemovedBody>* removeLost) {
  const double g = def.gravity.norm();
  if (!(g > 0.0)) return;  // nothing falls (top-down scenes): nothing is lost below
  refreshStaticBounds();
  if (!hasStaticBodies) return;  // nothing to fall off
  Floor floor;
  floor.down = def.gravity / g;
  floor.deepest = deepestCorner(staticBounds, floor.down);
  floor.height = floor.deepest + deepestCorner(staticBounds, -floor.down);

  // Awake dynamic bodies only: a sleeping one rests on something, and static bodies cost
  // nothing here. Each body is read once, in parallel blocks (a cache miss each), for its depth
  // and, if kinematic, for how low it reaches (one below the static ones may still catch a
  // body); then the candidates are listed in order.
  std::vector<int>& candidates = scratch.lostCandidates;
  std::vector<double>& tops = scratch.lostTops;  // by movable place, then by candidate
  const int count = static_cast<int>(movableSlots.size());
  tops.resize(movableSlots.size());
  scratch.kinematicBottoms.assign((movableSlots.size() + kBodiesPerBlock - 1) / kBodiesPerBlock,
                                  floor.deepest);
  stepWorkers.forRanges(count, kBodiesPerBlock, [&](int begin, int end, int) {
    double& kinematicBottom =
        scratch.kinematicBottoms[static_cast<size_t>(begin / kBodiesPerBlock)];
    for (int k = begin; k < end; ++k) {
      const int i = movableSlots[static_cast<size_t>(k)];
      const Body& body = bodies.items[i];
      double& top = tops[static_cast<size_t>(k)];
      top = -std::numeric_limits<double>::infinity();  // not a candidate
      if (body.type == BodyType::Kinematic) {
        kinematicBottom = std::max(kinematicBottom, floor.bottom(body));
      }
      if (body.type != BodyType::Dynamic || !body.awake) continue;
      if (floor.top(body) > floor.deepest + floor.height) {
        top = floor.top(body);
      } else {
        bookkeeping[i].lost = false;  // back, or never gone
      }
    }
  });
  candidates.clear();
  for (int k = 0; k < count; ++k) {
    const double top = tops[static_cast<size_t>(k)];
    if (top > floor.deepest + floor.height) {
      tops[candidates.size()] = top;  // never ahead of k
      candidates.push_back(movableSlots[static_cast<size_t>(k)]);
    }
  }
  if (candidates.empty()) return;
  double floorLine = floor.deepest;
  for (const double bottom : scratch.kinematicBottoms) floorLine = std::max(floorLine, bottom);
  // 0: not a candidate, 1: a candidate, 2: a candidate already grouped (or known held).
  std::vector<char>& mark = scratch.lostCandidateMark;
  mark.assign(bodies.items.size(), 0);
  for (size_t c = 0; c < candidates.size(); ++c) {
    const int slot = candidates[c];
    const bool below = tops[c] > floorLine + floor.height;
    mark[slot] = below ? 1 : 0;
    if (!below) bookkeeping[slot].lost = false;
  }

  // Bodies joined by joints go together: a joint to anything that is not below (a body above,
  // a static pin) holds the whole group (a chain hanging from a ledge, a rope over the edge),
  // and a group that rises as a whole (thrown up, bouncing off another) may still come back.
  // A group is held exactly when its jointed component has a body that is no candidate (the
  // component is connected: a group short of all of it has a neighbour outside, which would be
  // in the group if it were a candidate). So the candidates of such components are held without
  // a walk (v3_joint_grid hangs from seven pins: 10,000 candidates, every step), and only the
  // components of candidates alone are walked, in the same order as before.
  jointNeighbours.refresh(jointsOfBody, jointBodies);
  std::vector<int>& inComponent = scratch.candidatesInComponent;
  inComponent.assign(static_cast<size_t>(jointNeighbours.componentCount()), 0);
  for (const int slot : candidates) {
    if (mark[slot] == 1) ++inComponent[static_cast<size_t>(jointNeighbours.componentOf(slot))];
  }
  for (const int slot : candidates) {
    const int component = jointNeighbours.componentOf(slot);
    if (mark[slot] != 1 ||
        inComponent[static_cast<size_t>(component)] == jointNeighbours.componentSize(component)) {
      continue;
    }
    mark[slot] = 2;
    bookkeeping[slot].lost = false;
  }
  std::vector<int>& group = scratch.lostGroup;
  for (const int first : candidates) {
    if (mark[first] != 1) continue;
    group.assign(1, first);
    mark[first] = 2;
    bool held = false;
    for (size_t k = 0; k < group.size(); ++k) {
      const int slot = group[k];
      for (const int* it = jointNeighbours.begin(slot); it != jointNeighbours.end(slot); ++it) {
        const int other = *it;
        if (mark[other] == 0) held = true;
        if (mark[other] == 1) {
          mark[other] = 2;
          group.push_back(other);
        }
      }
    }
    // Only a group that nothing holds reads its bodies (a grid hanging from a few pins is all
    // candidates, every step).
    double momentumDown = 0.0;
    if (!held) {
      for (const int slot : group) {
        const Body& body = bodies.items[slot];
        momentumDown += body.mass * floor.down.dot(body.linearVelocity);
      }
    }
    const bool lost = !held && momentumDown >= 0.0;
    for (const int slot : group) {
      const bool reported = bookkeeping[slot].lost;
      bookkeeping[slot].lost = lost;
      if (!lost || (reported && !def.removeLostBodies)) continue;
      const Body& body = bodies.items[slot];
      const double depth = floor.top(body) - floor.deepest;
      std::string reason = "lost for good: it fell " + metres(depth) +
                           " below every static body, more than their height of " +
                           metres(floor.height) + ", and nothing can stop it";
      if (def.removeLostBodies) {
        removeLost->push_back(RemovedBody{body.id, body.name, body.xf.p, std::move(reason),
                                          RemovalCause::LostForGood});
        continue;
      }
      ++lostBodyCount;
      if (lostBodies.size() < kMaxReports) {
        lostBodies.push_back(LostBody{body.id, body.name, body.xf.p, depth, std::move(reason)});
      }
    }
  }
}

void JointNeighbours::refresh(const std::vector<std::vector<int>>& jointsOfBody,
                              const std::vector<std::pair<int, int>>& jointBodies) {
  if (valid_) return;
  valid_ = true;
  start_.assign(1, 0);
  others_.clear();
  for (size_t slot = 0; slot < jointsOfBody.size(); ++slot) {
    for (const int j : jointsOfBody[slot]) {
      const auto [bodyA, bodyB] = jointBodies[static_cast<size_t>(j)];
      others_.push_back(bodyA == static_cast<int>(slot) ? bodyB : bodyA);
    }
    start_.push_back(static_cast<int>(others_.size()));
  }
  component_.assign(jointsOfBody.size(), -1);
  componentSize_.clear();
  for (size_t first = 0; first < jointsOfBody.size(); ++first) {
    if (component_[first] >= 0) continue;
    const int component = static_cast<int>(componentSize_.size());
    componentSize_.push_back(0);
    component_[first] = component;
    stack_.assign(1, static_cast<int>(first));
    while (!stack_.empty()) {
      const int slot = stack_.back();
      stack_.pop_back();
      ++componentSize_.back();
      for (const int* it = begin(slot); it != end(slot); ++it) {
        const int other = *it;
        if (component_[static_cast<size_t>(other)] >= 0) continue;
        component_[static_cast<size_t>(other)] = component;
        stack_.push_back(other);
      }
    }
  }
}

void World::removeEscapedBodies() {
  const StageClock clock(impl_->stage(&StepProfile::sleep));
  WorldImpl& w = *impl_;
  auto remove = [&w, this](RemovedBody report) {
    const BodyId id = report.id;
    if (w.removedBodies.size() < kMaxReports) w.removedBodies.push_back(std::move(report));
    ++w.removedBodyCount;
    destroyBody(id);
  };
  for (const int slot : w.overflowedBodies) {
    if (!w.bodies.alive[slot]) continue;
    const Body& body = w.bodies.items[slot];
    remove(RemovedBody{body.id, body.name, body.xf.p, "its velocity stopped being finite",
                       RemovalCause::Overflow});
  }
  w.overflowedBodies.clear();
  // Only what moves can leave: static bodies never do (the solver never writes them), and
  // sleeping ones have not moved since they were checked.
  // Each body read in parallel blocks, the reports then made in order.
  std::vector<std::pair<const char*, RemovalCause>>& escapes = w.scratch.escapes;
  const int count = static_cast<int>(w.movableSlots.size());
  escapes.resize(w.movableSlots.size());
  w.stepWorkers.forRanges(count, kBodiesPerBlock, [&](int begin, int end, int) {
    for (int k = begin; k < end; ++k) {
      const Body& body = w.bodies.items[w.movableSlots[static_cast<size_t>(k)]];
      auto& [why, cause] = escapes[static_cast<size_t>(k)];
      why = body.awake ? escapeReason(body, &cause) : nullptr;
    }
  });
  std::vector<RemovedBody> escaped;
  for (int k = 0; k < count; ++k) {
    const auto& [why, cause] = escapes[static_cast<size_t>(k)];
    if (why == nullptr) continue;
    const Body& body = w.bodies.items[w.movableSlots[static_cast<size_t>(k)]];
    escaped.push_back(RemovedBody{body.id, body.name, body.xf.p, why, cause});
  }
  for (RemovedBody& report : escaped) remove(std::move(report));
  escaped.clear();
  w.findLostBodies(&escaped);
  for (RemovedBody& report : escaped) remove(std::move(report));
}

std::vector<RemovedBody> World::takeRemovedBodies() {
  std::vector<RemovedBody> out;
  out.swap(impl_->removedBodies);
  return out;
}

uint64_t World::removedBodyCount() const { return impl_->removedBodyCount; }

std::vector<LostBody> World::takeLostBodies() {
  std::vector<LostBody> out;
  out.swap(impl_->lostBodies);
  return out;
}

uint64_t World::lostBodyCount() const { return impl_->lostBodyCount; }

}  // namespace impulse2d
