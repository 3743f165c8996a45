// Joints. Keys that only some joint types use are refused on the others rather than ignored;
// values are checked here as far as they can be without the bodies, and again by the world.
#include "names.hpp"
#include "scene_parsers.hpp"
#include "yaml_fields.hpp"

#include <cmath>

namespace impulse2d {
namespace scene_detail {
namespace {

JointType parseJointType(const std::string& type) {
  if (type == "revolute") return JointType::Revolute;
  if (type == "prismatic") return JointType::Prismatic;
  if (type == "weld") return JointType::Weld;
  if (type == "distance") return JointType::Distance;
  throw SceneError("type", "must be revolute, prismatic, weld or distance, not " + quoted(type));
}

struct TypeSpecificKey {
  const char* key;
  const char* takenBy;  ///< as the message says it
  bool (*takes)(JointType);
};

bool isHinge(JointType t) { return t == JointType::Revolute || t == JointType::Prismatic; }
bool isPrismatic(JointType t) { return t == JointType::Prismatic; }
bool isDistance(JointType t) { return t == JointType::Distance; }
bool isSpring(JointType t) { return t == JointType::Weld || t == JointType::Distance; }

const TypeSpecificKey kTypeSpecificKeys[] = {
    {"axis", "prismatic joints", isPrismatic},
    {"lower", "revolute and prismatic joints", isHinge},
    {"upper", "revolute and prismatic joints", isHinge},
    {"motor_speed", "revolute and prismatic joints", isHinge},
    {"max_motor_torque", "revolute and prismatic joints", isHinge},
    {"length", "distance joints", isDistance},
    {"anchor_b", "distance joints", isDistance},
    {"min_length", "distance joints", isDistance},
    {"max_length", "distance joints", isDistance},
    {"frequency", "weld and distance joints", isSpring},
    {"damping_ratio", "weld and distance joints", isSpring},
};

double nonNegative(const Fields& f, const char* key, double fallback) {
  const double v = f.number(key, fallback);
  if (!std::isfinite(v) || v < 0.0) throw SceneError(key, "must be finite and >= 0");
  return v;
}

void parseLimitsAndMotor(const Fields& f, JointDef* d) {
  if (f.has("lower") != f.has("upper")) {
    throw SceneError(f.has("lower") ? "upper" : "lower", "limits need both lower and upper");
  }
  d->enableLimit = f.has("lower");
  d->lower = f.number("lower", d->lower);
  d->upper = f.number("upper", d->upper);
  if (!std::isfinite(d->lower)) throw SceneError("lower", "must be finite");
  if (!std::isfinite(d->upper)) throw SceneError("upper", "must be finite");
  if (d->lower > d->upper) throw SceneError("upper", "must be >= lower");
  d->enableMotor = f.has("motor_speed") || f.has("max_motor_torque");
  d->motorSpeed = f.number("motor_speed", d->motorSpeed);
  if (!std::isfinite(d->motorSpeed)) throw SceneError("motor_speed", "must be finite");
  d->maxMotorTorque = nonNegative(f, "max_motor_torque", d->maxMotorTorque);
}

void parseDistance(const Fields& f, SceneJoint* joint) {
  JointDef& d = joint->def;
  joint->hasLength = f.has("length");
  d.length = f.number("length", d.length);
  if (joint->hasLength && (!std::isfinite(d.length) || d.length <= 0.0)) {
    throw SceneError("length", "must be finite and > 0");
  }
  d.useAnchorB = f.has("anchor_b");
  d.anchorB = f.vec2("anchor_b", d.anchorB);
  if (!isFinite(d.anchorB)) throw SceneError("anchor_b", "must be finite");
  d.minLength = nonNegative(f, "min_length", d.minLength);
  d.maxLength = f.number("max_length", d.maxLength);  // .inf: no upper limit
  if (std::isnan(d.maxLength) || d.maxLength < d.minLength) {
    throw SceneError("max_length", "must be >= min_length");
  }
}

}  // namespace

SceneJoint parseJoint(const YAML::Node& node) {
  const Fields f(node, "a joint",
                 {"name", "type", "body_a", "body_b", "anchor", "axis", "lower", "upper",
                  "motor_speed", "max_motor_torque", "length", "anchor_b", "min_length",
                  "max_length", "frequency", "damping_ratio", "collide_connected"});
  SceneJoint joint;
  JointDef& d = joint.def;
  d.name = f.name("name");
  d.type = parseJointType(f.string("type", "revolute"));
  for (const TypeSpecificKey& k : kTypeSpecificKeys) {
    if (f.has(k.key) && !k.takes(d.type)) {
      throw SceneError(k.key, std::string("only ") + k.takenBy + " take it");
    }
  }
  joint.bodyA = f.name("body_a");
  joint.bodyB = f.name("body_b");
  if (joint.bodyA == joint.bodyB) {
    throw SceneError("body_b", "joins body " + quoted(joint.bodyA) + " to itself");
  }
  d.anchor = f.vec2("anchor", d.anchor);
  if (!isFinite(d.anchor)) throw SceneError("anchor", "must be finite");
  d.axis = f.vec2("axis", d.axis);
  if (!isFinite(d.axis) || d.axis.isZero()) {
    throw SceneError("axis", "must be a finite non-zero direction");
  }
  parseLimitsAndMotor(f, &d);
  parseDistance(f, &joint);
  d.frequency = nonNegative(f, "frequency", d.frequency);
  d.dampingRatio = nonNegative(f, "damping_ratio", d.dampingRatio);
  d.collideConnected = f.boolean("collide_connected", d.collideConnected);
  return joint;
}

}  // namespace scene_detail
}  // namespace impulse2d
