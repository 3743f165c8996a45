// World's public API: creating and destroying bodies and joints, lookups, state changes and
// read-outs. The step itself is in world_step.cpp.
#include "world_impl.hpp"

#include <impulse2d/limits.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace impulse2d {

World::World(const WorldDef& def) : impl_(std::make_unique<WorldImpl>()) { impl_->def = def; }
World::~World() = default;

WorldDef& World::settings() { return impl_->def; }
const WorldDef& World::settings() const { return impl_->def; }

// --- broad-phase bookkeeping ---

void WorldImpl::markMoved(int proxy) {
  if (proxy >= static_cast<int>(proxyMoved.size())) proxyMoved.resize(proxy + 1, 0);
  if (proxyMoved[proxy]) return;
  proxyMoved[proxy] = 1;
  movedProxies.push_back(proxy);
}

void WorldImpl::addMovable(int slot) {
  if (slot >= static_cast<int>(movableIndex.size())) movableIndex.resize(slot + 1, -1);
  const auto at = std::lower_bound(movableSlots.begin(), movableSlots.end(), slot);
  const size_t from = static_cast<size_t>(at - movableSlots.begin());
  movableSlots.insert(at, slot);
  // A slot reused below the highest one shifts the places after it (new slots come last).
  for (size_t k = from; k < movableSlots.size(); ++k) movableIndex[movableSlots[k]] = k;
}

void WorldImpl::removeMovable(int slot) {
  if (!isMovable(slot)) return;
  const size_t from = static_cast<size_t>(movableIndex[slot]);
  movableSlots.erase(movableSlots.begin() + from);
  movableIndex[slot] = -1;
  for (size_t k = from; k < movableSlots.size(); ++k) movableIndex[movableSlots[k]] = k;
}

void WorldImpl::createProxies(int slot) {
  const Body& body = bodies.items[slot];
  BodyBookkeeping& book = bookkeeping[slot];
  book.proxies.clear();
  book.staticProxies.clear();
  book.proxyXf = body.xf;
  for (size_t i = 0; i < body.shapes.size(); ++i) {
    const Aabb box = computeAabb(body.shapes[i], body.xf).inflated(kAabbMargin);
    const int proxy = tree.createProxy(box, proxyData(slot, static_cast<int>(i)));
    if (proxyFilters.size() <= static_cast<size_t>(proxy)) {
      proxyFilters.resize(static_cast<size_t>(proxy) + 1);
    }
    proxyFilters[static_cast<size_t>(proxy)] = {body.shapes[i].filter, body.shapes.size() == 1};
    book.proxies.push_back(proxy);
    markMoved(proxy);
    if (body.type == BodyType::Static) {
      book.staticProxies.push_back(
          staticTree.createProxy(box, proxyData(slot, static_cast<int>(i))));
    }
  }
}

void WorldImpl::destroyProxies(int slot) {
  std::vector<int>& proxies = bookkeeping[slot].proxies;
  for (const int proxy : proxies) {
    if (proxy < static_cast<int>(proxyMoved.size()) && proxyMoved[proxy]) {
      proxyMoved[proxy] = 0;
      movedProxies.erase(std::find(movedProxies.begin(), movedProxies.end(), proxy));
    }
    tree.destroyProxy(proxy);
  }
  proxies.clear();
  for (const int proxy : bookkeeping[slot].staticProxies) staticTree.destroyProxy(proxy);
  bookkeeping[slot].staticProxies.clear();
}

void WorldImpl::updateProxies(int slot, bool forced) {
  const Body& body = bodies.items[slot];
  BodyBookkeeping& book = bookkeeping[slot];
  if (forced) book.proxyXf = body.xf;
  for (size_t i = 0; i < body.shapes.size(); ++i) {
    const Aabb box = computeAabb(body.shapes[i], body.xf);
    const int proxy = book.proxies[i];
    if (!forced && tree.fatAabb(proxy).contains(box)) continue;
    tree.moveProxy(proxy, box.inflated(kAabbMargin));
    markMoved(proxy);
    if (!book.staticProxies.empty()) {
      staticTree.moveProxy(book.staticProxies[i], box.inflated(kAabbMargin));
    }
  }
}

void WorldImpl::destroyContactsOf(int bodySlot) {
  for (Contact& c : contacts) {
    if (c.bodyA != bodySlot && c.bodyB != bodySlot) continue;  // a dead one's bodies are -1
    wakeBody(bodies.items[c.bodyA == bodySlot ? c.bodyB : c.bodyA]);
    contactKeys.erase(c.key);
    c.bodyA = c.bodyB = -1;
    ++deadContacts;
  }
}

bool WorldImpl::shouldCollide(int bodyA, int bodyB) const {
  const Body& a = bodies.items[bodyA];
  const Body& b = bodies.items[bodyB];
  if (a.type != BodyType::Dynamic && b.type != BodyType::Dynamic) return false;
  for (const int j : jointsOfBody[bodyA]) {
    const auto [jointA, jointB] = jointBodies[j];
    const bool connects =
        (jointA == bodyA && jointB == bodyB) || (jointA == bodyB && jointB == bodyA);
    if (connects && !joints.items[j].params.collideConnected) return false;
  }
  // Filters belong to shapes: the pair of bodies is kept when any two of their shapes may touch,
  // and updateContact leaves the others without points.
  for (const Shape& shapeA : a.shapes) {
    for (const Shape& shapeB : b.shapes) {
      if (filtersAllowContact(shapeA.filter, shapeB.filter)) return true;
    }
  }
  return false;
}

void WorldImpl::wakeBody(Body& body) {
  body.awake = true;
  body.sleepTime = 0.0;
}

// --- bodies ---

BodyId World::createBody(const BodyDef& def, std::string* error) {
  WorldImpl& w = *impl_;
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return BodyId();
  };
  const std::string why = validate(def);
  if (!why.empty()) return fail(why);
  if (!def.name.empty() && w.bodyByName.count(def.name)) {
    return fail("name: a body named '" + def.name + "' already exists");
  }
  static_assert(kMaxBodies <= size_t(kMaxBodySlots), "contact keys hold 24-bit body slots");
  if (w.bodies.count() >= kMaxBodies) {
    return fail("the world already holds the maximum of " + std::to_string(kMaxBodies) + " bodies");
  }
  if (w.shapeCount + def.shapes.size() > kMaxShapes) {
    return fail("shapes: the world would exceed its maximum of " + std::to_string(kMaxShapes) +
                " shapes");
  }

  std::vector<Shape> shapes;
  for (size_t i = 0; i < def.shapes.size(); ++i) {
    Shape shape;
    const std::string shapeWhy = makeShape(def.shapes[i], &shape);
    if (!shapeWhy.empty()) return fail("shapes[" + std::to_string(i) + "]." + shapeWhy);
    shapes.push_back(shape);
  }

  // Mass: sum the shapes, then move every inertia to the common centre (parallel axis theorem).
  MassData total;
  if (def.type == BodyType::Dynamic) {
    std::vector<MassData> parts;
    for (const Shape& shape : shapes) {
      parts.push_back(computeMass(shape));
      total.mass += parts.back().mass;
      total.center += parts.back().mass * parts.back().center;
    }
    if (!(total.mass > 0.0) && !(def.mass > 0.0)) {
      return fail("mass: a dynamic body needs mass: give its shapes a density > 0 or set mass");
    }
    if (!(total.mass > 0.0)) {  // an explicit mass with massless shapes: spread it by area
      for (size_t i = 0; i < shapes.size(); ++i) {
        Shape unit = shapes[i];
        unit.density = 1.0;
        parts[i] = computeMass(unit);
        total.mass += parts[i].mass;
        total.center += parts[i].mass * parts[i].center;
      }
    }
    total.center /= total.mass;
    for (const MassData& part : parts) {
      total.inertia += part.inertia + part.mass * (part.center - total.center).squaredNorm();
    }
    if (def.mass > 0.0) {
      total.inertia *= def.mass / total.mass;
      total.mass = def.mass;
    }
    if (def.useLocalCenter) {
      total.inertia += total.mass * (def.localCenter - total.center).squaredNorm();
      total.center = def.localCenter;
    }
    if (def.inertia > 0.0) total.inertia = def.inertia;
    // Lighter bodies would turn a legal force (kMaxForce) into a velocity beyond any double.
    total.mass = std::max(total.mass, kMinMass);
    total.inertia = std::max(total.inertia, kMinInertia);
  }

  const int slot = w.bodies.acquire();
  if (slot >= static_cast<int>(w.jointsOfBody.size())) {
    w.jointsOfBody.resize(slot + 1);
    w.jointNeighbours.invalidate();
    w.bookkeeping.resize(slot + 1);
  }
  Body& body = w.bodies.items[slot];
  body.id = BodyId{slot, w.bodies.generation[slot]};
  body.name = def.name;
  body.type = def.type;
  if (def.type != BodyType::Static) w.addMovable(slot);
  body.shapes = std::move(shapes);
  body.angle = def.angle;
  body.xf = Transform(def.position, Rot(def.angle));
  body.mass = total.mass;
  body.invMass = total.mass > 0.0 ? 1.0 / total.mass : 0.0;
  body.inertia = total.inertia;
  body.invInertia = total.inertia > 0.0 ? 1.0 / total.inertia : 0.0;
  body.localCenter = total.center;
  body.center = body.xf.apply(body.localCenter);
  if (def.type != BodyType::Static) {
    body.linearVelocity = def.linearVelocity;
    body.angularVelocity = def.angularVelocity;
  }
  body.linearDamping = def.linearDamping;
  body.angularDamping = def.angularDamping;
  body.bullet = def.bullet;
  body.awake = def.awake || def.type != BodyType::Dynamic || !w.def.enableSleep;
  body.minExtent = std::numeric_limits<double>::infinity();
  for (const Shape& shape : body.shapes) {
    body.minExtent = std::min(body.minExtent, innerRadius(shape));
    const Aabb box = computeAabb(shape, Transform());
    for (const Vec2& corner : {box.lower, box.upper, Vec2(box.lower.x(), box.upper.y()),
                               Vec2(box.upper.x(), box.lower.y())}) {
      body.maxExtent = std::max(body.maxExtent, (corner - body.localCenter).norm());
    }
  }
  w.createProxies(slot);
  w.shapeCount += body.shapes.size();
  if (!def.name.empty()) w.bodyByName[def.name] = slot;
  if (def.type == BodyType::Static) w.staticBodiesChanged();
  return body.id;
}

bool World::destroyBody(BodyId id) {
  WorldImpl& w = *impl_;
  if (!isValid(id)) return false;
  const std::vector<int> attached = w.jointsOfBody[id.index];
  for (const int j : attached) destroyJoint(w.joints.items[j].id);
  w.destroyContactsOf(id.index);
  Body& body = w.bodies.items[id.index];
  if (body.type == BodyType::Static) w.staticBodiesChanged();
  w.destroyProxies(id.index);
  w.shapeCount -= body.shapes.size();
  if (!body.name.empty()) w.bodyByName.erase(body.name);
  w.bodies.release(id.index);
  w.removeMovable(id.index);
  w.jointsOfBody[id.index].clear();
  w.jointNeighbours.invalidate();
  w.bookkeeping[id.index] = BodyBookkeeping();
  return true;
}

void World::clear() {
  const WorldDef def = impl_->def;
  impl_ = std::make_unique<WorldImpl>();
  impl_->def = def;
}

// --- joints ---

std::string World::validate(const JointDef& def) const {
  const WorldImpl& w = *impl_;
  if (!def.name.empty() && w.jointByName.count(def.name)) {
    return "name: a joint named '" + def.name + "' already exists";
  }
  if (!isValid(def.bodyA)) return "body_a: no such body";
  if (!isValid(def.bodyB)) return "body_b: no such body";
  if (def.bodyA == def.bodyB) return "body_b: a joint needs two different bodies";
  if (body(def.bodyA).type != BodyType::Dynamic && body(def.bodyB).type != BodyType::Dynamic) {
    return "body_a, body_b: at least one of the two bodies must be dynamic";
  }
  if (def.type != JointType::Revolute && def.type != JointType::Prismatic &&
      def.type != JointType::Weld && def.type != JointType::Distance) {
    return "type: must be revolute, prismatic, weld or distance";
  }
  // Finite everywhere, even in fields a type does not use: a NaN is always a mistake.
  if (!isFinite(def.anchor)) return "anchor: must be finite";
  if (!isFinite(def.anchorB)) return "anchor_b: must be finite";
  if (!std::isfinite(def.lower) || !std::isfinite(def.upper)) return "lower, upper: must be finite";
  if (!std::isfinite(def.motorSpeed)) return "motor_speed: must be finite";
  if (!std::isfinite(def.maxMotorTorque) || def.maxMotorTorque < 0.0) {
    return "max_motor_torque: must be finite and >= 0";
  }
  if (!std::isfinite(def.frequency) || def.frequency < 0.0) {
    return "frequency: must be finite and >= 0";
  }
  if (!std::isfinite(def.dampingRatio) || def.dampingRatio < 0.0) {
    return "damping_ratio: must be finite and >= 0";
  }
  constexpr double kMinDistance = 0.001;  // m; shorter rods have no usable direction
  switch (def.type) {
    case JointType::Revolute:
      if (def.enableLimit && def.lower > def.upper) return "lower: must not exceed upper";
      break;
    case JointType::Prismatic:
      if (!isFinite(def.axis) || def.axis.isZero()) {
        return "axis: must be a finite non-zero direction";
      }
      if (def.enableLimit && def.lower > def.upper) return "lower: must not exceed upper";
      break;
    case JointType::Weld:
      break;
    case JointType::Distance: {
      if (!std::isfinite(def.length)) return "length: must be finite";
      if (def.length > 0.0 && def.length < kMinDistance) return "length: must be >= 0.001 m";
      if (!std::isfinite(def.minLength) || def.minLength < 0.0) {
        return "min_length: must be finite and >= 0";
      }
      if (std::isnan(def.maxLength)) return "max_length: must be a number";
      if (def.minLength > def.maxLength) return "min_length: must not exceed max_length";
      if (def.length > 0.0 && (def.length < def.minLength || def.length > def.maxLength)) {
        return "length: must be within [min_length, max_length]";
      }
      if (def.length <= 0.0) {
        const Vec2 anchorB = def.useAnchorB ? def.anchorB : body(def.bodyB).xf.p;
        if ((anchorB - def.anchor).norm() < kMinDistance) {
          return "length: the anchors are closer than 0.001 m; give a length";
        }
      }
      break;
    }
  }
  return "";
}

JointId World::createJoint(const JointDef& def, std::string* error) {
  WorldImpl& w = *impl_;
  std::string why = validate(def);
  if (why.empty() && w.joints.count() >= kMaxJoints) {
    why = "the world already holds the maximum of " + std::to_string(kMaxJoints) + " joints";
  }
  if (!why.empty()) {
    if (error) *error = why;
    return JointId();
  }
  w.syncJoints();  // the last step's joints back in their slots before one is added
  const int slot = w.joints.acquire();
  Joint& joint = w.joints.items[slot];
  joint.id = JointId{slot, w.joints.generation[slot]};
  if (w.jointDefs.size() < w.joints.items.size()) w.jointDefs.resize(w.joints.items.size());
  w.jointDefs[slot] = def;
  joint.bodyA = def.bodyA.index;
  joint.bodyB = def.bodyB.index;
  Body& a = w.bodies.items[joint.bodyA];
  Body& b = w.bodies.items[joint.bodyB];
  initJoint(joint, def, a, b);
  if (w.jointBodies.size() < w.joints.items.size()) w.jointBodies.resize(w.joints.items.size());
  w.jointBodies[slot] = {joint.bodyA, joint.bodyB};
  if (isRigidWeld(joint)) ++w.rigidWelds;
  w.jointsOfBody[joint.bodyA].push_back(slot);
  w.jointsOfBody[joint.bodyB].push_back(slot);
  w.jointNeighbours.invalidate();
  if (!def.name.empty()) w.jointByName[def.name] = slot;
  if (!def.collideConnected) {  // contacts between the two bodies end now
    const int lo = std::min(joint.bodyA, joint.bodyB), hi = std::max(joint.bodyA, joint.bodyB);
    w.eraseContactsIf([&](const Contact& c) { return c.bodyA == lo && c.bodyB == hi; });
  }
  w.wakeBody(a);
  w.wakeBody(b);
  return joint.id;
}

bool World::destroyJoint(JointId id) {
  WorldImpl& w = *impl_;
  if (!isValid(id)) return false;
  w.syncJoints();  // the held joints back in their slots before this one's is freed
  Joint& joint = w.joints.items[id.index];
  if (isRigidWeld(joint)) --w.rigidWelds;
  for (const int slot : {joint.bodyA, joint.bodyB}) {
    auto& list = w.jointsOfBody[slot];
    list.erase(std::remove(list.begin(), list.end(), id.index), list.end());
    w.jointNeighbours.invalidate();
    w.wakeBody(w.bodies.items[slot]);
    // The pair may collide again: let the broad phase report it anew.
    for (const int proxy : w.bookkeeping[slot].proxies) w.markMoved(proxy);
  }
  const std::string& name = w.jointDefs[id.index].name;
  if (!name.empty()) w.jointByName.erase(name);
  w.jointDefs[id.index] = JointDef();
  w.joints.release(id.index);
  return true;
}

// --- lookup ---

bool World::isValid(BodyId id) const { return impl_->bodies.isAlive(id.index, id.generation); }
bool World::isValid(JointId id) const { return impl_->joints.isAlive(id.index, id.generation); }

BodyId World::findBody(const std::string& name) const {
  const auto it = impl_->bodyByName.find(name);
  return it == impl_->bodyByName.end() ? BodyId() : impl_->bodies.items[it->second].id;
}

JointId World::findJoint(const std::string& name) const {
  const auto it = impl_->jointByName.find(name);
  return it == impl_->jointByName.end() ? JointId() : impl_->joints.items[it->second].id;
}

const Body& World::body(BodyId id) const { return impl_->bodies.items[id.index]; }
const JointDef& World::jointDef(JointId id) const { return impl_->jointDefs[id.index]; }

JointState World::jointState(JointId id) const {
  const Joint& joint = impl_->joints.items[id.index];
  return measureJoint(joint, impl_->bodies.items[joint.bodyA], impl_->bodies.items[joint.bodyB]);
}

std::vector<BodyId> World::bodies() const {
  std::vector<BodyId> ids;
  for (size_t i = 0; i < impl_->bodies.items.size(); ++i) {
    if (impl_->bodies.alive[i]) ids.push_back(impl_->bodies.items[i].id);
  }
  return ids;
}

std::vector<JointId> World::joints() const {
  std::vector<JointId> ids;
  for (size_t i = 0; i < impl_->joints.items.size(); ++i) {
    if (impl_->joints.alive[i]) ids.push_back(impl_->joints.items[i].id);
  }
  return ids;
}

size_t World::bodyCount() const { return impl_->bodies.count(); }
size_t World::jointCount() const { return impl_->joints.count(); }

// --- changing state ---

bool World::setTransform(BodyId id, const Vec2& position, double angle) {
  if (!isValid(id) || !isFinite(position) || !std::isfinite(angle)) return false;
  WorldImpl& w = *impl_;
  // The bodies rigidly welded to it go with it, so the welds stay closed (the solver moves them
  // as one body and would never close them again).
  const std::vector<int> group =
      rigidlyWeldedTo(id.index, w.bodies.items, w.joints.items, w.jointsOfBody);
  const Transform from = w.bodies.items[id.index].xf;
  const Transform to(position, Rot(angle));
  const double turn = angle - w.bodies.items[id.index].angle;
  std::vector<std::pair<Vec2, double>> poses;
  for (const int slot : group) {
    const Body& member = w.bodies.items[slot];
    const Vec2 p = slot == id.index ? position : to.apply(from.applyInverse(member.xf.p));
    if (std::abs(p.x()) > kMaxCoordinate || std::abs(p.y()) > kMaxCoordinate) return false;
    poses.emplace_back(p, slot == id.index ? angle : member.angle + turn);
  }
  for (size_t k = 0; k < group.size(); ++k) {
    Body& body = w.bodies.items[group[k]];
    body.angle = poses[k].second;
    body.xf = Transform(poses[k].first, Rot(body.angle));
    body.center = body.xf.apply(body.localCenter);
    w.updateProxies(group[k], true);
    w.wakeBody(body);
    if (body.type == BodyType::Static) w.staticBodiesChanged();
  }
  return true;
}

bool World::setVelocity(BodyId id, const Vec2& linear, double angular) {
  if (!isValid(id) || !isFinite(linear) || !std::isfinite(angular)) return false;
  if (linear.norm() > kMaxSpeed || std::abs(angular) > kMaxSpeed) return false;
  WorldImpl& w = *impl_;
  if (w.bodies.items[id.index].type == BodyType::Static) return false;
  // The bodies rigidly welded to it move with it, as one rigid body.
  const std::vector<int> group =
      rigidlyWeldedTo(id.index, w.bodies.items, w.joints.items, w.jointsOfBody);
  const Vec2 center = w.bodies.items[id.index].center;
  for (const int slot : group) {
    const Vec2 v = linear + cross(angular, Vec2(w.bodies.items[slot].center - center));
    if (v.norm() > kMaxSpeed) return false;
  }
  for (const int slot : group) {
    Body& body = w.bodies.items[slot];
    body.linearVelocity = linear + cross(angular, Vec2(body.center - center));
    body.angularVelocity = angular;
    w.wakeBody(body);
  }
  return true;
}

bool World::applyForce(BodyId id, const Vec2& force, const Vec2& worldPoint) {
  if (!isValid(id) || !isFinite(force) || !isFinite(worldPoint)) return false;
  // Bounded so that the torque about the centre stays finite.
  if (force.norm() > kMaxForce || worldPoint.cwiseAbs().maxCoeff() > kWorldExtent) return false;
  Body& body = impl_->bodies.items[id.index];
  if (body.type != BodyType::Dynamic) return false;
  body.force += force;
  body.torque += cross(Vec2(worldPoint - body.center), force);
  impl_->wakeBody(body);
  return true;
}

bool World::applyTorque(BodyId id, double torque) {
  if (!isValid(id) || !std::isfinite(torque) || std::abs(torque) > kMaxForce) return false;
  Body& body = impl_->bodies.items[id.index];
  if (body.type != BodyType::Dynamic) return false;
  body.torque += torque;
  impl_->wakeBody(body);
  return true;
}

bool World::setJointMotor(JointId id, bool enable, double speed, double maxForceOrTorque) {
  if (!isValid(id) || !std::isfinite(speed) || !std::isfinite(maxForceOrTorque) ||
      maxForceOrTorque < 0.0) {
    return false;
  }
  impl_->syncJoints();  // before its params change in its slot
  Joint& joint = impl_->joints.items[id.index];
  JointDef& def = impl_->jointDefs[id.index];
  def.enableMotor = joint.params.enableMotor = enable;
  def.motorSpeed = joint.params.motorSpeed = speed;
  def.maxMotorTorque = joint.params.maxMotorTorque = maxForceOrTorque;
  impl_->wakeBody(impl_->bodies.items[joint.bodyA]);
  impl_->wakeBody(impl_->bodies.items[joint.bodyB]);
  return true;
}

// --- read-outs ---

double World::time() const { return impl_->time; }
uint64_t World::stepCount() const { return impl_->steps; }
void World::setProfiling(bool on) { impl_->profiling = on; }
bool World::profiling() const { return impl_->profiling; }
const StepProfile& World::profile() const { return impl_->profile; }

namespace {
bool touching(const Contact& contact, int point, double linearSlop) {
  return contact.manifold.points[point].separation <= linearSlop ||
         contact.normalImpulse[point] > 0.0;
}
}  // namespace

std::vector<ContactInfo> World::contacts() const {
  std::vector<ContactInfo> out;
  for (const Contact& contact : impl_->contacts) {
    if (WorldImpl::isDead(contact)) continue;
    for (int i = 0; i < contact.manifold.pointCount; ++i) {
      if (!touching(contact, i, impl_->def.linearSlop)) continue;
      ContactInfo info;
      info.bodyA = impl_->bodies.items[contact.bodyA].id;
      info.bodyB = impl_->bodies.items[contact.bodyB].id;
      info.point = contact.manifold.points[i].point;
      info.normal = contact.manifold.normal;
      info.separation = contact.manifold.points[i].separation;
      info.normalImpulse = contact.normalImpulse[i];
      info.tangentImpulse = contact.tangentImpulse[i];
      out.push_back(info);
    }
  }
  return out;
}

size_t World::contactCount() const {
  size_t count = 0;
  for (const Contact& contact : impl_->contacts) {
    if (WorldImpl::isDead(contact)) continue;
    for (int i = 0; i < contact.manifold.pointCount; ++i) {
      count += touching(contact, i, impl_->def.linearSlop) ? 1 : 0;
    }
  }
  return count;
}

uint64_t World::hash() const {
  uint64_t h = 14695981039346656037ull;  // FNV-1a offset basis
  auto mix = [&h](const void* data, size_t size) {
    const unsigned char* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) {
      h ^= bytes[i];
      h *= 1099511628211ull;  // FNV prime
    }
  };
  for (size_t i = 0; i < impl_->bodies.items.size(); ++i) {
    if (!impl_->bodies.alive[i]) continue;
    const Body& b = impl_->bodies.items[i];
    const double state[6] = {b.xf.p.x(),           b.xf.p.y(),           b.angle,
                             b.linearVelocity.x(), b.linearVelocity.y(), b.angularVelocity};
    mix(&i, sizeof(i));
    mix(state, sizeof(state));
  }
  return h;
}

}  // namespace impulse2d
