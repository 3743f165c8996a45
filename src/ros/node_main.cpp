// impulse2d_node: the world as a standalone node, running the same WorldNode as the nodelet.
#include "world_node.hpp"

#include <ros/ros.h>

#include <algorithm>
#include <thread>

int main(int argc, char** argv) {
  ros::init(argc, argv, "impulse2d");
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  impulse2d::bridge::WorldNode node(nh, pnh, ros::this_node::getName());
  // Several threads, so that service calls are answered while the world steps and publishes;
  // WorldNode serialises the world itself.
  const unsigned threads = std::max(4u, std::thread::hardware_concurrency());
  ros::MultiThreadedSpinner spinner(threads);
  spinner.spin();
  return 0;
}
