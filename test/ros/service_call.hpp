// Service calls of the rostest clients, over persistent connections kept until the end.
#pragma once

#include <ros/ros.h>

#include <map>
#include <mutex>
#include <string>

namespace impulse2d_test {

// Why persistent, and why kept open: a non-persistent call lets the server close the connection
// after answering, and Debian's roscpp 1.15 sometimes drops the connection on that hang-up before
// it has read the response (ros/ros_comm#1976), so the call fails although the server answered
// (2 world_node.test runs in 20 under ASan). Closing each connection from this side right after
// its response instead has the node's roscpp tear the connection down while the spinner thread
// that answered is still on it (races inside roscpp, which ThreadSanitizer reports). Kept open,
// the connections close at the end, once.

struct ServiceClients {
  std::mutex mutex;
  std::map<std::string, ros::ServiceClient> byName;
};

inline ServiceClients& serviceClients() {
  static ServiceClients clients;
  return clients;
}

/// Calls `name` over this process's persistent connection to it (opened on first use, and again
/// after a failure).
template <typename Srv>
bool callService(const std::string& name, Srv& srv) {
  ros::ServiceClient client;
  {
    ServiceClients& clients = serviceClients();
    std::lock_guard<std::mutex> lock(clients.mutex);
    ros::ServiceClient& kept = clients.byName[name];
    if (!kept.isValid()) kept = ros::NodeHandle().serviceClient<Srv>(name, /*persistent=*/true);
    client = kept;
  }
  return client.call(srv);
}

/// Closes the connections callService opened; before ros::shutdown().
inline void closeServiceClients() {
  ServiceClients& clients = serviceClients();
  std::lock_guard<std::mutex> lock(clients.mutex);
  clients.byName.clear();
}

}  // namespace impulse2d_test
