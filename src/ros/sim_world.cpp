// The engine side of the ROS node. No ROS header may appear here (see sim_world.hpp).
#include "sim_world.hpp"

#include <impulse2d/devices.hpp>
#include <impulse2d/limits.hpp>
#include <impulse2d/scene.hpp>
#include <impulse2d/world.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace impulse2d {
namespace bridge {
namespace {

void outline(const Shape& shape, ShapeOutline* out) {
  out->circle = shape.type == ShapeType::Circle;
  if (out->circle) {
    out->center = shape.circle.center;
    out->radius = shape.circle.radius;
  } else {
    out->vertices.assign(shape.polygon.vertices, shape.polygon.vertices + shape.polygon.count);
  }
}

// m: a force applied closer than this to the centre of mass is applied there, for a note.
constexpr double kWrenchArmWorthNoting = 1e-3;

// A relative tolerance so that a duration of exactly k time steps gives k steps, not k + 1.
// Capped so the conversion to an integer stays defined for any finite duration (a wrench held
// for 1e15 steps outlives any run anyway).
uint64_t stepsFor(double duration, double timeStep) {
  constexpr double kMaxSteps = 1e15;
  if (!(duration > 0.0)) return 1;
  const double steps = std::ceil(duration / timeStep * (1.0 - 1e-9));
  return static_cast<uint64_t>(std::clamp(steps, 1.0, kMaxSteps));
}

}  // namespace

SimWorld::SimWorld() : world_(std::make_unique<World>()), devices_(std::make_unique<DeviceSet>()) {}

SimWorld::~SimWorld() = default;

void SimWorld::setPackageFinder(std::function<std::string(const std::string&, std::string*)> find) {
  findPackage_ = std::move(find);
}

bool SimWorld::parse(const std::string& yamlText, Scene* scene, std::string* error) const {
  ScenePaths paths;
  paths.findPackage = findPackage_;
  return parseScene(yamlText, paths, scene, error);
}

bool SimWorld::loadStartScene(const std::string& yamlText, std::string* error) {
  startDevices_.clear();
  startDevicesAttached_ = false;
  Scene scene;
  if (!parse(yamlText, &scene, error)) {
    startYaml_.clear();
    restoreStart();
    return false;
  }
  startDevices_.swap(scene.devices);  // they may name URDF bodies spawned after this
  World candidate(scene.world);
  if (!impulse2d::addScene(scene, candidate, error)) {
    startYaml_.clear();
    startDevices_.clear();
    restoreStart();
    return false;
  }
  startYaml_ = yamlText;
  restoreStart();
  return true;
}

bool SimWorld::attachStartDevices(std::string* error) {
  if (startDevicesAttached_) return true;
  if (!addDevices(startDevices_, error)) {
    startYaml_.clear();
    startDevices_.clear();
    restoreStart();
    return false;
  }
  startDevicesAttached_ = true;
  return true;
}

void SimWorld::restoreStart() {
  world_ = std::make_unique<World>();
  frameId_ = "world";
  plane_ = "xz";
  wrenches_.clear();
  urdfJoints_.clear();
  urdfFrames_.clear();
  foldedJoints_.clear();
  devices_->clear();
  scans_.clear();
  imuReadings_.clear();
  bumperChanges_.clear();
  maps_.clear();
  models_.clear();
  ++mapVersion_;
  ++staticVersion_;
  if (!startYaml_.empty()) {
    // The start scene was checked when it was loaded, so this cannot fail (unless a map's file
    // changed since: it is read again).
    Scene scene;
    std::string error;
    if (parse(startYaml_, &scene, &error)) {
      world_ = std::make_unique<World>(scene.world);
      frameId_ = scene.frameId;
      plane_ = scene.plane;
      scene.devices.clear();
      if (impulse2d::addScene(scene, *world_, &error)) {
        for (SceneMap& map : scene.maps) maps_.push_back({map.name, std::move(map.grid)});
        recordModels(scene.models);
      }
    }
  }
  if (threads_ > 0) world_->settings().threads = threads_;
  respawnStartUrdfs();
  addFollowedWalls();
  if (startDevicesAttached_) {
    std::string error;
    addDevices(startDevices_, &error);  // attached once onto the same world: cannot fail
  }
}

void SimWorld::reset() { restoreStart(); }

void SimWorld::setThreads(int threads) {
  threads_ = threads;
  if (threads_ > 0) world_->settings().threads = threads_;
}

int SimWorld::threads() const { return world_->settings().threads; }

bool SimWorld::addScene(const std::string& yamlText, std::string* error) {
  Scene scene;
  if (!parse(yamlText, &scene, error)) return false;
  // Checked against the devices here before anything is added; addScene checks their bodies.
  *error = checkModelNames(scene.models);
  if (!error->empty()) return false;
  *error = devices_->check(scene.devices, deviceContext());
  if (!error->empty()) return false;
  if (!impulse2d::addScene(scene, *world_, error)) return false;
  addDevices(scene.devices, error);  // checked above: cannot fail
  recordModels(scene.models);
  for (SceneMap& map : scene.maps) maps_.push_back({map.name, std::move(map.grid)});
  if (!scene.maps.empty()) ++mapVersion_;
  ++staticVersion_;
  return true;
}

bool SimWorld::spawnBody(const BodyDef& def, std::string* error) {
  if (world_->findBody(def.name).valid()) {
    *error = "body.name: a body named " + quoted(def.name) + " already exists";
    return false;
  }
  const std::string why = World::validate(def);
  if (!why.empty()) {
    *error = "body." + why;
    return false;
  }
  std::string createError;
  if (!world_->createBody(def, &createError).valid()) {
    *error = "body." + createError;
    return false;
  }
  if (def.type == BodyType::Static) ++staticVersion_;
  return true;
}

bool SimWorld::deleteBody(const std::string& name, std::string* error) {
  const BodyId id = world_->findBody(name);
  if (name.empty() || !id.valid()) {
    *error = name.empty() ? "name: must not be empty" : "name: no body named " + quoted(name);
    return false;
  }
  ++staticVersion_;  // a static body, or frames fixed to the body, leave tf_static
  wrenches_.erase(std::remove_if(wrenches_.begin(), wrenches_.end(),
                                 [&](const Wrench& w) { return w.body == id; }),
                  wrenches_.end());
  world_->destroyBody(id);
  devices_->dropDetached(*world_);
  pruneUrdfFrames();
  return true;
}

bool SimWorld::createJoint(const JointDef& def, const std::string& bodyA, const std::string& bodyB,
                           std::string* error) {
  if (world_->findJoint(def.name).valid()) {
    *error = "joint.name: a joint named " + quoted(def.name) + " already exists";
    return false;
  }
  JointDef resolved = def;
  resolved.bodyA = world_->findBody(bodyA);
  resolved.bodyB = world_->findBody(bodyB);
  if (!resolved.bodyA.valid()) {
    *error = "joint.body_a: no body named " + quoted(bodyA);
    return false;
  }
  if (!resolved.bodyB.valid()) {
    *error = "joint.body_b: no body named " + quoted(bodyB);
    return false;
  }
  std::string why = world_->validate(resolved);
  if (why.empty() && !world_->createJoint(resolved, &why).valid() && why.empty()) {
    why = "the world refused the joint";
  }
  if (!why.empty()) {
    *error = "joint." + why;
    return false;
  }
  return true;
}

bool SimWorld::deleteJoint(const std::string& name, std::string* error) {
  const JointId id = world_->findJoint(name);
  if (name.empty() || !id.valid()) {
    *error = name.empty() ? "name: must not be empty" : "name: no joint named " + quoted(name);
    return false;
  }
  world_->destroyJoint(id);
  return true;
}

bool SimWorld::applyWrench(const std::string& body, const Vec2& force, double torque,
                           const Vec2& point, double duration, std::string* error,
                           std::vector<std::string>* notes) {
  const BodyId id = world_->findBody(body);
  if (body.empty() || !id.valid()) {
    *error = body.empty() ? "body: must not be empty" : "body: no body named " + quoted(body);
    return false;
  }
  if (world_->body(id).type != BodyType::Dynamic) {
    *error = "body: " + quoted(body) + " is not dynamic, so forces do not move it";
    return false;
  }
  if (!isFinite(force) || !std::isfinite(torque) || !isFinite(point) || std::isnan(duration)) {
    *error = "force, torque, point, duration: must be finite";
    return false;
  }
  if (force.norm() > kMaxForce || std::abs(torque) > kMaxForce) {
    *error = "force, torque: must be at most 1e12 N (N m)";
    return false;
  }
  if (point.cwiseAbs().maxCoeff() > kMaxCoordinate) {
    *error = "point: must be within 1e6 m of the origin on each axis";
    return false;
  }
  if (wrenches_.size() >= kMaxPendingWrenches) {
    *error = "the world already holds the maximum of " + std::to_string(kMaxPendingWrenches) +
             " pending wrenches; wait for some to end";
    return false;
  }
  // (0, 0) is what a client sends when it leaves the point out; meant or not, it is the world
  // origin, and a force there far from the body spins it.
  const double arm = (world_->body(id).center - point).norm();
  if (notes != nullptr && point.isZero() && !force.isZero() && arm > kWrenchArmWorthNoting) {
    char text[160];
    std::snprintf(text, sizeof(text),
                  "point: (0, 0), the world origin, %.3g m from the centre of mass: the force "
                  "also turns the body",
                  arm);
    notes->push_back(text);
  }
  Wrench wrench;
  wrench.body = id;
  wrench.force = force;
  wrench.torque = torque;
  wrench.localPoint = world_->body(id).xf.applyInverse(point);
  wrench.stepsLeft = stepsFor(duration, timeStep());
  wrenches_.push_back(wrench);
  return true;
}

bool SimWorld::setBodyState(const std::string& name, const Vec2& position, double angle,
                            const Vec2& linearVelocity, double angularVelocity,
                            std::string* error) {
  const BodyId id = world_->findBody(name);
  if (name.empty() || !id.valid()) {
    *error = name.empty() ? "name: must not be empty" : "name: no body named " + quoted(name);
    return false;
  }
  if (std::abs(position.x()) > kMaxCoordinate || std::abs(position.y()) > kMaxCoordinate) {
    *error = "pose: must be within 1e6 m of the origin on each axis";
    return false;
  }
  if (linearVelocity.norm() > kMaxSpeed || std::abs(angularVelocity) > kMaxSpeed) {
    *error = "twist: must be at most 1e6 m/s (rad/s)";
    return false;
  }
  const bool isStatic = world_->body(id).type == BodyType::Static;
  if (isStatic && (linearVelocity != Vec2::Zero() || angularVelocity != 0.0)) {
    *error = "twist: " + quoted(name) + " is static and cannot move";
    return false;
  }
  world_->setTransform(id, position, angle);
  if (!isStatic) world_->setVelocity(id, linearVelocity, angularVelocity);
  if (isStatic) ++staticVersion_;
  return true;
}

bool SimWorld::getBodyState(const std::string& name, BodySnapshot* out, std::string* error) const {
  const BodyId id = world_->findBody(name);
  if (name.empty() || !id.valid()) {
    *error = name.empty() ? "name: must not be empty" : "name: no body named " + quoted(name);
    return false;
  }
  const Body& body = world_->body(id);
  out->index = id.index;
  out->name = body.name;
  out->type = body.type;
  out->position = body.xf.p;
  out->angle = body.angle;
  out->linearVelocity = body.linearVelocity;
  out->angularVelocity = body.angularVelocity;
  out->awake = body.awake;
  return true;
}

bool SimWorld::getBodyProperties(const std::string& name, BodyProperties* out,
                                 std::string* error) const {
  const BodyId id = world_->findBody(name);
  if (name.empty() || !id.valid()) {
    *error = name.empty() ? "name: must not be empty" : "name: no body named " + quoted(name);
    return false;
  }
  const Body& body = world_->body(id);
  out->type = body.type;
  out->mass = body.mass;
  out->inertia = body.inertia;
  out->localCenter = body.localCenter;
  out->linearDamping = body.linearDamping;
  out->angularDamping = body.angularDamping;
  out->bullet = body.bullet;
  out->shapes.clear();
  for (const Shape& shape : body.shapes) {
    ShapeProperties p;
    outline(shape, &p);
    p.density = shape.density;
    p.friction = shape.friction;
    p.restitution = shape.restitution;
    out->shapes.push_back(std::move(p));
  }
  return true;
}

const StepProfile& SimWorld::lastProfile() const { return world_->profile(); }

void SimWorld::step() {
  for (Wrench& w : wrenches_) {
    if (!world_->isValid(w.body)) {
      w.stepsLeft = 0;
      continue;
    }
    const Vec2 point = world_->body(w.body).xf.apply(w.localPoint);
    world_->applyForce(w.body, w.force, point);
    if (w.torque != 0.0) world_->applyTorque(w.body, w.torque);
    --w.stepsLeft;
  }
  wrenches_.erase(std::remove_if(wrenches_.begin(), wrenches_.end(),
                                 [](const Wrench& w) { return w.stepsLeft == 0; }),
                  wrenches_.end());
  devices_->beforeStep(*world_, 1e-9 * static_cast<double>(simTimeNs_));  // after the wrenches
  world_->setProfiling(true);  // /diagnostics reports the stages (a few clock reads a step)
  world_->step();
  ++steps_;
  simTimeNs_ += static_cast<int64_t>(std::llround(timeStep() * 1e9));
  // The node drains these after every step; the cap only guards a caller that never does.
  constexpr size_t kMaxLosses = 1024;
  bool removedAny = false;
  for (RemovedBody& removed : world_->takeRemovedBodies()) {
    removedAny = true;
    ++staticVersion_;  // it may have been static: tf_static is sent again
    ++removedCount_;
    if (losses_.size() < kMaxLosses) {
      losses_.push_back({std::move(removed.name), removed.cause, true, std::move(removed.reason),
                         removed.position, simTimeNs_});
    }
  }
  for (LostBody& lost : world_->takeLostBodies()) {
    ++lostCount_;
    if (losses_.size() < kMaxLosses) {
      losses_.push_back({std::move(lost.name), RemovalCause::LostForGood, false,
                         std::move(lost.reason), lost.position, simTimeNs_});
    }
  }
  devices_->afterStep(*world_, 1e-9 * static_cast<double>(simTimeNs_));
  rollFoldedWheels();
  collectDeviceReadings(removedAny);
}

std::string BodyLoss::describe() const {
  if (removed) return "removed body " + quoted(name) + ": " + reason;
  return "body " + quoted(name) + " is " + reason +
         "; world.remove_lost_bodies: true removes such bodies at once";
}

std::vector<BodyLoss> SimWorld::takeBodyLosses() {
  std::vector<BodyLoss> out;
  out.swap(losses_);
  return out;
}

double SimWorld::timeStep() const { return world_->settings().timeStep; }

size_t SimWorld::bodyCount() const { return world_->bodyCount(); }

size_t SimWorld::contactCount() const { return world_->contactCount(); }

std::vector<BodySnapshot> SimWorld::bodies(bool withShapes) const {
  std::vector<BodySnapshot> out;
  const std::vector<BodyId> ids = world_->bodies();
  out.reserve(ids.size());
  std::string unused;
  for (const BodyId id : ids) {
    const Body& body = world_->body(id);
    BodySnapshot snap;
    snap.index = id.index;
    snap.name = body.name;
    snap.type = body.type;
    snap.position = body.xf.p;
    snap.angle = body.angle;
    snap.linearVelocity = body.linearVelocity;
    snap.angularVelocity = body.angularVelocity;
    snap.awake = body.awake;
    if (withShapes) {
      for (const Shape& shape : body.shapes) {
        snap.shapes.emplace_back();
        outline(shape, &snap.shapes.back());
      }
    }
    out.push_back(std::move(snap));
  }
  return out;
}

ContactSnapshot SimWorld::snapshotOf(const ContactInfo& c) const {
  ContactSnapshot snap;
  snap.bodyA = world_->body(c.bodyA).name;
  snap.bodyB = world_->body(c.bodyB).name;
  snap.point = c.point;
  snap.normal = c.normal;
  snap.separation = c.separation;
  snap.normalImpulse = c.normalImpulse;
  snap.tangentImpulse = c.tangentImpulse;
  return snap;
}

std::vector<ContactSnapshot> SimWorld::contacts() const {
  std::vector<ContactSnapshot> out;
  for (const ContactInfo& c : world_->contacts()) {
    out.push_back(snapshotOf(c));
  }
  return out;
}

std::vector<JointSnapshot> SimWorld::joints() const {
  std::vector<JointSnapshot> out;
  for (const JointId id : world_->joints()) {
    const JointDef& def = world_->jointDef(id);
    const JointState state = world_->jointState(id);
    JointSnapshot snap;
    snap.index = id.index;
    snap.name = def.name;
    snap.type = def.type;
    snap.originA = world_->body(def.bodyA).xf.p;
    snap.originB = world_->body(def.bodyB).xf.p;
    snap.anchorA = state.anchorA;
    snap.anchorB = state.anchorB;
    out.push_back(std::move(snap));
  }
  return out;
}

}  // namespace bridge
}  // namespace impulse2d
