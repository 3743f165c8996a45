// The node's ROS-side pieces without a master: message conversions, the plane mapping, the
// ~scene parameter as YAML, and SimWorld's bookkeeping (reset, wrenches, simulated time).
#include "../../src/ros/conversions.hpp"
#include "../../src/ros/markers.hpp"
#include "../../src/ros/scene_param.hpp"
#include "../../src/ros/sim_world.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace impulse2d {
namespace bridge {
namespace {

impulse2d::Body boxMsg(const std::string& name) {
  impulse2d::Body body;
  body.name = name;
  body.type = impulse2d::Body::DYNAMIC;
  impulse2d::Shape box;
  box.type = impulse2d::Shape::BOX;
  box.width = 1.0;
  box.height = 0.5;
  body.shapes.push_back(box);
  return body;
}

TEST(Plane, XzMapsYToZAndTurnsAboutMinusY) {
  const geometry_msgs::Point p = toPoint(Plane::XZ, Vec2(1.0, 2.0));
  EXPECT_EQ(p.x, 1.0);
  EXPECT_EQ(p.y, 0.0);
  EXPECT_EQ(p.z, 2.0);
  // A quarter turn takes the body's x axis (1, 0, 0) to the plane's y axis (0, 0, 1).
  const geometry_msgs::Quaternion q = toQuaternion(Plane::XZ, kPi / 2);
  const double x = 1.0 - 2.0 * (q.y * q.y + q.z * q.z);  // first column of the rotation
  const double z = 2.0 * (q.x * q.z - q.w * q.y);
  EXPECT_NEAR(x, 0.0, 1e-12);
  EXPECT_NEAR(z, 1.0, 1e-12);
}

TEST(Plane, XyIsTopDown) {
  const geometry_msgs::Point p = toPoint(Plane::XY, Vec2(1.0, 2.0));
  EXPECT_EQ(p.y, 2.0);
  EXPECT_EQ(p.z, 0.0);
  const geometry_msgs::Quaternion q = toQuaternion(Plane::XY, 0.5);
  EXPECT_NEAR(q.z, std::sin(0.25), 1e-15);
  EXPECT_NEAR(q.w, std::cos(0.25), 1e-15);
  Plane plane;
  EXPECT_TRUE(parsePlane("xy", &plane));
  EXPECT_FALSE(parsePlane("yz", &plane));
}

TEST(Conversions, BodyMessageBecomesADefinition) {
  impulse2d::Body msg = boxMsg("b");
  msg.pose.x = 1.0;
  msg.pose.theta = 0.25;
  msg.twist.linear.y = -2.0;
  BodyDef def;
  ASSERT_EQ(toBodyDef(msg, &def), "");
  EXPECT_EQ(def.type, BodyType::Dynamic);
  EXPECT_EQ(def.position, Vec2(1.0, 0.0));
  EXPECT_EQ(def.angle, 0.25);
  EXPECT_EQ(def.linearVelocity, Vec2(0.0, -2.0));
  ASSERT_EQ(def.shapes.size(), 1u);
  EXPECT_EQ(def.shapes[0].size, Vec2(1.0, 0.5));
  EXPECT_EQ(def.shapes[0].density, 1.0);  // 0 in the message means the default
}

TEST(Conversions, BadBodyMessagesNameTheField) {
  BodyDef def;
  impulse2d::Body msg = boxMsg("b");
  msg.shapes[0].height = 0.0;
  EXPECT_EQ(toBodyDef(msg, &def), "body.shapes[0].height: must be finite and > 0");
  msg = boxMsg("b");
  msg.pose.theta = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(toBodyDef(msg, &def), "body.pose.theta: must be finite");
  msg = boxMsg("");
  EXPECT_EQ(toBodyDef(msg, &def), "body.name: must not be empty");
  msg = boxMsg("b");
  msg.shapes.clear();
  EXPECT_EQ(toBodyDef(msg, &def), "body.shapes: a body needs at least one shape");
  msg = boxMsg("b");
  msg.shapes[0].type = impulse2d::Shape::POLYGON;
  EXPECT_EQ(toBodyDef(msg, &def), "body.shapes[0].vertices: a polygon needs at least 3");
}

TEST(Conversions, JointMessages) {
  impulse2d::Joint msg;
  msg.name = "j";
  msg.body_a = "a";
  msg.body_b = "a";
  JointDef def;
  EXPECT_EQ(toJointDef(msg, &def), "joint.body_b: must differ from body_a");
  msg.body_b = "b";
  msg.type = impulse2d::Joint::PRISMATIC;
  msg.axis.x = 2.0;
  msg.anchor.y = 3.0;
  Notes notes;
  ASSERT_EQ(toJointDef(msg, &def, &notes), "");
  EXPECT_EQ(def.axis, Vec2(1.0, 0.0));
  EXPECT_EQ(def.anchor, Vec2(0.0, 3.0));
  EXPECT_TRUE(notes.empty());
}

// Zero is what a client sends for a field it leaves out. Where zero is no useful request it
// means what the omitted YAML key means, and the answer says so where that could surprise.
TEST(Conversions, ZeroFieldsMeanTheYamlDefaults) {
  const ShapeDef yaml;  // what a scene's shape without those keys gets
  impulse2d::Body msg = boxMsg("b");
  BodyDef def;
  Notes notes;
  ASSERT_EQ(toBodyDef(msg, &def, &notes), "");
  EXPECT_EQ(def.shapes[0].friction, yaml.friction);
  EXPECT_EQ(def.shapes[0].friction, 0.6);
  EXPECT_EQ(def.shapes[0].density, yaml.density);
  EXPECT_EQ(def.shapes[0].restitution, yaml.restitution);
  EXPECT_EQ(def.mass, BodyDef().mass);
  ASSERT_EQ(notes, Notes{"shapes[0].friction: default 0.6"});
  EXPECT_EQ(okWithNotes(notes), "ok (shapes[0].friction: default 0.6)");
  EXPECT_EQ(okWithNotes(Notes()), "ok");

  // No friction at all is asked for by name; other negative values are mistakes.
  msg.shapes[0].friction = impulse2d::Shape::FRICTIONLESS;
  notes.clear();
  ASSERT_EQ(toBodyDef(msg, &def, &notes), "");
  EXPECT_EQ(def.shapes[0].friction, 0.0);
  EXPECT_TRUE(notes.empty());
  msg.shapes[0].friction = 0.25;
  ASSERT_EQ(toBodyDef(msg, &def, &notes), "");
  EXPECT_EQ(def.shapes[0].friction, 0.25);
  EXPECT_TRUE(notes.empty());
  for (const double bad :
       {-0.5, -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
    msg.shapes[0].friction = bad;
    EXPECT_EQ(toBodyDef(msg, &def),
              "body.shapes[0].friction: must be >= 0 (0: the default 0.6), or FRICTIONLESS (-1) "
              "for none")
        << bad;
  }

  // STATIC is 0, where an omitted YAML type is dynamic: the answer says what the body is.
  msg = boxMsg("b");
  msg.type = impulse2d::Body::STATIC;
  msg.shapes.push_back(msg.shapes[0]);
  msg.shapes[1].friction = 0.9;
  msg.shapes.push_back(msg.shapes[0]);
  notes.clear();
  ASSERT_EQ(toBodyDef(msg, &def, &notes), "");
  EXPECT_EQ(def.type, BodyType::Static);
  EXPECT_EQ(okWithNotes(notes),
            "ok (type: STATIC (0), it never moves; DYNAMIC is 2; shapes[0].friction: default "
            "0.6; shapes[2].friction: default 0.6)");
}

TEST(Conversions, FieldsTheTypeDoesNotUseArePointedOut) {
  impulse2d::Body msg = boxMsg("b");
  msg.shapes[0].radius = 0.5;
  msg.shapes[0].friction = 0.5;
  BodyDef def;
  Notes notes;
  ASSERT_EQ(toBodyDef(msg, &def, &notes), "");
  EXPECT_EQ(notes, Notes{"shapes[0].radius: not used by a BOX"});
  msg.shapes[0].type = impulse2d::Shape::CIRCLE;
  notes.clear();
  ASSERT_EQ(toBodyDef(msg, &def, &notes), "");
  EXPECT_EQ(notes, Notes{"shapes[0].width, height: not used by a CIRCLE"});

  impulse2d::Joint joint;
  joint.name = "j";
  joint.body_a = "a";
  joint.body_b = "b";
  JointDef jointDef;
  notes.clear();
  ASSERT_EQ(toJointDef(joint, &jointDef, &notes), "");
  EXPECT_TRUE(notes.empty()) << "a plain revolute joint";

  joint.type = impulse2d::Joint::PRISMATIC;  // axis left out: YAML's [1, 0]
  ASSERT_EQ(toJointDef(joint, &jointDef, &notes), "");
  EXPECT_EQ(jointDef.axis, Vec2(1.0, 0.0));
  EXPECT_EQ(jointDef.axis, JointDef().axis);
  EXPECT_EQ(notes, Notes{"axis: default (1, 0)"});

  joint.type = impulse2d::Joint::REVOLUTE;
  joint.axis.y = 1.0;
  joint.length = 2.0;
  joint.lower = -1.0;
  joint.upper = 1.0;
  joint.enable_motor = true;
  notes.clear();
  ASSERT_EQ(toJointDef(joint, &jointDef, &notes), "");
  EXPECT_EQ(okWithNotes(notes),
            "ok (axis: not used by a REVOLUTE joint; length: not used by a REVOLUTE joint; "
            "lower, upper: not used, enable_limit is false; max_motor_torque: 0, so the motor "
            "cannot drive the joint)");
  EXPECT_FALSE(jointDef.enableLimit);

  joint = impulse2d::Joint();
  joint.name = "j";
  joint.body_a = "a";
  joint.body_b = "b";
  joint.type = impulse2d::Joint::WELD;
  joint.motor_speed = 1.0;
  joint.enable_limit = true;
  notes.clear();
  ASSERT_EQ(toJointDef(joint, &jointDef, &notes), "");
  EXPECT_EQ(okWithNotes(notes),
            "ok (enable_limit, lower, upper: not used by a WELD joint; enable_motor, motor_speed, "
            "max_motor_torque: not used by a WELD joint)");
}

TEST(SceneParam, DictionaryBecomesYamlWithExactNumbers) {
  XmlRpc::XmlRpcValue scene;
  scene["world"]["time_step"] = 0.1;
  scene["world"]["plane"] = std::string("xy");
  scene["bodies"][0]["name"] = std::string("a \"quoted\" name");
  scene["bodies"][0]["bullet"] = true;
  scene["bodies"][0]["position"][0] = 1;
  scene["bodies"][0]["position"][1] = -std::numeric_limits<double>::infinity();
  EXPECT_EQ(toYaml(scene),
            "{\"bodies\": [{\"bullet\": true, \"name\": \"a \\\"quoted\\\" name\", "
            "\"position\": [1, -.inf]}], \"world\": {\"plane\": \"xy\", "
            "\"time_step\": 0.10000000000000001}}");
}

const char* kScene = R"(
world: {time_step: 0.01, plane: xy, frame_id: map}
bodies:
  - {name: ground, type: static, position: [0, -0.5], shapes: [{type: box, size: [10, 1]}]}
  - {name: box, position: [0, 5], shapes: [{type: box, size: [1, 1]}]}
)";

TEST(SimWorld, ResetRestoresTheStartSceneButNotTheClock) {
  SimWorld sim;
  std::string error;
  ASSERT_TRUE(sim.loadStartScene(kScene, &error)) << error;
  EXPECT_EQ(sim.frameId(), "map");
  EXPECT_EQ(sim.plane(), "xy");
  BodyDef extra;
  extra.name = "extra";
  extra.shapes.resize(1);
  ASSERT_TRUE(sim.spawnBody(extra, &error)) << error;
  EXPECT_FALSE(sim.spawnBody(extra, &error));
  EXPECT_EQ(error, "body.name: a body named 'extra' already exists");
  for (int i = 0; i < 3; ++i) sim.step();
  EXPECT_EQ(sim.simTimeNs(), 30000000);
  sim.reset();
  EXPECT_EQ(sim.bodyCount(), 2u);
  BodySnapshot box;
  ASSERT_TRUE(sim.getBodyState("box", &box, &error));
  EXPECT_EQ(box.position, Vec2(0.0, 5.0));
  EXPECT_EQ(sim.simTimeNs(), 30000000);
}

TEST(SimWorld, BadStartSceneLeavesAnEmptyWorld) {
  SimWorld sim;
  std::string error;
  EXPECT_FALSE(sim.loadStartScene("bodies: [{name: x}]", &error));
  EXPECT_FALSE(error.empty());
  EXPECT_EQ(sim.bodyCount(), 0u);
  sim.reset();
  EXPECT_EQ(sim.bodyCount(), 0u);
}

TEST(SimWorld, WrenchLastsItsDuration) {
  SimWorld sim;
  std::string error;
  ASSERT_TRUE(sim.loadStartScene(kScene, &error)) << error;
  // 1 kg; twice its weight upwards for 5 steps, then gravity alone for 5.
  ASSERT_TRUE(sim.applyWrench("box", Vec2(0.0, 2 * 9.81), 0.0, Vec2(0.0, 5.0), 0.05, &error));
  for (int i = 0; i < 5; ++i) sim.step();
  BodySnapshot box;
  ASSERT_TRUE(sim.getBodyState("box", &box, &error));
  EXPECT_NEAR(box.linearVelocity.y(), 5 * 9.81 * 0.01, 1e-9);
  for (int i = 0; i < 5; ++i) sim.step();
  ASSERT_TRUE(sim.getBodyState("box", &box, &error));
  EXPECT_NEAR(box.linearVelocity.y(), 0.0, 1e-9);
  EXPECT_FALSE(sim.applyWrench("ground", Vec2(1.0, 0.0), 0.0, Vec2::Zero(), 0.0, &error));
}

TEST(Markers, StartWithDeleteAllAndDrawEveryBody) {
  SimWorld sim;
  std::string error;
  ASSERT_TRUE(sim.loadStartScene(kScene, &error)) << error;
  MarkerInput in;
  in.bodies = sim.bodies(true);
  const visualization_msgs::MarkerArray out = buildMarkers(in);
  ASSERT_FALSE(out.markers.empty());
  EXPECT_EQ(out.markers[0].action, visualization_msgs::Marker::DELETEALL);
  int outlines = 0;
  for (const auto& m : out.markers) {
    if (m.ns == "bodies") {
      ++outlines;
      EXPECT_EQ(m.points.size(), 8u);  // a box: four edges
    }
  }
  EXPECT_EQ(outlines, 2);
}

}  // namespace
}  // namespace bridge
}  // namespace impulse2d
