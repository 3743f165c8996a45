// Devices (`devices:`): each type's keys and values. Keys of another device type are refused, not
// ignored. Whether the body exists is checked when the scene is added (add.cpp); what depends on
// the other devices of the world (unique topics and frames) by the device set (devices.hpp).
#include <impulse2d/limits.hpp>

#include "names.hpp"
#include "scene_parsers.hpp"
#include "yaml_fields.hpp"

#include <cmath>
#include <cstring>

namespace impulse2d {
namespace scene_detail {
namespace {

DeviceType parseDeviceType(const YAML::Node& node) {
  const YAML::Node type = node.IsMap() ? node["type"] : YAML::Node();
  if (!type) throw SceneError("type", "must be given (diff_drive, laser or bumper)");
  const std::string name = type.IsScalar() ? type.Scalar() : "";
  for (DeviceType t : {DeviceType::DiffDrive, DeviceType::Laser, DeviceType::Bumper}) {
    if (name == deviceTypeName(t)) return t;
  }
  throw SceneError("type", "must be diff_drive, laser or bumper, not " + quoted(name));
}

struct TypeKeys {
  DeviceType type;
  std::initializer_list<const char*> keys;
};

const TypeKeys kTypeKeys[] = {
    {DeviceType::DiffDrive,
     {"cmd_vel_topic", "odom_topic", "odom_frame", "publish_tf", "ground_truth_tf",
      "max_linear_accel", "max_angular_accel", "cmd_timeout", "max_force", "max_torque",
      "pose_variance", "twist_variance"}},
    {DeviceType::Laser,
     {"offset", "topic", "range_min", "range_max", "angle_min", "angle_max", "angle_increment",
      "update_rate", "noise_stddev", "seed"}},
    {DeviceType::Bumper, {"topic"}},
};

// A key of some device type other than `type` (and not also one of its own).
void refuseOtherTypesKeys(const Fields& f, DeviceType type) {
  auto takes = [](DeviceType t, const char* key) {
    for (const TypeKeys& entry : kTypeKeys) {
      if (entry.type != t) continue;
      for (const char* k : entry.keys) {
        if (std::strcmp(k, key) == 0) return true;
      }
    }
    return false;
  };
  for (const TypeKeys& entry : kTypeKeys) {
    for (const char* key : entry.keys) {
      if (f.has(key) && !takes(type, key)) {
        throw SceneError(key, std::string("is not used by a ") + deviceTypeName(type) +
                                  " (it is a " + deviceTypeName(entry.type) + " key)");
      }
    }
  }
}

std::string topic(const Fields& f, const char* key, const std::string& fallback) {
  const std::string value = f.string(key, fallback);
  const std::string why = checkTopic(value);
  if (!why.empty()) throw SceneError(key, why);
  return value;
}

double positive(const Fields& f, const char* key, double fallback) {
  const double v = f.number(key, fallback);
  if (!std::isfinite(v) || v <= 0.0) throw SceneError(key, "must be finite and > 0");
  return v;
}

double nonNegative(const Fields& f, const char* key, double fallback) {
  const double v = f.number(key, fallback);
  if (!std::isfinite(v) || v < 0.0) throw SceneError(key, "must be finite and >= 0");
  return v;
}

// Three variances (x, y, heading).
Eigen::Vector3d variances(const Fields& f, const char* key, const Vec2& xy, double theta) {
  const Eigen::Vector3d v = f.vec3(key, Eigen::Vector3d(xy.x(), xy.y(), theta));
  if (!v.allFinite() || (v.array() < 0.0).any()) {
    throw SceneError(key, "must be three finite numbers >= 0 (x, y, theta)");
  }
  return v;
}

DriveDef parseDiffDrive(const Fields& f) {
  DriveDef d;
  d.cmdVelTopic = topic(f, "cmd_vel_topic", d.cmdVelTopic);
  d.odomTopic = topic(f, "odom_topic", d.odomTopic);
  if (d.odomTopic == d.cmdVelTopic)
    throw SceneError("odom_topic", "must differ from cmd_vel_topic");
  if (f.has("odom_frame")) d.odomFrame = f.name("odom_frame");
  d.publishTf = f.boolean("publish_tf", d.publishTf);
  d.groundTruthTf = f.boolean("ground_truth_tf", d.groundTruthTf);
  d.maxLinearAccel = positive(f, "max_linear_accel", d.maxLinearAccel);
  d.maxAngularAccel = positive(f, "max_angular_accel", d.maxAngularAccel);
  d.cmdTimeout = nonNegative(f, "cmd_timeout", d.cmdTimeout);
  d.maxForce = nonNegative(f, "max_force", d.maxForce);
  d.maxTorque = nonNegative(f, "max_torque", d.maxTorque);
  if (d.maxForce > kMaxForce) throw SceneError("max_force", "must be at most 1e12 N");
  if (d.maxTorque > kMaxForce) throw SceneError("max_torque", "must be at most 1e12 N m");
  const Eigen::Vector3d pose = variances(f, "pose_variance", d.poseVarianceXy, d.poseVarianceTheta);
  d.poseVarianceXy = pose.head<2>();
  d.poseVarianceTheta = pose.z();
  const Eigen::Vector3d twist =
      variances(f, "twist_variance", d.twistVarianceXy, d.twistVarianceTheta);
  d.twistVarianceXy = twist.head<2>();
  d.twistVarianceTheta = twist.z();
  return d;
}

LaserDef parseLaser(const Fields& f) {
  LaserDef l;
  const Eigen::Vector3d offset =
      f.vec3("offset", Eigen::Vector3d(l.offset.x(), l.offset.y(), l.offsetAngle));
  if (!offset.allFinite() || offset.head<2>().cwiseAbs().maxCoeff() > kMaxCoordinate) {
    throw SceneError("offset", "must be three finite numbers (x, y, theta), x and y within 1e6 m");
  }
  l.offset = offset.head<2>();
  l.offsetAngle = offset.z();
  l.topic = topic(f, "topic", l.topic);
  l.rangeMin = nonNegative(f, "range_min", l.rangeMin);
  l.rangeMax = positive(f, "range_max", l.rangeMax);
  if (l.rangeMax <= l.rangeMin) throw SceneError("range_max", "must be greater than range_min");
  if (l.rangeMax > kMaxCoordinate) throw SceneError("range_max", "must be at most 1e6 m");
  l.angleMin = f.number("angle_min", l.angleMin);
  l.angleMax = f.number("angle_max", l.angleMax);
  if (!std::isfinite(l.angleMin)) throw SceneError("angle_min", "must be finite");
  if (!std::isfinite(l.angleMax)) throw SceneError("angle_max", "must be finite");
  if (l.angleMax < l.angleMin) throw SceneError("angle_max", "must not be less than angle_min");
  if (l.angleMax - l.angleMin > 2.0 * kPi + 1e-9) {
    throw SceneError("angle_max", "angle_max - angle_min must be at most 2 pi (one turn)");
  }
  l.angleIncrement = positive(f, "angle_increment", l.angleIncrement);
  if ((l.angleMax - l.angleMin) / l.angleIncrement >= static_cast<double>(kMaxLaserBeams)) {
    throw SceneError("angle_increment", "gives more than " + std::to_string(kMaxLaserBeams) +
                                            " beams; make it larger");
  }
  l.updateRate = positive(f, "update_rate", l.updateRate);
  if (l.updateRate > 1e6) throw SceneError("update_rate", "must be at most 1e6 Hz");
  l.noiseStddev = nonNegative(f, "noise_stddev", l.noiseStddev);
  if (l.noiseStddev > kMaxCoordinate) throw SceneError("noise_stddev", "must be at most 1e6 m");
  if (f.has("seed")) {
    const double seed = f.number("seed", 0.0);
    if (!(seed >= 0.0 && seed <= 4294967295.0) || std::floor(seed) != seed) {
      throw SceneError("seed", "must be an integer from 0 to 4294967295");
    }
    l.hasSeed = true;
    l.seed = static_cast<uint32_t>(seed);
  }
  return l;
}

}  // namespace

DeviceDef parseDevice(const YAML::Node& node) {
  if (!node.IsMap()) throw SceneError("", "must be a map describing a device");
  const DeviceType type = parseDeviceType(node);
  const Fields f(node, "a device",
                 {"type",
                  "name",
                  "body",
                  "cmd_vel_topic",
                  "odom_topic",
                  "odom_frame",
                  "publish_tf",
                  "ground_truth_tf",
                  "max_linear_accel",
                  "max_angular_accel",
                  "cmd_timeout",
                  "max_force",
                  "max_torque",
                  "pose_variance",
                  "twist_variance",
                  "offset",
                  "topic",
                  "range_min",
                  "range_max",
                  "angle_min",
                  "angle_max",
                  "angle_increment",
                  "update_rate",
                  "noise_stddev",
                  "seed"});
  refuseOtherTypesKeys(f, type);
  DeviceDef def;
  def.type = type;
  def.name = f.name("name");
  def.body = f.name("body");
  switch (type) {
    case DeviceType::DiffDrive:
      def.drive = parseDiffDrive(f);
      break;
    case DeviceType::Laser:
      def.laser = parseLaser(f);
      break;
    case DeviceType::Bumper:
      def.bumper.topic = topic(f, "topic", def.bumper.topic);
      break;
  }
  return def;
}

}  // namespace scene_detail
}  // namespace impulse2d
