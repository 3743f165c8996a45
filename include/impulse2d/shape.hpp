// Collision geometry in a body's frame: circles and convex polygons (boxes are polygons).
#pragma once

#include <impulse2d/defs.hpp>
#include <impulse2d/limits.hpp>
#include <impulse2d/math.hpp>

#include <string>
#include <vector>

namespace impulse2d {

/// Smallest edge a polygon may have and the smallest box side / circle radius, in metres.
constexpr double kMinFeatureSize = 1e-4;

struct Circle {
  Vec2 center = Vec2::Zero();  ///< m, in the body frame
  double radius = 0.0;         ///< m
};

/// A convex polygon, counter-clockwise, with outward unit edge normals:
/// normals[i] is the normal of the edge vertices[i] -> vertices[i + 1].
struct Polygon {
  Polygon() {
    for (Vec2& v : vertices) v.setZero();
    for (Vec2& n : normals) n.setZero();
  }
  int count = 0;
  Vec2 vertices[kMaxPolygonVertices];
  Vec2 normals[kMaxPolygonVertices];
  Vec2 centroid = Vec2::Zero();
};

/// Mass properties of a shape or a body: mass (kg), centre of mass (m, body frame) and the
/// rotational inertia about the centre of mass (kg m^2).
struct MassData {
  double mass = 0.0;
  Vec2 center = Vec2::Zero();
  double inertia = 0.0;
};

enum class ShapeType { Circle, Polygon };

/// One collision shape with its material.
struct Shape {
  ShapeType type = ShapeType::Polygon;
  Circle circle;
  Polygon polygon;
  double density = 1.0;      ///< kg/m^2
  double friction = 0.6;     ///< Coulomb coefficient
  double restitution = 0.0;  ///< 0 = no bounce, 1 = elastic
  double reflectance = 0.0;  ///< what a laser reads as the intensity of a hit, >= 0
  CollisionFilter filter;
};

/// Builds a polygon from points in any winding. Returns an empty string on success, otherwise a
/// reason ("not convex", "too few vertices", ...) and leaves `out` untouched.
std::string makePolygon(const std::vector<Vec2>& points, Polygon* out);

/// A box of full width w and height h, centred at `center`, rotated by `angle` (rad).
Polygon makeBox(double w, double h, const Vec2& center = Vec2::Zero(), double angle = 0.0);

/// Applies a rigid transform to a polygon (used to place shapes at an offset in a body).
Polygon transformed(const Polygon& polygon, const Transform& xf);

/// Builds the body-frame shape a ShapeDef describes (offset and angle applied). Returns an empty
/// string on success, otherwise one reason naming the YAML key ("size: ...", "radius: ...",
/// "vertices: ...", "density: ...") and leaves `out` untouched.
std::string makeShape(const ShapeDef& def, Shape* out);

MassData computeMass(const Shape& shape);
/// The radius of the largest circle about the shape's centre that fits inside it (m).
double innerRadius(const Shape& shape);
Aabb computeAabb(const Shape& shape, const Transform& xf);

}  // namespace impulse2d
