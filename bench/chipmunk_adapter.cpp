// Chipmunk 7 (double precision) building the same scenes. Chipmunk multiplies the two shapes'
// friction and elasticity where Box2D and impulse2d take the geometric mean and the maximum, so
// each shape gets sqrt(mu) (exact) and sqrt(e) (exact between equal values); joints are told not to
// collide their bodies (Chipmunk's default is to collide them). Capsules and rounded polygons are
// native (segment and polygon radii); revolute limits, motors and springs are extra constraints.
#include <chipmunk/chipmunk.h>

#include <cmath>
#include <unordered_set>

#include "engine_adapter.hpp"

namespace impulse2d_bench {
namespace {

cpVect toCp(const Vec2& v) { return cpv(v.x(), v.y()); }

// Per-body linear damping (Chipmunk has only the space's): the body's user data is its rate.
void dampedVelocity(cpBody* body, cpVect gravity, cpFloat damping, cpFloat dt) {
  const double rate = *static_cast<const double*>(cpBodyGetUserData(body));
  cpBodyUpdateVelocity(body, gravity, damping * std::exp(-rate * dt), dt);
}

class ChipmunkAdapter : public GroupedAdapter<cpBody*> {
 public:
  ~ChipmunkAdapter() override { release(); }

  void build(const SceneSpec& scene, const EngineSettings& settings) override {
    release();
    startScene(scene, nullptr);
    timeStep_ = settings.timeStep;
    space_ = cpSpaceNew();
    cpSpaceSetGravity(space_, toCp(scene.gravity));
    cpSpaceSetIterations(space_, settings.velocityIterations);
    if (scene.sleep) cpSpaceSetSleepTimeThreshold(space_, 0.5);  // as Box2D and impulse2d
    // "default" keeps Chipmunk's own slop (0.1) and bias; "slop5mm" uses the other engines' slop.
    if (settings.solver == "slop5mm") cpSpaceSetCollisionSlop(space_, 0.005);
    shapes_.assign(scene.bodies.size(), {});
    constraints_.assign(scene.joints.size(), {});
    damping_.assign(scene.bodies.size(), 0.0);
    createGroup(-1);
  }
  void step() override { cpSpaceStep(space_, timeStep_); }
  Vec2 position(int body) const override {
    const cpVect p = cpBodyGetPosition(bodies_[body]);
    return Vec2(p.x, p.y);
  }
  void setVelocity(int body, const Vec2& velocity) override {
    cpBodySetVelocity(bodies_[body], toCp(velocity));
  }
  void read(std::vector<BodyState>* states) const override {
    states->resize(bodies_.size());
    for (size_t i = 0; i < bodies_.size(); ++i) {
      const cpBody* b = bodies_[i];
      if (b == nullptr) {
        (*states)[i].alive = false;
        continue;
      }
      const cpVect p = cpBodyGetPosition(b), v = cpBodyGetVelocity(b);
      (*states)[i] = {Vec2(p.x, p.y), cpBodyGetAngle(b), Vec2(v.x, v.y),
                      cpBodyGetAngularVelocity(b), true};
    }
  }
  size_t contactCount() const override {
    struct Count {
      std::unordered_set<cpArbiter*> seen;
      size_t points = 0;
    } count;
    for (cpBody* b : bodies_) {
      if (b == nullptr) continue;
      cpBodyEachArbiter(
          b,
          [](cpBody*, cpArbiter* arbiter, void* data) {
            Count& c = *static_cast<Count*>(data);
            if (c.seen.insert(arbiter).second) c.points += cpArbiterGetCount(arbiter);
          },
          &count);
    }
    return count.points;
  }

 private:
  cpBody* createBody(int index) override {
    const BenchBody& body = scene_->bodies[index];
    cpBody* b = nullptr;
    if (body.isStatic) {
      b = cpBodyNewStatic();
    } else if (body.isKinematic) {
      b = cpBodyNewKinematic();
      cpBodySetVelocity(b, toCp(body.velocity));
      cpBodySetAngularVelocity(b, body.angularVelocity);
    } else {
      double mass = 0.0, inertia = 0.0;
      nominalMass(body, &mass, &inertia);
      b = cpBodyNew(mass, inertia);
      cpBodySetVelocity(b, toCp(body.velocity));
      if (body.linearDamping > 0.0) {
        damping_[index] = body.linearDamping;
        cpBodySetUserData(b, &damping_[index]);
        cpBodySetVelocityUpdateFunc(b, dampedVelocity);
      }
    }
    cpBodySetPosition(b, toCp(body.position));
    cpBodySetAngle(b, body.angle);
    cpSpaceAddBody(space_, b);
    for (const BenchShape& shape : body.shapes) {
      cpShape* s = makeShape(b, shape);
      cpShapeSetFriction(s, std::sqrt(shape.friction));
      cpShapeSetElasticity(s, std::sqrt(shape.restitution));
      const impulse2d::CollisionFilter& f = shape.filter;
      // Chipmunk's groups never collide within themselves: Box2D's negative groups.
      const cpGroup group = f.groupIndex < 0 ? static_cast<cpGroup>(-f.groupIndex) : CP_NO_GROUP;
      cpShapeSetFilter(s, cpShapeFilterNew(group, static_cast<cpBitmask>(f.categoryBits),
                                           static_cast<cpBitmask>(f.maskBits)));
      cpSpaceAddShape(space_, s);
      shapes_[index].push_back(s);
    }
    if (!body.isDriven() && !body.awake && scene_->sleep) cpBodySleep(b);
    return b;
  }
  void destroyJoint(int index) override {
    for (cpConstraint* c : constraints_[index]) {
      cpSpaceRemoveConstraint(space_, c);
      cpConstraintFree(c);
    }
    constraints_[index].clear();
  }
  void destroyBody(int index) override {
    for (cpShape* s : shapes_[index]) {
      cpSpaceRemoveShape(space_, s);
      cpShapeFree(s);
    }
    shapes_[index].clear();
    cpSpaceRemoveBody(space_, bodies_[index]);
    cpBodyFree(bodies_[index]);
  }
  static cpShape* makeShape(cpBody* b, const BenchShape& shape) {
    switch (shape.kind) {
      case BenchShape::Kind::Box: {
        const Vec2 half = 0.5 * shape.size;
        return cpBoxShapeNew2(b,
                              cpBBNew(shape.center.x() - half.x(), shape.center.y() - half.y(),
                                      shape.center.x() + half.x(), shape.center.y() + half.y()),
                              0.0);
      }
      case BenchShape::Kind::Circle:
        return cpCircleShapeNew(b, shape.radius, toCp(shape.center));
      case BenchShape::Kind::Capsule:
        return cpSegmentShapeNew(b, toCp(shape.vertices[0]), toCp(shape.vertices[1]), shape.radius);
      case BenchShape::Kind::Polygon:
        break;
    }
    std::vector<cpVect> points;
    for (const Vec2& v : shape.vertices) points.push_back(toCp(v));
    return cpPolyShapeNew(b, static_cast<int>(points.size()), points.data(), cpTransformIdentity,
                          shape.radius);
  }
  void createJoint(int index) override {
    const BenchJoint& joint = scene_->joints[index];
    cpBody* a = bodies_[joint.bodyA];
    cpBody* b = bodies_[joint.bodyB];
    std::vector<cpConstraint*>& parts = constraints_[index];
    parts.push_back(cpPivotJointNew(a, b, toCp(joint.anchor)));
    if (joint.enableLimit) {
      parts.push_back(cpRotaryLimitJointNew(a, b, joint.lower + joint.referenceAngle,
                                            joint.upper + joint.referenceAngle));
    }
    if (joint.enableMotor) {
      // cpSimpleMotor drives b.w - a.w to -rate.
      cpConstraint* motor = cpSimpleMotorNew(a, b, -joint.motorSpeed);
      cpConstraintSetMaxForce(motor, joint.maxMotorTorque);
      parts.push_back(motor);
    }
    if (joint.springHertz > 0.0) {
      // Box2D v3's soft spring on the pair's effective inertia: k = I w^2, c = 2 zeta I w.
      double massA = 0.0, inertiaA = 0.0, massB = 0.0, inertiaB = 0.0;
      nominalMass(scene_->bodies[joint.bodyA], &massA, &inertiaA);
      nominalMass(scene_->bodies[joint.bodyB], &massB, &inertiaB);
      const double invSum = (scene_->bodies[joint.bodyA].isDriven() ? 0.0 : 1.0 / inertiaA) +
                            (scene_->bodies[joint.bodyB].isDriven() ? 0.0 : 1.0 / inertiaB);
      const double inertia = 1.0 / invSum, omega = 2.0 * impulse2d::kPi * joint.springHertz;
      parts.push_back(cpDampedRotarySpringNew(a, b, joint.referenceAngle, inertia * omega * omega,
                                              2.0 * joint.springDampingRatio * inertia * omega));
    }
    for (cpConstraint* c : parts) {
      cpConstraintSetCollideBodies(c, cpFalse);
      cpSpaceAddConstraint(space_, c);
    }
  }
  // The space first: removing objects one by one would filter its arbiters each time (quadratic).
  void release() {
    if (space_) cpSpaceFree(space_);
    space_ = nullptr;
    for (auto& parts : constraints_) {
      for (cpConstraint* c : parts) cpConstraintFree(c);
    }
    for (auto& shapes : shapes_) {
      for (cpShape* s : shapes) cpShapeFree(s);
    }
    for (cpBody* b : bodies_) {
      if (b) cpBodyFree(b);
    }
    constraints_.clear();
    shapes_.clear();
    bodies_.clear();
  }

  double timeStep_ = 1.0 / 60.0;
  cpSpace* space_ = nullptr;
  std::vector<std::vector<cpShape*>> shapes_;            // per scene body
  std::vector<std::vector<cpConstraint*>> constraints_;  // per scene joint
  std::vector<double> damping_;                          // per scene body, read by dampedVelocity
};

}  // namespace

EngineInfo chipmunkEngine() {
  EngineInfo info;
  info.name = "chipmunk";
  info.solvers = {"default", "slop5mm"};
  info.hasPositionIterations = false;
  info.defaults.solver = "default";
  info.defaults.velocityIterations = 10;  // cpSpace's default iterations
  info.defaults.positionIterations = 0;
  info.make = [] { return std::make_unique<ChipmunkAdapter>(); };
  info.refuses = [](const SceneSpec& scene, const EngineSettings& settings) -> std::string {
    for (const BenchBody& body : scene.bodies) {
      for (const BenchShape& shape : body.shapes) {
        if (shape.filter.groupIndex > 0)
          return "Chipmunk has no always-colliding (positive) groups";
        if (shape.filter.categoryBits > 0xFFFFFFFFu) return "Chipmunk's categories have 32 bits";
      }
    }
    return singleThreadOnly("Chipmunk", settings);
  };
  return info;
}

}  // namespace impulse2d_bench
