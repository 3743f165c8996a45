// Messages to engine definitions and back, and the plane mapping (see conversions.hpp).
#include "conversions.hpp"

#include <impulse2d/limits.hpp>

#include <cmath>
#include <string>

namespace impulse2d {
namespace bridge {
namespace {

std::string indexed(const std::string& list, size_t i) {
  return list + "[" + std::to_string(i) + "]";
}

// Each check returns "" or "<field>: <why>", so the first failure names its field.
std::string finite(const std::string& field, double v) {
  return std::isfinite(v) ? "" : field + ": must be finite";
}

std::string positive(const std::string& field, double v) {
  return std::isfinite(v) && v > 0.0 ? "" : field + ": must be finite and > 0";
}

std::string nonNegative(const std::string& field, double v) {
  return std::isfinite(v) && v >= 0.0 ? "" : field + ": must be finite and >= 0";
}

std::string firstOf(std::initializer_list<std::string> checks) {
  for (const std::string& why : checks) {
    if (!why.empty()) return why;
  }
  return "";
}

Vec2 plane2(const geometry_msgs::Point& p) { return Vec2(p.x, p.y); }
Vec2 plane2(const geometry_msgs::Vector3& v) { return Vec2(v.x, v.y); }

std::string toShapeDef(const impulse2d::Shape& msg, const std::string& field, ShapeDef* out) {
  std::string why = firstOf(
      {finite(field + ".offset.x", msg.offset.x), finite(field + ".offset.y", msg.offset.y),
       finite(field + ".offset.theta", msg.offset.theta),
       nonNegative(field + ".density", msg.density), nonNegative(field + ".friction", msg.friction),
       nonNegative(field + ".restitution", msg.restitution)});
  if (!why.empty()) return why;
  switch (msg.type) {
    case impulse2d::Shape::BOX:
      why =
          firstOf({positive(field + ".width", msg.width), positive(field + ".height", msg.height)});
      out->kind = ShapeKind::Box;
      out->size = Vec2(msg.width, msg.height);
      break;
    case impulse2d::Shape::CIRCLE:
      why = positive(field + ".radius", msg.radius);
      out->kind = ShapeKind::Circle;
      out->radius = msg.radius;
      break;
    case impulse2d::Shape::POLYGON:
      if (msg.vertices.size() < 3) return field + ".vertices: a polygon needs at least 3";
      if (msg.vertices.size() > size_t(kMaxPolygonVertices)) {
        return field + ".vertices: at most " + std::to_string(kMaxPolygonVertices) + " vertices";
      }
      out->kind = ShapeKind::Polygon;
      out->vertices.clear();
      for (size_t i = 0; i < msg.vertices.size() && why.empty(); ++i) {
        const std::string vertex = indexed(field + ".vertices", i);
        why = firstOf(
            {finite(vertex + ".x", msg.vertices[i].x), finite(vertex + ".y", msg.vertices[i].y)});
        out->vertices.push_back(plane2(msg.vertices[i]));
      }
      break;
    default:
      return field + ".type: must be BOX (0), CIRCLE (1) or POLYGON (2)";
  }
  if (!why.empty()) return why;
  out->offset = Vec2(msg.offset.x, msg.offset.y);
  out->angle = msg.offset.theta;
  out->density = msg.density == 0.0 ? 1.0 : msg.density;  // the message's documented default
  out->friction = msg.friction;
  out->restitution = msg.restitution;
  return "";
}

}  // namespace

bool parsePlane(const std::string& name, Plane* out) {
  if (name == "xz") {
    *out = Plane::XZ;
    return true;
  }
  if (name == "xy") {
    *out = Plane::XY;
    return true;
  }
  return false;
}

geometry_msgs::Point toPoint(Plane plane, const Vec2& v) {
  geometry_msgs::Point p;
  p.x = v.x();
  if (plane == Plane::XZ) {
    p.z = v.y();
  } else {
    p.y = v.y();
  }
  return p;
}

geometry_msgs::Vector3 toVector(Plane plane, const Vec2& v) {
  const geometry_msgs::Point p = toPoint(plane, v);
  geometry_msgs::Vector3 out;
  out.x = p.x;
  out.y = p.y;
  out.z = p.z;
  return out;
}

geometry_msgs::Quaternion toQuaternion(Plane plane, double angle) {
  // A rotation by `angle` about the plane's normal: (0, -1, 0) for xz, (0, 0, 1) for xy.
  geometry_msgs::Quaternion q;
  q.w = std::cos(0.5 * angle);
  const double s = std::sin(0.5 * angle);
  if (plane == Plane::XZ) {
    q.y = -s;
  } else {
    q.z = s;
  }
  return q;
}

geometry_msgs::Pose toPose(Plane plane, const Vec2& position, double angle) {
  geometry_msgs::Pose pose;
  pose.position = toPoint(plane, position);
  pose.orientation = toQuaternion(plane, angle);
  return pose;
}

geometry_msgs::Transform toTransform(Plane plane, const Vec2& position, double angle) {
  geometry_msgs::Transform xf;
  xf.translation = toVector(plane, position);
  xf.rotation = toQuaternion(plane, angle);
  return xf;
}

std::string toBodyDef(const impulse2d::Body& msg, BodyDef* out) {
  if (msg.name.empty()) return "body.name: must not be empty";
  switch (msg.type) {
    case impulse2d::Body::STATIC:
      out->type = BodyType::Static;
      break;
    case impulse2d::Body::KINEMATIC:
      out->type = BodyType::Kinematic;
      break;
    case impulse2d::Body::DYNAMIC:
      out->type = BodyType::Dynamic;
      break;
    default:
      return "body.type: must be STATIC (0), KINEMATIC (1) or DYNAMIC (2)";
  }
  std::string why = firstOf(
      {finite("body.pose.x", msg.pose.x), finite("body.pose.y", msg.pose.y),
       finite("body.pose.theta", msg.pose.theta), finite("body.twist.linear.x", msg.twist.linear.x),
       finite("body.twist.linear.y", msg.twist.linear.y),
       finite("body.twist.angular.z", msg.twist.angular.z), nonNegative("body.mass", msg.mass),
       nonNegative("body.linear_damping", msg.linear_damping),
       nonNegative("body.angular_damping", msg.angular_damping)});
  if (!why.empty()) return why;
  if (msg.shapes.empty()) return "body.shapes: a body needs at least one shape";
  if (msg.shapes.size() > kMaxShapesPerBody) {
    return "body.shapes: at most " + std::to_string(kMaxShapesPerBody) + " shapes per body";
  }
  out->shapes.assign(msg.shapes.size(), ShapeDef());
  for (size_t i = 0; i < msg.shapes.size(); ++i) {
    why = toShapeDef(msg.shapes[i], indexed("body.shapes", i), &out->shapes[i]);
    if (!why.empty()) return why;
  }
  out->name = msg.name;
  out->position = Vec2(msg.pose.x, msg.pose.y);
  out->angle = msg.pose.theta;
  out->linearVelocity = Vec2(msg.twist.linear.x, msg.twist.linear.y);
  out->angularVelocity = msg.twist.angular.z;
  out->mass = msg.mass;
  out->linearDamping = msg.linear_damping;
  out->angularDamping = msg.angular_damping;
  out->bullet = msg.bullet;
  return "";
}

std::string toJointDef(const impulse2d::Joint& msg, JointDef* out) {
  if (msg.name.empty()) return "joint.name: must not be empty";
  if (msg.body_a.empty()) return "joint.body_a: must not be empty";
  if (msg.body_b.empty()) return "joint.body_b: must not be empty";
  if (msg.body_a == msg.body_b) return "joint.body_b: must differ from body_a";
  switch (msg.type) {
    case impulse2d::Joint::REVOLUTE:
      out->type = JointType::Revolute;
      break;
    case impulse2d::Joint::PRISMATIC:
      out->type = JointType::Prismatic;
      break;
    case impulse2d::Joint::WELD:
      out->type = JointType::Weld;
      break;
    case impulse2d::Joint::DISTANCE:
      out->type = JointType::Distance;
      break;
    default:
      return "joint.type: must be REVOLUTE (0), PRISMATIC (1), WELD (2) or DISTANCE (3)";
  }
  std::string why =
      firstOf({finite("joint.anchor.x", msg.anchor.x), finite("joint.anchor.y", msg.anchor.y),
               finite("joint.axis.x", msg.axis.x), finite("joint.axis.y", msg.axis.y),
               finite("joint.lower", msg.lower), finite("joint.upper", msg.upper),
               finite("joint.motor_speed", msg.motor_speed),
               nonNegative("joint.max_motor_torque", msg.max_motor_torque),
               nonNegative("joint.length", msg.length)});
  if (!why.empty()) return why;
  if (msg.enable_limit && msg.lower > msg.upper) return "joint.lower: must not exceed upper";
  const Vec2 axis = plane2(msg.axis);
  if (out->type == JointType::Prismatic && axis.norm() == 0.0) {
    return "joint.axis: a prismatic joint needs a non-zero axis in the plane";
  }
  out->name = msg.name;
  out->anchor = plane2(msg.anchor);
  if (out->type == JointType::Prismatic) out->axis = axis.normalized();
  out->enableLimit = msg.enable_limit;
  out->lower = msg.lower;
  out->upper = msg.upper;
  out->enableMotor = msg.enable_motor;
  out->motorSpeed = msg.motor_speed;
  out->maxMotorTorque = msg.max_motor_torque;
  out->length = msg.length;
  out->collideConnected = msg.collide_connected;
  return "";
}

impulse2d::Contact toContactMsg(const ContactSnapshot& contact) {
  impulse2d::Contact msg;
  msg.body_a = contact.bodyA;
  msg.body_b = contact.bodyB;
  msg.point.x = contact.point.x();
  msg.point.y = contact.point.y();
  msg.normal.x = contact.normal.x();
  msg.normal.y = contact.normal.y();
  msg.separation = contact.separation;
  msg.normal_impulse = contact.normalImpulse;
  msg.tangent_impulse = contact.tangentImpulse;
  return msg;
}

}  // namespace bridge
}  // namespace impulse2d
