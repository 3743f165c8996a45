// Box2D 2.4 (single precision) building the same scenes. Box2D wraps every polygon in a skin of
// b2_polygonRadius (1 cm); the polygons are shrunk by it so that the collision surface is the
// scene's geometry, and masses are set from the scene's geometry so all engines move the same
// bodies. It has no rounded shapes (capsules and rounded polygons become 8-point outlines, its
// b2_maxPolygonVertices) and no revolute spring.
#include <box2d/box2d.h>

#include <cmath>
#include <cstdint>

#include "engine_adapter.hpp"

namespace impulse2d_bench {
namespace {

b2Vec2 toB2(const Vec2& v) { return b2Vec2(static_cast<float>(v.x()), static_cast<float>(v.y())); }

// Every edge of a convex counter-clockwise polygon moved in by `skin`.
std::vector<Vec2> inset(const std::vector<Vec2>& points, double skin) {
  const size_t n = points.size();
  std::vector<Vec2> out;
  for (size_t i = 0; i < n; ++i) {
    const Vec2 in = points[i] - points[(i + n - 1) % n];
    const Vec2 onward = points[(i + 1) % n] - points[i];
    const Vec2 n1 = Vec2(in.y(), -in.x()).normalized(),
               n2 = Vec2(onward.y(), -onward.x()).normalized();
    out.push_back(points[i] - skin * (n1 + n2) / (1.0 + n1.dot(n2)));
  }
  return out;
}

// Box2D 2.4's filter has 16 bits and a 16-bit group.
bool fitsFilter(const impulse2d::CollisionFilter& f) {
  return f.categoryBits <= 0xFFFF && f.groupIndex >= INT16_MIN && f.groupIndex <= INT16_MAX;
}

class Box2dAdapter : public GroupedAdapter<b2Body*> {
 public:
  void build(const SceneSpec& scene, const EngineSettings& settings) override {
    startScene(scene, nullptr);
    settings_ = settings;
    world_ = std::make_unique<b2World>(toB2(scene.gravity));
    world_->SetAllowSleeping(scene.sleep);
    createGroup(-1);
  }
  void step() override {
    world_->Step(static_cast<float>(settings_.timeStep), settings_.velocityIterations,
                 settings_.positionIterations);
  }
  Vec2 position(int body) const override {
    const b2Vec2 p = bodies_[body]->GetWorldCenter();
    return Vec2(p.x, p.y);
  }
  void setVelocity(int body, const Vec2& velocity) override {
    bodies_[body]->SetLinearVelocity(toB2(velocity));
  }
  void read(std::vector<BodyState>* states) const override {
    states->resize(bodies_.size());
    for (size_t i = 0; i < bodies_.size(); ++i) {
      const b2Body* b = bodies_[i];
      if (b == nullptr) {
        (*states)[i].alive = false;
        continue;
      }
      const b2Vec2 p = b->GetWorldCenter();
      const b2Vec2 v = b->GetLinearVelocity();
      (*states)[i] = {Vec2(p.x, p.y), b->GetAngle(), Vec2(v.x, v.y), b->GetAngularVelocity(), true};
    }
  }
  size_t contactCount() const override {
    size_t points = 0;
    for (const b2Contact* c = world_->GetContactList(); c; c = c->GetNext()) {
      if (c->IsTouching()) points += static_cast<size_t>(c->GetManifold()->pointCount);
    }
    return points;
  }

 private:
  b2Body* createBody(int index) override {
    const BenchBody& body = scene_->bodies[index];
    b2BodyDef def;
    def.type = body.isStatic ? b2_staticBody : body.isKinematic ? b2_kinematicBody : b2_dynamicBody;
    def.position = toB2(body.position);
    def.angle = static_cast<float>(body.angle);
    def.linearVelocity = toB2(body.velocity);
    def.angularVelocity = static_cast<float>(body.angularVelocity);
    def.linearDamping = static_cast<float>(body.linearDamping);
    def.awake = body.awake;
    def.allowSleep = body.canSleep;
    b2Body* b = world_->CreateBody(&def);
    for (const BenchShape& shape : body.shapes) addFixture(b, shape);
    if (!body.isDriven()) {
      double mass = 0.0, inertia = 0.0;
      nominalMass(body, &mass, &inertia);
      b2MassData data;
      data.mass = static_cast<float>(mass);
      data.center.SetZero();
      data.I = static_cast<float>(inertia);
      b->SetMassData(&data);
    }
    return b;
  }
  void addFixture(b2Body* b, const BenchShape& shape) {
    b2FixtureDef fixture;
    fixture.density = static_cast<float>(shape.density);
    fixture.friction = static_cast<float>(shape.friction);
    fixture.restitution = static_cast<float>(shape.restitution);
    fixture.filter.categoryBits = static_cast<uint16>(shape.filter.categoryBits);
    fixture.filter.maskBits = static_cast<uint16>(shape.filter.maskBits & 0xFFFF);
    fixture.filter.groupIndex = static_cast<int16>(shape.filter.groupIndex);
    b2PolygonShape polygon;
    b2CircleShape circle;
    const float skin = b2_polygonRadius;
    if (shape.kind == BenchShape::Kind::Box) {
      polygon.SetAsBox(0.5f * static_cast<float>(shape.size.x()) - skin,
                       0.5f * static_cast<float>(shape.size.y()) - skin, toB2(shape.center), 0.0f);
      fixture.shape = &polygon;
    } else if (shape.kind == BenchShape::Kind::Circle) {
      circle.m_p = toB2(shape.center);
      circle.m_radius = static_cast<float>(shape.radius);
      fixture.shape = &circle;
    } else {
      const std::vector<Vec2> points = inset(outlinePolygon(shape, b2_maxPolygonVertices), skin);
      b2Vec2 vertices[b2_maxPolygonVertices];
      for (size_t i = 0; i < points.size(); ++i) vertices[i] = toB2(points[i]);
      polygon.Set(vertices, static_cast<int32>(points.size()));
      fixture.shape = &polygon;
    }
    b->CreateFixture(&fixture);
  }
  void createJoint(int index) override {
    const BenchJoint& joint = scene_->joints[index];
    b2RevoluteJointDef def;
    def.Initialize(bodies_[joint.bodyA], bodies_[joint.bodyB], toB2(joint.anchor));
    def.referenceAngle = static_cast<float>(joint.referenceAngle);
    def.enableLimit = joint.enableLimit;
    def.lowerAngle = static_cast<float>(joint.lower);
    def.upperAngle = static_cast<float>(joint.upper);
    def.enableMotor = joint.enableMotor;
    def.motorSpeed = static_cast<float>(joint.motorSpeed);
    def.maxMotorTorque = static_cast<float>(joint.maxMotorTorque);
    world_->CreateJoint(&def);
  }

  void destroyBody(int index) override { world_->DestroyBody(bodies_[index]); }  // and joints

  EngineSettings settings_;
  std::unique_ptr<b2World> world_;
};

}  // namespace

EngineInfo box2dEngine() {
  EngineInfo info;
  info.name = "box2d";
  info.solvers = {"default"};
  info.defaults.solver = "default";
  info.defaults.velocityIterations = 8;  // the Box2D 2.4 manual's recommendation at 60 Hz
  info.defaults.positionIterations = 3;
  info.make = [] { return std::make_unique<Box2dAdapter>(); };
  info.refuses = [](const SceneSpec& scene, const EngineSettings& settings) -> std::string {
    int dynamicBodies = 0;
    for (const BenchBody& body : scene.bodies) {
      for (const BenchShape& shape : body.shapes) {
        if (!fitsFilter(shape.filter))
          return "a collision filter needs more than Box2D 2.4's 16 bits";
      }
      dynamicBodies += body.isDriven() ? 0 : 1;
    }
    // Box2D 2.4 sub-steps each fast body's time of impact against kinematic ones: the washer's
    // 8,100 boxes in its turning drum did not finish 500 steps in 400 s (2026-11-26).
    if (scene.hasMovingKinematic() && dynamicBodies > 1000) {
      return "Box2D 2.4's time of impact against a moving kinematic body takes minutes here";
    }
    return singleThreadOnly("Box2D 2.4", settings);
  };
  return info;
}

}  // namespace impulse2d_bench
