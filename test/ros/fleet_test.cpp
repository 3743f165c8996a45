// The fleet demo (fleet.test): four robots of one model file, each driven by a wanderer launched
// in its namespace without remaps, all move; none leaves the building or touches another's
// topics; nothing is removed.
#include "world_test_util.hpp"

#include <impulse2d/RemovedBodies.h>
#include <nav_msgs/Odometry.h>

#include <cmath>
#include <map>

namespace impulse2d_test {
namespace {

constexpr double kWait = 60.0;

TEST(Fleet, EveryRobotWandersInTheBuilding) {
  const std::vector<std::string> robots = {"r1", "r2", "r3", "r4"};
  std::map<std::string, std::unique_ptr<Latest<nav_msgs::Odometry>>> truth;
  for (const std::string& r : robots) {
    truth[r] = std::make_unique<Latest<nav_msgs::Odometry>>("/" + r + "/ground_truth");
  }
  Latest<impulse2d::RemovedBodies> removed(worldNs() + "/removed_bodies");
  std::map<std::string, geometry_msgs::Point> start;
  ASSERT_TRUE(waitFor(
      [&] {
        for (const std::string& r : robots) {
          const nav_msgs::Odometry::ConstPtr m = truth[r]->get();
          if (!m) return false;
          if (!start.count(r)) start[r] = m->pose.pose.position;
        }
        return true;
      },
      kWait));
  std::map<std::string, double> farthest;
  ASSERT_TRUE(waitFor(
      [&] {
        for (const std::string& r : robots) {
          const geometry_msgs::Point& p = truth[r]->get()->pose.pose.position;
          // The building: x and y within -9..9 m (config/maps/offices.yaml).
          EXPECT_LT(std::abs(p.x), 9.0) << r;
          EXPECT_LT(std::abs(p.y), 9.0) << r;
          farthest[r] = std::max(farthest[r], std::hypot(p.x - start[r].x, p.y - start[r].y));
        }
        for (const std::string& r : robots) {
          if (farthest[r] < 1.0) return false;
        }
        return true;
      },
      kWait))
      << "r1 " << farthest["r1"] << " m, r2 " << farthest["r2"] << " m, r3 " << farthest["r3"]
      << " m, r4 " << farthest["r4"] << " m from where they started";
  const impulse2d::RemovedBodies::ConstPtr gone = removed.get();
  EXPECT_TRUE(!gone || gone->bodies.empty());
}

}  // namespace
}  // namespace impulse2d_test
