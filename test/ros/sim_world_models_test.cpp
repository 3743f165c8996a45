// SimWorld's models without a master: a jointed model moved whole keeps its shape; deleting a
// model takes its own bodies only, never a user's body that took the name of one removed since.
#include "../../src/ros/sim_world.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace impulse2d {
namespace bridge {
namespace {

// A cart: a body with a wheel on a revolute joint 0.5 m ahead of it.
const char* const kCart = R"(
bodies:
  - {name: base_link, shapes: [{type: box, size: [1.0, 0.5]}]}
  - {name: wheel, position: [0.5, 0.0], shapes: [{type: circle, radius: 0.1}]}
joints:
  - {name: axle, type: revolute, body_a: base_link, body_b: wheel, anchor: [0.5, 0.0]}
devices:
  - {type: diff_drive, name: drive, body: base_link}
)";

void start(SimWorld& sim) {
  std::string error;
  ASSERT_TRUE(sim.loadStartScene("world: {plane: xy, gravity: [0, 0]}\n", &error)) << error;
  ASSERT_TRUE(sim.attachStartDevices(&error)) << error;
  ModelRequest cart;
  cart.where.name = "c";
  cart.where.position = Vec2(1.0, 2.0);
  cart.yaml = kCart;
  ModelSpawned spawned;
  ASSERT_TRUE(sim.spawnModel(cart, &spawned, &error)) << error;
  EXPECT_EQ(spawned.joints, std::vector<std::string>{"c/axle"});
}

TEST(SimWorldModels, AMovedModelKeepsItsShapeAndStops) {
  SimWorld sim;
  start(sim);
  std::string error;
  ASSERT_TRUE(sim.commandDrive("c/drive", 1.0, 0.0, 1.0, &error)) << error;
  for (int i = 0; i < 100; ++i) sim.step();
  ASSERT_TRUE(sim.moveModel("c", Vec2(-3.0, 4.0), M_PI / 2, &error)) << error;
  BodySnapshot base, wheel;
  ASSERT_TRUE(sim.getBodyState("c/base_link", &base, &error));
  ASSERT_TRUE(sim.getBodyState("c/wheel", &wheel, &error));
  EXPECT_NEAR((base.position - Vec2(-3.0, 4.0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(std::remainder(base.angle - M_PI / 2, 2 * M_PI), 0.0, 1e-9);
  // The wheel is still 0.5 m ahead of the base, which now faces +y.
  EXPECT_NEAR((wheel.position - Vec2(-3.0, 4.5)).norm(), 0.0, 1e-3);
  for (int i = 0; i < 10; ++i) sim.step();
  ASSERT_TRUE(sim.getBodyState("c/base_link", &base, &error));
  EXPECT_NEAR(base.linearVelocity.norm(), 0.0, 1e-9);  // the drive forgot its command
  EXPECT_NEAR((base.position - Vec2(-3.0, 4.0)).norm(), 0.0, 1e-6);
}

TEST(SimWorldModels, DeletingAModelTakesOnlyItsOwnBodies) {
  SimWorld sim;
  start(sim);
  std::string error;
  // The user deletes the wheel and spawns a body of their own under its name.
  ASSERT_TRUE(sim.deleteBody("c/wheel", &error)) << error;
  BodyDef mine;
  mine.name = "c/wheel";
  mine.position = Vec2(10.0, 0.0);
  mine.shapes.push_back(ShapeDef());
  ASSERT_TRUE(sim.spawnBody(mine, &error)) << error;
  ASSERT_TRUE(sim.deleteModel("c", &error)) << error;
  BodySnapshot kept;
  EXPECT_TRUE(sim.getBodyState("c/wheel", &kept, &error)) << error;
  EXPECT_FALSE(sim.getBodyState("c/base_link", &kept, &error));
  EXPECT_TRUE(sim.devices().empty());
  EXPECT_TRUE(sim.modelNames().empty());
  // Moving a model whose bodies are all gone says so.
  start(sim);
  ASSERT_TRUE(sim.deleteBody("c/base_link", &error));
  ASSERT_TRUE(sim.deleteBody("c/wheel", &error));
  EXPECT_FALSE(sim.moveModel("c", Vec2::Zero(), 0.0, &error));
  EXPECT_EQ(error, "model_name: 'c' has no body left in the world");
}

}  // namespace
}  // namespace bridge
}  // namespace impulse2d
