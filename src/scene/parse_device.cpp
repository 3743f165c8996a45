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
  const char* kTypes = "diff_drive, omni, ackermann, laser, bumper or imu";
  if (!type) throw SceneError("type", std::string("must be given (") + kTypes + ")");
  const std::string name = type.IsScalar() ? type.Scalar() : "";
  for (DeviceType t : kDeviceTypes) {
    if (name == deviceTypeName(t)) return t;
  }
  throw SceneError("type", std::string("must be ") + kTypes + ", not " + quoted(name));
}

struct TypeKeys {
  DeviceType type;
  std::initializer_list<const char*> keys;
};

const TypeKeys kTypeKeys[] = {
    {DeviceType::DiffDrive,
     {"cmd_vel_topic", "odom_topic", "ground_truth_topic", "odom_frame", "publish_tf",
      "ground_truth_tf", "max_linear_accel", "max_angular_accel", "cmd_timeout", "max_force",
      "max_torque", "pose_variance", "twist_variance"}},
    {DeviceType::Omni,
     {"cmd_vel_topic", "odom_topic", "ground_truth_topic", "odom_frame", "publish_tf",
      "ground_truth_tf", "max_linear_accel", "max_angular_accel", "cmd_timeout", "max_force",
      "max_torque", "pose_variance", "twist_variance"}},
    {DeviceType::Ackermann,
     {"cmd_vel_topic", "odom_topic", "ground_truth_topic", "odom_frame", "publish_tf",
      "ground_truth_tf", "max_linear_accel", "cmd_timeout", "max_force", "max_torque",
      "pose_variance", "twist_variance", "wheelbase", "max_steering_angle", "steering_rate"}},
    {DeviceType::Laser,
     {"offset", "topic", "range_min", "range_max", "angle_min", "angle_max", "angle_increment",
      "update_rate", "noise_stddev", "seed", "flip", "frame"}},
    {DeviceType::Bumper, {"topic"}},
    {DeviceType::Imu,
     {"offset", "topic", "frame", "update_rate", "seed", "orientation_noise",
      "angular_velocity_noise", "linear_acceleration_noise", "angular_velocity_bias",
      "linear_acceleration_bias"}},
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
        throw SceneError(key, "is not used by " + deviceTypeWithArticle(type) + " (it is " +
                                  deviceTypeWithArticle(entry.type) + " key)");
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

DriveDef parseDrive(const Fields& f, DeviceType type) {
  DriveDef d;
  d.cmdVelTopic = topic(f, "cmd_vel_topic", d.cmdVelTopic);
  d.odomTopic = topic(f, "odom_topic", d.odomTopic);
  if (d.odomTopic == d.cmdVelTopic)
    throw SceneError("odom_topic", "must differ from cmd_vel_topic");
  if (f.has("ground_truth_topic")) d.groundTruthTopic = topic(f, "ground_truth_topic", "");
  const std::string truth = groundTruthTopicOf(d);
  if (truth == d.odomTopic || truth == d.cmdVelTopic) {
    throw SceneError("ground_truth_topic", "must differ from odom_topic and cmd_vel_topic");
  }
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
  if (type == DeviceType::Ackermann) {
    if (!f.has("wheelbase")) {
      throw SceneError("wheelbase",
                       "must be given: m from the rear axle (the body's origin) "
                       "to the front axle");
    }
    d.wheelbase = positive(f, "wheelbase", d.wheelbase);
    if (d.wheelbase > kMaxCoordinate) throw SceneError("wheelbase", "must be at most 1e6 m");
    d.maxSteeringAngle = f.number("max_steering_angle", d.maxSteeringAngle);
    if (!(d.maxSteeringAngle > 0.0 && d.maxSteeringAngle < 0.5 * kPi)) {
      throw SceneError("max_steering_angle", "must be in (0, pi/2) rad");
    }
    d.steeringRate = positive(f, "steering_rate", d.steeringRate);
  }
  return d;
}

// The `seed` key: whether it is given, and its value.
bool seed(const Fields& f, uint32_t* out) {
  if (!f.has("seed")) return false;
  const double seed = f.number("seed", 0.0);
  if (!(seed >= 0.0 && seed <= 4294967295.0) || std::floor(seed) != seed) {
    throw SceneError("seed", "must be an integer from 0 to 4294967295");
  }
  *out = static_cast<uint32_t>(seed);
  return true;
}

// A sensor's `offset` [x, y, theta] on its body, over the defaults in `at` and `angle`.
void mountOffset(const Fields& f, Vec2* at, double* angle) {
  const Eigen::Vector3d offset = f.vec3("offset", Eigen::Vector3d(at->x(), at->y(), *angle));
  if (!offset.allFinite() || offset.head<2>().cwiseAbs().maxCoeff() > kMaxCoordinate) {
    throw SceneError("offset", "must be three finite numbers (x, y, theta), x and y within 1e6 m");
  }
  *at = offset.head<2>();
  *angle = offset.z();
}

LaserDef parseLaser(const Fields& f) {
  LaserDef l;
  mountOffset(f, &l.offset, &l.offsetAngle);
  l.topic = topic(f, "topic", l.topic);
  l.rangeMin = nonNegative(f, "range_min", l.rangeMin);
  l.rangeMax = positive(f, "range_max", l.rangeMax);
  if (l.rangeMax <= l.rangeMin) throw SceneError("range_max", "must be greater than range_min");
  if (l.rangeMax > kMaxCoordinate) throw SceneError("range_max", "must be at most 1e6 m");
  l.angleMin = f.number("angle_min", l.angleMin);
  l.angleMax = f.number("angle_max", l.angleMax);
  if (!std::isfinite(l.angleMin)) throw SceneError("angle_min", "must be finite");
  if (!std::isfinite(l.angleMax)) throw SceneError("angle_max", "must be finite");
  l.angleIncrement = f.number("angle_increment", l.angleIncrement);
  if (!std::isfinite(l.angleIncrement) || l.angleIncrement == 0.0) {
    throw SceneError("angle_increment", "must be finite and not 0 (< 0 sweeps clockwise)");
  }
  // Beams sweep from angle_min towards angle_max: counter-clockwise with a positive increment,
  // clockwise with a negative one.
  if (l.angleIncrement > 0.0 && l.angleMax < l.angleMin) {
    throw SceneError("angle_max",
                     "must not be less than angle_min (or give a negative "
                     "angle_increment to sweep clockwise)");
  }
  if (l.angleIncrement < 0.0 && l.angleMax > l.angleMin) {
    throw SceneError("angle_max",
                     "must not be greater than angle_min with a negative "
                     "angle_increment (a clockwise sweep)");
  }
  if (std::abs(l.angleMax - l.angleMin) > 2.0 * kPi + 1e-9) {
    throw SceneError("angle_max", "angle_max - angle_min must be at most 2 pi (one turn)");
  }
  if ((l.angleMax - l.angleMin) / l.angleIncrement >= static_cast<double>(kMaxLaserBeams)) {
    throw SceneError("angle_increment", "gives more than " + std::to_string(kMaxLaserBeams) +
                                            " beams; make it larger");
  }
  l.updateRate = positive(f, "update_rate", l.updateRate);
  if (l.updateRate > 1e6) throw SceneError("update_rate", "must be at most 1e6 Hz");
  l.noiseStddev = nonNegative(f, "noise_stddev", l.noiseStddev);
  if (l.noiseStddev > kMaxCoordinate) throw SceneError("noise_stddev", "must be at most 1e6 m");
  l.hasSeed = seed(f, &l.seed);
  l.flip = f.boolean("flip", l.flip);
  return l;
}

// A number for all three axes (x, y, z), or a list of three; each finite, >= 0 unless `isSigned`,
// and at most `limit` (`limitText` in words) in size.
Eigen::Vector3d perAxis(const Fields& f, const char* key, bool isSigned, double limit,
                        const char* limitText) {
  if (!f.has(key)) return Eigen::Vector3d::Zero();
  const YAML::Node& n = f.node(key);
  const Eigen::Vector3d v =
      n.IsScalar() ? Eigen::Vector3d::Constant(f.number(key, 0.0)) : f.vec3(key, {});
  if (!v.allFinite() || (!isSigned && (v.array() < 0.0).any()) ||
      (v.cwiseAbs().array() > limit).any()) {
    throw SceneError(key, std::string("must be a number or a list of three (x, y, z), each ") +
                              (isSigned ? "" : ">= 0, ") + "finite and at most " + limitText +
                              " in size");
  }
  return v;
}

ImuDef parseImu(const Fields& f) {
  ImuDef u;
  mountOffset(f, &u.offset, &u.offsetAngle);
  u.topic = topic(f, "topic", u.topic);
  u.updateRate = positive(f, "update_rate", u.updateRate);
  if (u.updateRate > 1e6) throw SceneError("update_rate", "must be at most 1e6 Hz");
  u.orientationNoise = perAxis(f, "orientation_noise", false, kPi, "pi rad");
  u.angularVelocityNoise = perAxis(f, "angular_velocity_noise", false, 1e6, "1e6 rad/s");
  u.linearAccelerationNoise = perAxis(f, "linear_acceleration_noise", false, 1e6, "1e6 m/s^2");
  u.angularVelocityBias = perAxis(f, "angular_velocity_bias", true, 1e6, "1e6 rad/s");
  u.linearAccelerationBias = perAxis(f, "linear_acceleration_bias", true, 1e6, "1e6 m/s^2");
  u.hasSeed = seed(f, &u.seed);
  return u;
}

}  // namespace

DeviceDef parseDevice(const YAML::Node& node) {
  if (!node.IsMap()) throw SceneError("", "must be a map describing a device");
  const DeviceType type = parseDeviceType(node);
  const Fields f(node, "a device",
                 {"type",
                  "name",
                  "body",
                  "frame",
                  "cmd_vel_topic",
                  "odom_topic",
                  "ground_truth_topic",
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
                  "seed",
                  "flip",
                  "wheelbase",
                  "max_steering_angle",
                  "steering_rate",
                  "orientation_noise",
                  "angular_velocity_noise",
                  "linear_acceleration_noise",
                  "angular_velocity_bias",
                  "linear_acceleration_bias"});
  refuseOtherTypesKeys(f, type);
  DeviceDef def;
  def.type = type;
  def.name = f.name("name");
  def.body = f.name("body");
  if (f.has("frame")) def.frame = f.name("frame");
  switch (type) {
    case DeviceType::DiffDrive:
    case DeviceType::Omni:
    case DeviceType::Ackermann:
      def.drive = parseDrive(f, type);
      break;
    case DeviceType::Laser:
      def.laser = parseLaser(f);
      break;
    case DeviceType::Bumper:
      def.bumper.topic = topic(f, "topic", def.bumper.topic);
      break;
    case DeviceType::Imu:
      def.imu = parseImu(f);
      break;
  }
  return def;
}

}  // namespace scene_detail
}  // namespace impulse2d
