// Placing a model in a scene: its names put in the model's namespace, its poses carried by the
// model's pose. One model file then serves a whole fleet:
//
//   model file        placed as r1 at (2, 0, pi/2)          as r2 at (-2, 0, 0)
//   base_link         r1/base_link                           r2/base_link
//   drive: cmd_vel    /r1/cmd_vel, frame r1/odom             /r2/cmd_vel, frame r2/odom
//   laser: scan       /r1/scan, frame r1/base_link/laser     /r2/scan, frame r2/base_link/laser
#include <impulse2d/limits.hpp>
#include <impulse2d/scene.hpp>

#include "names.hpp"
#include "yaml_fields.hpp"

#include <cmath>
#include <set>

namespace impulse2d {
namespace scene_detail {
namespace {

// The model's names and poses in the world: everything placeModel changes, nothing else.
class Placement {
 public:
  Placement(const ModelPlacement& where, const std::set<std::string>& modelBodies)
      : ns_(where.ns), rotation_(where.angle), where_(where), modelBodies_(modelBodies) {}

  std::string name(const std::string& local) const {
    const std::string placed = ns_ + "/" + local;
    const std::string why = checkName(placed);
    if (!why.empty()) throw SceneError("name", quoted(placed) + ": " + why);
    return placed;
  }
  // A body the model's joint or device names: one of its own, by its placed name.
  std::string body(const std::string& local, const char* key) const {
    if (!modelBodies_.count(local)) {
      throw SceneError(key, quoted(local) +
                                " is not a body of the model (a model's joints and "
                                "devices name its own bodies)");
    }
    return name(local);
  }
  // A relative topic moves into the namespace; an absolute one stays where it is.
  std::string topic(const std::string& topic) const {
    if (!topic.empty() && topic[0] == '/') return topic;
    const std::string placed = "/" + ns_ + "/" + topic;
    const std::string why = checkTopic(placed);
    if (!why.empty()) throw SceneError("topic", quoted(placed) + ": " + why);
    return placed;
  }
  Vec2 point(const Vec2& p) const { return rotation_.apply(p) + where_.position; }
  Vec2 direction(const Vec2& d) const { return rotation_.apply(d); }
  double angle(double a) const { return a + where_.angle; }

 private:
  std::string ns_;
  Rot rotation_;
  const ModelPlacement& where_;
  const std::set<std::string>& modelBodies_;
};

std::string listed(const char* list, size_t i, const std::string& name) {
  return std::string(list) + "[" + std::to_string(i) + "] " + quoted(name);
}

void placeDevice(const Placement& at, DeviceDef* d) {
  const std::string localName = d->name, localBody = d->body;
  d->name = at.name(localName);
  d->body = at.body(localBody, "body");
  if (d->type == DeviceType::Laser || d->type == DeviceType::Imu) {
    d->frame = at.name(d->frame.empty() ? localBody + "/" + localName : d->frame);
  }
  if (isDrive(d->type)) {
    DriveDef& drive = d->drive;
    drive.cmdVelTopic = at.topic(drive.cmdVelTopic);
    drive.odomTopic = at.topic(drive.odomTopic);
    if (!drive.groundTruthTopic.empty()) drive.groundTruthTopic = at.topic(drive.groundTruthTopic);
    drive.odomFrame = at.name(drive.odomFrame);
  }
  if (d->type == DeviceType::Laser) d->laser.topic = at.topic(d->laser.topic);
  if (d->type == DeviceType::Bumper) d->bumper.topic = at.topic(d->bumper.topic);
  if (d->type == DeviceType::Imu) d->imu.topic = at.topic(d->imu.topic);
}

}  // namespace
}  // namespace scene_detail

bool placeModel(const Scene& model, const ModelPlacement& request, Scene* scene, std::string* error,
                const std::string& file) {
  using namespace scene_detail;
  std::string why = checkName(request.name);
  if (!why.empty()) {
    *error = "name: " + why;
    return false;
  }
  ModelPlacement where = request;
  if (!where.ns.empty() && where.ns[0] == '/') where.ns.erase(0, 1);
  if (where.ns.empty()) where.ns = where.name;
  why = checkTopic(where.ns);
  if (!why.empty() || where.ns[0] == '/') {
    *error = "namespace: " + quoted(where.ns) + " cannot name topics (" +
             (why.empty() ? "a single leading '/' at most" : why) +
             "); give a namespace of letters, digits and '_'";
    return false;
  }
  if (!where.position.allFinite() || where.position.cwiseAbs().maxCoeff() > kMaxCoordinate ||
      !std::isfinite(where.angle)) {
    *error = "position, angle: must be finite, the position within 1e6 m of the origin";
    return false;
  }
  for (const SceneModel& other : scene->models) {
    if (other.name == where.name) {
      *error = "name: a model named " + quoted(where.name) + " already exists";
      return false;
    }
  }

  std::set<std::string> modelBodies;
  for (const BodyDef& body : model.bodies) modelBodies.insert(body.name);
  const Placement at(where, modelBodies);
  Scene placed;
  SceneModel record;
  record.name = where.name;
  record.ns = where.ns;
  record.file = file;
  std::set<std::string> taken;  // the scene's names, which the model's may not take
  for (const BodyDef& b : scene->bodies) taken.insert("body " + b.name);
  for (const SceneJoint& j : scene->joints) taken.insert("joint " + j.def.name);
  for (const DeviceDef& d : scene->devices) taken.insert("device " + d.name);
  const auto claim = [&](const char* kind, const std::string& name, const std::string& entry) {
    if (!taken.insert(std::string(kind) + " " + name).second) {
      throw SceneError("", entry + ": a " + kind + " named " + quoted(name) + " already exists");
    }
  };
  try {
    for (size_t i = 0; i < model.bodies.size(); ++i) {
      const std::string entry = listed("bodies", i, model.bodies[i].name);
      BodyDef body = model.bodies[i];
      record.localPositions.push_back(body.position);
      record.localAngles.push_back(body.angle);
      try {
        body.name = at.name(body.name);
      } catch (const SceneError& e) {
        throw SceneError("", entry + ": " + e.what());
      }
      body.position = at.point(body.position);
      body.angle = at.angle(body.angle);
      body.linearVelocity = at.direction(body.linearVelocity);
      claim("body", body.name, entry);
      record.bodies.push_back(body.name);
      placed.bodies.push_back(std::move(body));
    }
    for (size_t i = 0; i < model.joints.size(); ++i) {
      const std::string entry = listed("joints", i, model.joints[i].def.name);
      SceneJoint joint = model.joints[i];
      try {
        joint.def.name = at.name(joint.def.name);
        joint.bodyA = at.body(joint.bodyA, "body_a");
        joint.bodyB = at.body(joint.bodyB, "body_b");
      } catch (const SceneError& e) {
        throw SceneError("", entry + ": " + e.what());
      }
      joint.def.anchor = at.point(joint.def.anchor);
      joint.def.anchorB = at.point(joint.def.anchorB);
      joint.def.axis = at.direction(joint.def.axis);
      claim("joint", joint.def.name, entry);
      record.joints.push_back(joint.def.name);
      placed.joints.push_back(std::move(joint));
    }
    for (size_t i = 0; i < model.devices.size(); ++i) {
      const std::string entry = listed("devices", i, model.devices[i].name);
      DeviceDef device = model.devices[i];
      try {
        placeDevice(at, &device);
      } catch (const SceneError& e) {
        throw SceneError("", entry + ": " + e.what());
      }
      claim("device", device.name, entry);
      record.devices.push_back(device.name);
      placed.devices.push_back(std::move(device));
    }
  } catch (const SceneError& e) {
    *error = "model " + quoted(where.name) + ": " + e.what();
    return false;
  }
  for (BodyDef& b : placed.bodies) scene->bodies.push_back(std::move(b));
  for (SceneJoint& j : placed.joints) scene->joints.push_back(std::move(j));
  for (DeviceDef& d : placed.devices) scene->devices.push_back(std::move(d));
  scene->models.push_back(std::move(record));
  return true;
}

}  // namespace impulse2d
