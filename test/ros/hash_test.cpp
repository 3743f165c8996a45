// The node steps the canonical scene (test/determinism/canonical.yaml) to the same exact state as
// impulse2d_sim: World::hash() recomputed here from ~get_body_state (float64 fields carry every
// bit) equals `impulse2d_sim --hash`, after stepping in chunks while paused, and again after
// ~reset and the same steps. hash.test starts the node paused on that scene.
#include <gtest/gtest.h>
#include <impulse2d/GetBodyState.h>
#include <impulse2d/Step.h>
#include <ros/ros.h>
#include <std_srvs/Empty.h>

#include <cinttypes>
#include <cstdio>
#include <string>
#include <vector>

#include "scene_names.hpp"
#include "service_call.hpp"

namespace {

constexpr uint32_t kSteps = 300;

const std::string kScene = std::string(IMPULSE2D_SOURCE_DIR) + "/test/determinism/canonical.yaml";

std::string hex(uint64_t h) {
  char text[19];
  std::snprintf(text, sizeof text, "%016" PRIx64, h);
  return text;
}

// World::hash(): FNV-1a over (slot index, x, y, angle, vx, vy, omega) of every body in slot
// order. A freshly loaded scene fills slots 0..n-1 in the scene's order.
uint64_t nodeHash() {
  uint64_t h = 14695981039346656037ull;
  auto mix = [&h](const void* data, size_t size) {
    const unsigned char* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) {
      h ^= bytes[i];
      h *= 1099511628211ull;
    }
  };
  const std::vector<std::string> names = impulse2d_test::sceneBodyNames(kScene);
  EXPECT_FALSE(names.empty());
  for (size_t i = 0; i < names.size(); ++i) {
    impulse2d::GetBodyState srv;
    srv.request.name = names[i];
    EXPECT_TRUE(impulse2d_test::callService("/impulse2d/get_body_state", srv) &&
                srv.response.success)
        << names[i];
    const auto& r = srv.response;
    const double state[6] = {r.pose.x,         r.pose.y,         r.pose.theta,
                             r.twist.linear.x, r.twist.linear.y, r.twist.angular.z};
    mix(&i, sizeof(i));
    mix(state, sizeof(state));
  }
  return h;
}

void step(uint32_t steps) {
  impulse2d::Step srv;
  srv.request.steps = steps;
  ASSERT_TRUE(impulse2d_test::callService("/impulse2d/step", srv));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
}

std::string cliHash() {
  const std::string command = std::string(IMPULSE2D_SIM_EXECUTABLE) + " " + kScene + " --steps " +
                              std::to_string(kSteps) + " --hash";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return "";
  std::string output;
  char buffer[256];
  while (fgets(buffer, sizeof buffer, pipe) != nullptr) output += buffer;
  pclose(pipe);
  const size_t at = output.find("hash: ");
  return at == std::string::npos ? output : output.substr(at + 6, 16);
}

TEST(NodeHash, MatchesTheCliAfterChunkedStepsAndAfterReset) {
  const std::string expected = cliHash();
  ASSERT_EQ(expected.size(), 16u) << expected;
  step(1);
  step(99);
  step(kSteps - 100);
  EXPECT_EQ(hex(nodeHash()), expected) << "node after 1 + 99 + 200 steps";

  std_srvs::Empty reset;
  ASSERT_TRUE(impulse2d_test::callService("/impulse2d/reset", reset));
  step(kSteps);
  EXPECT_EQ(hex(nodeHash()), expected) << "node after reset and " << kSteps << " steps";
  std::printf("determinism: node and CLI %s\n", expected.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "impulse2d_hash_test");
  ros::NodeHandle nh;
  if (!ros::service::waitForService("/impulse2d/step", ros::Duration(30.0))) return 1;
  const int result = RUN_ALL_TESTS();
  impulse2d_test::closeServiceClients();
  return result;
}
