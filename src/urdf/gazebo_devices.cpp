// The gazebo_ros plugins and sensors of a URDF as devices (gazebo_devices.hpp).
#include "gazebo_devices.hpp"

#include "link_geometry.hpp"

#include "names.hpp"

#include <impulse2d/limits.hpp>

#include <tinyxml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace impulse2d {
namespace urdf_detail {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The text of a child element, or `fallback`.
std::string text(const TiXmlElement& parent, const char* child, const std::string& fallback = "") {
  const TiXmlElement* e = parent.FirstChildElement(child);
  return e != nullptr && e->GetText() != nullptr ? std::string(e->GetText()) : fallback;
}

// A child element's number; `fallback` when absent; false when present but not a finite number.
bool number(const TiXmlElement& parent, const char* child, double fallback, double* out) {
  const std::string value = text(parent, child);
  if (value.empty()) {
    *out = fallback;
    return true;
  }
  char* end = nullptr;
  *out = std::strtod(value.c_str(), &end);
  while (end != nullptr && (*end == ' ' || *end == '\n' || *end == '\t' || *end == '\r')) ++end;
  return end != nullptr && *end == '\0' && std::isfinite(*out);
}

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

std::string trimmed(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r\n");
  const size_t b = s.find_last_not_of(" \t\r\n");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

class Reader {
 public:
  Reader(const PlaneAxes& plane, const std::string& modelName, const LinkLocator& locate,
         std::vector<DeviceDef>* devices, std::vector<std::string>* warnings)
      : plane_(plane), model_(modelName), locate_(locate), devices_(devices), warnings_(warnings) {}

  std::string read(const TiXmlElement& robot) {
    for (const TiXmlElement* gazebo = robot.FirstChildElement("gazebo"); gazebo != nullptr;
         gazebo = gazebo->NextSiblingElement("gazebo")) {
      const char* reference = gazebo->Attribute("reference");
      for (const TiXmlElement* plugin = gazebo->FirstChildElement("plugin"); plugin != nullptr;
           plugin = plugin->NextSiblingElement("plugin")) {
        const std::string why = modelPlugin(*plugin, reference ? reference : "");
        if (!why.empty()) return why;
      }
      for (const TiXmlElement* sensor = gazebo->FirstChildElement("sensor"); sensor != nullptr;
           sensor = sensor->NextSiblingElement("sensor")) {
        const std::string why = readSensor(*sensor, reference ? reference : "");
        if (!why.empty()) return why;
      }
    }
    return "";
  }

 private:
  static std::string describe(const TiXmlElement& e) {
    const char* name = e.Attribute("name");
    const char* file = e.Attribute("filename");
    std::string out = std::string(e.Value()) + " " + quotedName(name ? name : "");
    if (file != nullptr) out += " (" + quotedName(file) + ")";
    return out;
  }

  // A device name: "<model>/<name>", the element's name made a valid name.
  std::string deviceName(const TiXmlElement& e, const char* fallback) const {
    std::string name = e.Attribute("name") ? e.Attribute("name") : fallback;
    for (char& c : name) {
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) c = '_';
    }
    if (name.empty()) name = fallback;
    return model_ + "/" + name;
  }

  // gazebo_ros puts a relative topic under the plugin's robotNamespace, or at the root.
  static std::string topic(const TiXmlElement& plugin, const char* key, const std::string& fallback,
                           std::string* error) {
    std::string value = trimmed(text(plugin, key, fallback));
    std::string ns = trimmed(text(plugin, "robotNamespace"));
    while (!ns.empty() && ns.front() == '/') ns.erase(0, 1);
    while (!ns.empty() && ns.back() == '/') ns.pop_back();
    if (!value.empty() && value[0] != '/') value = (ns.empty() ? "/" : "/" + ns + "/") + value;
    const std::string why = scene_detail::checkTopic(value);
    if (!why.empty()) *error = std::string(key) + " " + quotedName(value) + ": " + why;
    return value;
  }

  // The frame that `key` names ("" when it is not given): a frame named after a link of the
  // model is that link's frame; other names are the model's. It must be a name the scene format
  // takes for its own frames (names.hpp), or tf would carry it.
  std::string frame(const TiXmlElement& plugin, const char* key, const std::string& fallback,
                    std::string* error) const {
    std::string f = trimmed(text(plugin, key, fallback));
    while (!f.empty() && f.front() == '/') f.erase(0, 1);
    if (f.empty()) return "";
    f = model_ + "/" + f;
    const std::string why = scene_detail::checkName(f);
    if (!why.empty() && error->empty())
      *error = std::string(key) + " " + quotedName(f) + ": " + why;
    return f;
  }

  bool locate(const std::string& link, LinkPlace* out) const { return locate_(link, out); }

  std::string modelPlugin(const TiXmlElement& plugin, const std::string& reference) {
    const std::string file = plugin.Attribute("filename") ? plugin.Attribute("filename") : "";
    const bool diff = endsWith(file, "libgazebo_ros_diff_drive.so");
    const bool planar = endsWith(file, "libgazebo_ros_planar_move.so");
    const bool imu = endsWith(file, "libgazebo_ros_imu.so");
    if (!diff && !planar && !imu) {
      warnings_->push_back("gazebo " + describe(plugin) + ": skipped (no device of that kind)");
      return "";
    }
    const std::string where = "gazebo " + describe(plugin) + ": ";
    if (plane_.name != "xy") {
      warnings_->push_back(where + "skipped: " + (imu ? "an imu" : "a drive") +
                           " needs a top-down world (plane xy)");
      return "";
    }
    const std::string baseLink = trimmed(
        text(plugin, imu ? "bodyName" : "robotBaseFrame", imu ? reference : "base_footprint"));
    LinkPlace place;
    if (!locate(baseLink, &place)) {
      return where + (imu ? "bodyName " : "robotBaseFrame ") + quotedName(baseLink) +
             " is no link of the model with a body";
    }
    DeviceDef d;
    d.name = deviceName(plugin, imu ? "imu" : "drive");
    d.body = place.body;
    std::string error;
    if (imu) {
      d.type = DeviceType::Imu;
      d.imu.topic = topic(plugin, "topicName", "imu", &error);
      double rate = 0.0, noise = 0.0;
      if (!number(plugin, "updateRate", d.imu.updateRate, &rate) ||
          !number(plugin, "gaussianNoise", 0.0, &noise) || rate > 1e6 || noise < 0.0 ||
          noise > 1e6) {
        return where + "updateRate (at most 1e6 Hz) and gaussianNoise (0 to 1e6) must be numbers";
      }
      if (rate > 0.0) d.imu.updateRate = rate;
      d.imu.angularVelocityNoise = d.imu.linearAccelerationNoise = Eigen::Vector3d::Constant(noise);
      const std::string f = frame(plugin, "frameName", "", &error);
      if (!f.empty()) d.frame = f;
      const std::string why = mount(place.inBody, &d.imu.offset, &d.imu.offsetAngle, nullptr);
      if (!why.empty()) {
        warnings_->push_back(where + "skipped: bodyName's link " + why);
        return "";
      }
    } else {
      d.type = diff ? DeviceType::DiffDrive : DeviceType::Omni;
      DriveDef& drive = d.drive;
      drive.cmdVelTopic = topic(plugin, "commandTopic", "cmd_vel", &error);
      if (error.empty()) drive.odomTopic = topic(plugin, "odometryTopic", "odom", &error);
      const std::string odomFrame = frame(plugin, "odometryFrame", "odom", &error);
      if (!odomFrame.empty()) drive.odomFrame = odomFrame;
      const std::string publishTf = trimmed(text(plugin, "publishOdomTF", "true"));
      drive.publishTf = !(publishTf == "false" || publishTf == "0");
      double accel = 0.0, torque = 0.0, diameter = 0.0, separation = 0.0;
      if (!number(plugin, "wheelAcceleration", 0.0, &accel) ||
          !number(plugin, "wheelTorque", 0.0, &torque) ||
          !number(plugin, "wheelDiameter", 0.0, &diameter) ||
          !number(plugin, "wheelSeparation", 0.0, &separation)) {
        return where +
               "wheelAcceleration, wheelTorque, wheelDiameter and wheelSeparation must be numbers";
      }
      if (accel > 1e6) return where + "wheelAcceleration must be at most 1e6 m/s^2";
      if (accel > 0.0) drive.maxLinearAccel = accel;  // m/s^2 at the wheels' rim, as gazebo's
      if (torque > 0.0 && diameter > 0.0) {
        // Two wheels, each pushing torque / r: together forward, or in turn at half the track.
        const double push = torque / (0.5 * diameter);
        drive.maxForce = std::min(kMaxForce, 2.0 * push);
        if (separation > 0.0) drive.maxTorque = std::min(kMaxForce, push * separation);
      }
    }
    if (!error.empty()) return where + error;
    devices_->push_back(d);
    return "";
  }

  // The sensor's frame in the body: its link's, then its <pose> "x y z roll pitch yaw". Lasers
  // may be upside down (rolled half a turn); anything else tilted is refused.
  std::string mount(const Eigen::Isometry3d& sensorInBody, Vec2* offset, double* angle,
                    bool* flip) const {
    const Eigen::Vector3d up = sensorInBody.linear() * Eigen::Vector3d::UnitZ();
    const bool upright = isNormal(plane_, up);
    const bool upsideDown = isNormal(plane_, -up) && flip != nullptr;
    if (!upright && !upsideDown) return "is tilted out of the floor's plane";
    *offset = project(plane_, sensorInBody.translation());
    *angle = angleOf(plane_, sensorInBody.linear() * Eigen::Vector3d::UnitX());
    if (flip != nullptr) *flip = upsideDown && !upright;
    return "";
  }

  static bool pose(const TiXmlElement& sensor, Eigen::Isometry3d* out) {
    *out = Eigen::Isometry3d::Identity();
    const std::string value = text(sensor, "pose");
    if (value.empty()) return true;
    std::istringstream in(value);
    double v[6];
    for (double& x : v) {
      if (!(in >> x) || !std::isfinite(x)) return false;
    }
    out->translation() = Eigen::Vector3d(v[0], v[1], v[2]);
    out->linear() = (Eigen::AngleAxisd(v[5], Eigen::Vector3d::UnitZ()) *
                     Eigen::AngleAxisd(v[4], Eigen::Vector3d::UnitY()) *
                     Eigen::AngleAxisd(v[3], Eigen::Vector3d::UnitX()))
                        .toRotationMatrix();
    return true;
  }

  std::string readSensor(const TiXmlElement& sensor, const std::string& reference) {
    const std::string type = sensor.Attribute("type") ? sensor.Attribute("type") : "";
    const std::string where =
        "gazebo reference " + quotedName(reference) + " " + describe(sensor) + ": ";
    const TiXmlElement* plugin = sensor.FirstChildElement("plugin");
    const std::string file =
        plugin != nullptr && plugin->Attribute("filename") ? plugin->Attribute("filename") : "";
    const bool laser =
        (type == "ray" || type == "gpu_ray") &&
        (endsWith(file, "libgazebo_ros_laser.so") || endsWith(file, "libgazebo_ros_gpu_laser.so"));
    const bool imu = type == "imu" && endsWith(file, "libgazebo_ros_imu_sensor.so");
    const bool bumper = type == "contact" && endsWith(file, "libgazebo_ros_bumper.so");
    if (!laser && !imu && !bumper) {
      warnings_->push_back(where + "skipped (no gazebo_ros plugin impulse2d knows)");
      return "";
    }
    if (imu && plane_.name != "xy") {
      warnings_->push_back(where + "skipped: an imu needs a top-down world (plane xy)");
      return "";
    }
    LinkPlace place;
    if (!locate(reference, &place)) {
      return where + "reference " + quotedName(reference) + " is no link of the model with a body";
    }
    Eigen::Isometry3d inLink;
    if (!pose(sensor, &inLink)) return where + "pose must be six finite numbers";
    DeviceDef d;
    d.name = deviceName(sensor, laser ? "laser" : imu ? "imu" : "bumper");
    d.body = place.body;
    std::string error;
    double rate = 0.0;
    if (!number(sensor, "update_rate", 0.0, &rate)) return where + "update_rate must be a number";
    const std::string f = frame(*plugin, "frameName", "", &error);
    if (laser) {
      d.type = DeviceType::Laser;
      LaserDef& l = d.laser;
      const std::string why = mount(place.inBody * inLink, &l.offset, &l.offsetAngle, &l.flip);
      if (!why.empty()) {  // e.g. a horizontal scanner in a side view: it cannot scan the plane
        warnings_->push_back(where + "skipped: it " + why);
        return "";
      }
      l.topic = topic(*plugin, "topicName", "scan", &error);
      const TiXmlElement* ray = sensor.FirstChildElement("ray");
      const TiXmlElement* scan = ray ? ray->FirstChildElement("scan") : nullptr;
      const TiXmlElement* horizontal = scan ? scan->FirstChildElement("horizontal") : nullptr;
      const TiXmlElement* range = ray ? ray->FirstChildElement("range") : nullptr;
      const TiXmlElement* noise = ray ? ray->FirstChildElement("noise") : nullptr;
      double samples = 0.0, minAngle = l.angleMin, maxAngle = l.angleMax;
      if (horizontal != nullptr && (!number(*horizontal, "samples", 0.0, &samples) ||
                                    !number(*horizontal, "min_angle", l.angleMin, &minAngle) ||
                                    !number(*horizontal, "max_angle", l.angleMax, &maxAngle))) {
        return where + "ray/scan/horizontal: samples, min_angle and max_angle must be numbers";
      }
      if (range != nullptr && (!number(*range, "min", l.rangeMin, &l.rangeMin) ||
                               !number(*range, "max", l.rangeMax, &l.rangeMax))) {
        return where + "ray/range: min and max must be numbers";
      }
      if (noise != nullptr && !number(*noise, "stddev", 0.0, &l.noiseStddev)) {
        return where + "ray/noise/stddev must be a number";
      }
      if (samples > kMaxLaserBeams) {
        warnings_->push_back(where + "ray/scan/horizontal: samples beyond " +
                             std::to_string(kMaxLaserBeams) +
                             " beams: kept the scanner's default beams");
      }
      if (samples >= 1.0 && samples <= kMaxLaserBeams && maxAngle >= minAngle) {
        l.angleMin = minAngle;
        l.angleMax = maxAngle;
        // samples beams from min_angle to max_angle; one beam: a tiny increment, one ray.
        l.angleIncrement =
            samples >= 2.0 ? (maxAngle - minAngle) / (std::floor(samples) - 1.0) : 1e-3;
        // A full turn's last beam repeats its first (gazebo's 0 .. 2 pi): keep one of them.
        if (l.angleMax - l.angleMin > 2.0 * kPi - 1e-6) l.angleMax -= 0.5 * l.angleIncrement;
      }
      if (rate > 0.0) l.updateRate = rate;
      // The scene format's bounds (scene_format.md, devices[]).
      if (!(l.rangeMin >= 0.0 && l.rangeMax > l.rangeMin && l.rangeMax <= kMaxCoordinate &&
            l.noiseStddev >= 0.0 && l.noiseStddev <= kMaxCoordinate && l.updateRate <= 1e6)) {
        return where +
               "range min and max, noise stddev or update_rate are not a scanner's (0 <= min < "
               "max <= 1e6 m, stddev 0 to 1e6 m, at most 1e6 Hz)";
      }
    } else if (imu) {
      d.type = DeviceType::Imu;
      const std::string why =
          mount(place.inBody * inLink, &d.imu.offset, &d.imu.offsetAngle, nullptr);
      if (!why.empty()) {
        warnings_->push_back(where + "skipped: it " + why);
        return "";
      }
      d.imu.topic = topic(*plugin, "topicName", "imu", &error);
      double noise = 0.0;
      if (!number(*plugin, "gaussianNoise", 0.0, &noise) || noise < 0.0 || noise > 1e6 ||
          rate > 1e6) {
        return where + "gaussianNoise (0 to 1e6) and update_rate (at most 1e6 Hz) must be numbers";
      }
      d.imu.angularVelocityNoise = d.imu.linearAccelerationNoise = Eigen::Vector3d::Constant(noise);
      if (rate > 0.0) d.imu.updateRate = rate;
    } else {
      d.type = DeviceType::Bumper;
      d.bumper.topic = topic(*plugin, "bumperTopicName", "bumper", &error);
    }
    if (!error.empty()) return where + error;
    if (!f.empty() && !bumper) {
      if (f == place.body) {  // the body's own frame cannot hang below the body
        d.frame = place.body + "/" + d.name.substr(model_.size() + 1);
        warnings_->push_back(where +
                             "frameName names its body's own frame: the readings' frame is " +
                             quotedName(d.frame));
      } else {
        d.frame = f;
      }
    }
    devices_->push_back(d);
    return "";
  }

  const PlaneAxes& plane_;
  std::string model_;
  const LinkLocator& locate_;
  std::vector<DeviceDef>* devices_;
  std::vector<std::string>* warnings_;
};

}  // namespace

std::string gazeboDevices(const std::string& xml, const PlaneAxes& plane,
                          const std::string& modelName, const LinkLocator& locate,
                          std::vector<DeviceDef>* devices, std::vector<std::string>* warnings) {
  TiXmlDocument document;
  document.Parse(xml.c_str());
  const TiXmlElement* robot = document.Error() ? nullptr : document.FirstChildElement("robot");
  if (robot == nullptr) return "";  // urdfdom read it; nothing of gazebo's to find
  return Reader(plane, modelName, locate, devices, warnings).read(*robot);
}

}  // namespace urdf_detail
}  // namespace impulse2d
