// Bodies and their shapes. Types are checked here; values by World::validate(BodyDef), so a scene
// and a ROS spawn request are refused in the same words.
#include "names.hpp"
#include "scene_parsers.hpp"
#include "yaml_fields.hpp"

namespace impulse2d {
namespace scene_detail {
namespace {

CollisionFilter parseFilter(const YAML::Node& node) {
  const Fields f(node, "a collision filter", {"category", "mask", "group"});
  CollisionFilter filter;
  filter.categoryBits = f.bits("category", filter.categoryBits);
  filter.maskBits = f.bits("mask", filter.maskBits);
  filter.groupIndex = f.integer("group", filter.groupIndex);
  return filter;
}

ShapeDef parseShape(const YAML::Node& node) {
  const Fields f(node, "a shape",
                 {"type", "size", "radius", "vertices", "offset", "angle", "density", "friction",
                  "restitution", "reflectance", "filter"});
  ShapeDef def;
  const std::string type = f.string("type", "box");
  std::string geometryKey;  // the one key that gives this type's geometry
  if (type == "box") {
    def.kind = ShapeKind::Box;
    geometryKey = "size";
  } else if (type == "circle") {
    def.kind = ShapeKind::Circle;
    geometryKey = "radius";
  } else if (type == "polygon") {
    def.kind = ShapeKind::Polygon;
    geometryKey = "vertices";
  } else {
    throw SceneError("type", "must be box, circle or polygon, not " + quoted(type));
  }
  // A radius on a box is a mistake that would otherwise go unnoticed.
  for (const char* key : {"size", "radius", "vertices"}) {
    if (key != geometryKey && f.has(key)) {
      throw SceneError(key, "is not used by a " + type + " (it takes " + geometryKey + ")");
    }
  }
  def.size = f.vec2("size", def.size);
  def.radius = f.number("radius", def.radius);
  if (def.kind == ShapeKind::Polygon) def.vertices = f.points("vertices");
  def.offset = f.vec2("offset", def.offset);
  def.angle = f.number("angle", def.angle);
  def.density = f.number("density", def.density);
  def.friction = f.number("friction", def.friction);
  def.restitution = f.number("restitution", def.restitution);
  def.reflectance = f.number("reflectance", def.reflectance);
  if (f.has("filter")) {
    try {
      def.filter = parseFilter(f.node("filter"));
    } catch (const SceneError& e) {
      throw e.within("filter");
    }
  }
  return def;
}

BodyType parseBodyType(const std::string& type) {
  if (type == "static") return BodyType::Static;
  if (type == "kinematic") return BodyType::Kinematic;
  if (type == "dynamic") return BodyType::Dynamic;
  throw SceneError("type", "must be static, kinematic or dynamic, not " + quoted(type));
}

}  // namespace

BodyDef parseBody(const YAML::Node& node) {
  const Fields f(node, "a body",
                 {"name", "type", "position", "angle", "linear_velocity", "angular_velocity",
                  "linear_damping", "angular_damping", "bullet", "awake", "mass", "shapes"});
  BodyDef def;
  def.name = f.name("name");
  def.type = parseBodyType(f.string("type", "dynamic"));
  def.position = f.vec2("position", def.position);
  def.angle = f.number("angle", def.angle);
  def.linearVelocity = f.vec2("linear_velocity", def.linearVelocity);
  def.angularVelocity = f.number("angular_velocity", def.angularVelocity);
  def.linearDamping = f.number("linear_damping", def.linearDamping);
  def.angularDamping = f.number("angular_damping", def.angularDamping);
  def.bullet = f.boolean("bullet", def.bullet);
  def.awake = f.boolean("awake", def.awake);
  def.mass = f.number("mass", def.mass);
  if (f.has("shapes")) {
    const YAML::Node& shapes = f.node("shapes");
    if (!shapes.IsSequence()) throw SceneError("shapes", "must be a list of shapes");
    size_t i = 0;
    for (const YAML::Node& shape : shapes) {
      try {
        def.shapes.push_back(parseShape(shape));
      } catch (const SceneError& e) {
        throw e.within("shapes[" + std::to_string(i) + "]");
      }
      ++i;
    }
  }
  const std::string why = World::validate(def);
  if (!why.empty()) throw SceneError("", why);
  return def;
}

}  // namespace scene_detail
}  // namespace impulse2d
