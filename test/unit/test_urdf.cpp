// The URDF loader: links onto the plane as bodies and shapes, inertials, joints with their
// limits and axis signs, fixed links merged, and refusals that name the link or joint.
#include <impulse2d/body.hpp>
#include <impulse2d/urdf.hpp>
#include <impulse2d/world.hpp>

#include <gtest/gtest.h>

#include "urdf_fixture.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

namespace impulse2d {
namespace {

constexpr double kTol = 1e-9;
constexpr double kPi = 3.14159265358979323846;
// URDF files write pi/2 as 1.5707963; the shapes' angles inherit that rounding.
constexpr double kRpyTol = 1e-6;

std::string fixture(const std::string& name) { return test::urdfFixture(name); }

UrdfModel load(const std::string& xml, const std::string& model = "m",
               const std::string& plane = "xz") {
  UrdfPlacement placement;
  placement.modelName = model;
  placement.plane = plane;
  UrdfModel out;
  std::string error;
  EXPECT_TRUE(parseUrdf(xml, placement, &out, &error)) << error;
  return out;
}

std::string refusal(const std::string& xml, const std::string& plane = "xz") {
  UrdfPlacement placement;
  placement.modelName = "m";
  placement.plane = plane;
  UrdfModel out;
  out.warnings.push_back("stale");
  std::string error;
  EXPECT_FALSE(parseUrdf(xml, placement, &out, &error));
  EXPECT_TRUE(out.scene.bodies.empty() && out.scene.joints.empty() && out.warnings.empty());
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  return error;
}

const BodyDef& bodyNamed(const UrdfModel& model, const std::string& name) {
  for (const BodyDef& body : model.scene.bodies) {
    if (body.name == name) return body;
  }
  ADD_FAILURE() << "no body " << name;
  static const BodyDef none;
  return none;
}

const SceneJoint& jointNamed(const UrdfModel& model, const std::string& name) {
  for (const SceneJoint& joint : model.scene.joints) {
    if (joint.def.name == name) return joint;
  }
  ADD_FAILURE() << "no joint " << name;
  static const SceneJoint none;
  return none;
}

const UrdfJointInfo& infoNamed(const UrdfModel& model, const std::string& name) {
  for (const UrdfJointInfo& info : model.joints) {
    if (info.name == name) return info;
  }
  ADD_FAILURE() << "no joint info " << name;
  static const UrdfJointInfo none;
  return none;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// A minimal robot: `body` goes inside <robot>.
std::string robot(const std::string& body) {
  return "<?xml version=\"1.0\"?><robot name=\"r\">" + body + "</robot>";
}

const char* const kBoxLink =
    "<link name=\"base\"><collision><geometry><box size=\"1 1 1\"/></geometry></collision></link>";

std::string armWithJoint(const std::string& jointAttributes, const std::string& jointBody) {
  return robot(std::string(kBoxLink) + "<joint name=\"j\" " + jointAttributes +
               "><parent link=\"base\"/><child link=\"arm\"/>" + jointBody +
               "</joint><link name=\"arm\"><collision><origin xyz=\"0.5 0 0\"/><geometry>"
               "<box size=\"1 0.1 0.1\"/></geometry></collision></link>");
}

TEST(Urdf, TwoLinkArmBodiesShapesAndMasses) {
  const UrdfModel model = load(fixture("two_link_arm.urdf"), "arm");
  ASSERT_EQ(model.scene.bodies.size(), 3u);
  EXPECT_EQ(model.scene.plane, "xz");

  const BodyDef& base = bodyNamed(model, "arm/base_link");
  EXPECT_EQ(base.type, BodyType::Static);
  ASSERT_EQ(base.shapes.size(), 1u);
  EXPECT_EQ(base.shapes[0].kind, ShapeKind::Box);
  EXPECT_NEAR(base.shapes[0].size.x(), 0.4, kTol);  // x extent
  EXPECT_NEAR(base.shapes[0].size.y(), 0.1, kTol);  // z extent; y (0.4) is along the normal
  EXPECT_NEAR(base.shapes[0].offset.y(), 0.05, kTol);

  const BodyDef& upper = bodyNamed(model, "arm/upper_arm");
  EXPECT_EQ(upper.type, BodyType::Dynamic);
  EXPECT_NEAR(upper.position.x(), 0.0, kTol);
  EXPECT_NEAR(upper.position.y(), 0.2, kTol);
  EXPECT_NEAR(upper.mass, 2.0, kTol);
  EXPECT_NEAR(upper.inertia, 0.17, kTol);  // iyy: the xz plane's normal is 3D y
  EXPECT_TRUE(upper.useLocalCenter);
  EXPECT_NEAR(upper.localCenter.x(), 0.5, kTol);

  // The elbow's 0.1 m along y is dropped; the lying cylinder is a rectangle, with a sphere.
  const BodyDef& forearm = bodyNamed(model, "arm/forearm");
  EXPECT_NEAR(forearm.position.x(), 1.0, kTol);
  EXPECT_NEAR(forearm.position.y(), 0.2, kTol);
  ASSERT_EQ(forearm.shapes.size(), 2u);
  EXPECT_EQ(forearm.shapes[0].kind, ShapeKind::Box);
  EXPECT_NEAR(forearm.shapes[0].size.x(), 0.8, kTol);
  EXPECT_NEAR(forearm.shapes[0].size.y(), 0.1, kTol);
  EXPECT_NEAR(std::abs(std::sin(forearm.shapes[0].angle)), 0.0, kRpyTol);
  EXPECT_EQ(forearm.shapes[1].kind, ShapeKind::Circle);
  EXPECT_NEAR(forearm.shapes[1].radius, 0.06, kTol);
  EXPECT_NEAR(forearm.shapes[1].offset.x(), 0.8, kTol);
  EXPECT_NEAR(forearm.mass, 1.0, kTol);
  EXPECT_NEAR(forearm.inertia, 0.06, kTol);

  World world;
  std::string error;
  ASSERT_TRUE(addScene(model.scene, world, &error)) << error;
  const Body& upperBody = world.body(world.findBody("arm/upper_arm"));
  EXPECT_NEAR(upperBody.mass, 2.0, kTol);
  EXPECT_NEAR(upperBody.inertia, 0.17, kTol);
  EXPECT_NEAR(upperBody.localCenter.x(), 0.5, kTol);
  EXPECT_NEAR(upperBody.localCenter.y(), 0.0, kTol);
}

TEST(Urdf, TwoLinkArmJoints) {
  const UrdfModel model = load(fixture("two_link_arm.urdf"), "arm");
  ASSERT_EQ(model.scene.joints.size(), 2u);
  const SceneJoint& shoulder = jointNamed(model, "arm/shoulder");
  EXPECT_EQ(shoulder.def.type, JointType::Revolute);
  EXPECT_EQ(shoulder.bodyA, "arm/base_link");
  EXPECT_EQ(shoulder.bodyB, "arm/upper_arm");
  EXPECT_NEAR(shoulder.def.anchor.y(), 0.2, kTol);
  EXPECT_TRUE(shoulder.def.enableLimit);
  EXPECT_NEAR(shoulder.def.lower, -1.5, kTol);
  EXPECT_NEAR(shoulder.def.upper, 1.5, kTol);
  EXPECT_NEAR(shoulder.def.maxMotorTorque, 50.0, kTol);
  EXPECT_FALSE(shoulder.def.enableMotor);
  const UrdfJointInfo& info = infoNamed(model, "arm/shoulder");
  EXPECT_EQ(info.sign, -1.0);  // axis +y, the xz plane's counter-clockwise normal is -y
  EXPECT_NEAR(info.maxEffort, 50.0, kTol);
  EXPECT_NEAR(info.maxVelocity, 2.0, kTol);

  const SceneJoint& elbow = jointNamed(model, "arm/elbow");
  EXPECT_EQ(elbow.def.type, JointType::Revolute);
  EXPECT_FALSE(elbow.def.enableLimit);  // continuous
  EXPECT_NEAR(elbow.def.anchor.x(), 1.0, kTol);
  EXPECT_NEAR(infoNamed(model, "arm/elbow").maxEffort, 20.0, kTol);
}

TEST(Urdf, AxisSignTurnsLimitsAndMatchesGravity) {
  // Axis +y: a positive URDF angle turns x toward -z, i.e. clockwise in the plane.
  const UrdfModel model =
      load(armWithJoint("type=\"revolute\"",
                        "<origin xyz=\"0 0 1\"/><axis xyz=\"0 1 0\"/>"
                        "<limit lower=\"-0.2\" upper=\"1.0\" effort=\"3\" velocity=\"1\"/>"),
           "m");
  const SceneJoint& joint = jointNamed(model, "m/j");
  EXPECT_NEAR(joint.def.lower, -1.0, kTol);
  EXPECT_NEAR(joint.def.upper, 0.2, kTol);
  const UrdfJointInfo& info = infoNamed(model, "m/j");
  ASSERT_EQ(info.sign, -1.0);

  // The base falls with the arm; pin it so that gravity turns the arm about the hinge.
  UrdfModel pinned = model;
  for (BodyDef& body : pinned.scene.bodies) {
    if (body.name == "m/base") body.type = BodyType::Static;
  }
  World world;
  std::string error;
  ASSERT_TRUE(addScene(pinned.scene, world, &error)) << error;
  for (int i = 0; i < 20; ++i) world.step();
  const double enginePosition = world.jointState(world.findJoint("m/j")).position;
  EXPECT_LT(enginePosition, -0.01);             // the arm swings down: clockwise in the x-z plane
  EXPECT_GT(info.sign * enginePosition, 0.01);  // and about +y that is a positive URDF angle
}

TEST(Urdf, PlacementMovesAndTurnsTheModel) {
  UrdfPlacement placement;
  placement.modelName = "arm";
  placement.position = Vec2(1.0, 2.0);
  placement.angle = kPi / 2;
  UrdfModel model;
  std::string error;
  ASSERT_TRUE(parseUrdf(fixture("two_link_arm.urdf"), placement, &model, &error)) << error;
  const BodyDef& forearm = bodyNamed(model, "arm/forearm");
  // (1.0, 0.2) turned a quarter: (-0.2, 1.0), then moved by (1, 2).
  EXPECT_NEAR(forearm.position.x(), 0.8, kTol);
  EXPECT_NEAR(forearm.position.y(), 3.0, kTol);
  EXPECT_NEAR(forearm.angle, kPi / 2, kTol);
  EXPECT_NEAR(jointNamed(model, "arm/elbow").def.anchor.x(), 0.8, kTol);
  EXPECT_NEAR(jointNamed(model, "arm/elbow").def.anchor.y(), 3.0, kTol);
}

TEST(Urdf, CartPolePrismaticAndRevolute) {
  const UrdfModel model = load(fixture("cart_pole.urdf"), "cp");
  ASSERT_EQ(model.scene.bodies.size(), 3u);
  const SceneJoint& slider = jointNamed(model, "cp/slider");
  EXPECT_EQ(slider.def.type, JointType::Prismatic);
  EXPECT_NEAR(slider.def.axis.x(), 1.0, kTol);
  EXPECT_NEAR(slider.def.axis.y(), 0.0, kTol);
  EXPECT_TRUE(slider.def.enableLimit);
  EXPECT_NEAR(slider.def.lower, -1.5, kTol);
  EXPECT_NEAR(slider.def.upper, 1.5, kTol);
  EXPECT_NEAR(slider.def.maxMotorTorque, 100.0, kTol);
  EXPECT_EQ(infoNamed(model, "cp/slider").sign, 1.0);
  EXPECT_EQ(infoNamed(model, "cp/slider").type, JointType::Prismatic);

  const SceneJoint& hinge = jointNamed(model, "cp/pole_hinge");
  EXPECT_EQ(hinge.def.type, JointType::Revolute);
  EXPECT_EQ(hinge.bodyA, "cp/cart");
  EXPECT_EQ(hinge.bodyB, "cp/pole");
  const BodyDef& pole = bodyNamed(model, "cp/pole");
  EXPECT_NEAR(pole.position.y(), 0.1, kTol);
  EXPECT_NEAR(pole.mass, 0.1, kTol);
  EXPECT_NEAR(pole.localCenter.y(), 0.5, kTol);
  EXPECT_NEAR(pole.inertia, 0.0083, kTol);
  ASSERT_EQ(pole.shapes.size(), 1u);
  EXPECT_NEAR(pole.shapes[0].size.x(), 0.04, kTol);
  EXPECT_NEAR(pole.shapes[0].size.y(), 1.0, kTol);

  // The motor drives the cart along the rail at the commanded speed.
  World world;
  std::string error;
  ASSERT_TRUE(addScene(model.scene, world, &error)) << error;
  const JointId id = world.findJoint("cp/slider");
  ASSERT_TRUE(world.setJointMotor(id, true, 0.5, 100.0));
  for (int i = 0; i < 50; ++i) world.step();
  EXPECT_NEAR(world.jointState(id).velocity, 0.5, 1e-3);
  EXPECT_NEAR(world.jointState(id).position, 0.25, 0.01);
}

TEST(Urdf, FixedSensorLinksMergeIntoTheBase) {
  const UrdfModel model = load(fixture("sensor_robot.urdf"), "bot");
  ASSERT_EQ(model.scene.bodies.size(), 3u);  // base (with lidar and camera) and two wheels
  const BodyDef& base = bodyNamed(model, "bot/base_link");
  EXPECT_EQ(base.type, BodyType::Dynamic);  // a free root
  ASSERT_EQ(base.shapes.size(), 2u);
  EXPECT_NEAR(base.shapes[0].size.x(), 0.6, kTol);
  EXPECT_NEAR(base.shapes[0].size.y(), 0.2, kTol);
  // The upright lidar cylinder seen from the side: 0.1 wide (2 r), 0.1 tall (length).
  EXPECT_NEAR(base.shapes[1].offset.x(), 0.2, kTol);
  EXPECT_NEAR(base.shapes[1].offset.y(), 0.15, kTol);
  EXPECT_NEAR(base.shapes[1].size.x(), 0.1, kTol);
  EXPECT_NEAR(base.shapes[1].size.y(), 0.1, kTol);

  // Masses: base 5 at the origin, lidar 0.2 at (0.2, 0.15), camera 0.1 at (0.3, 0.05).
  const double mass = 5.3;
  const Vec2 center = (0.2 * Vec2(0.2, 0.15) + 0.1 * Vec2(0.3, 0.05)) / mass;
  const double inertia = 0.17 + 0.0002 + 0.0001 + 0.2 * Vec2(0.2, 0.15).squaredNorm() +
                         0.1 * Vec2(0.3, 0.05).squaredNorm() - mass * center.squaredNorm();
  EXPECT_NEAR(base.mass, mass, kTol);
  EXPECT_NEAR(base.localCenter.x(), center.x(), kTol);
  EXPECT_NEAR(base.localCenter.y(), center.y(), kTol);
  EXPECT_NEAR(base.inertia, inertia, kTol);

  // Wheels: cylinders along 3D y stand on the plane as circles.
  const BodyDef& wheel = bodyNamed(model, "bot/front_wheel");
  ASSERT_EQ(wheel.shapes.size(), 1u);
  EXPECT_EQ(wheel.shapes[0].kind, ShapeKind::Circle);
  EXPECT_NEAR(wheel.shapes[0].radius, 0.07, kTol);
  EXPECT_NEAR(wheel.position.x(), 0.2, kTol);
  EXPECT_NEAR(wheel.position.y(), -0.1, kTol);
  EXPECT_EQ(model.scene.joints.size(), 2u);
  EXPECT_TRUE(model.warnings.empty());
}

TEST(Urdf, TopDownPlaneUsesZAsTheNormal) {
  const std::string baseLink =
      "<link name=\"base\"><collision><geometry><box size=\"1 2 3\"/></geometry></collision>"
      "<collision><origin xyz=\"0 0 5\"/><geometry><cylinder length=\"1\" radius=\"0.3\"/>"
      "</geometry></collision></link>";
  const std::string xml = robot(
      baseLink +
      "<joint name=\"turn\" type=\"continuous\"><parent link=\"base\"/><child link=\"arm\"/>"
      "<origin xyz=\"2 1 0\" rpy=\"0 0 0.5\"/><axis xyz=\"0 0 1\"/></joint>"
      "<link name=\"arm\"><collision><geometry><sphere radius=\"0.2\"/></geometry></collision>"
      "</link>");
  const UrdfModel model = load(xml, "m", "xy");
  const BodyDef& base = bodyNamed(model, "m/base");
  EXPECT_NEAR(base.shapes[0].size.x(), 1.0, kTol);
  EXPECT_NEAR(base.shapes[0].size.y(), 2.0, kTol);
  EXPECT_EQ(base.shapes[1].kind, ShapeKind::Circle);  // upright cylinder seen from above
  const BodyDef& arm = bodyNamed(model, "m/arm");
  EXPECT_NEAR(arm.position.x(), 2.0, kTol);
  EXPECT_NEAR(arm.position.y(), 1.0, kTol);
  EXPECT_NEAR(arm.angle, 0.5, kTol);
  EXPECT_EQ(infoNamed(model, "m/turn").sign, 1.0);

  // The base in the x-z plane: the box shows x and z, the cylinder its side. (The yawed joint
  // would turn the arm out of that plane.)
  const UrdfModel side = load(robot(baseLink), "m", "xz");
  EXPECT_NEAR(bodyNamed(side, "m/base").shapes[0].size.y(), 3.0, kTol);
  EXPECT_EQ(bodyNamed(side, "m/base").shapes[1].kind, ShapeKind::Box);
}

TEST(Urdf, WithoutInertialTheShapesGiveTheMass) {
  const UrdfModel model = load(robot(kBoxLink));
  ASSERT_EQ(model.scene.bodies.size(), 1u);
  EXPECT_EQ(model.scene.bodies[0].mass, 0.0);
  EXPECT_FALSE(model.scene.bodies[0].useLocalCenter);
  EXPECT_EQ(model.scene.bodies[0].inertia, 0.0);
}

TEST(Urdf, MeshesAndBareLeafLinksAreSkippedWithAWarning) {
  const UrdfModel model = load(
      robot(std::string(kBoxLink) +
            "<joint name=\"free\" type=\"continuous\"><parent link=\"base\"/><child link=\"tip\"/>"
            "<axis xyz=\"0 1 0\"/></joint><link name=\"tip\"><collision><geometry>"
            "<mesh filename=\"file:///etc/passwd\"/></geometry></collision></link>"));
  EXPECT_EQ(model.scene.bodies.size(), 1u);
  EXPECT_TRUE(model.scene.joints.empty());
  EXPECT_TRUE(model.joints.empty());
  ASSERT_EQ(model.warnings.size(), 3u);  // the mesh, the link, its joint
  EXPECT_TRUE(contains(model.warnings[0], "link 'tip'") && contains(model.warnings[0], "mesh"));
  EXPECT_TRUE(contains(model.warnings[1], "link 'tip'"));
  EXPECT_TRUE(contains(model.warnings[2], "joint 'free'"));
}

TEST(Urdf, FloatingJointsLeaveTheChildFree) {
  const UrdfModel model = load(
      robot(std::string(kBoxLink) +
            "<joint name=\"loose\" type=\"floating\"><parent link=\"base\"/><child link=\"ball\"/>"
            "<origin xyz=\"3 0 0\"/></joint><link name=\"ball\"><collision><geometry>"
            "<sphere radius=\"0.5\"/></geometry></collision></link>"));
  EXPECT_EQ(model.scene.bodies.size(), 2u);
  EXPECT_TRUE(model.scene.joints.empty());
  EXPECT_NEAR(bodyNamed(model, "m/ball").position.x(), 3.0, kTol);
}

TEST(Urdf, SpawnIsAllOrNothing) {
  const UrdfModel model = load(fixture("cart_pole.urdf"), "cp");
  World world;
  std::string error;
  ASSERT_TRUE(addScene(model.scene, world, &error)) << error;
  const size_t bodies = world.bodyCount(), joints = world.jointCount();
  EXPECT_FALSE(addScene(model.scene, world, &error));
  EXPECT_TRUE(contains(error, "cp/rail")) << error;
  EXPECT_EQ(world.bodyCount(), bodies);
  EXPECT_EQ(world.jointCount(), joints);
}

TEST(Urdf, BrokenFixturesAreRefusedNamingTheCulprit) {
  const std::string badXml = refusal(fixture("broken/bad_xml.urdf"));
  EXPECT_TRUE(contains(badXml, "urdf_xml: not a valid URDF")) << badXml;

  const std::string unknownParent = refusal(fixture("broken/unknown_parent.urdf"));
  EXPECT_TRUE(contains(unknownParent, "no_such_link")) << unknownParent;

  const std::string axis = refusal(fixture("broken/axis_in_plane.urdf"));
  EXPECT_TRUE(contains(axis, "joint 'twist'") && contains(axis, "axis (1 0 0)")) << axis;

  const std::string zero = refusal(fixture("broken/zero_size_box.urdf"));
  EXPECT_TRUE(contains(zero, "link 'flat'") && contains(zero, "box")) << zero;

  const std::string roll = refusal(fixture("broken/roll_in_origin.urdf"));
  EXPECT_TRUE(contains(roll, "joint 'hinge'") && contains(roll, "link 'arm'") &&
              contains(roll, "roll or pitch"))
      << roll;
}

TEST(Urdf, RefusalsNameTheElement) {
  EXPECT_TRUE(contains(refusal(""), "urdf_xml: empty"));
  EXPECT_TRUE(contains(refusal("<robot name=\"r\"><link name=\"a\"/>"), "urdf_xml"));
  const std::string dotted =
      refusal(robot("<link name=\"link.001\"><collision><geometry><sphere radius=\"1\"/></geometry>"
                    "</collision></link>"));
  EXPECT_TRUE(contains(dotted, "link 'link.001'") && contains(dotted, "name")) << dotted;

  const std::string prismatic = refusal(armWithJoint("type=\"prismatic\"",
                                                     "<axis xyz=\"0 1 0\"/>"
                                                     "<limit lower=\"0\" upper=\"1\" effort=\"1\" "
                                                     "velocity=\"1\"/>"));
  EXPECT_TRUE(contains(prismatic, "joint 'j'") && contains(prismatic, "not in the xz plane"))
      << prismatic;

  const std::string bareMiddle = refusal(
      robot(std::string(kBoxLink) +
            "<joint name=\"a\" type=\"continuous\"><parent link=\"base\"/><child link=\"mid\"/>"
            "<axis xyz=\"0 1 0\"/></joint><link name=\"mid\"/>"
            "<joint name=\"b\" type=\"continuous\"><parent link=\"mid\"/><child link=\"tip\"/>"
            "<axis xyz=\"0 1 0\"/></joint><link name=\"tip\"><collision><geometry>"
            "<sphere radius=\"1\"/></geometry></collision></link>"));
  EXPECT_TRUE(contains(bareMiddle, "link 'mid'") && contains(bareMiddle, "joint 'b'"))
      << bareMiddle;

  const std::string tilted =
      refusal(robot("<link name=\"can\"><collision><origin rpy=\"0.5 0 0\"/><geometry>"
                    "<cylinder length=\"1\" radius=\"0.1\"/></geometry></collision></link>"));
  EXPECT_TRUE(contains(tilted, "link 'can'") && contains(tilted, "cylinder")) << tilted;

  const std::string fromWorld = refusal(
      robot("<link name=\"world\"/><joint name=\"pin\" type=\"continuous\"><parent link=\"world\"/>"
            "<child link=\"base\"/><axis xyz=\"0 1 0\"/></joint>" +
            std::string(kBoxLink)));
  EXPECT_TRUE(contains(fromWorld, "joint 'pin'")) << fromWorld;

  // Text that is not UTF-8 is refused before any XML parser sees it: TinyXML read past the end
  // of a text ending in a lead byte (found by the URDF fuzzer; under ASan that crashed).
  const std::string cutShort = refusal(robot(std::string(kBoxLink)) + "\xe1");
  EXPECT_TRUE(contains(cutShort, "not valid UTF-8 at byte")) << cutShort;
  const std::string stray = refusal(robot("<link name=\"b\xe9se\"/>"));
  EXPECT_TRUE(contains(stray, "not valid UTF-8")) << stray;
  const std::string utf8 = refusal(robot("<link name=\"b\xc3\xa9se\"/>"));
  EXPECT_FALSE(contains(utf8, "UTF-8")) << utf8;  // well-formed: refused for other reasons

  std::string deep;
  for (int i = 0; i < 100000; ++i) deep += "<a>";
  EXPECT_TRUE(contains(refusal(robot(deep)), "nested deeper")) << "deep nesting";

  const std::string selfLoop = refusal(
      robot(std::string(kBoxLink) +
            "<joint name=\"again\" type=\"fixed\"><parent link=\"base\"/><child link=\"base\"/>"
            "</joint>"));
  EXPECT_TRUE(contains(selfLoop, "joint 'again'") && contains(selfLoop, "loop")) << selfLoop;
  const std::string loop = refusal(
      robot(std::string(kBoxLink) + "<link name=\"other\"/>" +
            "<joint name=\"there\" type=\"fixed\"><parent link=\"base\"/><child link=\"other\"/>"
            "</joint><joint name=\"back\" type=\"fixed\"><parent link=\"other\"/>"
            "<child link=\"base\"/></joint>"));
  EXPECT_TRUE(contains(loop, "loop through link")) << loop;

  const std::string noBodies = refusal(robot("<link name=\"empty\"/>"));
  EXPECT_TRUE(contains(noBodies, "no link with collision geometry")) << noBodies;

  const std::string negativeMass = refusal(
      robot("<link name=\"base\"><inertial><mass value=\"-1\"/><inertia ixx=\"1\" ixy=\"0\" "
            "ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial><collision><geometry>"
            "<sphere radius=\"1\"/></geometry></collision></link>"));
  EXPECT_TRUE(contains(negativeMass, "link 'base'") && contains(negativeMass, "mass"))
      << negativeMass;
}

TEST(Urdf, PlacementIsChecked) {
  UrdfPlacement placement;
  UrdfModel model;
  std::string error;
  placement.modelName = "";
  EXPECT_FALSE(parseUrdf(robot(kBoxLink), placement, &model, &error));
  EXPECT_TRUE(contains(error, "model_name")) << error;
  placement.modelName = "/abs";
  EXPECT_FALSE(parseUrdf(robot(kBoxLink), placement, &model, &error));
  EXPECT_TRUE(contains(error, "model_name")) << error;
  placement.modelName = "ok";
  placement.plane = "yz";
  EXPECT_FALSE(parseUrdf(robot(kBoxLink), placement, &model, &error));
  EXPECT_TRUE(contains(error, "plane")) << error;
  placement.plane = "xz";
  placement.angle = std::nan("");
  EXPECT_FALSE(parseUrdf(robot(kBoxLink), placement, &model, &error));
  EXPECT_TRUE(contains(error, "pose")) << error;
}

}  // namespace
}  // namespace impulse2d
