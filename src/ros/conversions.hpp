// Messages to engine definitions and back, and the mapping of the 2D plane into 3D for tf and
// RViz. Sees messages, so it must not include the engine's body.hpp, shape.hpp or world.hpp.
#pragma once

#include "sim_world.hpp"

#include <geometry_msgs/Point.h>
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Quaternion.h>
#include <geometry_msgs/Transform.h>
#include <geometry_msgs/Vector3.h>
#include <impulse2d/Body.h>
#include <impulse2d/Contact.h>
#include <impulse2d/Joint.h>
#include <impulse2d/Shape.h>

#include <string>
#include <vector>

namespace impulse2d {
namespace bridge {

/// Where the 2D world lies in 3D. xz: a vertical plane, 2D (x, y) -> 3D (x, 0, y), angles turn
/// about -y so that x, z and the normal -y form a right-handed frame (counter-clockwise as seen
/// from -y looking along +y). xy: top-down, 2D (x, y) -> 3D (x, y, 0), angles about +z.
enum class Plane { XZ, XY };

/// "xz" or "xy"; anything else gives false.
bool parsePlane(const std::string& name, Plane* out);

geometry_msgs::Point toPoint(Plane plane, const Vec2& v);
geometry_msgs::Vector3 toVector(Plane plane, const Vec2& v);
geometry_msgs::Quaternion toQuaternion(Plane plane, double angle);
geometry_msgs::Pose toPose(Plane plane, const Vec2& position, double angle);
geometry_msgs::Transform toTransform(Plane plane, const Vec2& position, double angle);

/// What a request's fields were taken to mean where that could surprise, one line each: a zero
/// (a field the client left out) that stands for a YAML default, as "shapes[0].friction:
/// default 0.6", and fields the request's types do not use, as "radius: not used by a BOX".
using Notes = std::vector<std::string>;

/// A service's answer on success: "ok", or "ok (note; note)".
std::string okWithNotes(const Notes& notes);

/// A request's Body as a BodyDef. Checks what the message's own fields can tell (finite numbers,
/// sizes > 0, a name, at least one shape, known types) and names the failing field, e.g.
/// "body.shapes[1].width: must be > 0". Returns "" on success. Zero fields mean what omitted YAML
/// keys mean where zero is not a useful request (docs/ros_api.md lists each); `notes` gets the
/// ones that could surprise.
std::string toBodyDef(const impulse2d::Body& msg, BodyDef* out, Notes* notes = nullptr);

/// A request's Joint as a JointDef; the bodies stay named (msg.body_a, msg.body_b).
std::string toJointDef(const impulse2d::Joint& msg, JointDef* out, Notes* notes = nullptr);

uint8_t toBodyTypeMsg(BodyType type);

/// A shape as a spawn request would give it (GetBodyProperties.srv): POLYGON with its vertices
/// or CIRCLE with radius and offset; a friction of 0 as FRICTIONLESS.
impulse2d::Shape toShapeMsg(const ShapeProperties& shape);

/// A contact in the plane's 2D coordinates (z = 0), as the services use them.
impulse2d::Contact toContactMsg(const ContactSnapshot& contact);

}  // namespace bridge
}  // namespace impulse2d
