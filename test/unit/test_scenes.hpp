// Small scene builders shared by the physics tests.
#pragma once

#include <impulse2d/world.hpp>

#include <string>
#include <vector>

namespace impulse2d {
namespace test {

inline BodyId addBox(World& world, const std::string& name, const Vec2& position, double w,
                     double h, BodyType type, double density = 1.0, double friction = 0.6) {
  BodyDef def;
  def.name = name;
  def.type = type;
  def.position = position;
  ShapeDef shape;
  shape.kind = ShapeKind::Box;
  shape.size = Vec2(w, h);
  shape.density = density;
  shape.friction = friction;
  def.shapes.push_back(shape);
  return world.createBody(def);
}

inline BodyId addCircle(World& world, const std::string& name, const Vec2& position, double radius,
                        BodyType type, double density = 1.0) {
  BodyDef def;
  def.name = name;
  def.type = type;
  def.position = position;
  ShapeDef shape;
  shape.kind = ShapeKind::Circle;
  shape.radius = radius;
  shape.density = density;
  def.shapes.push_back(shape);
  return world.createBody(def);
}

/// A rigid distance joint from `anchor` on A to B's origin, its length as they stand.
inline JointDef distanceDef(BodyId a, BodyId b, const Vec2& anchor) {
  JointDef joint;
  joint.type = JointType::Distance;
  joint.bodyA = a;
  joint.bodyB = b;
  joint.anchor = anchor;
  return joint;
}

inline JointDef weldDef(BodyId a, BodyId b, const Vec2& anchor, double frequency = 0.0) {
  JointDef joint;
  joint.type = JointType::Weld;
  joint.bodyA = a;
  joint.bodyB = b;
  joint.anchor = anchor;
  joint.frequency = frequency;
  return joint;
}

/// Collision shapes centred on their body's origin.
inline Shape boxShape(double w, double h) {
  Shape s;
  s.type = ShapeType::Polygon;
  s.polygon = makeBox(w, h);
  return s;
}

inline Shape circleShape(double radius) {
  Shape s;
  s.type = ShapeType::Circle;
  s.circle.radius = radius;
  return s;
}

struct Momentum {
  Vec2 linear = Vec2::Zero();
  double angular = 0.0;  // about the world origin
};

/// Total linear momentum, and angular momentum about the world origin.
inline Momentum momentum(const World& world) {
  Momentum m;
  for (BodyId id : world.bodies()) {
    const Body& b = world.body(id);
    m.linear += b.mass * b.linearVelocity;
    m.angular += b.mass * cross(b.center, b.linearVelocity) + b.inertia * b.angularVelocity;
  }
  return m;
}

/// A static ground whose top surface is y = 0.
inline BodyId addGround(World& world, double width = 40.0) {
  return addBox(world, "ground", Vec2(0.0, -0.5), width, 1.0, BodyType::Static);
}

struct Placed {
  BodyId id;
  Vec2 start;
};

/// A pyramid of `rows` rows of boxes of side `size` standing on y = 0, centred on x = 0, each
/// row resting exactly on the one below (no gap, no overlap).
inline std::vector<Placed> addPyramid(World& world, int rows, double size,
                                      const Vec2& origin = Vec2::Zero()) {
  std::vector<Placed> out;
  for (int row = 0; row < rows; ++row) {
    const int count = rows - row;
    for (int i = 0; i < count; ++i) {
      const Vec2 p = origin + Vec2((i - 0.5 * (count - 1)) * size, (row + 0.5) * size);
      const std::string name = "box_" + std::to_string(row) + "_" + std::to_string(i);
      out.push_back({addBox(world, name, p, size, size, BodyType::Dynamic), p});
    }
  }
  return out;
}

}  // namespace test
}  // namespace impulse2d
