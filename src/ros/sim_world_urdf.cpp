// SimWorld's URDF side: spawning models, their joints' states in the URDF's sense, and joint
// motors. No ROS header may appear here (see sim_world.hpp).
#include "sim_world.hpp"

#include <impulse2d/devices.hpp>
#include <impulse2d/drive.hpp>
#include <impulse2d/urdf.hpp>
#include <impulse2d/world.hpp>

#include <algorithm>
#include <cmath>

namespace impulse2d {
namespace bridge {

bool SimWorld::spawnUrdf(const UrdfRequest& request, bool atStart, UrdfSpawned* out,
                         std::string* error) {
  UrdfPlacement placement;
  placement.modelName = request.modelName;
  placement.position = request.position;
  placement.angle = request.angle;
  placement.plane = plane_;
  placement.strict = request.strict;
  placement.findPackage = findPackage_;  // package:// collision meshes
  UrdfModel model;
  if (!parseUrdf(request.xml, placement, &model, error)) return false;
  // Its gazebo plugins' devices are checked against the devices here before anything is added.
  *error = devices_->check(model.scene.devices, deviceContext());
  if (!error->empty()) return false;
  std::vector<BodyId> bodies;
  std::vector<JointId> joints;
  if (!impulse2d::addScene(model.scene, *world_, error, &bodies, &joints)) return false;
  addDevices(model.scene.devices, error);  // checked above: cannot fail
  for (const DeviceDef& device : model.scene.devices) out->devices.push_back(device.name);
  for (const BodyId id : bodies) out->bodies.push_back(world_->body(id).name);
  for (const JointId id : joints) out->joints.push_back(world_->jointDef(id).name);
  out->warnings = model.warnings;
  pruneUrdfFrames();
  for (const UrdfFrame& frame : model.frames) {
    FixedFrame fixed;
    fixed.name = frame.name;
    fixed.parent = frame.body;
    fixed.owner = frame.body.empty() ? out->bodies.front() : frame.body;
    fixed.pose = frame.pose;
    urdfFrames_.push_back(fixed);
  }
  urdfJoints_.erase(std::remove_if(urdfJoints_.begin(), urdfJoints_.end(),
                                   [&](const UrdfJoint& j) { return !world_->isValid(j.id); }),
                    urdfJoints_.end());
  // addScene creates the scene's joints in order, so joints[i] is model.joints[i]'s.
  for (size_t i = 0; i < joints.size() && i < model.joints.size(); ++i) {
    const UrdfJointInfo& info = model.joints[i];
    urdfJoints_.push_back({joints[i], info.name, info.sign, info.maxEffort, info.maxVelocity});
  }
  foldedJoints_.erase(
      std::remove_if(foldedJoints_.begin(), foldedJoints_.end(),
                     [&](const FoldedJoint& j) { return !world_->isValid(j.body); }),
      foldedJoints_.end());
  for (const UrdfFoldedJoint& f : model.folded) {
    foldedJoints_.push_back({f.name, f.link, world_->findBody(f.body), f.pose, f.axis, f.center,
                             f.planeAxis, f.wheelRadius});
  }
  ++staticVersion_;
  if (atStart) startUrdfs_.push_back(request);
  return true;
}

void SimWorld::rollFoldedWheels() {
  const double dt = timeStep();
  for (FoldedJoint& joint : foldedJoints_) {
    if (joint.wheelRadius <= 0.0 || !world_->isValid(joint.body)) continue;
    const Body& body = world_->body(joint.body);
    // The wheel centre's velocity in the body frame: the drive's wheel speeds when the body has
    // a drive (they spin against a wall too), else the body's own motion.
    Vec2 origin = body.xf.q.applyInverse(body.velocityAt(body.xf.p));
    double turn = body.angularVelocity;
    for (const Device& device : devices_->devices()) {
      if (device.drive && device.body == joint.body) {
        origin = Vec2(device.drive->speed(), device.drive->sideSpeed());
        turn = device.drive->turnRate();
      }
    }
    const Vec2 atCenter = origin + turn * Vec2(-joint.center.y(), joint.center.x());
    // Rolling without slip about the axis a: the centre moves along (a_y, -a_x) at rate * r.
    const Vec2 forward(joint.planeAxis.y(), -joint.planeAxis.x());
    joint.velocity = atCenter.dot(forward) / joint.wheelRadius;
    joint.position += joint.velocity * dt;
  }
}

std::vector<FixedFrame> SimWorld::rollingFrames() const {
  std::vector<FixedFrame> out;
  for (const FoldedJoint& joint : foldedJoints_) {
    if (joint.link.empty() || !world_->isValid(joint.body)) continue;
    FixedFrame frame;
    frame.name = joint.link;
    frame.parent = frame.owner = world_->body(joint.body).name;
    frame.pose = joint.pose * Eigen::AngleAxisd(joint.position, joint.axis);
    out.push_back(frame);
  }
  return out;
}

void SimWorld::respawnStartUrdfs() {
  // Each was spawned once already, onto the same start scene, so this cannot fail.
  for (const UrdfRequest& request : startUrdfs_) {
    UrdfSpawned unused;
    std::string error;
    spawnUrdf(request, false, &unused, &error);
  }
}

bool SimWorld::setJointMotor(const std::string& name, double speed, double maxEffort, bool release,
                             std::string* error) {
  const JointId id = world_->findJoint(name);
  if (name.empty() || !id.valid()) {
    *error = name.empty() ? "name: must not be empty" : "name: no joint named '" + name + "'";
    return false;
  }
  const JointType type = world_->jointDef(id).type;
  if (type != JointType::Revolute && type != JointType::Prismatic) {
    *error = "name: '" + name + "' is neither a revolute nor a prismatic joint";
    return false;
  }
  if (!std::isfinite(speed)) {
    *error = "speed: must be finite";
    return false;
  }
  if (!std::isfinite(maxEffort) || maxEffort < 0.0) {
    *error = "max_effort: must be finite and >= 0";
    return false;
  }
  if (release) return world_->setJointMotor(id, false, 0.0, 0.0);
  const auto urdf = std::find_if(urdfJoints_.begin(), urdfJoints_.end(),
                                 [&](const UrdfJoint& j) { return j.id == id; });
  double sign = 1.0;
  if (urdf != urdfJoints_.end()) {
    sign = urdf->sign;
    if (maxEffort == 0.0 || (urdf->maxEffort > 0.0 && maxEffort > urdf->maxEffort)) {
      maxEffort = urdf->maxEffort;
    }
    if (urdf->maxVelocity > 0.0) {
      speed = std::clamp(speed, -urdf->maxVelocity, urdf->maxVelocity);
    }
  }
  if (maxEffort == 0.0) {
    *error = "max_effort: must be > 0 (the joint has no URDF effort limit to default to)";
    return false;
  }
  return world_->setJointMotor(id, true, sign * speed, maxEffort);
}

std::vector<JointReading> SimWorld::urdfJointStates() const {
  std::vector<JointReading> out;
  for (const UrdfJoint& joint : urdfJoints_) {
    // A deleted joint (or body) leaves an invalid id behind; its slot's new joint is another.
    if (!world_->isValid(joint.id)) continue;
    const JointState state = world_->jointState(joint.id);
    // Adding 0.0 turns a -0.0 (a resting joint with sign -1) into 0.0 for readers.
    out.push_back(
        {joint.name, joint.sign * state.position + 0.0, joint.sign * state.velocity + 0.0});
  }
  for (const FoldedJoint& joint : foldedJoints_) {
    if (world_->isValid(joint.body)) out.push_back({joint.name, joint.position, joint.velocity});
  }
  return out;
}

}  // namespace bridge
}  // namespace impulse2d
