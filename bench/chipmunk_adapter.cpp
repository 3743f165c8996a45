// Chipmunk 7 (double precision) building the same scenes. Chipmunk multiplies the two shapes'
// friction where Box2D and impulse2d take the geometric mean, so each shape gets sqrt(mu); joints
// are told not to collide their bodies (Chipmunk's default is to collide them).
#include <chipmunk/chipmunk.h>

#include <cmath>
#include <unordered_set>

#include "engine_adapter.hpp"

namespace impulse2d_bench {
namespace {

cpVect toCp(const Vec2& v) { return cpv(v.x(), v.y()); }

class ChipmunkAdapter : public EngineAdapter {
 public:
  ~ChipmunkAdapter() override { release(); }

  void build(const SceneSpec& scene, const EngineSettings& settings) override {
    release();
    timeStep_ = settings.timeStep;
    space_ = cpSpaceNew();
    cpSpaceSetGravity(space_, cpv(0.0, -9.81));
    cpSpaceSetIterations(space_, settings.velocityIterations);
    // "default" keeps Chipmunk's own slop (0.1) and bias; "slop5mm" uses the other engines' slop.
    if (settings.solver == "slop5mm") cpSpaceSetCollisionSlop(space_, 0.005);
    for (const BenchBody& body : scene.bodies) {
      cpBody* b = nullptr;
      if (body.isStatic) {
        b = cpBodyNewStatic();
      } else {
        double mass = 0.0, inertia = 0.0;
        nominalMass(body.shape, &mass, &inertia);
        b = cpBodyNew(mass, inertia);
      }
      cpBodySetPosition(b, toCp(body.position));
      cpBodySetAngle(b, body.angle);
      cpSpaceAddBody(space_, b);
      cpShape* shape = nullptr;
      switch (body.shape.kind) {
        case BenchShape::Kind::Box:
          shape = cpBoxShapeNew(b, body.shape.size.x(), body.shape.size.y(), 0.0);
          break;
        case BenchShape::Kind::Circle:
          shape = cpCircleShapeNew(b, body.shape.radius, cpvzero);
          break;
        case BenchShape::Kind::Polygon: {
          std::vector<cpVect> points;
          for (const Vec2& v : body.shape.vertices) points.push_back(toCp(v));
          shape = cpPolyShapeNew(b, static_cast<int>(points.size()), points.data(),
                                 cpTransformIdentity, 0.0);
          break;
        }
      }
      cpShapeSetFriction(shape, std::sqrt(body.shape.friction));
      cpSpaceAddShape(space_, shape);
      bodies_.push_back(b);
      shapes_.push_back(shape);
    }
    for (const BenchJoint& joint : scene.joints) {
      cpConstraint* c =
          cpPivotJointNew(bodies_[joint.bodyA], bodies_[joint.bodyB], toCp(joint.anchor));
      cpConstraintSetCollideBodies(c, cpFalse);
      cpSpaceAddConstraint(space_, c);
      constraints_.push_back(c);
    }
  }
  void step() override { cpSpaceStep(space_, timeStep_); }
  void read(std::vector<BodyState>* states) const override {
    states->resize(bodies_.size());
    for (size_t i = 0; i < bodies_.size(); ++i) {
      const cpBody* b = bodies_[i];
      const cpVect p = cpBodyGetPosition(b), v = cpBodyGetVelocity(b);
      (*states)[i] = {Vec2(p.x, p.y), cpBodyGetAngle(b), Vec2(v.x, v.y),
                      cpBodyGetAngularVelocity(b)};
    }
  }
  size_t contactCount() const override {
    struct Count {
      std::unordered_set<cpArbiter*> seen;
      size_t points = 0;
    } count;
    for (cpBody* b : bodies_) {
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
  // The space first: removing objects one by one would filter its arbiters each time (quadratic).
  void release() {
    if (space_) cpSpaceFree(space_);
    space_ = nullptr;
    for (cpConstraint* c : constraints_) cpConstraintFree(c);
    for (cpShape* s : shapes_) cpShapeFree(s);
    for (cpBody* b : bodies_) cpBodyFree(b);
    constraints_.clear();
    shapes_.clear();
    bodies_.clear();
  }

  double timeStep_ = 1.0 / 60.0;
  cpSpace* space_ = nullptr;
  std::vector<cpBody*> bodies_;
  std::vector<cpShape*> shapes_;
  std::vector<cpConstraint*> constraints_;
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
  return info;
}

}  // namespace impulse2d_bench
