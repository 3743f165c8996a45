// Issue 14's recipe, as a new user tried it with the stock clients: impulse2d_node at ~rate 0 on
// a 40 m ground, a two-link URDF arm spawned onto it, then 50 boxes spawned 0.1 s apart from
// 8 m with their friction left out. Left-out friction was 0 (ice): boxes slid off the ground at
// the speed of a touch and fell until the world removed them, 8 to 41 of 50 in a dozen runs.
// Now it is the default 0.6, as in YAML: every box stays, and only a box that asks for no
// friction slides.
#include "world_test_util.hpp"

#include <impulse2d/RemovedBodies.h>
#include <impulse2d/SpawnUrdf.h>
#include <impulse2d/Step.h>
#include <rosgraph_msgs/Clock.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

namespace impulse2d_test {
namespace {

constexpr int kBoxes = 50;

double simulatedSeconds(const Latest<rosgraph_msgs::Clock>& clock) {
  const auto msg = clock.get();
  return msg ? msg->clock.toSec() : 0.0;
}

impulse2d::Body smallBox(const std::string& name, double x, double y) {
  impulse2d::Body body;
  body.name = name;
  body.type = impulse2d::Body::DYNAMIC;
  body.pose.x = x;
  body.pose.y = y;
  impulse2d::Shape box;  // density, friction and restitution left out
  box.type = impulse2d::Shape::BOX;
  box.width = 0.3;
  box.height = 0.3;
  body.shapes.push_back(box);
  body.mass = 1.0;
  return body;
}

// Two boxes resting on the ground, sent sliding at 1 m/s: the one that asks for no friction
// keeps its speed; the one that leaves friction out stops within v^2 / (2 mu g) = 8.5 cm, mu
// being the geometric mean of its 0.6 and the ground's 0.6.
TEST(Recipe, FrictionlessAskedForSlidesWhereLeftOutFrictionHolds) {
  PausedWorld paused;
  impulse2d::Body ice = smallBox("ice", -15.0, 0.15);
  ice.shapes[0].friction = impulse2d::Shape::FRICTIONLESS;
  ice.twist.linear.x = 1.0;
  std::string answer;
  ASSERT_TRUE(spawn(ice, &answer)) << answer;
  EXPECT_EQ(answer, "ok");
  impulse2d::Body grip = smallBox("grip", 15.0, 0.15);
  grip.twist.linear.x = -1.0;
  ASSERT_TRUE(spawn(grip, &answer)) << answer;
  EXPECT_EQ(answer, "ok (shapes[0].friction: default 0.6)");

  impulse2d::Step step;
  step.request.steps = 100;  // 1 s
  ASSERT_TRUE(call("step", step));
  impulse2d::GetBodyState::Response state;
  ASSERT_TRUE(getState("ice", &state));
  EXPECT_NEAR(state.twist.linear.x, 1.0, 1e-9);
  EXPECT_NEAR(state.pose.x, -14.0, 1e-6);
  ASSERT_TRUE(getState("grip", &state));
  EXPECT_NEAR(state.twist.linear.x, 0.0, 1e-3);
  EXPECT_NEAR(state.pose.x, 15.0 - 1.0 / (2.0 * 0.6 * 9.81), 0.01);
  // Not left to slide off the ground: this test is not about losing bodies.
  EXPECT_TRUE(remove("ice"));
  EXPECT_TRUE(remove("grip"));
}

TEST(Recipe, FiftyBoxesOnAUrdfArmAtFullSpeedAreAllKept) {
  Latest<impulse2d::RemovedBodies> removed(worldNs() + "/removed_bodies");
  Latest<rosgraph_msgs::Clock> clock("/clock");

  const std::string path = ros::NodeHandle("~").param<std::string>("urdf", "");
  std::ifstream in(path);
  ASSERT_TRUE(in.good()) << "~urdf: cannot read '" << path << "'";
  std::stringstream xml;
  xml << in.rdbuf();
  impulse2d::SpawnUrdf arm;
  arm.request.model_name = "arm";
  arm.request.urdf_xml = xml.str();
  ASSERT_TRUE(call("spawn_urdf", arm));
  ASSERT_TRUE(arm.response.success) << arm.response.message;

  for (int i = 0; i < kBoxes; ++i) {
    std::string answer;
    ASSERT_TRUE(spawn(smallBox("burst" + std::to_string(i), -2.0 + 0.08 * i, 8.0), &answer))
        << answer;
    EXPECT_EQ(answer, "ok (shapes[0].friction: default 0.6)");
    ros::WallDuration(0.1).sleep();
  }
  // Run on: a box sliding at the 0.2 m/s of a touch, as the issue traced one, would leave the
  // 40 m ground within 100 s; at full speed this takes seconds.
  const double lastSpawn = simulatedSeconds(clock);
  EXPECT_TRUE(waitFor([&] { return simulatedSeconds(clock) > lastSpawn + 300.0; }, 90.0))
      << "simulated only " << simulatedSeconds(clock) - lastSpawn << " s after the last spawn";

  ASSERT_TRUE(waitFor([&] { return removed.get() != nullptr; }, 10.0));
  std::string names;
  for (const impulse2d::RemovedBody& body : removed.get()->bodies) names += " " + body.name;
  EXPECT_EQ(removed.get()->count, 0u) << "removed:" << names;
  for (int i = 0; i < kBoxes; ++i) {
    const std::string name = "burst" + std::to_string(i);
    impulse2d::GetBodyState::Response state;
    ASSERT_TRUE(getState(name, &state)) << name;
    // On the ground (its top face is y = 0), or on the arm or other boxes.
    EXPECT_LT(std::abs(state.pose.x), 20.0) << name;
    EXPECT_GT(state.pose.y, 0.1) << name;
    EXPECT_LT(state.pose.y, 3.0) << name;
  }
}

}  // namespace
}  // namespace impulse2d_test
