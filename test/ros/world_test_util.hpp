// Helpers for the rostests of the world node: requests, service calls and bounded waits.
#pragma once

#include <gtest/gtest.h>
#include <impulse2d/Body.h>
#include <impulse2d/GetBodyState.h>
#include <ros/ros.h>
#include <std_srvs/Empty.h>

#include <atomic>
#include <functional>
#include <mutex>
#include <string>

#include "service_call.hpp"

namespace impulse2d_test {

/// The world under test's namespace, from the private parameter ~world (default /impulse2d).
const std::string& worldNs();
/// Whether the world publishes /clock (private parameter ~expect_clock).
bool expectClock();
/// The world's time step; the test scene uses 0.01 s.
constexpr double kTimeStep = 0.01;

/// Calls worldNs()/<service>; fails the test (and returns false) if the call itself fails.
template <typename Srv>
bool call(const std::string& service, Srv& srv) {
  const std::string name = worldNs() + "/" + service;
  if (!ros::service::waitForService(name, ros::Duration(10.0))) {
    ADD_FAILURE() << name << " is not available";
    return false;
  }
  const bool ok = callService(name, srv);
  EXPECT_TRUE(ok) << "calling " << name << " failed";
  return ok;
}

/// A box of `width` x `height` at (x, y); dynamic unless told otherwise.
impulse2d::Body boxBody(const std::string& name, double x, double y, double width = 1.0,
                        double height = 1.0, uint8_t type = impulse2d::Body::DYNAMIC);

bool spawn(const impulse2d::Body& body, std::string* message = nullptr);
bool remove(const std::string& name);
/// Reads a body; false (without failing the test) when the world does not know it.
bool getState(const std::string& name, impulse2d::GetBodyState::Response* out);
void emptyCall(const std::string& service);

/// Polls `done` every 10 ms until it is true or `timeout` wall seconds pass.
bool waitFor(const std::function<bool()>& done, double timeout);

/// Keeps the latest message of a topic.
template <typename Msg>
class Latest {
 public:
  explicit Latest(const std::string& topic) {
    sub_ = ros::NodeHandle().subscribe(topic, 10, &Latest::onMessage, this);
  }
  typename Msg::ConstPtr get() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return msg_;
  }
  int count() const { return count_.load(); }

 private:
  void onMessage(const typename Msg::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    msg_ = msg;
    ++count_;
  }
  mutable std::mutex mutex_;
  typename Msg::ConstPtr msg_;
  std::atomic<int> count_{0};
  ros::Subscriber sub_;
};

/// Pauses the world for the scope, and lets it run again afterwards.
class PausedWorld {
 public:
  PausedWorld() { emptyCall("pause"); }
  ~PausedWorld() { emptyCall("unpause"); }
  PausedWorld(const PausedWorld&) = delete;
  PausedWorld& operator=(const PausedWorld&) = delete;
};

}  // namespace impulse2d_test
