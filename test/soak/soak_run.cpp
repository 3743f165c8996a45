#include "soak_run.hpp"

#include <impulse2d/world.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <sstream>

namespace impulse2d {
namespace soak {
namespace {

constexpr double kHalfWidth = 10.0;  // m, the arena's inside: x in [-10, 10]
constexpr double kHeight = 20.0;     // m, y in [0, 20]
constexpr double kWall = 2.0;        // m, thickness of the four static walls
// m a centre of mass may sink into a wall before it counts as gone through: half the wall. (A
// rigid assembly wider than the arena, welded together by a user, jams between two walls and
// sinks into both; only getting past the middle of one is leaving.)
constexpr double kArenaSlack = 0.5 * kWall;
constexpr size_t kMaxOwnBodies = 160;
constexpr size_t kMaxOwnJoints = 140;
constexpr size_t kEditsKept = 24;
// JointType's order, for --watch.
constexpr const char* kJointTypeNames[] = {"revolute", "prismatic", "weld", "distance"};
// Kinematic bodies are driven around the middle, far enough from the walls that they cannot
// squeeze a dynamic body into one.
constexpr double kKinematicHalfWidth = 6.0, kKinematicLow = 4.0, kKinematicHigh = 16.0;

struct Wrench {
  BodyId body;
  Vec2 force = Vec2::Zero();
  Vec2 localPoint = Vec2::Zero();  // where it pushes, in the body's frame (wrenchesAtPoints)
  double torque = 0.0;
  int stepsLeft = 0;
};

class Soak {
 public:
  explicit Soak(const Options& options) : options_(options), random_(options.seed) {
    WorldDef def;
    def.solver = options.solver;
    def.threads = options.threads;
    def.gravity = options.gravity ? Vec2(0.0, -9.81) : Vec2::Zero();
    world_.settings() = def;
    addWall("ground", Vec2(0.0, -0.5 * kWall), Vec2(2 * kHalfWidth + 2 * kWall, kWall));
    addWall("ceiling", Vec2(0.0, kHeight + 0.5 * kWall), Vec2(2 * kHalfWidth + 2 * kWall, kWall));
    addWall("left", Vec2(-kHalfWidth - 0.5 * kWall, 0.5 * kHeight), Vec2(kWall, kHeight));
    addWall("right", Vec2(kHalfWidth + 0.5 * kWall, 0.5 * kHeight), Vec2(kWall, kHeight));
  }

  Report run() {
    for (int step = 0; step < options_.steps && report_.violations.empty(); ++step) {
      const int edits = uniformInt(0, 3);
      for (int k = 0; k < edits; ++k) edit();
      applyWrenches();
      steerKinematic();
      stepAndCheck();
    }
    if (report_.violations.empty()) quietPhase();
    return report_;
  }

 private:
  // --- random numbers ---
  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(random_);
  }
  int uniformInt(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(random_); }
  bool chance(double p) { return uniform(0.0, 1.0) < p; }
  Vec2 insideArena(double margin) {
    return Vec2(uniform(-kHalfWidth + margin, kHalfWidth - margin),
                uniform(margin, kHeight - margin));
  }

  void addWall(const char* name, const Vec2& center, const Vec2& size) {
    BodyDef def;
    def.name = name;
    def.type = BodyType::Static;
    def.position = center;
    ShapeDef box;
    box.size = size;
    def.shapes.push_back(box);
    world_.createBody(def);
  }

  void log(const std::string& text) {
    ++report_.edits;
    report_.lastEdits.push_back("step " + std::to_string(world_.stepCount()) + ": " + text);
    if (report_.lastEdits.size() > kEditsKept) report_.lastEdits.pop_front();
  }
  static std::string str(const Vec2& v) {
    char text[64];
    std::snprintf(text, sizeof(text), "[%.4g, %.4g]", v.x(), v.y());
    return text;
  }
  void violation(const std::string& text) {
    if (report_.violations.size() < 16) {
      report_.violations.push_back("step " + std::to_string(world_.stepCount()) + ": " + text);
    }
  }
  std::string nameOf(BodyId id) const { return world_.isValid(id) ? world_.body(id).name : "?"; }

  BodyId randomBody() {
    if (bodies_.empty()) return BodyId();
    auto it = bodies_.begin();
    std::advance(it, uniformInt(0, static_cast<int>(bodies_.size()) - 1));
    return it->second;
  }

  // --- edits ---
  void edit() {
    const double pick = uniform(0.0, 1.0);
    if (pick < 0.30)
      spawn();
    else if (pick < 0.40)
      destroySome();
    else if (pick < 0.62)
      join();
    else if (pick < 0.68)
      unjoin();
    else if (pick < 0.76)
      teleport();
    else if (pick < 0.84)
      push();
    else if (pick < 0.89)
      driveKinematic();
    else if (pick < 0.91)
      toggleSleep();
    else if (pick < 0.93)
      setMotor();
    else
      badRequest();
  }

  ShapeDef randomShape() {
    ShapeDef shape;
    const int kind = uniformInt(0, 2);
    if (kind == 0) {
      shape.kind = ShapeKind::Box;
      shape.size = Vec2(uniform(0.1, 1.2), uniform(0.1, 1.2));
    } else if (kind == 1) {
      shape.kind = ShapeKind::Circle;
      shape.radius = uniform(0.05, 0.6);
    } else {
      shape.kind = ShapeKind::Polygon;
      const int n = uniformInt(3, 8);
      const double r = uniform(0.1, 0.7);
      for (int i = 0; i < n; ++i) {
        const double a = 2.0 * kPi * (i + uniform(0.0, 0.4)) / n;
        shape.vertices.push_back(Vec2(r * std::cos(a), r * std::sin(a)));
      }
    }
    if (chance(0.5)) shape.density = chance(0.2) ? 0.1 : uniform(0.2, 5.0);
    if (chance(0.5)) shape.friction = uniform(0.0, 1.0);
    if (chance(0.3)) shape.restitution = uniform(0.0, 0.9);
    return shape;
  }

  void spawn() {
    if (bodies_.size() >= kMaxOwnBodies) return destroySome();
    BodyDef def;
    def.name = "b" + std::to_string(nextName_++);
    def.type = chance(0.2) ? BodyType::Kinematic : BodyType::Dynamic;
    def.position = def.type == BodyType::Kinematic
                       ? Vec2(uniform(-kKinematicHalfWidth, kKinematicHalfWidth),
                              uniform(kKinematicLow, kKinematicHigh))
                       : insideArena(1.0);
    def.angle = uniform(-kPi, kPi);
    def.linearVelocity = Vec2(uniform(-5.0, 5.0), uniform(-5.0, 5.0));
    def.angularVelocity = uniform(-3.0, 3.0);
    def.bullet = chance(0.1);
    def.awake = !chance(0.1);
    def.shapes.push_back(randomShape());
    if (def.type == BodyType::Dynamic && chance(0.15)) {
      ShapeDef second = randomShape();
      second.offset = Vec2(uniform(-0.5, 0.5), uniform(-0.5, 0.5));
      def.shapes.push_back(second);
    }
    std::string error;
    const BodyId id = world_.createBody(def, &error);
    log("spawn " + def.name + (def.type == BodyType::Kinematic ? " kinematic" : "") + " at " +
        str(def.position));
    if (!id.valid()) return violation("a valid spawn was refused: " + error);
    bodies_[def.name] = id;
  }

  void destroySome() {
    const BodyId id = randomBody();
    if (!id.valid()) return;
    const std::string name = nameOf(id);
    log("delete " + name);
    if (!world_.destroyBody(id)) violation("deleting " + name + " failed");
    bodies_.erase(name);
    for (auto it = joints_.begin(); it != joints_.end();) {
      it = world_.isValid(*it) ? std::next(it) : joints_.erase(it);
    }
  }

  void join() {
    if (joints_.size() >= kMaxOwnJoints || bodies_.size() < 2) return unjoin();
    JointDef def;
    def.bodyA = randomBody();
    def.bodyB = randomBody();
    if (def.bodyA == def.bodyB) return;
    def.type = static_cast<JointType>(uniformInt(0, 3));
    def.anchor = insideArena(0.0);
    def.collideConnected = chance(0.3);
    if (def.type == JointType::Prismatic) {
      const double a = uniform(-kPi, kPi);
      def.axis = Vec2(std::cos(a), std::sin(a));
    }
    if ((def.type == JointType::Revolute || def.type == JointType::Prismatic) && chance(0.3)) {
      def.enableLimit = true;
      def.lower = uniform(-1.0, 0.0);
      def.upper = uniform(0.0, 1.0);
    }
    if ((def.type == JointType::Revolute || def.type == JointType::Prismatic) && chance(0.2)) {
      def.enableMotor = true;
      def.motorSpeed = uniform(-5.0, 5.0);
      def.maxMotorTorque = uniform(0.0, 100.0);
    }
    if (def.type == JointType::Distance) {
      def.length = uniform(0.2, 3.0);
      def.useAnchorB = chance(0.5);
      def.anchorB = insideArena(0.0);
      if ((def.anchorB - def.anchor).norm() < 0.01) def.useAnchorB = false;
    }
    if ((def.type == JointType::Distance || def.type == JointType::Weld) && chance(0.3)) {
      def.frequency = uniform(0.5, 10.0);
      def.dampingRatio = uniform(0.0, 1.0);
    }
    std::string error;
    const JointId id = world_.createJoint(def, &error);
    const char* types[] = {"revolute", "prismatic", "weld", "distance"};
    log(std::string("joint ") + types[static_cast<int>(def.type)] + " " + nameOf(def.bodyA) + "-" +
        nameOf(def.bodyB) + " at " + str(def.anchor));
    const bool bothStill = world_.body(def.bodyA).type != BodyType::Dynamic &&
                           world_.body(def.bodyB).type != BodyType::Dynamic;
    if (id.valid()) {
      joints_.push_back(id);
    } else if (!bothStill) {
      violation("a valid joint was refused: " + error);
    }
  }

  void unjoin() {
    if (joints_.empty()) return;
    const size_t k = static_cast<size_t>(uniformInt(0, static_cast<int>(joints_.size()) - 1));
    log("delete joint " + std::to_string(joints_[k].index));
    if (!world_.destroyJoint(joints_[k])) violation("deleting a joint failed");
    joints_.erase(joints_.begin() + static_cast<long>(k));
  }

  void teleport() {
    const BodyId id = randomBody();
    if (!id.valid() || world_.body(id).type != BodyType::Dynamic) return;
    const Vec2 to = insideArena(1.0);
    const Vec2 v(uniform(-5.0, 5.0), uniform(-5.0, 5.0));
    log("teleport " + nameOf(id) + " to " + str(to) + " at " + str(v));
    const Vec2 from = world_.body(id).xf.p;
    const double fromAngle = world_.body(id).angle;
    if (!world_.setTransform(id, to, uniform(-kPi, kPi)) ||
        !world_.setVelocity(id, v, uniform(-5.0, 5.0))) {
      violation("a valid teleport was refused");
    }
    // The bodies welded to it came along: a user keeps them inside the walls too.
    for (const BodyId other : weldedGroup(id)) {
      const Vec2 c = world_.body(other).center;
      if (std::abs(c.x()) > kHalfWidth - 0.5 || c.y() < 0.5 || c.y() > kHeight - 0.5) {
        log("teleport undone: " + nameOf(other) + " would be in a wall");
        world_.setTransform(id, from, fromAngle);
        break;
      }
    }
  }

  void push() {
    const BodyId id = randomBody();
    if (!id.valid() || world_.body(id).type != BodyType::Dynamic) return;
    Wrench w;
    w.body = id;
    const double a = uniform(-kPi, kPi), f = uniform(0.0, 200.0);
    w.force = Vec2(f * std::cos(a), f * std::sin(a));
    w.torque = uniform(-20.0, 20.0);
    const Body& body = world_.body(id);
    const Vec2 offset(uniform(-0.5, 0.5), uniform(-0.5, 0.5));  // drawn either way: same paths
    w.localPoint =
        options_.wrenchesAtPoints ? body.xf.applyInverse(body.center + offset) : body.localCenter;
    w.stepsLeft = uniformInt(1, static_cast<int>(0.5 / world_.settings().timeStep));
    log("wrench " + nameOf(id) + " " + str(w.force) + " for " + std::to_string(w.stepsLeft));
    wrenches_.push_back(w);
  }

  // Kinematic bodies outside their box head back to the middle, every step: a user's conveyor
  // or paddle stays in the arena.
  void steerKinematic() {
    const Vec2 home(0.0, 0.5 * (kKinematicLow + kKinematicHigh));
    for (const auto& [name, id] : bodies_) {
      const Body& body = world_.body(id);
      if (body.type != BodyType::Kinematic) continue;
      const bool out = std::abs(body.center.x()) > kKinematicHalfWidth ||
                       body.center.y() < kKinematicLow || body.center.y() > kKinematicHigh;
      const Vec2 back = 2.0 * (home - body.center).normalized();
      if (out && body.linearVelocity.dot(back) <= 0.0) {
        world_.setVelocity(id, back, body.angularVelocity);
      }
    }
  }

  void applyWrenches() {
    for (Wrench& w : wrenches_) {
      if (!world_.isValid(w.body)) w.stepsLeft = 0;
      if (w.stepsLeft-- <= 0) continue;
      const Vec2 point = world_.body(w.body).xf.apply(w.localPoint);
      if (!world_.applyForce(w.body, w.force, point) || !world_.applyTorque(w.body, w.torque)) {
        violation("a valid wrench was refused");
      }
    }
    wrenches_.erase(std::remove_if(wrenches_.begin(), wrenches_.end(),
                                   [](const Wrench& w) { return w.stepsLeft <= 0; }),
                    wrenches_.end());
  }

  void driveKinematic() {
    for (const auto& [name, id] : bodies_) {
      const Body& body = world_.body(id);
      if (body.type != BodyType::Kinematic) continue;
      // Head back to the middle when out of its box, else anywhere.
      const Vec2 home(0.0, 0.5 * (kKinematicLow + kKinematicHigh));
      const bool out = std::abs(body.center.x()) > kKinematicHalfWidth ||
                       body.center.y() < kKinematicLow || body.center.y() > kKinematicHigh;
      Vec2 v(uniform(-2.0, 2.0), uniform(-2.0, 2.0));
      if (out) v = 2.0 * (home - body.center).normalized();
      world_.setVelocity(id, v, uniform(-2.0, 2.0));
    }
    log("drive the kinematic bodies");
  }

  void toggleSleep() {
    world_.settings().enableSleep = !world_.settings().enableSleep;
    log(std::string("sleep ") + (world_.settings().enableSleep ? "on" : "off"));
  }

  void setMotor() {
    if (joints_.empty()) return;
    const JointId id =
        joints_[static_cast<size_t>(uniformInt(0, static_cast<int>(joints_.size()) - 1))];
    const JointType type = world_.jointDef(id).type;
    if (type != JointType::Revolute && type != JointType::Prismatic) return;
    log("motor on joint " + std::to_string(id.index));
    world_.setJointMotor(id, chance(0.7), uniform(-5.0, 5.0), uniform(0.0, 100.0));
  }

  // Each must be refused and leave the world as it was.
  void badRequest() {
    const size_t bodies = world_.bodyCount(), joints = world_.jointCount();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    const BodyId some = randomBody();
    bool refused = true;
    const int kind = uniformInt(0, 5);
    BodyDef body;
    body.shapes.push_back(randomShape());
    JointDef joint;
    switch (kind) {
      case 0:
        body.position = Vec2(nan, 1.0);
        refused = !world_.createBody(body).valid();
        break;
      case 1:
        body.shapes[0] = ShapeDef();
        body.shapes[0].size = Vec2(-1.0, 0.5);
        refused = !world_.createBody(body).valid();
        break;
      case 2:
        if (!some.valid()) return;
        body.name = nameOf(some);  // duplicate
        refused = !world_.createBody(body).valid();
        break;
      case 3:
        joint.bodyA = BodyId{100000, 0};
        joint.bodyB = some;
        refused = !world_.createJoint(joint).valid();
        break;
      case 4:
        if (!some.valid()) return;
        refused = !world_.applyForce(some, Vec2(inf, 0.0), Vec2::Zero());
        break;
      case 5:
        if (!some.valid()) return;
        refused = !world_.setTransform(some, Vec2(0.0, nan), 0.0);
        break;
    }
    log("bad request " + std::to_string(kind));
    if (!refused) violation("bad request " + std::to_string(kind) + " was accepted");
    if (world_.bodyCount() != bodies || world_.jointCount() != joints) {
      violation("bad request " + std::to_string(kind) + " changed the world");
    }
    ++report_.badRefused;
  }

  // --- invariants ---
  // The bodies that a kinematic body can carry: jointed to one, directly or through others, or
  // touching one.
  std::set<int> carriedByKinematic() {
    std::map<int, std::vector<int>> links;
    for (const JointId id : joints_) {
      const JointDef& def = world_.jointDef(id);
      links[def.bodyA.index].push_back(def.bodyB.index);
      links[def.bodyB.index].push_back(def.bodyA.index);
    }
    std::set<int> carried;
    std::vector<int> todo;
    for (const auto& [name, id] : bodies_) {
      if (world_.body(id).type == BodyType::Kinematic) todo.push_back(id.index);
    }
    for (const ContactInfo& c : world_.contacts()) {
      const bool kinA = world_.body(c.bodyA).type == BodyType::Kinematic;
      const bool kinB = world_.body(c.bodyB).type == BodyType::Kinematic;
      if (kinA) todo.push_back(c.bodyB.index);
      if (kinB) todo.push_back(c.bodyA.index);
    }
    while (!todo.empty()) {
      const int slot = todo.back();
      todo.pop_back();
      if (!carried.insert(slot).second) continue;
      for (const int other : links[slot]) todo.push_back(other);
    }
    return carried;
  }

  // The dynamic bodies rigidly welded to `id`, itself included.
  std::vector<BodyId> weldedGroup(BodyId id) const {
    std::vector<BodyId> group{id};
    for (size_t k = 0; k < group.size(); ++k) {
      for (const JointId j : joints_) {
        const JointDef& def = world_.jointDef(j);
        if (def.type != JointType::Weld || def.frequency > 0.0) continue;
        BodyId other;
        if (def.bodyA == group[k]) other = def.bodyB;
        if (def.bodyB == group[k]) other = def.bodyA;
        if (!other.valid() || world_.body(other).type != BodyType::Dynamic) continue;
        if (std::find(group.begin(), group.end(), other) == group.end()) group.push_back(other);
      }
    }
    return group;
  }

  // The velocity of the centre of mass of the bodies rigidly welded to `id` (itself included).
  Vec2 weldedGroupVelocity(BodyId id) const {
    const std::vector<BodyId> group = weldedGroup(id);
    if (group.size() == 1) return world_.body(id).linearVelocity;
    Vec2 momentum = Vec2::Zero();
    double mass = 0.0;
    for (const BodyId b : group) {
      momentum += world_.body(b).mass * world_.body(b).linearVelocity;
      mass += world_.body(b).mass;
    }
    return momentum / mass;
  }

  void stepAndCheck() {
    world_.step();
    if (!options_.watch.empty()) {
      const char* watch = options_.watch.c_str();
      auto it = bodies_.find(options_.watch);
      if (it != bodies_.end() && world_.isValid(it->second)) {
        const Body& b = world_.body(it->second);
        fprintf(stderr, "W %llu %s at %s a %g v %s w %g ext %g %g\n",
                (unsigned long long)world_.stepCount(), watch, str(b.center).c_str(), b.angle,
                str(b.linearVelocity).c_str(), b.angularVelocity, b.minExtent, b.maxExtent);
        for (const JointId j : joints_) {
          const JointDef& d = world_.jointDef(j);
          if (d.bodyA != it->second && d.bodyB != it->second) continue;
          const BodyId other = d.bodyA == it->second ? d.bodyB : d.bodyA;
          const JointState js = world_.jointState(j);
          fprintf(stderr,
                  "     joint %d %s to %s (%s, mass %g) at %s f %g length %g anchors %s %s\n",
                  j.index, kJointTypeNames[static_cast<int>(d.type)], nameOf(other).c_str(),
                  world_.body(other).type == BodyType::Kinematic ? "kinematic" : "dynamic",
                  world_.body(other).mass, str(world_.body(other).center).c_str(), d.frequency,
                  d.length, str(js.anchorA).c_str(), str(js.anchorB).c_str());
        }
        for (const ContactInfo& c : world_.contacts())
          if ((c.bodyA == it->second || c.bodyB == it->second))
            fprintf(stderr, "     contact %s-%s n %s sep %g imp %g\n",
                    world_.body(c.bodyA).name.c_str(), world_.body(c.bodyB).name.c_str(),
                    str(c.normal).c_str(), c.separation, c.normalImpulse);
      }
    }
    ++report_.steps;
    report_.maxBodies = std::max(report_.maxBodies, bodies_.size());
    report_.maxJoints = std::max(report_.maxJoints, joints_.size());
    for (const RemovedBody& r : world_.takeRemovedBodies()) {
      violation("the world removed " + r.name + ": " + r.reason);
    }
    for (const LostBody& lost : world_.takeLostBodies()) {
      violation(lost.name + " was found lost for good, at " + str(lost.position) + ": " +
                lost.reason);
    }
    const WorldDef& def = world_.settings();
    const int substeps = usesSubsteps(def.solver) ? std::max(1, def.velocityIterations) : 1;
    const double maxTurnRate = def.maxRotation * substeps / def.timeStep;
    std::set<int> carried;
    bool carriedKnown = false;
    for (const auto& [name, id] : bodies_) {
      report_.checks += 4;
      if (!world_.isValid(id)) {
        violation(name + " is gone though it was never deleted");
        continue;
      }
      const Body& b = world_.body(id);
      if (!isFinite(b.center) || !isFinite(b.linearVelocity) || !std::isfinite(b.angle) ||
          !std::isfinite(b.angularVelocity)) {
        violation(name + ": its state is not finite");
        continue;
      }
      if (b.type != BodyType::Dynamic) continue;
      // Rigidly welded bodies move as one: the limit holds for their common centre of mass
      // (a member far from it turns with it faster).
      const Vec2 v = weldedGroupVelocity(id);
      if (v.norm() > def.maxLinearSpeed * (1.0 + 1e-9)) {
        violation(name + " moves at " + std::to_string(v.norm()) + " m/s");
      }
      if (std::abs(b.angularVelocity) > maxTurnRate * (1.0 + 1e-9)) {
        violation(name + " turns at " + std::to_string(b.angularVelocity) + " rad/s");
      }
      const bool inside = std::abs(b.center.x()) <= kHalfWidth + kArenaSlack &&
                          b.center.y() >= -kArenaSlack && b.center.y() <= kHeight + kArenaSlack;
      if (!inside) {
        if (!carriedKnown) carried = carriedByKinematic(), carriedKnown = true;
        // Carried out by a kinematic body: the user's doing, excused from then on.
        if (carried.count(id.index)) carriedOut_.insert(name);
        if (!carriedOut_.count(name)) violation(name + " left the arena, at " + str(b.center));
      }
    }
  }

  // --- the quiet phase: nothing does work on the world ---
  double energy() const {
    double e = 0.0;
    const Vec2 g = world_.settings().gravity;
    for (const auto& [name, id] : bodies_) {
      const Body& b = world_.body(id);
      if (b.type != BodyType::Dynamic) continue;
      e += 0.5 * b.mass * b.linearVelocity.squaredNorm() +
           0.5 * b.inertia * b.angularVelocity * b.angularVelocity - b.mass * g.dot(b.center);
    }
    return e;
  }

  // An upper bound on what the springs hold: 0.5 k x^2 with k = m w^2 on each spring's row, m at
  // most the reduced mass (distance) or the angle row's own mass (weld).
  // The inverse mass and inverse inertia (about its centre of mass) of the rigid body that
  // `id` is part of: itself with what is rigidly welded to it, as the solver moves it.
  std::pair<double, double> inverseMassOf(BodyId id) const {
    if (world_.body(id).type != BodyType::Dynamic) return {0.0, 0.0};
    const std::vector<BodyId> group = weldedGroup(id);
    double mass = 0.0, inertia = 0.0;
    Vec2 center = Vec2::Zero();
    for (const BodyId b : group) {
      mass += world_.body(b).mass;
      center += world_.body(b).mass * world_.body(b).center;
    }
    center /= mass;
    for (const BodyId b : group) {
      const Body& body = world_.body(b);
      inertia += body.inertia + body.mass * (body.center - center).squaredNorm();
    }
    return {1.0 / mass, 1.0 / inertia};
  }

  double springEnergy() const {
    double e = 0.0;
    for (const JointId id : joints_) {
      const JointDef& def = world_.jointDef(id);
      if (def.frequency <= 0.0) continue;
      const auto [invMassA, invInertiaA] = inverseMassOf(def.bodyA);
      const auto [invMassB, invInertiaB] = inverseMassOf(def.bodyB);
      const double w = 2.0 * kPi * def.frequency;
      const JointState s = world_.jointState(id);
      if (def.type == JointType::Distance) {
        const double m = 1.0 / (invMassA + invMassB);
        const double x = s.position - def.length;  // the soak always gives a length
        e += 0.5 * m * w * w * x * x;
      } else {
        const double i = 1.0 / (invInertiaA + invInertiaB);
        const double x = s.position;
        e += 0.5 * i * w * w * x * x;
      }
    }
    return e;
  }

  // The overlaps (m) of each pair of bodies touching in a resting pile with no joint and no
  // kinematic body in it: what a solver must push apart, with nothing holding it together.
  std::map<std::pair<int, int>, double> freeOverlaps() {
    int slots = 0;
    for (const BodyId id : world_.bodies()) slots = std::max(slots, id.index + 1);
    std::vector<int> parent(static_cast<size_t>(slots));
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    std::set<int> held;
    for (const JointId id : joints_) {
      held.insert(world_.jointDef(id).bodyA.index);
      held.insert(world_.jointDef(id).bodyB.index);
    }
    const std::vector<ContactInfo> contacts = world_.contacts();
    for (const ContactInfo& c : contacts) {
      const Body& a = world_.body(c.bodyA);
      const Body& b = world_.body(c.bodyB);
      if (a.type == BodyType::Kinematic) held.insert(c.bodyB.index);
      if (b.type == BodyType::Kinematic) held.insert(c.bodyA.index);
      for (const Body* body : {&a, &b}) {  // moving or spinning: not resting
        const double surfaceSpeed =
            body->linearVelocity.norm() + std::abs(body->angularVelocity) * body->maxExtent;
        if (body->type == BodyType::Dynamic && surfaceSpeed > 0.1) {
          held.insert(body->id.index);
        }
      }
      if (a.type == BodyType::Dynamic && b.type == BodyType::Dynamic) {
        parent[find(c.bodyA.index)] = find(c.bodyB.index);
      }
    }
    std::set<int> heldRoots;
    for (const int slot : held) heldRoots.insert(find(slot));
    std::map<std::pair<int, int>, double> overlaps;
    for (const ContactInfo& c : contacts) {
      const int slot =
          world_.body(c.bodyA).type == BodyType::Dynamic ? c.bodyA.index : c.bodyB.index;
      if (heldRoots.count(find(slot))) continue;
      double& depth = overlaps[{c.bodyA.index, c.bodyB.index}];
      depth = std::max(depth, -c.separation);
    }
    return overlaps;
  }

  void quietPhase() {
    wrenches_.clear();
    for (const JointId id : joints_) {
      const JointDef& def = world_.jointDef(id);
      if (def.type == JointType::Revolute || def.type == JointType::Prismatic) {
        world_.setJointMotor(id, false, 0.0, 0.0);
      }
    }
    for (const auto& [name, id] : bodies_) {
      if (world_.body(id).type == BodyType::Kinematic) world_.setVelocity(id, Vec2::Zero(), 0.0);
    }
    log("quiet: motors off, kinematic bodies stopped");
    // First let spawned overlaps come apart (the position passes lift bodies out of each other,
    // which adds potential energy); then nothing may add energy.
    constexpr int kSettle = 100;
    double reference = 0.0, budget = 0.0, scale = 0.0;
    std::map<std::pair<int, int>, double> early;
    for (int step = 0; step < kQuietSteps && report_.violations.empty(); ++step) {
      stepAndCheck();
      if (step == kSettle) {
        reference = energy();
        budget = springEnergy();
        // 5 % of lifting every body across the arena and of the motion now (Baumgarte's push
        // and the springs' integration add a little).
        for (const auto& [name, id] : bodies_) {
          const Body& b = world_.body(id);
          if (b.type == BodyType::Dynamic) {
            scale += b.mass * (world_.settings().gravity.norm() * kHeight +
                               0.5 * b.linearVelocity.squaredNorm());
          }
        }
        scale += budget;
      }
      if (step > kSettle) {
        ++report_.checks;
        const double e = energy();
        if (e > reference + budget + 0.05 * scale + 1e-6) {
          // The body with the most kinetic energy: where to look.
          std::string most;
          double mostEnergy = -1.0;
          for (const auto& [n, id] : bodies_) {
            const Body& b = world_.body(id);
            const double k = 0.5 * b.mass * b.linearVelocity.squaredNorm() +
                             0.5 * b.inertia * b.angularVelocity * b.angularVelocity;
            if (k > mostEnergy) {
              mostEnergy = k;
              most = n + " at " + str(b.center) + " moving " + str(b.linearVelocity) + " m/s";
            }
          }
          char text[160];
          std::snprintf(text, sizeof(text),
                        "energy grew from %.6g J to %.6g J with nothing doing work (springs held "
                        "at most %.3g J); most kinetic: ",
                        reference, e, budget);
          violation(text + most);
        }
      }
      if (step == kQuietSteps - 101) early = freeOverlaps();
    }
    if (!report_.violations.empty()) return;
    // A pile at rest may not keep a deep overlap: it must be coming apart (by a tenth over the
    // last 100 steps) or be gone.
    constexpr double kDeep = 0.05;  // m, ten slops
    auto nameOf = [&](int slot) {
      for (const auto& [name, id] : bodies_) {
        if (id.index == slot) return name;
      }
      return "slot " + std::to_string(slot);
    };
    for (const auto& [pair, late] : freeOverlaps()) {
      ++report_.checks;
      const auto before = early.find(pair);
      if (late > kDeep && before != early.end() && late > 0.9 * before->second) {
        violation("a resting pile still overlaps by " + std::to_string(late) + " m (" +
                  std::to_string(before->second) + " m 100 steps before), bodies " +
                  nameOf(pair.first) + " and " + nameOf(pair.second));
      }
    }
  }

  Options options_;
  std::mt19937_64 random_;
  World world_;
  Report report_;
  std::map<std::string, BodyId> bodies_;
  std::vector<JointId> joints_;
  std::vector<Wrench> wrenches_;
  std::set<std::string> carriedOut_;  // left the arena carried by a kinematic body
  int nextName_ = 0;
};

}  // namespace

std::string Report::summary(const Options& options) const {
  std::ostringstream out;
  out << "soak seed " << options.seed << " solver " << solverName(options.solver) << " threads "
      << options.threads << (options.gravity ? "" : " top-down")
      << (options.wrenchesAtPoints ? " wrenches-at-points" : "") << ": " << steps << " steps, "
      << edits << " edits (" << badRefused << " bad, refused), up to " << maxBodies
      << " bodies and " << maxJoints << " joints, " << checks << " checks, " << violations.size()
      << " violations";
  if (!violations.empty()) out << "; first: " << violations.front();
  return out.str();
}

Report run(const Options& options) { return Soak(options).run(); }

}  // namespace soak
}  // namespace impulse2d
