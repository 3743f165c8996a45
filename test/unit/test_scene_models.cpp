// Model files (issue 23) without ROS: a scene's `models:` places one file once per robot, each in
// its own namespace and pose; a placed model moves and holds together as the file says; names a
// model cannot take are refused and leave the scene as it was.
#include <gtest/gtest.h>

#include <impulse2d/scene.hpp>
#include <impulse2d/world.hpp>

#include "temp_folder.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <string>

namespace impulse2d {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A cart: a box with a wheel on a revolute joint at its front, a drive, a laser with its own
// frame name, a bumper, and an IMU whose topic is absolute.
const char* const kCart = R"(
bodies:
  - {name: base_link, position: [0.0, 0.0], linear_velocity: [1.0, 0.0],
     shapes: [{type: box, size: [1.0, 0.5]}]}
  - {name: wheel, position: [0.5, 0.0], shapes: [{type: circle, radius: 0.1}]}
joints:
  - {name: axle, type: revolute, body_a: base_link, body_b: wheel, anchor: [0.5, 0.0]}
  - {name: slide, type: prismatic, body_a: base_link, body_b: wheel, anchor: [0.5, 0.0], axis: [1, 0]}
devices:
  - {type: diff_drive, name: drive, body: base_link}
  - {type: laser, name: laser, body: base_link, offset: [0.4, 0.0, 0.0]}
  - {type: laser, name: rear, body: base_link, frame: rear_laser, topic: rear_scan}
  - {type: bumper, name: bumper, body: base_link}
  - {type: imu, name: imu, body: base_link, topic: /all/imu}
)";

// A scene with a static wall and the `models:` entries given.
std::string sceneWithModels(const std::string& models) {
  return "world: {plane: xy, gravity: [0, 0]}\n"
         "bodies:\n"
         "  - {name: wall, type: static, position: [0, 10], shapes: [{type: box, size: [20, 1]}]}\n"
         "models:\n" +
         models + "\n";
}

const BodyDef* bodyNamed(const Scene& scene, const std::string& name) {
  for (const BodyDef& b : scene.bodies) {
    if (b.name == name) return &b;
  }
  return nullptr;
}

const DeviceDef* deviceNamed(const Scene& scene, const std::string& name) {
  for (const DeviceDef& d : scene.devices) {
    if (d.name == name) return &d;
  }
  return nullptr;
}

TEST(SceneModels, OneFilePlacedTwiceInTwoNamespacesAndPoses) {
  TempFolder folder;
  folder.write("cart.yaml", kCart);
  const std::string scenePath = folder.write("fleet.yaml", sceneWithModels(R"(
  - {name: r1, file: cart.yaml, position: [2.0, 1.0], angle: 1.5707963267948966}
  - {name: r2, file: cart.yaml, namespace: /fleet/r2})"));
  Scene scene;
  std::string error;
  ASSERT_TRUE(loadSceneFile(scenePath, &scene, &error)) << error;
  ASSERT_EQ(scene.models.size(), 2u);
  EXPECT_EQ(scene.bodies.size(), 5u);  // the wall and two bodies per cart
  EXPECT_EQ(scene.joints.size(), 4u);
  EXPECT_EQ(scene.devices.size(), 10u);

  // r1: namespace its name, turned a quarter turn about (2, 1).
  const SceneModel& r1 = scene.models[0];
  EXPECT_EQ(r1.ns, "r1");
  EXPECT_EQ(r1.file, folder.path() + "cart.yaml");
  EXPECT_EQ(r1.bodies, (std::vector<std::string>{"r1/base_link", "r1/wheel"}));
  EXPECT_EQ(r1.joints, (std::vector<std::string>{"r1/axle", "r1/slide"}));
  ASSERT_EQ(r1.localPositions.size(), 2u);
  EXPECT_EQ(r1.localPositions[1], Vec2(0.5, 0.0));
  const BodyDef* wheel = bodyNamed(scene, "r1/wheel");
  ASSERT_NE(wheel, nullptr);
  EXPECT_NEAR(wheel->position.x(), 2.0, 1e-12);
  EXPECT_NEAR(wheel->position.y(), 1.5, 1e-12);
  EXPECT_NEAR(wheel->angle, 0.5 * kPi, 1e-12);
  const BodyDef* base = bodyNamed(scene, "r1/base_link");
  ASSERT_NE(base, nullptr);
  EXPECT_NEAR(base->linearVelocity.x(), 0.0, 1e-12);  // the file's +x is the world's +y
  EXPECT_NEAR(base->linearVelocity.y(), 1.0, 1e-12);
  const SceneJoint& slide = scene.joints[1];
  EXPECT_EQ(slide.def.name, "r1/slide");
  EXPECT_EQ(slide.bodyA, "r1/base_link");
  EXPECT_EQ(slide.bodyB, "r1/wheel");
  EXPECT_NEAR(slide.def.anchor.x(), 2.0, 1e-12);
  EXPECT_NEAR(slide.def.anchor.y(), 1.5, 1e-12);
  EXPECT_NEAR(slide.def.axis.x(), 0.0, 1e-12);
  EXPECT_NEAR(slide.def.axis.y(), 1.0, 1e-12);

  // Relative topics and frames go into the namespace; absolute topics stay.
  const DeviceDef* drive = deviceNamed(scene, "r1/drive");
  ASSERT_NE(drive, nullptr);
  EXPECT_EQ(drive->body, "r1/base_link");
  EXPECT_EQ(drive->drive.cmdVelTopic, "/r1/cmd_vel");
  EXPECT_EQ(drive->drive.odomTopic, "/r1/odom");
  EXPECT_EQ(groundTruthTopicOf(drive->drive), "/r1/ground_truth");
  EXPECT_EQ(drive->drive.odomFrame, "r1/odom");
  const DeviceDef* laser = deviceNamed(scene, "r1/laser");
  ASSERT_NE(laser, nullptr);
  EXPECT_EQ(laser->laser.topic, "/r1/scan");
  EXPECT_EQ(deviceFrameOf(*laser), "r1/base_link/laser");
  EXPECT_EQ(laser->laser.offset, Vec2(0.4, 0.0));  // mounts stay in the body's frame
  const DeviceDef* rear = deviceNamed(scene, "r1/rear");
  ASSERT_NE(rear, nullptr);
  EXPECT_EQ(deviceFrameOf(*rear), "r1/rear_laser");
  EXPECT_EQ(rear->laser.topic, "/r1/rear_scan");
  EXPECT_EQ(deviceNamed(scene, "r1/bumper")->bumper.topic, "/r1/bumper");
  EXPECT_EQ(deviceNamed(scene, "r1/imu")->imu.topic, "/all/imu");

  // r2: a namespace of its own, its leading '/' dropped, at the model's own pose.
  EXPECT_EQ(scene.models[1].ns, "fleet/r2");
  EXPECT_NE(bodyNamed(scene, "fleet/r2/base_link"), nullptr);
  EXPECT_EQ(bodyNamed(scene, "fleet/r2/wheel")->position, Vec2(0.5, 0.0));
  EXPECT_EQ(deviceNamed(scene, "fleet/r2/drive")->drive.cmdVelTopic, "/fleet/r2/cmd_vel");

  World world(scene.world);
  ASSERT_TRUE(addScene(scene, world, &error)) << error;
  EXPECT_EQ(world.bodyCount(), 5u);
}

TEST(SceneModels, APlacedModelHoldsTogetherAsTheFileSays) {
  // The wheel hangs from its axle: turned and moved, the joint's anchor is still where both
  // bodies meet, so nothing jumps at the first step.
  TempFolder folder;
  folder.write("cart.yaml", R"(
bodies:
  - {name: base_link, shapes: [{type: box, size: [1.0, 0.5]}]}
  - {name: wheel, position: [0.5, -0.4], shapes: [{type: circle, radius: 0.1}]}
joints:
  - {name: axle, type: revolute, body_a: base_link, body_b: wheel, anchor: [0.5, -0.4]}
)");
  const std::string scenePath =
      folder.write("scene.yaml",
                   "world: {gravity: [0, 0]}\nmodels:\n"
                   "  - {name: c, file: cart.yaml, position: [3.0, -2.0], angle: 2.0}\n");
  Scene scene;
  std::string error;
  ASSERT_TRUE(loadSceneFile(scenePath, &scene, &error)) << error;
  World world(scene.world);
  ASSERT_TRUE(addScene(scene, world, &error)) << error;
  for (int i = 0; i < 120; ++i) world.step();
  const Body& base = world.body(world.findBody("c/base_link"));
  const Body& wheel = world.body(world.findBody("c/wheel"));
  const Vec2 expectedWheel = base.xf.apply(Vec2(0.5, -0.4));
  EXPECT_NEAR((wheel.xf.p - expectedWheel).norm(), 0.0, 1e-9);
  EXPECT_NEAR(base.xf.p.x(), 3.0, 1e-9);
  EXPECT_NEAR(base.xf.p.y(), -2.0, 1e-9);
  EXPECT_NEAR(base.linearVelocity.norm(), 0.0, 1e-9);
}

TEST(SceneModels, NamesAModelCannotTakeAreRefused) {
  TempFolder folder;
  folder.write("cart.yaml", kCart);
  folder.write("with_world.yaml", std::string("world: {gravity: [0, 0]}\n") + kCart);
  folder.write("foreign.yaml", R"(
bodies:
  - {name: a, shapes: [{type: circle, radius: 0.1}]}
joints:
  - {name: j, type: weld, body_a: a, body_b: wall, anchor: [0, 0]}
)");
  folder.write("foreign_device.yaml", R"(
bodies:
  - {name: a, shapes: [{type: circle, radius: 0.1}]}
devices:
  - {type: bumper, name: b, body: wall}
)");
  folder.write("nested.yaml", "models: []\n");
  const std::string directory = folder.path() + "folder.yaml";
  ASSERT_EQ(mkdir(directory.c_str(), 0700), 0);
  struct Case {
    std::string models;
    std::string error;
  };
  const Case cases[] = {
      {"  - {name: r1, file: cart.yaml}\n  - {name: r1, file: cart.yaml, namespace: other}",
       "models[1] 'r1': name: a model named 'r1' already exists"},
      {"  - {name: r1, file: cart.yaml}\n  - {name: r2, file: cart.yaml, namespace: r1}",
       "models[1] 'r2': model 'r2': bodies[0] 'base_link': a body named 'r1/base_link' already "
       "exists"},
      {"  - {name: w, file: cart.yaml, namespace: wall}", ""},  // 'wall' != 'wall/base_link'
      {"  - {name: r1, file: with_world.yaml}",
       "with_world.yaml: world: unknown key (expected one of: bodies, joints, devices)"},
      {"  - {name: r1, file: foreign.yaml}",
       "joints[0] 'j': body_b: 'wall' is not a body of the model"},
      {"  - {name: r1, file: foreign_device.yaml}",
       "devices[0] 'b': body: 'wall' is not a body of the model"},
      {"  - {name: r1, file: nested.yaml}", "nested.yaml: models: unknown key"},
      {"  - {name: r1, file: missing.yaml}", "missing.yaml: cannot open (No such file"},
      {"  - {name: r1}", "models[0] 'r1': file: must be given"},
      // Only YAML files, and only regular ones (a FIFO would block the node).
      {"  - {name: r1, file: /etc/hostname}", "a model file's name ends in .yaml or .yml"},
      {"  - {name: r1, file: folder.yaml}", "folder.yaml: cannot open (a directory, not a file)"},
      {"  - {name: r-1, file: cart.yaml}", "namespace: 'r-1' cannot name topics"},
      {"  - {name: r1, file: cart.yaml, namespace: '1st'}", "namespace: '1st' cannot name topics"},
      {"  - {name: r1, file: cart.yaml, position: [.nan, 0]}", "position, angle: must be finite"},
      {"  - {name: r1, file: cart.yaml, position: [2e6, 0]}", "within 1e6 m"},
      {"  - {name: r1, file: cart.yaml, pose: [0, 0, 0]}",
       "pose: unknown key (expected one of: name, file, namespace, position, angle)"},
      {"  - {name: r1, file: cart.yaml, namespace: " + std::string(250, 'n') + "}",
       "at most 256 characters"},
  };
  for (const Case& c : cases) {
    const std::string path = folder.write("scene.yaml", sceneWithModels(c.models));
    Scene scene;
    std::string error;
    const bool loaded = loadSceneFile(path, &scene, &error);
    if (c.error.empty()) {
      EXPECT_TRUE(loaded) << c.models << ": " << error;
      continue;
    }
    EXPECT_FALSE(loaded) << c.models;
    EXPECT_NE(error.find(c.error), std::string::npos) << c.models << "\n  " << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
  rmdir(directory.c_str());
}

TEST(SceneModels, PlaceModelLeavesTheSceneAsItWasWhenItRefuses) {
  Scene model;
  std::string error;
  ASSERT_TRUE(parseModel(kCart, &model, &error)) << error;
  Scene scene;
  ModelPlacement where;
  where.name = "r1";
  ASSERT_TRUE(placeModel(model, where, &scene, &error)) << error;
  const size_t bodies = scene.bodies.size(), joints = scene.joints.size(),
               devices = scene.devices.size();
  // A second r1 under another namespace, and an r2 in r1's namespace: both refused, nothing added.
  where.ns = "elsewhere";
  EXPECT_FALSE(placeModel(model, where, &scene, &error));
  where.name = "r2";
  where.ns = "r1";
  EXPECT_FALSE(placeModel(model, where, &scene, &error));
  EXPECT_NE(error.find("already exists"), std::string::npos) << error;
  EXPECT_EQ(scene.bodies.size(), bodies);
  EXPECT_EQ(scene.joints.size(), joints);
  EXPECT_EQ(scene.devices.size(), devices);
  EXPECT_EQ(scene.models.size(), 1u);
  // A model text that is not a model.
  EXPECT_FALSE(parseModel("bodies: [{shapes: []}]", &model, &error));
  EXPECT_NE(error.find("bodies[0]: name"), std::string::npos) << error;
  EXPECT_FALSE(parseModel("", &model, &error));
  EXPECT_NE(error.find("the model is empty"), std::string::npos) << error;
}

}  // namespace
}  // namespace impulse2d
