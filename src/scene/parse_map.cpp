// Maps (`maps:`): an occupancy map in map_server's format, read and turned into static walls.
// A file name is absolute, relative to the scene's folder, or package://PACKAGE/PATH.
#include <impulse2d/limits.hpp>

#include "names.hpp"
#include "scene_parsers.hpp"
#include "yaml_fields.hpp"

#include <cmath>

namespace impulse2d {
namespace scene_detail {
SceneMap parseMap(const YAML::Node& node, const ScenePaths& paths, std::vector<BodyDef>* walls) {
  const Fields f(node, "a map", {"name", "file", "friction", "restitution", "reflectance"});
  SceneMap map;
  map.name = f.name("name");
  if (!f.has("file")) throw SceneError("file", "must be given: a map_server YAML file");
  const std::string file = f.string("file", "");
  if (file.empty()) throw SceneError("file", "must not be empty");
  map.file = resolveFile(file, paths);
  ShapeDef shape;
  shape.friction = f.number("friction", shape.friction);
  shape.restitution = f.number("restitution", shape.restitution);
  shape.reflectance = f.number("reflectance", shape.reflectance);
  Shape unused;
  const std::string why = makeShape(shape, &unused);  // the same rules as a body's shapes
  if (!why.empty()) throw SceneError("", why);
  std::string error;
  if (!loadMapFile(map.file, &map.grid, &error)) throw SceneError("file", error);
  const std::vector<CellBlock> blocks = mergeOccupiedCells(map.grid);
  std::vector<BodyDef> bodies = mapBodies(map.name, map.grid, blocks, shape);
  map.bodies = bodies.size();
  for (BodyDef& body : bodies) walls->push_back(std::move(body));
  return map;
}

}  // namespace scene_detail
}  // namespace impulse2d
