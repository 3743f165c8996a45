// impulse2d_wanderer: a reactive wanderer for the fleet demo. It reads `scan` and drives with
// `cmd_vel` (both relative: launched in <group ns="r1"> they are /r1/scan and /r1/cmd_vel):
// ahead while the way is clear, steering towards the more open side; turning on the spot when
// something is near ahead, keeping that turn until the way is clear again so that it does not
// dither in corners. No map, no plan: it only makes the demo move.
//
//              front (+-front_angle)
//               \   |   /
//        left    \  |  /    right
//                 robot
//
// Parameters: ~speed (m/s, 0.4), ~turn_rate (rad/s, 1.0), ~clearance (m, 0.6), ~front_angle
// (rad, 0.6).
#include <geometry_msgs/Twist.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace {

class Wanderer {
 public:
  Wanderer() {
    ros::NodeHandle pnh("~");
    pnh.param("speed", speed_, 0.4);
    pnh.param("turn_rate", turnRate_, 1.0);
    pnh.param("clearance", clearance_, 0.6);
    pnh.param("front_angle", frontAngle_, 0.6);
    cmdVel_ = nh_.advertise<geometry_msgs::Twist>("cmd_vel", 1);
    scan_ = nh_.subscribe("scan", 1, &Wanderer::onScan, this);
  }

 private:
  // The nearest reading in [from, to] rad of the scan; too near (-inf, REP 117) reads 0, nothing
  // within range (+inf) reads range_max.
  static double nearest(const sensor_msgs::LaserScan& scan, double from, double to) {
    double nearest = scan.range_max;
    for (size_t i = 0; i < scan.ranges.size(); ++i) {
      const double angle = scan.angle_min + scan.angle_increment * static_cast<double>(i);
      const double r = scan.ranges[i];
      if (angle < from || angle > to || std::isnan(r)) continue;
      nearest = std::min(nearest, r < 0.0 ? 0.0 : std::min<double>(r, scan.range_max));
    }
    return nearest;
  }

  void onScan(const sensor_msgs::LaserScan::ConstPtr& scan) {
    const double front = nearest(*scan, -frontAngle_, frontAngle_);
    const double left = nearest(*scan, frontAngle_, 2.0);
    const double right = nearest(*scan, -2.0, -frontAngle_);
    geometry_msgs::Twist cmd;
    if (front < clearance_ || (turning_ != 0 && front < 1.5 * clearance_)) {
      if (turning_ == 0) turning_ = left >= right ? 1 : -1;
      cmd.angular.z = turning_ * turnRate_;
    } else {
      turning_ = 0;
      // Slower as things come nearer ahead; a gentle pull towards the more open side.
      cmd.linear.x = speed_ * std::min(1.0, front / (3.0 * clearance_));
      const double pull = (std::min(left, 3.0) - std::min(right, 3.0)) / 3.0;
      cmd.angular.z = 0.5 * turnRate_ * std::clamp(pull, -1.0, 1.0);
    }
    cmdVel_.publish(cmd);
  }

  ros::NodeHandle nh_;
  ros::Publisher cmdVel_;
  ros::Subscriber scan_;
  double speed_ = 0.4, turnRate_ = 1.0, clearance_ = 0.6, frontAngle_ = 0.6;
  int turning_ = 0;  // -1 right, +1 left, 0 driving
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "wanderer");
  Wanderer wanderer;
  ros::spin();
  return 0;
}
