// Maps (`maps:`): an occupancy map in map_server's format, read and turned into static walls.
// A file name is absolute, relative to the scene's folder, or package://PACKAGE/PATH.
#include <impulse2d/limits.hpp>

#include "names.hpp"
#include "scene_parsers.hpp"
#include "yaml_fields.hpp"

#include <cctype>
#include <cmath>

namespace impulse2d {
namespace scene_detail {
namespace {

std::string resolvePath(const std::string& name, const ScenePaths& paths) {
  const std::string scheme = "package://";
  if (name.compare(0, scheme.size(), scheme) == 0) {
    const std::string rest = name.substr(scheme.size());
    const size_t slash = rest.find('/');
    if (slash == std::string::npos || slash == 0) {
      throw SceneError("file", "must be package://PACKAGE/PATH, not " + quoted(name));
    }
    const std::string package = rest.substr(0, slash);
    for (const char c : package) {
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) {
        throw SceneError("file", "package://" + package + ": not a ROS package name (REP 144)");
      }
    }
    if (!paths.findPackage) {
      throw SceneError("file",
                       "package:// names need a package finder (the node and "
                       "impulse2d_sim have one)");
    }
    std::string why;
    const std::string folder = paths.findPackage(package, &why);
    if (folder.empty()) throw SceneError("file", why);
    return folder + rest.substr(slash);
  }
  if (!name.empty() && name[0] == '/') return name;
  if (paths.folder.empty()) return name;
  return paths.folder + (paths.folder.back() == '/' ? "" : "/") + name;
}

}  // namespace

SceneMap parseMap(const YAML::Node& node, const ScenePaths& paths, std::vector<BodyDef>* walls) {
  const Fields f(node, "a map", {"name", "file", "friction", "restitution", "reflectance"});
  SceneMap map;
  map.name = f.name("name");
  if (!f.has("file")) throw SceneError("file", "must be given: a map_server YAML file");
  const std::string file = f.string("file", "");
  if (file.empty()) throw SceneError("file", "must not be empty");
  map.file = resolvePath(file, paths);
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
