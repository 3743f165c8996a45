// URDF models in the world node (urdf.test): the arm spawned at start from robot_description,
// each fixture over ~spawn_urdf with its frames on tf and joints in joint_states, refusals that
// leave the world as it was, and joint motors driven by ~joint_command and ~set_joint_motor.
#include "world_test_util.hpp"

#include <impulse2d/JointCommand.h>
#include <impulse2d/SetJointMotor.h>
#include <impulse2d/SpawnUrdf.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/transform_listener.h>

#include <cmath>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

namespace impulse2d_test {
namespace {

// Bounded waits: generous for a loaded CI machine; they bound, they do not measure.
constexpr double kWait = 20.0;

std::string fixture(const std::string& name) {
  const std::string dir = ros::NodeHandle("~").param<std::string>("fixtures", "");
  std::ifstream in(dir + "/" + name);
  EXPECT_TRUE(in.good()) << dir << "/" << name;
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

impulse2d::SpawnUrdf::Response spawnUrdf(const std::string& model, const std::string& xml, double x,
                                         double y) {
  impulse2d::SpawnUrdf srv;
  srv.request.model_name = model;
  srv.request.urdf_xml = xml;
  srv.request.pose.x = x;
  srv.request.pose.y = y;
  call("spawn_urdf", srv);
  return srv.response;
}

struct Reading {
  double position = 0.0;
  double velocity = 0.0;
};

/// The latest joint_states entry of every joint seen.
class JointStates {
 public:
  JointStates() { sub_ = ros::NodeHandle().subscribe("joint_states", 50, &JointStates::on, this); }
  bool get(const std::string& name, Reading* out) const {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = latest_.find(name);
    if (it == latest_.end()) return false;
    *out = it->second;
    return true;
  }
  bool has(const std::string& name) const {
    Reading unused;
    return get(name, &unused);
  }

 private:
  void on(const sensor_msgs::JointState::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (size_t i = 0; i < msg->name.size(); ++i) {
      Reading r;
      if (i < msg->position.size()) r.position = msg->position[i];
      if (i < msg->velocity.size()) r.velocity = msg->velocity[i];
      latest_[msg->name[i]] = r;
    }
  }
  mutable std::mutex mutex_;
  std::map<std::string, Reading> latest_;
  ros::Subscriber sub_;
};

class Urdf : public testing::Test {
 protected:
  bool hasFrame(const std::string& frame) {
    return waitFor([&] { return buffer_.canTransform("world", frame, ros::Time(0)); }, kWait);
  }
  tf2_ros::Buffer buffer_;
  tf2_ros::TransformListener listener_{buffer_};
  JointStates joints_;
};

TEST_F(Urdf, ArmFromUrdfParamAtStart) {
  EXPECT_TRUE(hasFrame("arm/base_link"));  // static: on /tf_static
  // The root link 'world' too, at the model's placement, as RViz's RobotModel looks for it.
  ASSERT_TRUE(hasFrame("arm/world"));
  const geometry_msgs::Transform root =
      buffer_.lookupTransform("world", "arm/world", ros::Time(0)).transform;
  EXPECT_NEAR(root.translation.x, 3.0, 1e-9);
  EXPECT_NEAR(root.translation.z, 0.0, 1e-9);
  EXPECT_TRUE(hasFrame("arm/upper_arm"));
  EXPECT_TRUE(hasFrame("arm/forearm"));
  EXPECT_TRUE(
      waitFor([&] { return joints_.has("arm/shoulder") && joints_.has("arm/elbow"); }, kWait));
  // ~urdf_x placed the model's root at x = 3.
  impulse2d::GetBodyState::Response base;
  ASSERT_TRUE(getState("arm/base_link", &base));
  EXPECT_NEAR(base.pose.x, 3.0, 1e-9);
}

TEST_F(Urdf, CartPoleSpawnsWithFramesAndJoints) {
  const impulse2d::SpawnUrdf::Response res = spawnUrdf("cp", fixture("cart_pole.urdf"), 8.0, 0.5);
  ASSERT_TRUE(res.success) << res.message;
  EXPECT_EQ(res.bodies, (std::vector<std::string>{"cp/rail", "cp/cart", "cp/pole"}));
  EXPECT_EQ(res.joints, (std::vector<std::string>{"cp/slider", "cp/pole_hinge"}));
  EXPECT_TRUE(hasFrame("cp/cart"));
  EXPECT_TRUE(hasFrame("cp/pole"));
  EXPECT_TRUE(
      waitFor([&] { return joints_.has("cp/slider") && joints_.has("cp/pole_hinge"); }, kWait));

  // The same name again is refused whole.
  const impulse2d::SpawnUrdf::Response again = spawnUrdf("cp", fixture("cart_pole.urdf"), 8.0, 3.0);
  EXPECT_FALSE(again.success);
  EXPECT_NE(again.message.find("cp/rail"), std::string::npos) << again.message;
  EXPECT_TRUE(again.bodies.empty());
}

TEST_F(Urdf, SensorRobotMergesFixedLinks) {
  const impulse2d::SpawnUrdf::Response res =
      spawnUrdf("bot", fixture("sensor_robot.urdf"), -10.0, 0.5);
  ASSERT_TRUE(res.success) << res.message;
  EXPECT_EQ(res.bodies.size(), 3u);
  EXPECT_EQ(res.joints.size(), 2u);
  EXPECT_TRUE(hasFrame("bot/base_link"));
  EXPECT_TRUE(hasFrame("bot/front_wheel"));
  EXPECT_TRUE(waitFor([&] { return joints_.has("bot/front_wheel_joint"); }, kWait));
  impulse2d::GetBodyState::Response lidar;
  EXPECT_FALSE(getState("bot/lidar_link", &lidar));  // part of bot/base_link's body
  // Every link has its frame on tf, as RViz's RobotModel (TF prefix 'bot') needs: the merged
  // ones as offsets from their body.
  for (const char* link : {"base_link", "lidar_link", "camera_link", "camera_optical_frame",
                           "front_wheel", "rear_wheel"}) {
    EXPECT_TRUE(hasFrame(std::string("bot/") + link)) << link;
  }
  const geometry_msgs::Transform mount =
      buffer_.lookupTransform("bot/base_link", "bot/lidar_link", ros::Time(0)).transform;
  EXPECT_NEAR(mount.translation.x, 0.2, 1e-9);
  EXPECT_NEAR(mount.translation.z, 0.15, 1e-9);
}

TEST_F(Urdf, TwoLinkArmOverTheService) {
  const impulse2d::SpawnUrdf::Response res =
      spawnUrdf("arm2", fixture("two_link_arm.urdf"), -3.0, 0.0);
  ASSERT_TRUE(res.success) << res.message;
  EXPECT_EQ(res.joints, (std::vector<std::string>{"arm2/shoulder", "arm2/elbow"}));
  EXPECT_TRUE(hasFrame("arm2/forearm"));
  EXPECT_TRUE(waitFor([&] { return joints_.has("arm2/elbow"); }, kWait));
}

TEST_F(Urdf, BrokenModelsAreRefusedAndAddNothing) {
  const std::map<std::string, std::string> expected = {
      {"bad_xml.urdf", "urdf_xml"},
      {"unknown_parent.urdf", "no_such_link"},
      {"axis_in_plane.urdf", "joint 'twist'"},
      {"zero_size_box.urdf", "link 'flat'"},
      {"roll_in_origin.urdf", "joint 'hinge'"},
  };
  for (const auto& [file, named] : expected) {
    const impulse2d::SpawnUrdf::Response res = spawnUrdf("broken", fixture("broken/" + file), 0, 5);
    EXPECT_FALSE(res.success) << file;
    EXPECT_NE(res.message.find(named), std::string::npos) << file << ": " << res.message;
    EXPECT_TRUE(res.bodies.empty() && res.joints.empty()) << file;
  }
  impulse2d::GetBodyState::Response state;
  EXPECT_FALSE(getState("broken/base_link", &state));
  EXPECT_FALSE(getState("broken/flat", &state));
}

TEST_F(Urdf, JointCommandDrivesTheCart) {
  ASSERT_TRUE(spawnUrdf("cmd", fixture("cart_pole.urdf"), 14.0, 0.5).success);
  const std::string slider = "cmd/slider";
  ros::Publisher pub =
      ros::NodeHandle().advertise<impulse2d::JointCommand>(worldNs() + "/joint_command", 1);
  ASSERT_TRUE(waitFor([&] { return pub.getNumSubscribers() > 0; }, kWait));
  impulse2d::JointCommand command;
  command.name = slider;
  command.speed = 0.5;  // max_effort 0: the URDF's 100 N
  pub.publish(command);
  // At 0.5 m/s the cart passes 0.3 m well before its 1.5 m limit.
  Reading r;
  EXPECT_TRUE(waitFor(
      [&] {
        return joints_.get(slider, &r) && r.position > 0.3 && std::abs(r.velocity - 0.5) < 0.05;
      },
      kWait))
      << "position " << r.position << ", velocity " << r.velocity;
}

TEST_F(Urdf, SetJointMotorTurnsTheShoulderInTheUrdfSense) {
  impulse2d::SetJointMotor srv;
  srv.request.name = "arm/shoulder";
  srv.request.speed = -0.3;
  ASSERT_TRUE(call("set_joint_motor", srv));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  // Negative about the URDF axis (+y) lifts the arm off the ground (counter-clockwise in the
  // x-z plane); joint_states reports it in the URDF's sense: -0.3 rad/s, a falling angle.
  Reading r;
  EXPECT_TRUE(waitFor(
      [&] {
        return joints_.get("arm/shoulder", &r) && r.position < -0.2 &&
               std::abs(r.velocity + 0.3) < 0.03;
      },
      kWait))
      << "position " << r.position << ", velocity " << r.velocity;

  srv.request.name = "arm/no_such_joint";
  ASSERT_TRUE(call("set_joint_motor", srv));
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("arm/no_such_joint"), std::string::npos);

  srv.request.name = "arm/shoulder";
  srv.request.speed = std::nan("");
  ASSERT_TRUE(call("set_joint_motor", srv));
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("speed"), std::string::npos);
}

}  // namespace
}  // namespace impulse2d_test
