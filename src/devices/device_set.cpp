// The devices of one world (devices.hpp): their checks against each other, and their turns
// around each step.
#include <impulse2d/devices.hpp>
#include <impulse2d/limits.hpp>

#include <algorithm>
#include <map>

namespace impulse2d {
namespace {

std::string describe(size_t index, const DeviceDef& def) {
  return "devices[" + std::to_string(index) + "] '" + def.name + "'";
}

// The topics a device uses, with the key that names each.
std::vector<std::pair<std::string, const char*>> topicsOf(const DeviceDef& def) {
  switch (def.type) {
    case DeviceType::DiffDrive:
    case DeviceType::Omni:
    case DeviceType::Ackermann:
      return {{def.drive.cmdVelTopic, "cmd_vel_topic"},
              {def.drive.odomTopic, "odom_topic"},
              {groundTruthTopicOf(def.drive), "ground_truth_topic"}};
    case DeviceType::Laser:
      return {{def.laser.topic, "topic"}};
    case DeviceType::Bumper:
      return {{def.bumper.topic, "topic"}};
    case DeviceType::Imu:
      return {{def.imu.topic, "topic"}};
  }
  return {};
}

}  // namespace

std::string DeviceSet::check(const std::vector<DeviceDef>& defs, const DeviceContext& world) const {
  if (devices_.size() + defs.size() > kMaxDevices) {
    return "devices: the world would hold more than " + std::to_string(kMaxDevices) + " devices";
  }
  // Each name taken so far, with who took it: one of the set's devices or of the new ones.
  std::map<std::string, std::string> names, topics, frames, drivenBodies;
  for (const std::string& topic : world.reservedTopics) topics[topic] = "the node itself";
  auto claim = [](std::map<std::string, std::string>& taken, const std::string& key,
                  const std::string& holder) -> std::string {
    const auto inserted = taken.emplace(key, holder);
    return inserted.second ? "" : inserted.first->second;
  };
  auto registerDevice = [&](const DeviceDef& def, const std::string& holder) -> std::string {
    std::string clash = claim(names, def.name, holder);
    if (!clash.empty()) return "name: already used by " + clash;
    for (const auto& [topic, key] : topicsOf(def)) {
      const std::string resolved = world.resolveTopic ? world.resolveTopic(topic) : topic;
      clash = claim(topics, resolved, holder + " (" + key + ")");
      if (!clash.empty()) {
        return std::string(key) + ": '" + topic + "' is already used by " + clash;
      }
    }
    if (def.type == DeviceType::Laser || def.type == DeviceType::Imu) {
      // Its frame hangs below its body in tf: one parent per frame.
      const std::string frame = deviceFrameOf(def);
      if (frame == world.worldFrame || frame == def.body) {
        return "frame: must differ from the world frame and from its body's frame";
      }
      clash = claim(frames, frame, holder);
      if (!clash.empty()) return "frame: '" + frame + "' is already published by " + clash;
    }
    if (!isDrive(def.type)) return "";
    clash = claim(drivenBodies, def.body, holder);
    if (!clash.empty()) return "body: '" + def.body + "' is already driven by " + clash;
    if (!def.drive.publishTf) return "";
    const std::string& frame = def.drive.odomFrame;
    if (frame == world.worldFrame)
      return "odom_frame: must differ from the world frame '" + frame + "'";
    if (frame == def.body) return "odom_frame: must differ from the body's own frame";
    clash = claim(frames, frame, holder);
    if (!clash.empty()) return "odom_frame: '" + frame + "' is already published by " + clash;
    return "";
  };
  for (const Device& device : devices_) {
    registerDevice(device.def, "the device '" + device.def.name + "'");
  }
  for (size_t i = 0; i < defs.size(); ++i) {
    const DeviceDef& def = defs[i];
    if (isDrive(def.type) && world.plane != "xy") {
      return describe(i, def) + ": type: " + deviceTypeWithArticle(def.type) +
             " drives on the floor of a top-down world (plane xy); this world's plane is " +
             world.plane;
    }
    if (def.type == DeviceType::Imu && world.plane != "xy") {
      return describe(i, def) + ": type: an imu rides on the floor of a top-down world " +
             "(plane xy), where z is up; this world's plane is " + world.plane;
    }
    const std::string why = registerDevice(def, describe(i, def));
    if (!why.empty()) return describe(i, def) + ": " + why;
  }
  return "";
}

bool DeviceSet::add(const std::vector<DeviceDef>& defs, const World& world,
                    const DeviceContext& context, double now, std::string* error) {
  const std::string why = check(defs, context);
  if (!why.empty()) {
    if (error != nullptr) *error = why;
    return false;
  }
  for (const DeviceDef& def : defs) {
    Device device;
    device.def = def;
    device.body = world.findBody(def.body);
    device.id = nextId_++;
    const uint32_t seed = [&] {
      if (def.type == DeviceType::Laser && def.laser.hasSeed) return def.laser.seed;
      if (def.type == DeviceType::Imu && def.imu.hasSeed) return def.imu.seed;
      return seedFromName(def.name);
    }();
    switch (def.type) {
      case DeviceType::DiffDrive:
      case DeviceType::Omni:
      case DeviceType::Ackermann:
        device.drive = std::make_unique<Drive>(def.drive, device.body, world, def.type);
        break;
      case DeviceType::Laser:
        device.laser = std::make_unique<Laser>(def.laser, device.body, seed);
        device.schedule = std::make_unique<ScanSchedule>(def.laser.updateRate, now);
        break;
      case DeviceType::Bumper:
        device.bumper = std::make_unique<Bumper>(def.bumper, device.body);
        break;
      case DeviceType::Imu:
        device.imu = std::make_unique<Imu>(def.imu, device.body, seed, world);
        device.schedule = std::make_unique<ScanSchedule>(def.imu.updateRate, now);
        break;
    }
    devices_.push_back(std::move(device));
  }
  if (!defs.empty()) ++version_;
  return true;
}

void DeviceSet::dropDetached(const World& world) {
  const size_t before = devices_.size();
  devices_.erase(std::remove_if(devices_.begin(), devices_.end(),
                                [&](const Device& d) { return !world.isValid(d.body); }),
                 devices_.end());
  if (devices_.size() != before) ++version_;
}

void DeviceSet::clear() {
  if (!devices_.empty()) ++version_;
  devices_.clear();
}

void DeviceSet::beforeStep(World& world, double now) {
  for (Device& device : devices_) {
    if (device.drive) device.drive->beforeStep(world, now);
  }
}

void DeviceSet::afterStep(const World& world, double now) {
  const double dt = world.settings().timeStep;
  for (Device& device : devices_) {
    if (device.drive) device.drive->afterStep(dt);
    if (device.laser) {
      // The schedule moves on whether or not anyone listens, so scans keep their phase.
      if (device.schedule->due(now) && device.active) {
        device.laser->scan(world, &device.ranges, &device.intensities);
        device.fresh = true;
        device.readingTime = now;
      }
    }
    if (device.imu) {
      device.imu->follow(world);  // every step: the acceleration is over the last one
      if (device.schedule->due(now) && device.active) {
        device.imuReading = device.imu->read();
        device.fresh = true;
        device.readingTime = now;
      }
    }
    if (device.bumper) {
      if (!device.active) {
        device.bumper->forget();
      } else if (device.bumper->update(world)) {
        device.fresh = true;
        device.readingTime = now;
      }
    }
  }
}

Device* DeviceSet::find(const std::string& name) {
  for (Device& device : devices_) {
    if (device.def.name == name) return &device;
  }
  return nullptr;
}

}  // namespace impulse2d
