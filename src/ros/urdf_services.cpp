// WorldNode's URDF side: ~spawn_urdf, the ~urdf_param model at start, joint_states, and the
// joint motor interface (~set_joint_motor service, ~joint_command topic).
#include "conversions.hpp"
#include "world_node.hpp"

#include <sensor_msgs/JointState.h>

#include <cmath>

namespace impulse2d {
namespace bridge {
namespace {

// The model name of ~urdf_param's model unless ~urdf_model_name gives one, and of a ~spawn_urdf
// request that leaves model_name out.
const char* const kDefaultModelName = "robot";

std::string withWarnings(const Notes& notes, const std::vector<std::string>& warnings) {
  std::string message = okWithNotes(notes);
  for (size_t i = 0; i < warnings.size(); ++i) message += "; " + warnings[i];
  return message;
}

}  // namespace

void WorldNode::loadStartUrdf() {
  std::string param;
  if (!pnh_.getParam("urdf_param", param) || param.empty()) return;
  // "~name" is private; NodeHandle refuses '~' names, so the private handle reads those.
  std::string xml;
  const bool found =
      param[0] == '~' ? pnh_.getParam(param.substr(1), xml) : nh_.getParam(param, xml);
  if (!found) {
    ROS_ERROR("[%s] ~urdf_param: no string parameter '%s'; no URDF model spawned", name_.c_str(),
              param.c_str());
    return;
  }
  UrdfRequest request;
  request.xml = xml;
  pnh_.param<std::string>("urdf_model_name", request.modelName, kDefaultModelName);
  double x = 0.0, y = 0.0, theta = 0.0;
  pnh_.param("urdf_x", x, 0.0);
  pnh_.param("urdf_y", y, 0.0);
  pnh_.param("urdf_theta", theta, 0.0);
  request.position = Vec2(x, y);
  request.angle = theta;
  pnh_.param("urdf_strict", request.strict, false);
  UrdfSpawned spawned;
  std::string error;
  if (!sim_.spawnUrdf(request, true, &spawned, &error)) {
    ROS_ERROR("[%s] ~urdf_param '%s': %s; no URDF model spawned", name_.c_str(), param.c_str(),
              error.c_str());
    return;
  }
  for (const std::string& warning : spawned.warnings) {
    ROS_WARN("[%s] ~urdf_param '%s': %s", name_.c_str(), param.c_str(), warning.c_str());
  }
  ROS_INFO("[%s] URDF model '%s' from '%s': %zu bodies, %zu joints", name_.c_str(),
           request.modelName.c_str(), param.c_str(), spawned.bodies.size(), spawned.joints.size());
}

void WorldNode::advertiseUrdf() {
  jointStatesPub_ = nh_.advertise<sensor_msgs::JointState>("joint_states", 10);
  services_.push_back(pnh_.advertiseService("spawn_urdf", &WorldNode::spawnUrdf, this));
  services_.push_back(pnh_.advertiseService("set_joint_motor", &WorldNode::setJointMotor, this));
  jointCommandSub_ = pnh_.subscribe("joint_command", 10, &WorldNode::onJointCommand, this);
}

bool WorldNode::spawnUrdf(SpawnUrdf::Request& req, SpawnUrdf::Response& res) {
  UrdfRequest request;
  Notes notes;
  request.modelName = req.model_name;
  if (request.modelName.empty()) {
    request.modelName = kDefaultModelName;
    notes.push_back(std::string("model_name: default '") + kDefaultModelName + "'");
  }
  request.xml = req.urdf_xml;
  request.position = Vec2(req.pose.x, req.pose.y);
  request.angle = req.pose.theta;
  request.strict = req.strict;
  UrdfSpawned spawned;
  std::string error;
  {
    Lock lock(*this);
    sim_.spawnUrdf(request, false, &spawned, &error);
  }
  syncDevices();  // its gazebo plugins' devices get their topics before the answer
  res.success = error.empty();
  res.message = error.empty() ? withWarnings(notes, spawned.warnings) : error;
  res.bodies = spawned.bodies;
  res.joints = spawned.joints;
  res.devices = spawned.devices;
  return true;
}

bool WorldNode::setJointMotor(SetJointMotor::Request& req, SetJointMotor::Response& res) {
  std::string error;
  {
    Lock lock(*this);
    sim_.setJointMotor(req.name, req.speed, req.max_effort, req.release, &error);
  }
  res.success = error.empty();
  res.message = error.empty() ? "ok" : error;
  return true;
}

void WorldNode::onJointCommand(const JointCommand::ConstPtr& command) {
  std::string error;
  {
    Lock lock(*this);
    sim_.setJointMotor(command->name, command->speed, command->max_effort, command->release,
                       &error);
  }
  if (!error.empty()) {
    ROS_WARN_THROTTLE(1.0, "[%s] ~joint_command: %s", name_.c_str(), error.c_str());
  }
}

void WorldNode::publishJointStates(const ros::Time& stamp,
                                   const std::vector<JointReading>& joints) {
  if (joints.empty()) return;
  sensor_msgs::JointState msg;
  msg.header.stamp = stamp;
  for (const JointReading& joint : joints) {
    msg.name.push_back(joint.name);
    msg.position.push_back(joint.position);
    msg.velocity.push_back(joint.velocity);
  }
  jointStatesPub_.publish(msg);
}

}  // namespace bridge
}  // namespace impulse2d
