// ~markers without a master: what RViz is given to draw. The colours are the ones the RViz
// screenshot stage (scripts/check_screenshot.py) looks for, by hue; the normals' lengths follow
// markers.hpp: 0.1 m + 1 cm per newton of normal force, at most 1 m.
#include "../../src/ros/markers.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace impulse2d {
namespace bridge {
namespace {

using visualization_msgs::Marker;
using visualization_msgs::MarkerArray;

BodySnapshot squareBody(int index, BodyType type, bool awake) {
  BodySnapshot body;
  body.index = index;
  body.name = "body" + std::to_string(index);
  body.type = type;
  body.awake = awake;
  body.position = Vec2(2.0 * index, 1.0);
  ShapeOutline square;
  square.vertices = {Vec2(-0.5, -0.5), Vec2(0.5, -0.5), Vec2(0.5, 0.5), Vec2(-0.5, 0.5)};
  body.shapes.push_back(square);
  return body;
}

const Marker* findMarker(const MarkerArray& array, const std::string& ns, int id) {
  for (const Marker& m : array.markers)
    if (m.ns == ns && m.id == id) return &m;
  return nullptr;
}

double segmentLength(const Marker& m, size_t first) {
  const geometry_msgs::Point& a = m.points.at(first);
  const geometry_msgs::Point& b = m.points.at(first + 1);
  return std::sqrt((b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y) +
                   (b.z - a.z) * (b.z - a.z));
}

TEST(Markers, BodyColoursTellTheState) {
  MarkerInput in;
  in.bodies = {squareBody(0, BodyType::Static, true), squareBody(1, BodyType::Kinematic, true),
               squareBody(2, BodyType::Dynamic, true), squareBody(3, BodyType::Dynamic, false)};
  const MarkerArray out = buildMarkers(in);
  const Marker* fixed = findMarker(out, "bodies", 0);
  const Marker* kinematic = findMarker(out, "bodies", 1);
  const Marker* awake = findMarker(out, "bodies", 2);
  const Marker* asleep = findMarker(out, "bodies", 3);
  ASSERT_TRUE(fixed && kinematic && awake && asleep);

  // Static: grey. Kinematic: orange (red > green > blue). Awake: green. Asleep: blue.
  EXPECT_EQ(fixed->color.r, fixed->color.g);
  EXPECT_EQ(fixed->color.g, fixed->color.b);
  EXPECT_GT(kinematic->color.r, kinematic->color.g);
  EXPECT_GT(kinematic->color.g, kinematic->color.b);
  EXPECT_GT(awake->color.g, awake->color.r);
  EXPECT_GT(awake->color.g, awake->color.b);
  EXPECT_GT(asleep->color.b, asleep->color.r);
  EXPECT_GT(asleep->color.b, asleep->color.g);
  for (const Marker* m : {fixed, kinematic, awake, asleep}) {
    EXPECT_EQ(m->color.a, 1.0f);
    EXPECT_EQ(m->type, Marker::LINE_LIST);
    EXPECT_EQ(m->points.size(), 8u);  // four edges
  }
}

TEST(Markers, NormalsGrowWithTheContactForce) {
  MarkerInput in;
  in.plane = Plane::XY;
  in.timeStep = 0.01;
  // Normal impulses of 0, 0.2 N s (20 N over a 0.01 s step), 1 N s (100 N: capped) and a
  // negative one, which pushes nothing and draws like 0.
  for (const double impulse : {0.0, 0.2, 1.0, -0.5}) {
    ContactSnapshot c;
    c.bodyA = "a";
    c.bodyB = "b";
    c.point = Vec2(1.0, 2.0);
    c.normal = Vec2(0.6, 0.8);
    c.normalImpulse = impulse;
    in.contacts.push_back(c);
  }
  const MarkerArray out = buildMarkers(in);
  const Marker* points = findMarker(out, "contact_points", 0);
  const Marker* normals = findMarker(out, "contact_normals", 0);
  ASSERT_TRUE(points && normals);
  EXPECT_EQ(points->points.size(), 4u);
  ASSERT_EQ(normals->points.size(), 8u);
  EXPECT_NEAR(segmentLength(*normals, 0), 0.1, 1e-12);
  EXPECT_NEAR(segmentLength(*normals, 2), 0.1 + 0.01 * 20.0, 1e-12);
  EXPECT_NEAR(segmentLength(*normals, 4), 1.0, 1e-12);
  EXPECT_NEAR(segmentLength(*normals, 6), 0.1, 1e-12);
  // Starts at the contact point and runs along the normal, in the xy plane.
  EXPECT_DOUBLE_EQ(normals->points[2].x, 1.0);
  EXPECT_DOUBLE_EQ(normals->points[2].y, 2.0);
  EXPECT_NEAR(normals->points[3].x, 1.0 + 0.3 * 0.6, 1e-12);
  EXPECT_NEAR(normals->points[3].y, 2.0 + 0.3 * 0.8, 1e-12);
  EXPECT_EQ(normals->points[3].z, 0.0);
}

TEST(Markers, JointsAreDrawnThroughTheirAnchors) {
  MarkerInput in;
  in.plane = Plane::XZ;
  JointSnapshot j;
  j.originA = Vec2(0.0, 0.0);
  j.anchorA = j.anchorB = Vec2(1.0, 0.0);
  j.originB = Vec2(2.0, 0.0);
  in.joints.push_back(j);
  const MarkerArray out = buildMarkers(in);
  const Marker* lines = findMarker(out, "joints", 0);
  const Marker* anchors = findMarker(out, "joint_anchors", 0);
  ASSERT_TRUE(lines && anchors);
  ASSERT_EQ(lines->points.size(), 6u);  // origin A -> anchor A -> anchor B -> origin B
  EXPECT_EQ(lines->points.front().x, 0.0);
  EXPECT_EQ(lines->points.back().x, 2.0);
  ASSERT_EQ(anchors->points.size(), 2u);
  EXPECT_EQ(anchors->points[0].x, 1.0);
  EXPECT_EQ(anchors->points[0].z, 0.0);  // xz: the scene's y is z
}

TEST(Markers, NothingToDrawIsJustTheDeleteAll) {
  const MarkerArray out = buildMarkers(MarkerInput());
  ASSERT_EQ(out.markers.size(), 1u);
  EXPECT_EQ(out.markers[0].action, Marker::DELETEALL);
}

}  // namespace
}  // namespace bridge
}  // namespace impulse2d
