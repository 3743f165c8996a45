// The step stage that keeps the world finite: a body that flew beyond kWorldExtent, or whose
// state overflowed to inf or NaN (an absurd force, a collapsing constraint), is removed with its
// joints and contacts and reported, rather than left to poison the broad phase and its
// neighbours with non-finite numbers on the next step.
#include "world_impl.hpp"

#include <impulse2d/limits.hpp>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace impulse2d {
namespace {

// Reports kept between two takeRemovedBodies() calls; a caller that never asks cannot make the
// list grow without bound.
constexpr size_t kMaxRemovedReports = 1024;

// Empty while the body may stay, else why it goes.
std::string escapeReason(const Body& body) {
  const bool finite = isFinite(body.center) && isFinite(body.xf.p) && std::isfinite(body.angle) &&
                      isFinite(body.linearVelocity) && std::isfinite(body.angularVelocity);
  if (!finite) return "its state stopped being finite";
  if (std::abs(body.center.x()) > kWorldExtent || std::abs(body.center.y()) > kWorldExtent) {
    return "it left the world extent of 1e7 m";
  }
  return "";
}

}  // namespace

void World::removeEscapedBodies() {
  WorldImpl& w = *impl_;
  std::vector<std::pair<BodyId, std::string>> escaped;
  for (size_t i = 0; i < w.bodies.items.size(); ++i) {
    const Body& body = w.bodies.items[i];
    // Static bodies are checked too: they never move, but a non-finite impulse from a body
    // gone wrong writes NaN into their velocities all the same, and would spread from there.
    if (!w.bodies.alive[i]) continue;
    std::string reason = escapeReason(body);
    if (!reason.empty()) escaped.emplace_back(body.id, std::move(reason));
  }
  for (auto& [id, reason] : escaped) {
    const Body& body = w.bodies.items[id.index];
    if (w.removedBodies.size() < kMaxRemovedReports) {
      w.removedBodies.push_back(RemovedBody{id, body.name, body.xf.p, std::move(reason)});
    }
    ++w.removedBodyCount;
    destroyBody(id);
  }
}

std::vector<RemovedBody> World::takeRemovedBodies() {
  std::vector<RemovedBody> out;
  out.swap(impl_->removedBodies);
  return out;
}

uint64_t World::removedBodyCount() const { return impl_->removedBodyCount; }

}  // namespace impulse2d
