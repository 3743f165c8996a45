// URDF link frames for tf: links merged into a body by fixed joints as offsets from it, the root
// "world" link at the model's placement, static links without geometry from the world. Bodies lie
// in the plane; these frames keep their URDF poses relative to them, along the normal too.
#include <impulse2d/urdf.hpp>

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace impulse2d {
namespace {

constexpr double kTol = 1e-9;
constexpr double kRpyTol = 1e-6;  // URDF files write pi/2 as 1.5707963

UrdfModel load(const std::string& xml, const std::string& plane, const Vec2& position = Vec2(0, 0),
               double angle = 0.0) {
  UrdfPlacement placement;
  placement.modelName = "m";
  placement.plane = plane;
  placement.position = position;
  placement.angle = angle;
  UrdfModel out;
  std::string error;
  EXPECT_TRUE(parseUrdf(xml, placement, &out, &error)) << error;
  return out;
}

const UrdfFrame& frameNamed(const UrdfModel& model, const std::string& name) {
  for (const UrdfFrame& frame : model.frames) {
    if (frame.name == name) return frame;
  }
  ADD_FAILURE() << "no frame " << name;
  static const UrdfFrame none;
  return none;
}

void expectTranslation(const UrdfFrame& frame, double x, double y, double z) {
  EXPECT_NEAR(frame.pose.translation().x(), x, kTol) << frame.name;
  EXPECT_NEAR(frame.pose.translation().y(), y, kTol) << frame.name;
  EXPECT_NEAR(frame.pose.translation().z(), z, kTol) << frame.name;
}

std::string fixture(const std::string& name) {
  std::ifstream in(std::string(IMPULSE2D_SOURCE_DIR) + "/test/urdf/" + name);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(UrdfFrames, MergedLinksAreOffsetsFromTheirBody) {
  // sensor_robot (xz): the lidar and the camera are fixed to base_link, the camera's optical
  // frame (rolled and yawed) to the camera.
  const UrdfModel model = load(fixture("sensor_robot.urdf"), "xz");
  ASSERT_EQ(model.frames.size(), 3u);
  const UrdfFrame& lidar = frameNamed(model, "m/lidar_link");
  EXPECT_EQ(lidar.body, "m/base_link");
  expectTranslation(lidar, 0.2, 0.0, 0.15);
  EXPECT_TRUE(lidar.pose.linear().isIdentity(kTol));
  const UrdfFrame& optical = frameNamed(model, "m/camera_optical_frame");
  EXPECT_EQ(optical.body, "m/base_link");
  expectTranslation(optical, 0.3, 0.0, 0.05);
  // rpy (-pi/2, 0, -pi/2): the optical z axis looks along the camera's x, its x along -y.
  const Eigen::Matrix3d r = optical.pose.linear();
  EXPECT_TRUE(r.col(2).isApprox(Eigen::Vector3d::UnitX(), kRpyTol)) << r;
  EXPECT_TRUE(r.col(0).isApprox(-Eigen::Vector3d::UnitY(), kRpyTol)) << r;
}

TEST(UrdfFrames, OffsetsFromTheBodyAlongTheNormalAreKept) {
  const std::string xml = R"(<robot name="r">
  <link name="base"><collision><geometry><cylinder radius="0.2" length="0.1"/></geometry></collision></link>
  <joint name="mount" type="fixed"><parent link="base"/><child link="mast"/>
    <origin xyz="0.1 0.3 0.4" rpy="0 0 0.5"/></joint>
  <link name="mast"/>
</robot>)";
  // Top-down (normal 3D z): the base's body lies in the plane, the mast 0.4 above it.
  const UrdfModel xy = load(xml, "xy");
  expectTranslation(frameNamed(xy, "m/mast"), 0.1, 0.3, 0.4);
  EXPECT_TRUE(frameNamed(xy, "m/mast")
                  .pose.linear()
                  .isApprox(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix()));
}

TEST(UrdfFrames, TheWorldLinkAndStaticLinksWithoutGeometryAreFixedToTheWorld) {
  const std::string xml = R"(<robot name="r">
  <link name="world"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/><origin xyz="1 0 0"/></joint>
  <link name="base"><collision><geometry><box size="0.4 0.4 0.1"/></geometry></collision></link>
  <joint name="mark" type="fixed"><parent link="world"/><child link="marker"/><origin xyz="0 0.7 2"/></joint>
  <link name="marker"/>
  <joint name="bad" type="fixed"><parent link="base"/><child link="tool.001"/></joint>
  <link name="tool.001"/>
</robot>)";
  // Side view (xz, normal -y) at (2, 3), turned 0.5 rad: the world link is the placement.
  const UrdfModel model = load(xml, "xz", Vec2(2.0, 3.0), 0.5);
  const UrdfFrame& world = frameNamed(model, "m/world");
  EXPECT_EQ(world.body, "");
  expectTranslation(world, 2.0, 0.0, 3.0);
  EXPECT_TRUE(world.pose.linear().isApprox(
      Eigen::AngleAxisd(0.5, -Eigen::Vector3d::UnitY()).toRotationMatrix()));
  // The marker, 2 m up the model's z and 0.7 along its y (the normal): (0, 2) in the model's
  // plane, turned 0.5 rad and moved to (2, 3), 0.7 off the plane.
  const UrdfFrame& marker = frameNamed(model, "m/marker");
  EXPECT_EQ(marker.body, "");
  expectTranslation(marker, 2.0 - 2.0 * std::sin(0.5), 0.7, 3.0 + 2.0 * std::cos(0.5));
  // A merged link whose name cannot be a frame stays off tf, with a warning.
  for (const UrdfFrame& frame : model.frames) EXPECT_NE(frame.name, "m/tool.001");
  bool warned = false;
  for (const std::string& w : model.warnings)
    warned |= w.find("'tool.001': not on tf") != std::string::npos;
  EXPECT_TRUE(warned);
  EXPECT_EQ(model.frames.size(), 2u);
}

}  // namespace
}  // namespace impulse2d
