// SimWorld's queries for ~ray_cast and ~query_point. No ROS header may appear here (see
// sim_world.hpp).
#include "sim_world.hpp"

#include <impulse2d/limits.hpp>
#include <impulse2d/world.hpp>

namespace impulse2d {
namespace bridge {
namespace {

std::string checkPoint(const std::string& field, const Vec2& p) {
  if (!isFinite(p)) return field + ": must be finite";
  if (p.cwiseAbs().maxCoeff() > kWorldExtent) return field + ": must be within 1e7 m of the origin";
  return "";
}

}  // namespace

bool SimWorld::rayCast(const Vec2& start, const Vec2& end, const std::vector<std::string>& ignore,
                       RayCastAnswer* out, std::string* error) const {
  *error = checkPoint("start", start);
  if (error->empty()) *error = checkPoint("end", end);
  if (!error->empty()) return false;
  RayFilter filter;
  for (size_t i = 0; i < ignore.size(); ++i) {
    const BodyId id = world_->findBody(ignore[i]);
    if (!id.valid()) {
      *error = "ignore_bodies[" + std::to_string(i) + "]: no body named '" + ignore[i] + "'";
      return false;
    }
    filter.ignore.push_back(id);
  }
  const RayHit hit = world_->rayCast(start, end, filter);
  *out = RayCastAnswer();
  if (!hit.hit()) return true;
  out->hit = true;
  out->body = world_->body(hit.body).name;
  out->point = hit.point;
  out->normal = hit.normal;
  out->fraction = hit.fraction;
  return true;
}

bool SimWorld::queryPoint(const Vec2& point, std::vector<std::string>* bodies,
                          std::string* error) const {
  *error = checkPoint("point", point);
  if (!error->empty()) return false;
  bodies->clear();
  for (const BodyId id : world_->queryPoint(point)) bodies->push_back(world_->body(id).name);
  return true;
}

}  // namespace bridge
}  // namespace impulse2d
