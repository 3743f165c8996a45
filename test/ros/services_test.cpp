// Every service of the world node: what succeeds, and that what fails names the bad field and
// leaves the world unchanged.
#include "world_test_util.hpp"

#include <impulse2d/ApplyWrench.h>
#include <impulse2d/CreateJoint.h>
#include <impulse2d/DeleteJoint.h>
#include <impulse2d/LoadScene.h>
#include <impulse2d/SetBodyState.h>
#include <impulse2d/SpawnBody.h>
#include <impulse2d/Step.h>

#include <cmath>
#include <future>
#include <limits>
#include <vector>

namespace impulse2d_test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Spawning `body` fails with a message that contains `field`, and no body of its name appears.
void expectSpawnRefused(const impulse2d::Body& body, const std::string& field) {
  std::string message;
  EXPECT_FALSE(spawn(body, &message)) << body.name;
  EXPECT_NE(message.find(field), std::string::npos) << "'" << message << "' names no " << field;
  impulse2d::GetBodyState::Response state;
  if (!body.name.empty() && body.name != "svc_dup") {
    EXPECT_FALSE(getState(body.name, &state));
  }
}

impulse2d::Joint hinge(const std::string& name, const std::string& a, const std::string& b,
                       double x, double y) {
  impulse2d::Joint joint;
  joint.name = name;
  joint.type = impulse2d::Joint::REVOLUTE;
  joint.body_a = a;
  joint.body_b = b;
  joint.anchor.x = x;
  joint.anchor.y = y;
  return joint;
}

bool createJoint(const impulse2d::Joint& joint, std::string* message = nullptr) {
  impulse2d::CreateJoint srv;
  srv.request.joint = joint;
  if (!call("create_joint", srv)) return false;
  if (message) *message = srv.response.message;
  return srv.response.success;
}

bool deleteJoint(const std::string& name) {
  impulse2d::DeleteJoint srv;
  srv.request.name = name;
  return call("delete_joint", srv) && srv.response.success;
}

TEST(Services, SpawnAndDeleteBody) {
  ASSERT_TRUE(spawn(boxBody("svc_spawned", -8.0, 6.0)));
  impulse2d::GetBodyState::Response state;
  ASSERT_TRUE(getState("svc_spawned", &state));
  EXPECT_NEAR(state.pose.x, -8.0, 1e-6);
  EXPECT_TRUE(remove("svc_spawned"));
  EXPECT_FALSE(getState("svc_spawned", &state));
  EXPECT_FALSE(remove("svc_spawned"));  // unknown now
  EXPECT_FALSE(remove(""));

  impulse2d::Body circle = boxBody("svc_circle", -7.0, 6.0);
  circle.shapes[0].type = impulse2d::Shape::CIRCLE;
  circle.shapes[0].radius = 0.3;
  EXPECT_TRUE(spawn(circle));
  EXPECT_TRUE(remove("svc_circle"));
}

TEST(Services, SpawnRefusesUnphysicalBodies) {
  impulse2d::Body body = boxBody("svc_bad", 0.0, 5.0);
  body.pose.x = kNaN;
  expectSpawnRefused(body, "body.pose.x");
  body = boxBody("svc_bad", 0.0, 5.0);
  body.twist.linear.y = kInf;
  expectSpawnRefused(body, "body.twist.linear.y");
  expectSpawnRefused(boxBody("svc_bad", 0.0, 5.0, 0.0, 1.0), "body.shapes[0].width");
  expectSpawnRefused(boxBody("svc_bad", 0.0, 5.0, 1.0, -2.0), "body.shapes[0].height");
  body = boxBody("svc_bad", 0.0, 5.0);
  body.shapes[0].type = impulse2d::Shape::CIRCLE;
  body.shapes[0].radius = 0.0;
  expectSpawnRefused(body, "body.shapes[0].radius");
  body = boxBody("svc_bad", 0.0, 5.0);
  body.shapes.clear();
  expectSpawnRefused(body, "body.shapes");
  expectSpawnRefused(boxBody("", 0.0, 5.0), "body.name");
  body = boxBody("svc_bad", 0.0, 5.0);
  body.type = 7;
  expectSpawnRefused(body, "body.type");
  body = boxBody("svc_bad", 0.0, 5.0);
  body.mass = -1.0;
  expectSpawnRefused(body, "body.mass");
  // A non-convex polygon: only the engine can tell.
  body = boxBody("svc_bad", 0.0, 5.0);
  body.shapes[0].type = impulse2d::Shape::POLYGON;
  for (const auto& xy : {std::make_pair(0.0, 0.0), {2.0, 0.0}, {0.5, 0.5}, {2.0, 2.0}}) {
    geometry_msgs::Point p;
    p.x = xy.first;
    p.y = xy.second;
    body.shapes[0].vertices.push_back(p);
  }
  expectSpawnRefused(body, "body.shapes[0]");

  // A duplicate leaves the first body where it was.
  ASSERT_TRUE(spawn(boxBody("svc_dup", -6.0, 8.0, 1.0, 1.0, impulse2d::Body::STATIC)));
  expectSpawnRefused(boxBody("svc_dup", 3.0, 3.0), "body.name");
  impulse2d::GetBodyState::Response state;
  ASSERT_TRUE(getState("svc_dup", &state));
  EXPECT_DOUBLE_EQ(state.pose.x, -6.0);
  EXPECT_TRUE(remove("svc_dup"));
}

TEST(Services, CreateAndDeleteJoint) {
  ASSERT_TRUE(spawn(boxBody("svc_anchor", -9.0, 9.0, 0.2, 0.2, impulse2d::Body::STATIC)));
  ASSERT_TRUE(spawn(boxBody("svc_link", -8.5, 9.0, 1.0, 0.2)));
  std::string message;
  EXPECT_TRUE(createJoint(hinge("svc_hinge", "svc_anchor", "svc_link", -9.0, 9.0), &message))
      << message;
  EXPECT_FALSE(createJoint(hinge("svc_hinge", "svc_anchor", "svc_link", -9.0, 9.0), &message));
  EXPECT_NE(message.find("joint.name"), std::string::npos) << message;
  EXPECT_FALSE(createJoint(hinge("svc_self", "svc_link", "svc_link", -9.0, 9.0), &message));
  EXPECT_NE(message.find("joint.body_b"), std::string::npos) << message;
  EXPECT_FALSE(createJoint(hinge("svc_ghost", "svc_anchor", "svc_nobody", -9.0, 9.0), &message));
  EXPECT_NE(message.find("joint.body_b"), std::string::npos) << message;
  EXPECT_FALSE(createJoint(hinge("", "svc_anchor", "svc_link", -9.0, 9.0), &message));
  EXPECT_NE(message.find("joint.name"), std::string::npos) << message;
  EXPECT_FALSE(createJoint(hinge("svc_nan", "svc_anchor", "svc_link", kNaN, 9.0), &message));
  EXPECT_NE(message.find("joint.anchor.x"), std::string::npos) << message;

  EXPECT_TRUE(deleteJoint("svc_hinge"));
  EXPECT_FALSE(deleteJoint("svc_hinge"));
  EXPECT_FALSE(deleteJoint(""));
  EXPECT_FALSE(deleteJoint("svc_nan"));  // refused above, so never created

  // Deleting a body takes its joints along.
  ASSERT_TRUE(createJoint(hinge("svc_hinge2", "svc_anchor", "svc_link", -9.0, 9.0)));
  EXPECT_TRUE(remove("svc_link"));
  EXPECT_FALSE(deleteJoint("svc_hinge2"));
  EXPECT_TRUE(remove("svc_anchor"));
}

TEST(Services, LoadSceneIsAllOrNothing) {
  impulse2d::LoadScene srv;
  srv.request.yaml =
      "bodies:\n"
      "  - {name: svc_scene_a, type: dynamic, position: [8.0, 8.0], shapes: [{type: circle, "
      "radius: 0.25}]}\n"
      "  - {name: svc_scene_b, type: static, position: [9.0, 8.0], shapes: [{type: box, size: "
      "[0.5, 0.5]}]}\n";
  ASSERT_TRUE(call("load_scene", srv));
  EXPECT_TRUE(srv.response.success) << srv.response.message;
  impulse2d::GetBodyState::Response state;
  EXPECT_TRUE(getState("svc_scene_a", &state));
  EXPECT_TRUE(getState("svc_scene_b", &state));

  // The second body clashes with one in the world: nothing of this scene is added.
  srv.request.yaml =
      "bodies:\n"
      "  - {name: svc_scene_c, position: [7.0, 8.0], shapes: [{type: circle, radius: 0.25}]}\n"
      "  - {name: svc_scene_a, position: [6.0, 8.0], shapes: [{type: circle, radius: 0.25}]}\n";
  ASSERT_TRUE(call("load_scene", srv));
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("svc_scene_a"), std::string::npos) << srv.response.message;
  EXPECT_FALSE(getState("svc_scene_c", &state));

  srv.request.yaml = "bodies: [";
  ASSERT_TRUE(call("load_scene", srv));
  EXPECT_FALSE(srv.response.success);
  EXPECT_FALSE(srv.response.message.empty());
  srv.request.yaml = "";
  ASSERT_TRUE(call("load_scene", srv));
  EXPECT_FALSE(srv.response.success);

  EXPECT_TRUE(remove("svc_scene_a"));
  EXPECT_TRUE(remove("svc_scene_b"));
}

TEST(Services, SetAndGetBodyState) {
  PausedWorld paused;  // so the body stays where it is put
  ASSERT_TRUE(spawn(boxBody("svc_teleported", 5.0, 9.0)));
  impulse2d::SetBodyState set;
  set.request.name = "svc_teleported";
  set.request.pose.x = 4.0;
  set.request.pose.y = 12.0;
  set.request.pose.theta = 0.5;
  set.request.twist.linear.x = 1.5;
  set.request.twist.angular.z = -2.0;
  ASSERT_TRUE(call("set_body_state", set));
  EXPECT_TRUE(set.response.success) << set.response.message;
  impulse2d::GetBodyState::Response state;
  ASSERT_TRUE(getState("svc_teleported", &state));
  EXPECT_DOUBLE_EQ(state.pose.x, 4.0);
  EXPECT_DOUBLE_EQ(state.pose.y, 12.0);
  EXPECT_NEAR(state.pose.theta, 0.5, 1e-12);
  EXPECT_NEAR(state.twist.linear.x, 1.5, 1e-12);
  EXPECT_NEAR(state.twist.angular.z, -2.0, 1e-12);

  set.request.pose.y = kNaN;
  ASSERT_TRUE(call("set_body_state", set));
  EXPECT_FALSE(set.response.success);
  EXPECT_NE(set.response.message.find("pose.y"), std::string::npos) << set.response.message;
  ASSERT_TRUE(getState("svc_teleported", &state));
  EXPECT_DOUBLE_EQ(state.pose.y, 12.0);  // unchanged

  set.request.pose.y = 1.0;
  set.request.name = "svc_nobody";
  ASSERT_TRUE(call("set_body_state", set));
  EXPECT_FALSE(set.response.success);
  set.request.name = "";
  ASSERT_TRUE(call("set_body_state", set));
  EXPECT_FALSE(set.response.success);
  EXPECT_FALSE(getState("", &state));
  EXPECT_FALSE(getState("svc_nobody", &state));
  EXPECT_TRUE(remove("svc_teleported"));
}

TEST(Services, ApplyWrenchForADuration) {
  PausedWorld paused;
  ASSERT_TRUE(spawn(boxBody("svc_pushed", 2.0, 30.0)));  // 1 kg, far above everything
  // Twice its weight upwards at its centre for 0.1 s: it gains (2g - g) * 0.1 s upwards.
  impulse2d::ApplyWrench wrench;
  wrench.request.body = "svc_pushed";
  wrench.request.force.y = 2.0 * 9.81;
  wrench.request.point.x = 2.0;
  wrench.request.point.y = 30.0;
  wrench.request.duration = 0.1;
  ASSERT_TRUE(call("apply_wrench", wrench));
  EXPECT_TRUE(wrench.response.success) << wrench.response.message;
  impulse2d::Step step;
  step.request.steps = 10;
  ASSERT_TRUE(call("step", step));
  EXPECT_TRUE(step.response.success);
  impulse2d::GetBodyState::Response state;
  ASSERT_TRUE(getState("svc_pushed", &state));
  EXPECT_NEAR(state.twist.linear.y, 0.981, 0.02);
  EXPECT_NEAR(state.twist.angular.z, 0.0, 1e-9);
  // The wrench is over: gravity alone slows it down again.
  ASSERT_TRUE(call("step", step));
  ASSERT_TRUE(getState("svc_pushed", &state));
  EXPECT_NEAR(state.twist.linear.y, 0.0, 0.02);

  wrench.request.duration = -1.0;
  ASSERT_TRUE(call("apply_wrench", wrench));
  EXPECT_FALSE(wrench.response.success);
  EXPECT_NE(wrench.response.message.find("duration"), std::string::npos);
  wrench.request.duration = 0.0;
  wrench.request.force.x = kNaN;
  ASSERT_TRUE(call("apply_wrench", wrench));
  EXPECT_FALSE(wrench.response.success);
  EXPECT_NE(wrench.response.message.find("force.x"), std::string::npos);
  wrench.request.force.x = 0.0;
  wrench.request.body = "svc_nobody";
  ASSERT_TRUE(call("apply_wrench", wrench));
  EXPECT_FALSE(wrench.response.success);
  wrench.request.body = "ground";  // static
  ASSERT_TRUE(call("apply_wrench", wrench));
  EXPECT_FALSE(wrench.response.success);
  EXPECT_TRUE(remove("svc_pushed"));
}

TEST(Services, PauseStepUnpause) {
  ASSERT_TRUE(spawn(boxBody("svc_faller", -3.0, 40.0)));
  impulse2d::GetBodyState::Response before, after;
  {
    PausedWorld paused;
    ASSERT_TRUE(getState("svc_faller", &before));
    // Paused means nothing moves, however long we look (a short look suffices).
    ros::WallDuration(0.3).sleep();
    ASSERT_TRUE(getState("svc_faller", &after));
    EXPECT_EQ(before.pose.y, after.pose.y);

    impulse2d::Step step;
    step.request.steps = 0;
    ASSERT_TRUE(call("step", step));
    EXPECT_FALSE(step.response.success);
    step.request.steps = 5;
    ASSERT_TRUE(call("step", step));
    EXPECT_TRUE(step.response.success);
    ASSERT_TRUE(getState("svc_faller", &after));
    // Five steps of free fall from rest (semi-implicit Euler): v = 5 g dt.
    EXPECT_NEAR(after.twist.linear.y - before.twist.linear.y, -5 * 9.81 * kTimeStep, 1e-6);
    EXPECT_LT(after.pose.y, before.pose.y);
  }
  // Running again: it keeps falling.
  EXPECT_TRUE(waitFor(
      [&] {
        impulse2d::GetBodyState::Response now;
        return getState("svc_faller", &now) && now.pose.y < after.pose.y - 0.1;
      },
      5.0));
  EXPECT_TRUE(remove("svc_faller"));
}

TEST(Services, ResetRestoresTheStartScene) {
  PausedWorld paused;
  ASSERT_TRUE(spawn(boxBody("svc_reset_probe", 0.0, 20.0)));
  impulse2d::SetBodyState set;
  set.request.name = "scene_box";
  set.request.pose.x = 7.0;
  set.request.pose.y = 15.0;
  ASSERT_TRUE(call("set_body_state", set));
  ASSERT_TRUE(set.response.success);

  emptyCall("reset");
  impulse2d::GetBodyState::Response state;
  EXPECT_FALSE(getState("svc_reset_probe", &state));
  ASSERT_TRUE(getState("scene_box", &state));
  EXPECT_DOUBLE_EQ(state.pose.x, -5.0);
  EXPECT_DOUBLE_EQ(state.pose.y, 0.5);
  EXPECT_TRUE(getState("ground", &state));
}

TEST(Services, ConcurrentSpawnsAreAllAnswered) {
  constexpr int kCount = 50;
  // Each thread its own connection, so the calls really overlap: persistent, opened before and
  // closed after the burst (service_call.hpp says why).
  std::vector<ros::ServiceClient> clients;
  for (int i = 0; i < kCount; ++i) {
    clients.push_back(ros::NodeHandle().serviceClient<impulse2d::SpawnBody>(
        worldNs() + "/spawn_body", /*persistent=*/true));
  }
  std::vector<std::future<std::string>> calls;
  for (int i = 0; i < kCount; ++i) {
    calls.push_back(std::async(std::launch::async, [i, &clients] {
      impulse2d::SpawnBody srv;
      srv.request.body = boxBody("burst_" + std::to_string(i), -9.0 + 2.0 * (i % 10),
                                 3.0 + 1.5 * (i / 10), 0.5, 0.5);
      if (!clients[i].call(srv)) return std::string("the call failed");
      return srv.response.success ? std::string() : srv.response.message;
    }));
  }
  for (int i = 0; i < kCount; ++i) EXPECT_EQ(calls[i].get(), "") << "burst_" << i;
  for (int i = 0; i < kCount; ++i) {
    impulse2d::GetBodyState::Response state;
    EXPECT_TRUE(getState("burst_" + std::to_string(i), &state)) << "burst_" << i;
  }
  for (int i = 0; i < kCount; ++i) EXPECT_TRUE(remove("burst_" + std::to_string(i)));
}

}  // namespace
}  // namespace impulse2d_test
