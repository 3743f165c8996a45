// The ~markers topic (see markers.hpp).
#include "markers.hpp"

#include <algorithm>
#include <cmath>

namespace impulse2d {
namespace bridge {
namespace {

using visualization_msgs::Marker;

constexpr double kLineWidth = 0.04;  // m: about two pixels with the RViz configs' views
constexpr int kCircleSegments = 32;
constexpr double kNormalBase = 0.1;  // m, so that light contacts still show
constexpr double kNormalMetresPerNewton = 0.01;
constexpr double kNormalMax = 1.0;  // m

std_msgs::ColorRGBA rgba(float r, float g, float b, float a = 1.0f) {
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

std_msgs::ColorRGBA bodyColor(const BodySnapshot& body) {
  if (body.type == BodyType::Static) return rgba(0.6f, 0.6f, 0.6f);
  if (body.type == BodyType::Kinematic) return rgba(1.0f, 0.6f, 0.1f);
  return body.awake ? rgba(0.2f, 0.9f, 0.3f) : rgba(0.35f, 0.45f, 0.9f);
}

Marker makeMarker(const MarkerInput& in, const std::string& ns, int id, int type) {
  Marker m;
  m.header.frame_id = in.frameId;
  m.header.stamp = in.stamp;
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.action = Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.scale.x = m.scale.y = m.scale.z = kLineWidth;
  return m;
}

void addSegment(Plane plane, const Vec2& a, const Vec2& b, Marker* m) {
  m->points.push_back(toPoint(plane, a));
  m->points.push_back(toPoint(plane, b));
}

// The outline in the body frame; a circle gets a radius line so that its rotation shows.
void addOutline(Plane plane, const ShapeOutline& shape, Marker* m) {
  if (shape.circle) {
    for (int i = 0; i < kCircleSegments; ++i) {
      const double a0 = 2.0 * kPi * i / kCircleSegments;
      const double a1 = 2.0 * kPi * (i + 1) / kCircleSegments;
      addSegment(plane, shape.center + shape.radius * Vec2(std::cos(a0), std::sin(a0)),
                 shape.center + shape.radius * Vec2(std::cos(a1), std::sin(a1)), m);
    }
    addSegment(plane, shape.center, shape.center + Vec2(shape.radius, 0.0), m);
    return;
  }
  const size_t n = shape.vertices.size();
  for (size_t i = 0; i < n; ++i)
    addSegment(plane, shape.vertices[i], shape.vertices[(i + 1) % n], m);
}

void addBodies(const MarkerInput& in, visualization_msgs::MarkerArray* out) {
  for (const BodySnapshot& body : in.bodies) {
    Marker outline = makeMarker(in, "bodies", body.index, Marker::LINE_LIST);
    outline.pose = toPose(in.plane, body.position, body.angle);
    outline.color = bodyColor(body);
    for (const ShapeOutline& shape : body.shapes) addOutline(in.plane, shape, &outline);
    if (!outline.points.empty()) out->markers.push_back(std::move(outline));

    if (body.name.empty()) continue;
    Marker label = makeMarker(in, "names", body.index, Marker::TEXT_VIEW_FACING);
    label.pose.position = toPoint(in.plane, body.position);
    label.scale.z = 0.15;
    label.color = rgba(1.0f, 1.0f, 1.0f, 0.8f);
    label.text = body.name;
    out->markers.push_back(std::move(label));
  }
}

void addContacts(const MarkerInput& in, visualization_msgs::MarkerArray* out) {
  if (in.contacts.empty()) return;
  Marker points = makeMarker(in, "contact_points", 0, Marker::SPHERE_LIST);
  points.scale.x = points.scale.y = points.scale.z = 0.12;
  points.color = rgba(1.0f, 0.2f, 0.2f);
  Marker normals = makeMarker(in, "contact_normals", 0, Marker::LINE_LIST);
  normals.color = rgba(1.0f, 0.9f, 0.2f);
  // A normal at a box's corner runs along the neighbouring edge; seen from above (xy) it is
  // lifted 2 cm towards the camera so the outline there does not hide it.
  if (in.plane == Plane::XY) normals.pose.position.z = 0.02;
  for (const ContactSnapshot& c : in.contacts) {
    points.points.push_back(toPoint(in.plane, c.point));
    const double force = std::max(0.0, c.normalImpulse) / in.timeStep;
    const double length = std::min(kNormalMax, kNormalBase + kNormalMetresPerNewton * force);
    addSegment(in.plane, c.point, c.point + length * c.normal, &normals);
  }
  out->markers.push_back(std::move(points));
  out->markers.push_back(std::move(normals));
}

void addJoints(const MarkerInput& in, visualization_msgs::MarkerArray* out) {
  if (in.joints.empty()) return;
  Marker lines = makeMarker(in, "joints", 0, Marker::LINE_LIST);
  lines.color = rgba(0.9f, 0.3f, 0.9f);
  Marker anchors = makeMarker(in, "joint_anchors", 0, Marker::SPHERE_LIST);
  anchors.scale.x = anchors.scale.y = anchors.scale.z = 0.15;
  anchors.color = lines.color;
  for (const JointSnapshot& j : in.joints) {
    addSegment(in.plane, j.originA, j.anchorA, &lines);
    addSegment(in.plane, j.anchorA, j.anchorB, &lines);  // a distance joint's rod; else ~0
    addSegment(in.plane, j.anchorB, j.originB, &lines);
    anchors.points.push_back(toPoint(in.plane, j.anchorA));
    anchors.points.push_back(toPoint(in.plane, j.anchorB));
  }
  out->markers.push_back(std::move(lines));
  out->markers.push_back(std::move(anchors));
}

}  // namespace

visualization_msgs::MarkerArray buildMarkers(const MarkerInput& in) {
  visualization_msgs::MarkerArray out;
  Marker clear;
  clear.header.frame_id = in.frameId;
  clear.header.stamp = in.stamp;
  clear.action = Marker::DELETEALL;
  clear.pose.orientation.w = 1.0;
  out.markers.push_back(clear);
  addBodies(in, &out);
  addContacts(in, &out);
  addJoints(in, &out);
  return out;
}

}  // namespace bridge
}  // namespace impulse2d
