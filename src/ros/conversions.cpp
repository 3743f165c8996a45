// Messages to engine definitions and back, and the plane mapping (see conversions.hpp).
#include "conversions.hpp"

#include <impulse2d/limits.hpp>

#include <cmath>
#include <cstdio>
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

// As a person writes it: 0.6, 1, 12.5, 1e+07.
std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", v);
  return text;
}

Vec2 plane2(const geometry_msgs::Point& p) { return Vec2(p.x, p.y); }
Vec2 plane2(const geometry_msgs::Vector3& v) { return Vec2(v.x, v.y); }

// Notes name the field as the request spells it below its top-level field ("shapes[0].friction",
// "axis"), like the YAML key it stands for.
void note(Notes* notes, const std::string& text) {
  if (notes != nullptr) notes->push_back(text);
}

// A field of another shape type (radius on a box) is refused in YAML; a message always has it,
// so a non-zero one is only pointed out.
void noteUnused(const impulse2d::Shape& msg, const std::string& field, const char* typeName,
                Notes* notes) {
  const bool box = msg.type == impulse2d::Shape::BOX;
  const bool circle = msg.type == impulse2d::Shape::CIRCLE;
  if (!box && (msg.width != 0.0 || msg.height != 0.0)) {
    note(notes, field + ".width, height: not used by a " + typeName);
  }
  if (!circle && msg.radius != 0.0) note(notes, field + ".radius: not used by a " + typeName);
  if (msg.type != impulse2d::Shape::POLYGON && !msg.vertices.empty()) {
    note(notes, field + ".vertices: not used by a " + typeName);
  }
}

std::string toShapeDef(const impulse2d::Shape& msg, const std::string& field,
                       const std::string& noteField, ShapeDef* out, Notes* notes) {
  std::string why =
      firstOf({finite(field + ".offset.x", msg.offset.x), finite(field + ".offset.y", msg.offset.y),
               finite(field + ".offset.theta", msg.offset.theta),
               nonNegative(field + ".density", msg.density),
               nonNegative(field + ".restitution", msg.restitution)});
  if (!why.empty()) return why;
  if (!(std::isfinite(msg.friction) &&
        (msg.friction >= 0.0 || msg.friction == impulse2d::Shape::FRICTIONLESS))) {
    return field + ".friction: must be >= 0 (0: the default " + number(ShapeDef().friction) +
           "), or FRICTIONLESS (-1) for none";
  }
  switch (msg.type) {
    case impulse2d::Shape::BOX:
      why =
          firstOf({positive(field + ".width", msg.width), positive(field + ".height", msg.height)});
      out->kind = ShapeKind::Box;
      out->size = Vec2(msg.width, msg.height);
      noteUnused(msg, noteField, "BOX", notes);
      break;
    case impulse2d::Shape::CIRCLE:
      why = positive(field + ".radius", msg.radius);
      out->kind = ShapeKind::Circle;
      out->radius = msg.radius;
      noteUnused(msg, noteField, "CIRCLE", notes);
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
      noteUnused(msg, noteField, "POLYGON", notes);
      break;
    default:
      return field + ".type: must be BOX (0), CIRCLE (1) or POLYGON (2)";
  }
  if (!why.empty()) return why;
  out->offset = Vec2(msg.offset.x, msg.offset.y);
  out->angle = msg.offset.theta;
  // Zero is what a client sends for a field it leaves out: it means what an omitted YAML key
  // means (ShapeDef's defaults), where zero is not itself a useful request.
  const ShapeDef defaults;
  out->density = msg.density == 0.0 ? defaults.density : msg.density;
  if (msg.friction == impulse2d::Shape::FRICTIONLESS) {
    out->friction = 0.0;
  } else if (msg.friction == 0.0) {
    out->friction = defaults.friction;
    // Before 0.6 was the default, 0 meant no friction: say what it means now.
    note(notes, noteField + ".friction: default " + number(defaults.friction));
  } else {
    out->friction = msg.friction;
  }
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

std::string okWithNotes(const Notes& notes) {
  if (notes.empty()) return "ok";
  std::string message = "ok (";
  for (size_t i = 0; i < notes.size(); ++i) message += (i > 0 ? "; " : "") + notes[i];
  return message + ")";
}

std::string toBodyDef(const impulse2d::Body& msg, BodyDef* out, Notes* notes) {
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
  Notes found;
  // An omitted YAML type is dynamic, but STATIC is 0 here: a message that leaves the type out
  // gets a body that never moves, which the answer says.
  if (out->type == BodyType::Static)
    found.push_back("type: STATIC (0), it never moves; DYNAMIC is 2");
  out->shapes.assign(msg.shapes.size(), ShapeDef());
  for (size_t i = 0; i < msg.shapes.size(); ++i) {
    why = toShapeDef(msg.shapes[i], indexed("body.shapes", i), indexed("shapes", i),
                     &out->shapes[i], &found);
    if (!why.empty()) return why;
  }
  if (notes != nullptr) notes->insert(notes->end(), found.begin(), found.end());
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

std::string toJointDef(const impulse2d::Joint& msg, JointDef* out, Notes* notes) {
  if (msg.name.empty()) return "joint.name: must not be empty";
  if (msg.body_a.empty()) return "joint.body_a: must not be empty";
  if (msg.body_b.empty()) return "joint.body_b: must not be empty";
  if (msg.body_a == msg.body_b) return "joint.body_b: must differ from body_a";
  const char* typeName = "";
  switch (msg.type) {
    case impulse2d::Joint::REVOLUTE:
      out->type = JointType::Revolute;
      typeName = "REVOLUTE";
      break;
    case impulse2d::Joint::PRISMATIC:
      out->type = JointType::Prismatic;
      typeName = "PRISMATIC";
      break;
    case impulse2d::Joint::WELD:
      out->type = JointType::Weld;
      typeName = "WELD";
      break;
    case impulse2d::Joint::DISTANCE:
      out->type = JointType::Distance;
      typeName = "DISTANCE";
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
  Notes found;
  const bool hinge = out->type == JointType::Revolute || out->type == JointType::Prismatic;
  const Vec2 axis = plane2(msg.axis);
  // Fields of another joint type are refused in YAML; a message always has them, so non-zero
  // ones are only pointed out. Limits and motors given without their switch likewise.
  const std::string unused = std::string(": not used by a ") + typeName + " joint";
  if (out->type != JointType::Prismatic && !axis.isZero()) found.push_back("axis" + unused);
  if (out->type != JointType::Distance && msg.length != 0.0) found.push_back("length" + unused);
  const bool limitGiven = msg.enable_limit || msg.lower != 0.0 || msg.upper != 0.0;
  const bool motorGiven = msg.enable_motor || msg.motor_speed != 0.0 || msg.max_motor_torque != 0.0;
  if (!hinge && limitGiven) found.push_back("enable_limit, lower, upper" + unused);
  if (!hinge && motorGiven) {
    found.push_back("enable_motor, motor_speed, max_motor_torque" + unused);
  }
  if (hinge && !msg.enable_limit && (msg.lower != 0.0 || msg.upper != 0.0)) {
    found.push_back("lower, upper: not used, enable_limit is false");
  }
  if (hinge && !msg.enable_motor && (msg.motor_speed != 0.0 || msg.max_motor_torque != 0.0)) {
    found.push_back("motor_speed, max_motor_torque: not used, enable_motor is false");
  }
  if (hinge && msg.enable_motor && msg.max_motor_torque == 0.0) {
    found.push_back("max_motor_torque: 0, so the motor cannot drive the joint");
  }
  out->name = msg.name;
  out->anchor = plane2(msg.anchor);
  if (out->type == JointType::Prismatic) {
    // Zero is what an omitted field is: the YAML default direction, as the answer says.
    if (axis.isZero()) {
      found.push_back("axis: default (1, 0)");
    } else {
      out->axis = axis.normalized();
    }
  }
  out->enableLimit = msg.enable_limit;
  out->lower = msg.lower;
  out->upper = msg.upper;
  out->enableMotor = msg.enable_motor;
  out->motorSpeed = msg.motor_speed;
  out->maxMotorTorque = msg.max_motor_torque;
  out->length = msg.length;
  out->collideConnected = msg.collide_connected;
  if (notes != nullptr) notes->insert(notes->end(), found.begin(), found.end());
  return "";
}

uint8_t toBodyTypeMsg(BodyType type) {
  switch (type) {
    case BodyType::Static:
      return impulse2d::Body::STATIC;
    case BodyType::Kinematic:
      return impulse2d::Body::KINEMATIC;
    case BodyType::Dynamic:
      break;
  }
  return impulse2d::Body::DYNAMIC;
}

impulse2d::Shape toShapeMsg(const ShapeProperties& shape) {
  impulse2d::Shape msg;
  if (shape.circle) {
    msg.type = impulse2d::Shape::CIRCLE;
    msg.radius = shape.radius;
    msg.offset.x = shape.center.x();
    msg.offset.y = shape.center.y();
  } else {
    msg.type = impulse2d::Shape::POLYGON;
    for (const Vec2& v : shape.vertices) {
      geometry_msgs::Point p;
      p.x = v.x();
      p.y = v.y();
      msg.vertices.push_back(p);
    }
  }
  msg.density = shape.density;
  msg.friction = shape.friction == 0.0 ? impulse2d::Shape::FRICTIONLESS : shape.friction;
  msg.restitution = shape.restitution;
  return msg;
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
