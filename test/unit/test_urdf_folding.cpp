// Real robots' URDFs top-down (issue 25): in plane xy a joint about an axis in the floor (a
// wheel's) is folded into its parent's body, the wheel's lying cylinder becoming the rectangle
// seen from above and its mass the body's; strict keeps today's refusal, and so does the xz plane.
#include <impulse2d/urdf.hpp>
#include <impulse2d/world.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

namespace impulse2d {
namespace {

std::string fixture(const std::string& name) {
  std::ifstream in(std::string(IMPULSE2D_SOURCE_DIR) + "/test/urdf/" + name);
  EXPECT_TRUE(in.good()) << name;
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

bool parse(const std::string& xml, const std::string& plane, bool strict, UrdfModel* out,
           std::string* error) {
  UrdfPlacement placement;
  placement.modelName = "tb";
  placement.plane = plane;
  placement.strict = strict;
  return parseUrdf(xml, placement, out, error);
}

TEST(UrdfFolding, ATeachingRobotsWheelsFoldIntoItsBaseSeenFromAbove) {
  UrdfModel model;
  std::string error;
  ASSERT_TRUE(parse(fixture("teaching_robot.urdf"), "xy", false, &model, &error)) << error;
  // One rigid body: the footprint with the base, both wheels, the caster and the laser mast.
  ASSERT_EQ(model.scene.bodies.size(), 1u);
  EXPECT_TRUE(model.scene.joints.empty());
  const BodyDef& base = model.scene.bodies[0];
  EXPECT_EQ(base.name, "tb/base_footprint");
  ASSERT_EQ(base.shapes.size(), 5u);  // base box, two wheels, caster sphere, laser cylinder
  // The wheels' cylinders (r 0.033, 0.018 long) lie along y: 0.066 along x, 0.018 along y.
  int wheels = 0;
  for (const ShapeDef& shape : base.shapes) {
    if (shape.kind != ShapeKind::Box || std::abs(std::abs(shape.offset.y()) - 0.08) > 1e-9) {
      continue;
    }
    ++wheels;
    EXPECT_NEAR(shape.size.x(), 0.018, 1e-12);
    EXPECT_NEAR(shape.size.y(), 0.066, 1e-12);
    EXPECT_NEAR(std::abs(std::sin(shape.angle)), 1.0, 1e-6);  // its length along y
    EXPECT_NEAR(shape.offset.x(), 0.0, 1e-12);
  }
  EXPECT_EQ(wheels, 2);
  EXPECT_NEAR(base.mass, 0.83 + 2 * 0.03, 1e-12);  // the wheels' masses join the base's

  // Both wheel joints are folded, each a wheel of radius 0.033 turning about +y, and said so.
  ASSERT_EQ(model.folded.size(), 2u);
  for (const UrdfFoldedJoint& wheel : model.folded) {
    EXPECT_EQ(wheel.body, "tb/base_footprint");
    EXPECT_NEAR(wheel.wheelRadius, 0.033, 1e-12);
    EXPECT_NEAR(wheel.planeAxis.y(), 1.0, 1e-6);
    EXPECT_NEAR(std::abs(wheel.center.y()), 0.08, 1e-12);
  }
  EXPECT_EQ(model.folded[0].name, "tb/wheel_left_joint");
  EXPECT_EQ(model.folded[0].link, "tb/wheel_left_link");
  EXPECT_GT(model.folded[0].center.y(), 0.0);
  bool said = false;
  for (const std::string& w : model.warnings) {
    said = said || w.find("joint 'wheel_left_joint': folded into body 'tb/base_footprint'") == 0;
  }
  EXPECT_TRUE(said);
  // The wheels' frames turn on /tf: they are not among the frames fixed to the body.
  for (const UrdfFrame& frame : model.frames) {
    EXPECT_NE(frame.name, "tb/wheel_left_link");
    EXPECT_NE(frame.name, "tb/wheel_right_link");
  }

  // The robot stands in a world and drives about like any body.
  World world(WorldDef{});
  world.settings().gravity = Vec2::Zero();
  ASSERT_TRUE(addScene(model.scene, world, &error)) << error;
  EXPECT_EQ(world.bodyCount(), 1u);
}

TEST(UrdfFolding, StrictAndTheSideViewRefuseAsBefore) {
  const std::string xml = fixture("teaching_robot.urdf");
  for (const auto& [plane, strict] : {std::pair<std::string, bool>{"xy", true}, {"xz", false}}) {
    UrdfModel model;
    std::string error;
    EXPECT_FALSE(parse(xml, plane, strict, &model, &error)) << plane;
    EXPECT_NE(error.find("joint 'wheel_left_joint': its origin turns link 'wheel_left_link' out "
                         "of the " +
                         plane + " plane"),
              std::string::npos)
        << error;
    EXPECT_TRUE(model.folded.empty());
  }
}

TEST(UrdfFolding, ATiltingSensorFoldsAndStaysAtZero) {
  // A sensor head on a revolute joint about x: folded, not a wheel (no coaxial cylinder).
  const std::string xml = R"(<robot name="r">
  <link name="base"><collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision>
    <inertial><mass value="2"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <joint name="tilt" type="revolute"><parent link="base"/><child link="head"/>
    <origin xyz="0.1 0 0.2"/><axis xyz="1 0 0"/><limit lower="-0.5" upper="0.5" effort="1" velocity="1"/></joint>
  <link name="head"><collision><geometry><box size="0.05 0.1 0.05"/></geometry></collision></link>
  <joint name="pan" type="continuous"><parent link="base"/><child link="turret"/>
    <origin xyz="-0.1 0 0.1"/><axis xyz="0 0 1"/></joint>
  <link name="turret"><collision><geometry><cylinder radius="0.05" length="0.05"/></geometry></collision>
    <inertial><mass value="0.2"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
</robot>)";
  UrdfModel model;
  std::string error;
  ASSERT_TRUE(parse(xml, "xy", false, &model, &error)) << error;
  ASSERT_EQ(model.folded.size(), 1u);
  EXPECT_EQ(model.folded[0].name, "tb/tilt");
  EXPECT_EQ(model.folded[0].wheelRadius, 0.0);
  // The pan joint turns about the vertical: it stays a revolute joint between two bodies.
  ASSERT_EQ(model.scene.joints.size(), 1u);
  EXPECT_EQ(model.scene.joints[0].def.name, "tb/pan");
  EXPECT_EQ(model.scene.bodies.size(), 2u);
}

}  // namespace
}  // namespace impulse2d
