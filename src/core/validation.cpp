// World's static checks of world and body definitions. The messages name the scene YAML keys, so
// the scene loader and the ROS services report a bad value in the same words.
#include <impulse2d/limits.hpp>
#include <impulse2d/shape.hpp>
#include <impulse2d/world.hpp>

#include <cmath>
#include <string>

namespace impulse2d {
namespace {

// Bounds on the work one definition can cause; beyond them a request is a mistake, not a scene.
// (The limits on counts and sizes are in limits.hpp.)
constexpr int kMaxIterations = 1000;

bool finiteNonNegative(double v) { return std::isfinite(v) && v >= 0.0; }

bool withinWorld(const Vec2& p) {
  return isFinite(p) && std::abs(p.x()) <= kMaxCoordinate && std::abs(p.y()) <= kMaxCoordinate;
}

bool frameNameChar(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '/' || c == '-';
}

// Body names become tf frames, so they keep to the characters tf and RViz handle everywhere.
std::string checkName(const std::string& name) {
  if (name.size() > kMaxNameLength) {
    return "name: must be at most " + std::to_string(kMaxNameLength) + " characters";
  }
  for (char c : name) {
    if (!frameNameChar(c)) return "name: may only contain letters, digits, '_', '-' and '/'";
  }
  if (!name.empty() && name[0] == '/') return "name: must not start with '/'";
  return "";
}

std::string checkShape(const ShapeDef& def, double* mass) {
  if (def.kind != ShapeKind::Box && def.kind != ShapeKind::Circle &&
      def.kind != ShapeKind::Polygon) {
    return "type: must be box, circle or polygon";
  }
  if (isFinite(def.offset) && !withinWorld(def.offset)) {
    return "offset: must be within 1e6 m of the body origin";
  }
  Shape shape;
  const std::string why = makeShape(def, &shape);
  if (!why.empty()) return why;
  const Aabb box = computeAabb(shape, Transform());
  const Vec2 extent = box.upper - box.lower;
  if (!isFinite(extent) || extent.maxCoeff() > kMaxCoordinate) {
    const char* key = def.kind == ShapeKind::Box      ? "size"
                      : def.kind == ShapeKind::Circle ? "radius"
                                                      : "vertices";
    return std::string(key) + ": the shape must be at most 1e6 m across";
  }
  *mass = computeMass(shape).mass;
  if (!std::isfinite(*mass)) return "density: too large for the shape's area";
  return "";
}

}  // namespace

std::string World::validate(const WorldDef& def) {
  if (!isFinite(def.gravity)) return "gravity: must be finite";
  if (!std::isfinite(def.timeStep) || def.timeStep <= 0.0) {
    return "time_step: must be finite and > 0";
  }
  if (def.velocityIterations < 1 || def.velocityIterations > kMaxIterations) {
    return "velocity_iterations: must be in [1, " + std::to_string(kMaxIterations) + "]";
  }
  if (def.positionIterations < 0 || def.positionIterations > kMaxIterations) {
    return "position_iterations: must be in [0, " + std::to_string(kMaxIterations) + "]";
  }
  if (def.threads < 1 || def.threads > kMaxThreads) {
    return "threads: must be in [1, " + std::to_string(kMaxThreads) + "]";
  }
  if (std::string(solverName(def.solver)) == "unknown") {
    return "solver: must be " + solverNameList();
  }
  if (!(std::isfinite(def.contactHertz) && def.contactHertz > 0.0)) {
    return "contact_hertz: must be finite and > 0";
  }
  if (!(std::isfinite(def.jointHertz) && def.jointHertz > 0.0)) {
    return "joint_hertz: must be finite and > 0";
  }
  if (!finiteNonNegative(def.contactDampingRatio)) {
    return "contact_damping_ratio: must be finite and >= 0";
  }
  if (!finiteNonNegative(def.jointDampingRatio)) {
    return "joint_damping_ratio: must be finite and >= 0";
  }
  if (!std::isfinite(def.baumgarte) || def.baumgarte < 0.0 || def.baumgarte > 1.0) {
    return "baumgarte: must be in [0, 1]";
  }
  if (!finiteNonNegative(def.linearSlop)) return "linear_slop: must be finite and >= 0";
  if (!finiteNonNegative(def.speculativeDistance)) {
    return "speculative_distance: must be finite and >= 0";
  }
  if (!finiteNonNegative(def.restitutionThreshold)) {
    return "restitution_threshold: must be finite and >= 0";
  }
  if (!finiteNonNegative(def.maxPushVelocity)) {
    return "max_push_velocity: must be finite and >= 0";
  }
  if (!(std::isfinite(def.maxLinearSpeed) && def.maxLinearSpeed > 0.0 &&
        def.maxLinearSpeed <= kMaxSpeed)) {
    return "max_linear_speed: must be > 0 and <= 1e6 m/s";
  }
  if (!(std::isfinite(def.maxRotation) && def.maxRotation > 0.0 && def.maxRotation <= 0.5 * kPi)) {
    return "max_rotation: must be > 0 and <= pi/2 rad";
  }
  if (!finiteNonNegative(def.timeToSleep)) return "time_to_sleep: must be finite and >= 0";
  if (!finiteNonNegative(def.sleepLinearTolerance)) {
    return "sleep_linear_tolerance: must be finite and >= 0";
  }
  if (!finiteNonNegative(def.sleepAngularTolerance)) {
    return "sleep_angular_tolerance: must be finite and >= 0";
  }
  return "";
}

std::string World::validate(const BodyDef& def) {
  std::string why = checkName(def.name);
  if (!why.empty()) return why;
  if (def.type != BodyType::Static && def.type != BodyType::Kinematic &&
      def.type != BodyType::Dynamic) {
    return "type: must be static, kinematic or dynamic";
  }
  if (!withinWorld(def.position)) return "position: must be finite and within 1e6 m of the origin";
  if (!std::isfinite(def.angle)) return "angle: must be finite";
  if (!isFinite(def.linearVelocity) || def.linearVelocity.norm() > kMaxSpeed) {
    return "linear_velocity: must be finite and at most 1e6 m/s";
  }
  if (!std::isfinite(def.angularVelocity) || std::abs(def.angularVelocity) > kMaxSpeed) {
    return "angular_velocity: must be finite and at most 1e6 rad/s";
  }
  if (!finiteNonNegative(def.linearDamping)) return "linear_damping: must be finite and >= 0";
  if (!finiteNonNegative(def.angularDamping)) return "angular_damping: must be finite and >= 0";
  if (!finiteNonNegative(def.mass)) return "mass: must be finite and >= 0";
  if (!finiteNonNegative(def.inertia)) return "inertia: must be finite and >= 0";
  if (def.useLocalCenter && !withinWorld(def.localCenter)) {
    return "local_center: must be finite and within 1e6 m of the body origin";
  }
  if (def.shapes.empty()) return "shapes: a body needs at least one shape";
  if (def.shapes.size() > kMaxShapesPerBody) {
    return "shapes: at most " + std::to_string(kMaxShapesPerBody) + " shapes per body";
  }
  double shapeMass = 0.0;
  for (size_t i = 0; i < def.shapes.size(); ++i) {
    double mass = 0.0;
    why = checkShape(def.shapes[i], &mass);
    if (!why.empty()) return "shapes[" + std::to_string(i) + "]." + why;
    shapeMass += mass;
  }
  if (!std::isfinite(shapeMass)) return "shapes: the densities are too large for the shapes' area";
  // A dynamic body without mass would have an infinite inverse mass.
  if (def.type == BodyType::Dynamic && def.mass == 0.0 && !(shapeMass > 0.0)) {
    return "mass: a dynamic body needs mass > 0 or a shape with density > 0";
  }
  return "";
}

}  // namespace impulse2d
