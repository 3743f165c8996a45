// The gtest node that world_node.test and world_nodelet.test run against the world.
#include "world_test_util.hpp"

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "impulse2d_world_tests");
  ros::NodeHandle nh;
  // Subscriptions (tf, contacts, markers, clock) are served while the tests wait.
  ros::AsyncSpinner spinner(2);
  spinner.start();
  if (!ros::service::waitForService(impulse2d_test::worldNs() + "/reset", ros::Duration(30.0))) {
    ROS_ERROR("the world under test never came up at %s", impulse2d_test::worldNs().c_str());
    return 1;
  }
  const int result = RUN_ALL_TESTS();
  impulse2d_test::closeServiceClients();
  spinner.stop();
  ros::shutdown();
  return result;
}
