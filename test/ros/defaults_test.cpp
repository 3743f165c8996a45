// A body spawned by message with fields left out is the body the same YAML makes, property by
// property; answers say which defaults they took; bodies the world removes are published.
#include "world_test_util.hpp"

#include <impulse2d/ApplyWrench.h>
#include <impulse2d/GetBodyProperties.h>
#include <impulse2d/LoadScene.h>
#include <impulse2d/RemovedBodies.h>
#include <impulse2d/SpawnBody.h>
#include <impulse2d/Step.h>

#include <string>
#include <vector>

namespace impulse2d_test {
namespace {

impulse2d::GetBodyProperties::Response properties(const std::string& name) {
  impulse2d::GetBodyProperties srv;
  srv.request.name = name;
  EXPECT_TRUE(call("get_body_properties", srv));
  EXPECT_TRUE(srv.response.success) << name << ": " << srv.response.message;
  return srv.response;
}

struct Body {
  impulse2d::GetBodyProperties::Response properties;
  impulse2d::GetBodyState::Response state;
};

// Reads the body and deletes it, so that the next one can take its name.
Body takeBody(const std::string& name) {
  Body body;
  body.properties = properties(name);
  EXPECT_TRUE(getState(name, &body.state)) << name;
  EXPECT_TRUE(remove(name)) << name;
  return body;
}

// Every property, exactly: both went through the same engine definition or they differ.
void expectSameBody(const Body& yaml, const Body& msg, const std::string& what) {
  SCOPED_TRACE(what);
  const auto& a = yaml.properties;
  const auto& b = msg.properties;
  EXPECT_EQ(a.type, b.type);
  EXPECT_EQ(a.mass, b.mass);
  EXPECT_EQ(a.inertia, b.inertia);
  EXPECT_EQ(a.center_of_mass.x, b.center_of_mass.x);
  EXPECT_EQ(a.center_of_mass.y, b.center_of_mass.y);
  EXPECT_EQ(a.linear_damping, b.linear_damping);
  EXPECT_EQ(a.angular_damping, b.angular_damping);
  EXPECT_EQ(a.bullet, b.bullet);
  ASSERT_EQ(a.shapes.size(), b.shapes.size());
  for (size_t i = 0; i < a.shapes.size(); ++i) {
    SCOPED_TRACE("shapes[" + std::to_string(i) + "]");
    const impulse2d::Shape& s = a.shapes[i];
    const impulse2d::Shape& t = b.shapes[i];
    EXPECT_EQ(s.type, t.type);
    EXPECT_EQ(s.radius, t.radius);
    EXPECT_EQ(s.offset.x, t.offset.x);
    EXPECT_EQ(s.offset.y, t.offset.y);
    ASSERT_EQ(s.vertices.size(), t.vertices.size());
    for (size_t k = 0; k < s.vertices.size(); ++k) {
      EXPECT_EQ(s.vertices[k].x, t.vertices[k].x) << k;
      EXPECT_EQ(s.vertices[k].y, t.vertices[k].y) << k;
    }
    EXPECT_EQ(s.density, t.density);
    EXPECT_EQ(s.friction, t.friction);
    EXPECT_EQ(s.restitution, t.restitution);
  }
  EXPECT_EQ(yaml.state.pose.x, msg.state.pose.x);
  EXPECT_EQ(yaml.state.pose.y, msg.state.pose.y);
  EXPECT_EQ(yaml.state.pose.theta, msg.state.pose.theta);
  EXPECT_EQ(yaml.state.twist.linear.x, msg.state.twist.linear.x);
  EXPECT_EQ(yaml.state.twist.linear.y, msg.state.twist.linear.y);
  EXPECT_EQ(yaml.state.twist.angular.z, msg.state.twist.angular.z);
}

Body fromYaml(const std::string& name, const std::string& keys) {
  impulse2d::LoadScene srv;
  srv.request.yaml = "bodies: [{name: " + name + ", " + keys + "}]";
  EXPECT_TRUE(call("load_scene", srv));
  EXPECT_TRUE(srv.response.success) << srv.response.message;
  return takeBody(name);
}

Body fromMessage(const impulse2d::Body& msg, const std::string& expectedAnswer) {
  std::string answer;
  EXPECT_TRUE(spawn(msg, &answer)) << answer;
  EXPECT_EQ(answer, expectedAnswer);
  return takeBody(msg.name);
}

impulse2d::Shape boxShape(double width, double height) {
  impulse2d::Shape box;
  box.type = impulse2d::Shape::BOX;
  box.width = width;
  box.height = height;
  return box;
}

geometry_msgs::Point point(double x, double y) {
  geometry_msgs::Point p;
  p.x = x;
  p.y = y;
  return p;
}

TEST(Defaults, ABodyByMessageIsTheBodyTheSameYamlMakes) {
  PausedWorld paused;  // nothing moves between spawning and reading
  const std::string name = "dfl_body";

  // The box: density, friction and restitution left out.
  impulse2d::Body msg;
  msg.name = name;
  msg.type = impulse2d::Body::DYNAMIC;
  msg.pose.x = -12.0;
  msg.pose.y = 8.0;
  msg.shapes.push_back(boxShape(0.3, 0.3));
  msg.mass = 1.0;
  Body yaml = fromYaml(name, "position: [-12.0, 8.0], mass: 1.0, shapes: [{size: [0.3, 0.3]}]");
  EXPECT_EQ(yaml.properties.shapes.at(0).friction, 0.6);
  expectSameBody(yaml, fromMessage(msg, "ok (shapes[0].friction: default 0.6)"), "box");

  // Nothing but a name, a type and one circle: every other field left out.
  msg = impulse2d::Body();
  msg.name = name;
  msg.type = impulse2d::Body::DYNAMIC;
  msg.shapes.resize(1);
  msg.shapes[0].type = impulse2d::Shape::CIRCLE;
  msg.shapes[0].radius = 0.25;
  yaml = fromYaml(name, "shapes: [{type: circle, radius: 0.25}]");
  expectSameBody(yaml, fromMessage(msg, "ok (shapes[0].friction: default 0.6)"), "bare circle");

  // Every field given, on a compound body: a polygon and an offset, turned circle.
  msg.pose.x = 3.0;
  msg.pose.y = 20.0;
  msg.pose.theta = 0.5;
  msg.twist.linear.x = 1.5;
  msg.twist.linear.y = -0.5;
  msg.twist.angular.z = 2.0;
  msg.linear_damping = 0.1;
  msg.angular_damping = 0.2;
  msg.bullet = true;
  msg.shapes[0].offset.x = 0.4;
  msg.shapes[0].offset.y = -0.1;
  msg.shapes[0].density = 3.0;
  msg.shapes[0].friction = 0.9;
  msg.shapes[0].restitution = 0.5;
  impulse2d::Shape wedge;
  wedge.type = impulse2d::Shape::POLYGON;
  wedge.vertices = {point(0.0, 0.0), point(1.0, 0.0), point(0.0, 1.0)};
  wedge.offset.theta = 0.3;
  wedge.density = 2.0;
  wedge.friction = 0.2;
  msg.shapes.push_back(wedge);
  yaml = fromYaml(name,
                  "position: [3.0, 20.0], angle: 0.5, linear_velocity: [1.5, -0.5], "
                  "angular_velocity: 2.0, linear_damping: 0.1, angular_damping: 0.2, bullet: "
                  "true, shapes: [{type: circle, radius: 0.25, offset: [0.4, -0.1], density: "
                  "3.0, friction: 0.9, restitution: 0.5}, {type: polygon, vertices: [[0, 0], [1, "
                  "0], [0, 1]], angle: 0.3, density: 2.0, friction: 0.2}]");
  expectSameBody(yaml, fromMessage(msg, "ok"), "every field");

  // An explicit mass with the densities left out.
  msg.mass = 5.0;
  msg.shapes[0].density = 0.0;
  msg.shapes[1].density = 0.0;
  yaml = fromYaml(name,
                  "position: [3.0, 20.0], angle: 0.5, linear_velocity: [1.5, -0.5], "
                  "angular_velocity: 2.0, linear_damping: 0.1, angular_damping: 0.2, bullet: "
                  "true, mass: 5.0, shapes: [{type: circle, radius: 0.25, offset: [0.4, -0.1], "
                  "friction: 0.9, restitution: 0.5}, {type: polygon, vertices: [[0, 0], [1, 0], "
                  "[0, 1]], angle: 0.3, friction: 0.2}]");
  expectSameBody(yaml, fromMessage(msg, "ok"), "mass");

  // No friction, asked for: FRICTIONLESS in a message, 0 in YAML.
  msg = impulse2d::Body();
  msg.name = name;
  msg.type = impulse2d::Body::DYNAMIC;
  msg.shapes.push_back(boxShape(1.0, 0.5));
  msg.shapes[0].friction = impulse2d::Shape::FRICTIONLESS;
  yaml = fromYaml(name, "shapes: [{size: [1.0, 0.5], friction: 0}]");
  EXPECT_EQ(yaml.properties.shapes.at(0).friction, impulse2d::Shape::FRICTIONLESS);
  expectSameBody(yaml, fromMessage(msg, "ok"), "frictionless");

  // STATIC is type 0, where an omitted YAML type is dynamic: the answer says so.
  msg.type = impulse2d::Body::STATIC;
  msg.shapes[0].friction = 0.0;
  yaml = fromYaml(name, "type: static, shapes: [{size: [1.0, 0.5]}]");
  EXPECT_EQ(yaml.properties.mass, 0.0);
  expectSameBody(yaml,
                 fromMessage(msg,
                             "ok (type: STATIC (0), it never moves; DYNAMIC is 2; "
                             "shapes[0].friction: default 0.6)"),
                 "static");
}

TEST(Defaults, AForceAtAnOmittedPointIsPointedOut) {
  PausedWorld paused;
  ASSERT_TRUE(spawn(boxBody("dfl_pushed", -8.0, 6.0)));
  impulse2d::ApplyWrench wrench;
  wrench.request.body = "dfl_pushed";
  wrench.request.force.x = 1.0;
  ASSERT_TRUE(call("apply_wrench", wrench));
  EXPECT_TRUE(wrench.response.success);
  EXPECT_EQ(wrench.response.message,
            "ok (point: (0, 0), the world origin, 10 m from the centre of mass: the force also "
            "turns the body)");
  wrench.request.point.x = -8.0;
  wrench.request.point.y = 6.0;
  ASSERT_TRUE(call("apply_wrench", wrench));
  EXPECT_EQ(wrench.response.message, "ok");
  EXPECT_TRUE(remove("dfl_pushed"));
}

// A body spawned far below the ground falls with nothing to stop it: lost for good, and with
// the start scene's remove_lost_bodies the world removes it at the end of the step, and
// ~removed_bodies says so, to subscribers then and to any that come later.
TEST(Defaults, BodiesTheWorldRemovesArePublishedLatched) {
  Latest<impulse2d::RemovedBodies> before(worldNs() + "/removed_bodies");
  ASSERT_TRUE(waitFor([&] { return before.get() != nullptr; }, 10.0)) << "latched at start";
  const uint64_t count = before.get()->count;

  {
    PausedWorld paused;  // so that the one step that removes it is the first it takes
    ASSERT_TRUE(spawn(boxBody("dfl_falling", 12.0, -10.0, 0.2, 0.2)));
    impulse2d::Step step;
    step.request.steps = 1;
    ASSERT_TRUE(call("step", step));
  }
  ASSERT_TRUE(waitFor([&] { return before.get()->count == count + 1; }, 10.0));
  impulse2d::GetBodyState::Response state;
  EXPECT_FALSE(getState("dfl_falling", &state));

  Latest<impulse2d::RemovedBodies> later(worldNs() + "/removed_bodies");
  ASSERT_TRUE(waitFor([&] { return later.get() != nullptr; }, 10.0));
  for (const auto& msg : {before.get(), later.get()}) {
    EXPECT_EQ(msg->count, count + 1);
    ASSERT_FALSE(msg->bodies.empty());
    const impulse2d::RemovedBody& removed = msg->bodies.back();
    EXPECT_EQ(removed.name, "dfl_falling");
    EXPECT_EQ(removed.cause, impulse2d::RemovedBody::LOST_FOR_GOOD);
    EXPECT_NE(removed.reason.find("lost for good"), std::string::npos) << removed.reason;
    EXPECT_EQ(removed.position.x, 12.0);
    EXPECT_LT(removed.position.y, -10.0);
  }
}

}  // namespace
}  // namespace impulse2d_test
