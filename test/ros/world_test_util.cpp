// Helpers for the rostests of the world node (see world_test_util.hpp).
#include "world_test_util.hpp"

#include <impulse2d/DeleteBody.h>
#include <impulse2d/SpawnBody.h>

namespace impulse2d_test {

const std::string& worldNs() {
  static const std::string ns = ros::NodeHandle("~").param<std::string>("world", "/impulse2d");
  return ns;
}

bool expectClock() { return ros::NodeHandle("~").param("expect_clock", false); }

impulse2d::Body boxBody(const std::string& name, double x, double y, double width, double height,
                        uint8_t type) {
  impulse2d::Body body;
  body.name = name;
  body.type = type;
  body.pose.x = x;
  body.pose.y = y;
  impulse2d::Shape box;
  box.type = impulse2d::Shape::BOX;
  box.width = width;
  box.height = height;
  box.density = 1.0;
  box.friction = 0.6;
  body.shapes.push_back(box);
  return body;
}

bool spawn(const impulse2d::Body& body, std::string* message) {
  impulse2d::SpawnBody srv;
  srv.request.body = body;
  if (!call("spawn_body", srv)) return false;
  if (message) *message = srv.response.message;
  return srv.response.success;
}

bool remove(const std::string& name) {
  impulse2d::DeleteBody srv;
  srv.request.name = name;
  return call("delete_body", srv) && srv.response.success;
}

bool getState(const std::string& name, impulse2d::GetBodyState::Response* out) {
  impulse2d::GetBodyState srv;
  srv.request.name = name;
  if (!call("get_body_state", srv)) return false;
  *out = srv.response;
  return srv.response.success;
}

void emptyCall(const std::string& service) {
  std_srvs::Empty srv;
  call(service, srv);
}

bool waitFor(const std::function<bool()>& done, double timeout) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
  while (ros::ok()) {
    if (done()) return true;
    if (ros::WallTime::now() > deadline) return false;
    ros::WallDuration(0.01).sleep();
  }
  return false;
}

}  // namespace impulse2d_test
