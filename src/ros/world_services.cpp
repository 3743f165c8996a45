// WorldNode: the private services. Each checks its request first (naming the bad field), then
// changes the world under the lock or not at all. A service always answers (returns true);
// `success` and `message` tell the outcome.
#include "conversions.hpp"
#include "world_node.hpp"

#include <cmath>

namespace impulse2d {
namespace bridge {
namespace {

// One call of `step` holds the world for at most this many steps.
constexpr uint32_t kMaxStepsPerCall = 1000000;

template <typename Response>
bool answer(Response& res, const std::string& error, const Notes& notes = Notes()) {
  res.success = error.empty();
  res.message = error.empty() ? okWithNotes(notes) : error;
  return true;
}

std::string finite(const std::string& field, double v) {
  return std::isfinite(v) ? "" : field + ": must be finite";
}

std::string firstOf(std::initializer_list<std::string> checks) {
  for (const std::string& why : checks) {
    if (!why.empty()) return why;
  }
  return "";
}

}  // namespace

void WorldNode::advertiseServices() {
  services_.push_back(pnh_.advertiseService("spawn_body", &WorldNode::spawnBody, this));
  services_.push_back(pnh_.advertiseService("delete_body", &WorldNode::deleteBody, this));
  services_.push_back(pnh_.advertiseService("create_joint", &WorldNode::createJoint, this));
  services_.push_back(pnh_.advertiseService("delete_joint", &WorldNode::deleteJoint, this));
  services_.push_back(pnh_.advertiseService("load_scene", &WorldNode::loadScene, this));
  services_.push_back(pnh_.advertiseService("apply_wrench", &WorldNode::applyWrench, this));
  services_.push_back(pnh_.advertiseService("get_body_state", &WorldNode::getBodyState, this));
  services_.push_back(pnh_.advertiseService("set_body_state", &WorldNode::setBodyState, this));
  services_.push_back(
      pnh_.advertiseService("get_body_properties", &WorldNode::getBodyProperties, this));
  services_.push_back(pnh_.advertiseService("step", &WorldNode::step, this));
  services_.push_back(pnh_.advertiseService("pause", &WorldNode::pause, this));
  services_.push_back(pnh_.advertiseService("unpause", &WorldNode::unpause, this));
  services_.push_back(pnh_.advertiseService("reset", &WorldNode::reset, this));
  services_.push_back(pnh_.advertiseService("ray_cast", &WorldNode::rayCast, this));
  services_.push_back(pnh_.advertiseService("query_point", &WorldNode::queryPoint, this));
  advertiseUrdf();
  advertiseModels();
}

bool WorldNode::spawnBody(SpawnBody::Request& req, SpawnBody::Response& res) {
  BodyDef def;
  Notes notes;
  std::string error = toBodyDef(req.body, &def, &notes);
  if (error.empty()) {
    Lock lock(*this);
    sim_.spawnBody(def, &error);
  }
  return answer(res, error, notes);
}

bool WorldNode::deleteBody(DeleteBody::Request& req, DeleteBody::Response& res) {
  std::string error;
  {
    Lock lock(*this);
    sim_.deleteBody(req.name, &error);
  }
  syncDevices();  // its devices went with it
  return answer(res, error);
}

bool WorldNode::createJoint(CreateJoint::Request& req, CreateJoint::Response& res) {
  JointDef def;
  Notes notes;
  std::string error = toJointDef(req.joint, &def, &notes);
  if (error.empty()) {
    Lock lock(*this);
    sim_.createJoint(def, req.joint.body_a, req.joint.body_b, &error);
  }
  return answer(res, error, notes);
}

bool WorldNode::deleteJoint(DeleteJoint::Request& req, DeleteJoint::Response& res) {
  std::string error;
  {
    Lock lock(*this);
    sim_.deleteJoint(req.name, &error);
  }
  return answer(res, error);
}

bool WorldNode::loadScene(LoadScene::Request& req, LoadScene::Response& res) {
  std::string error;
  if (req.yaml.empty()) {
    error = "yaml: must not be empty";
  } else {
    Lock lock(*this);
    if (!sim_.addScene(req.yaml, &error)) error = "yaml: " + error;
  }
  syncDevices();  // the scene's devices get their topics before the answer
  return answer(res, error);
}

bool WorldNode::applyWrench(ApplyWrench::Request& req, ApplyWrench::Response& res) {
  std::string error = firstOf({finite("force.x", req.force.x), finite("force.y", req.force.y),
                               finite("torque", req.torque), finite("point.x", req.point.x),
                               finite("point.y", req.point.y), finite("duration", req.duration)});
  if (error.empty() && req.duration < 0.0) error = "duration: must be >= 0 (0: one step)";
  Notes notes;
  if (error.empty()) {
    Lock lock(*this);
    sim_.applyWrench(req.body, Vec2(req.force.x, req.force.y), req.torque,
                     Vec2(req.point.x, req.point.y), req.duration, &error, &notes);
  }
  return answer(res, error, notes);
}

bool WorldNode::getBodyState(GetBodyState::Request& req, GetBodyState::Response& res) {
  BodySnapshot body;
  std::string error;
  {
    Lock lock(*this);
    sim_.getBodyState(req.name, &body, &error);
  }
  if (error.empty()) {
    res.pose.x = body.position.x();
    res.pose.y = body.position.y();
    res.pose.theta = body.angle;
    res.twist.linear.x = body.linearVelocity.x();
    res.twist.linear.y = body.linearVelocity.y();
    res.twist.angular.z = body.angularVelocity;
  }
  return answer(res, error);
}

bool WorldNode::getBodyProperties(GetBodyProperties::Request& req,
                                  GetBodyProperties::Response& res) {
  BodyProperties body;
  std::string error;
  {
    Lock lock(*this);
    sim_.getBodyProperties(req.name, &body, &error);
  }
  if (error.empty()) {
    res.type = toBodyTypeMsg(body.type);
    res.mass = body.mass;
    res.inertia = body.inertia;
    res.center_of_mass.x = body.localCenter.x();
    res.center_of_mass.y = body.localCenter.y();
    res.linear_damping = body.linearDamping;
    res.angular_damping = body.angularDamping;
    res.bullet = body.bullet;
    for (const ShapeProperties& shape : body.shapes) res.shapes.push_back(toShapeMsg(shape));
  }
  return answer(res, error);
}

bool WorldNode::setBodyState(SetBodyState::Request& req, SetBodyState::Response& res) {
  std::string error =
      firstOf({finite("pose.x", req.pose.x), finite("pose.y", req.pose.y),
               finite("pose.theta", req.pose.theta), finite("twist.linear.x", req.twist.linear.x),
               finite("twist.linear.y", req.twist.linear.y),
               finite("twist.angular.z", req.twist.angular.z)});
  if (error.empty()) {
    Lock lock(*this);
    sim_.setBodyState(req.name, Vec2(req.pose.x, req.pose.y), req.pose.theta,
                      Vec2(req.twist.linear.x, req.twist.linear.y), req.twist.angular.z, &error);
  }
  return answer(res, error);
}

bool WorldNode::step(Step::Request& req, Step::Response& res) {
  if (req.steps == 0) return answer(res, "steps: must be >= 1");
  if (req.steps > kMaxStepsPerCall) {
    return answer(res, "steps: at most " + std::to_string(kMaxStepsPerCall) + " per call");
  }
  int64_t simTimeNs = 0;
  // The lock is taken per step, so other calls are answered during a long request.
  for (uint32_t i = 0; i < req.steps; ++i) {
    Lock lock(*this);
    stepLocked();
    simTimeNs = sim_.simTimeNs();
  }
  if (publishClock_) publishClock(simTimeNs);
  return answer(res, "");
}

bool WorldNode::pause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  Lock lock(*this);
  paused_ = true;
  return true;
}

bool WorldNode::unpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  Lock lock(*this);
  if (paused_) restartSchedule();
  paused_ = false;
  return true;
}

bool WorldNode::reset(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  {
    Lock lock(*this);
    sim_.reset();
  }
  syncDevices();
  return true;
}

// Models: a model file spawned once per robot in its namespace, deleted and moved whole.
void WorldNode::advertiseModels() {
  services_.push_back(pnh_.advertiseService("spawn_model", &WorldNode::spawnModel, this));
  services_.push_back(pnh_.advertiseService("delete_model", &WorldNode::deleteModel, this));
  services_.push_back(pnh_.advertiseService("move_model", &WorldNode::moveModel, this));
}

bool WorldNode::spawnModel(SpawnModel::Request& req, SpawnModel::Response& res) {
  ModelRequest request;
  request.where.name = req.model_name;
  request.where.ns = req.robot_namespace;
  request.where.position = Vec2(req.pose.x, req.pose.y);
  request.where.angle = req.pose.theta;
  request.file = req.file;
  request.yaml = req.model_yaml;
  std::string error = firstOf({finite("pose.x", req.pose.x), finite("pose.y", req.pose.y),
                               finite("pose.theta", req.pose.theta)});
  if (error.empty() && req.model_name.empty()) error = "model_name: must not be empty";
  ModelSpawned spawned;
  if (error.empty()) {
    Lock lock(*this);
    sim_.spawnModel(request, &spawned, &error);
  }
  syncDevices();  // its devices get their topics before the answer
  res.bodies = spawned.bodies;
  res.joints = spawned.joints;
  res.devices = spawned.devices;
  return answer(res, error);
}

bool WorldNode::deleteModel(DeleteModel::Request& req, DeleteModel::Response& res) {
  std::string error;
  {
    Lock lock(*this);
    sim_.deleteModel(req.model_name, &error);
  }
  syncDevices();  // its devices went with it
  return answer(res, error);
}

bool WorldNode::moveModel(MoveModel::Request& req, MoveModel::Response& res) {
  std::string error = firstOf({finite("pose.x", req.pose.x), finite("pose.y", req.pose.y),
                               finite("pose.theta", req.pose.theta)});
  if (error.empty()) {
    Lock lock(*this);
    sim_.moveModel(req.model_name, Vec2(req.pose.x, req.pose.y), req.pose.theta, &error);
  }
  return answer(res, error);
}

}  // namespace bridge
}  // namespace impulse2d
