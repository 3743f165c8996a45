// A URDF's <gazebo> elements as devices: the gazebo_ros plugins and sensors a robot description
// already carries (urdfdom skips them) become the drives, lasers, IMUs and bumpers of the world.
#pragma once

#include "plane_projection.hpp"

#include <impulse2d/device_defs.hpp>

#include <Eigen/Geometry>

#include <functional>
#include <string>
#include <vector>

namespace impulse2d {
namespace urdf_detail {

/// Where a link went: the body it is part of ("model/top_link") and its frame in that body's.
struct LinkPlace {
  std::string body;
  Eigen::Isometry3d inBody = Eigen::Isometry3d::Identity();
};
/// Finds a link by its URDF name; false when the model has no such link, or it has no body.
using LinkLocator = std::function<bool(const std::string& link, LinkPlace* out)>;

/// Appends the devices of the validated URDF text's <gazebo> elements, named
/// "<model>/<plugin or sensor name>":
///   - libgazebo_ros_diff_drive.so: a diff_drive on robotBaseFrame's body (commandTopic,
///     odometryTopic, odometryFrame, publishOdomTF; wheelAcceleration as max_linear_accel,
///     wheelTorque over the wheel radius, for two wheels, as max_force);
///   - libgazebo_ros_planar_move.so: an omni drive (the same keys);
///   - a <sensor type="ray"> or "gpu_ray" with libgazebo_ros_laser.so or
///     libgazebo_ros_gpu_laser.so: a laser at the sensor's link and <pose> (samples, min_angle,
///     max_angle, range min and max, update_rate, Gaussian noise stddev, topicName, frameName);
///   - a <sensor type="imu"> with libgazebo_ros_imu_sensor.so, or libgazebo_ros_imu.so: an imu;
///   - a <sensor type="contact"> with libgazebo_ros_bumper.so: a bumper.
/// Topics stay where gazebo_ros puts them: a relative one under the plugin's robotNamespace, or
/// at the root. Frames named after a link of the model become "<model>/<link>". What the plane
/// cannot take (drives and IMUs outside a top-down world, a sensor tilted out of the plane, an
/// unknown plugin) is left out with a warning. Returns "" or the reason naming the element (a
/// value that is not a number, a topic that is not a ROS name, a link that is not the model's).
std::string gazeboDevices(const std::string& xml, const PlaneAxes& plane,
                          const std::string& modelName, const LinkLocator& locate,
                          std::vector<DeviceDef>* devices, std::vector<std::string>* warnings);

}  // namespace urdf_detail
}  // namespace impulse2d
