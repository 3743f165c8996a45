// Helpers for the rostests of robots in the loop (robot_test.cpp, devices_test.cpp): a cmd_vel
// publisher, stepping a paused world, a body's speed.
#pragma once

#include "world_test_util.hpp"

#include <geometry_msgs/Twist.h>
#include <impulse2d/Step.h>

#include <cmath>
#include <string>

namespace impulse2d_test {

// Bounded waits: generous for a loaded CI machine; they bound, they do not measure.
constexpr double kWait = 20.0;

inline double speedOf(const std::string& body) {
  impulse2d::GetBodyState::Response state;
  EXPECT_TRUE(getState(body, &state)) << body;
  return std::hypot(state.twist.linear.x, state.twist.linear.y);
}

inline void stepWorld(uint32_t steps) {
  impulse2d::Step srv;
  srv.request.steps = steps;
  ASSERT_TRUE(call("step", srv));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
}

/// A cmd_vel publisher, connected to the node before it is used.
class CmdVel {
 public:
  /// `topic` relative to the world's namespace, or absolute ("/r1/cmd_vel").
  explicit CmdVel(const std::string& topic)
      : pub_(ros::NodeHandle().advertise<geometry_msgs::Twist>(
            topic[0] == '/' ? topic : worldNs() + "/" + topic, 10)) {
    EXPECT_TRUE(waitFor([&] { return pub_.getNumSubscribers() > 0; }, kWait)) << topic;
  }
  /// linear.x = v, angular.z = w, linear.y = sideways (omni drives).
  void send(double v, double w = 0.0, double sideways = 0.0) {
    geometry_msgs::Twist twist;
    twist.linear.x = v;
    twist.linear.y = sideways;
    twist.angular.z = w;
    pub_.publish(twist);
  }

 private:
  ros::Publisher pub_;
};

}  // namespace impulse2d_test
