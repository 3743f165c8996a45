// SimWorld's maps: the package finder for scenes' map files, and a map followed from a topic
// whose walls are replaced with every message (the scene's `maps:` are in sim_world.cpp).
#include "sim_world.hpp"

#include <impulse2d/limits.hpp>
#include <impulse2d/scene.hpp>

#include <cmath>

namespace impulse2d {
namespace bridge {

namespace {

std::string checkGrid(const OccupancyGrid& grid) {
  if (grid.width <= 0 || grid.height <= 0) return "info.width, info.height: must be > 0";
  if (static_cast<double>(grid.width) * grid.height > static_cast<double>(kMaxMapCells)) {
    return "info.width x info.height: at most " + std::to_string(kMaxMapCells) + " cells";
  }
  if (grid.data.size() != static_cast<size_t>(grid.width) * static_cast<size_t>(grid.height)) {
    return "data: must hold info.width x info.height cells";
  }
  if (!(std::isfinite(grid.resolution) && grid.resolution > 0.0 && grid.resolution <= 1e3)) {
    return "info.resolution: must be finite, > 0 and at most 1000 m";
  }
  if (!std::isfinite(grid.origin.x()) || !std::isfinite(grid.origin.y()) ||
      grid.origin.cwiseAbs().maxCoeff() > kMaxCoordinate || !std::isfinite(grid.originYaw)) {
    return "info.origin: must be finite and within 1e6 m";
  }
  return "";
}

Scene wallsOf(const LoadedMap& map) {
  Scene walls;
  walls.bodies = mapBodies(map.name, map.grid, mergeOccupiedCells(map.grid), ShapeDef());
  return walls;
}

}  // namespace

const LoadedMap* SimWorld::latestMap() const {
  if (followed_) return followed_.get();
  return maps_.empty() ? nullptr : &maps_.back();
}

void SimWorld::addFollowedWalls() {
  followedWalls_.clear();
  if (!followed_) return;
  std::string error;
  if (!impulse2d::addScene(wallsOf(*followed_), *world_, &error, &followedWalls_)) {
    followed_.reset();
  }
}

bool SimWorld::followMap(const std::string& name, OccupancyGrid grid, std::string* error) {
  *error = checkGrid(grid);
  if (!error->empty()) return false;
  auto next = std::make_unique<LoadedMap>(LoadedMap{name, std::move(grid)});
  // The last message's walls go first; if the new ones cannot be added, they come back. They go
  // by id, not by name: a user's body may have taken the name of a wall deleted since.
  for (const BodyId wall : followedWalls_) {
    if (world_->isValid(wall)) world_->destroyBody(wall);
  }
  followedWalls_.clear();
  std::vector<BodyId> added;
  if (!impulse2d::addScene(wallsOf(*next), *world_, error, &added)) {
    *error = "the map's walls: " + *error;
    addFollowedWalls();
    return false;
  }
  followed_ = std::move(next);
  followedWalls_ = std::move(added);
  ++mapVersion_;
  ++staticVersion_;
  return true;
}

}  // namespace bridge
}  // namespace impulse2d
