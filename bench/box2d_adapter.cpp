// Box2D 2.4 (single precision) building the same scenes. Box2D wraps every polygon in a skin of
// b2_polygonRadius (1 cm); the polygons are shrunk by it so that the collision surface is the
// scene's geometry, and masses are set from the scene's geometry so all engines move the same
// bodies.
#include <box2d/box2d.h>

#include <cmath>

#include "engine_adapter.hpp"

namespace impulse2d_bench {
namespace {

b2Vec2 toB2(const Vec2& v) { return b2Vec2(static_cast<float>(v.x()), static_cast<float>(v.y())); }

class Box2dAdapter : public EngineAdapter {
 public:
  void build(const SceneSpec& scene, const EngineSettings& settings) override {
    settings_ = settings;
    world_ = std::make_unique<b2World>(b2Vec2(0.0f, -9.81f));
    world_->SetAllowSleeping(false);
    bodies_.clear();
    for (const BenchBody& body : scene.bodies) {
      b2BodyDef def;
      def.type = body.isStatic ? b2_staticBody : b2_dynamicBody;
      def.position = toB2(body.position);
      def.angle = static_cast<float>(body.angle);
      b2Body* b = world_->CreateBody(&def);
      b2FixtureDef fixture;
      fixture.density = static_cast<float>(body.shape.density);
      fixture.friction = static_cast<float>(body.shape.friction);
      b2PolygonShape polygon;
      b2CircleShape circle;
      const float skin = b2_polygonRadius;
      if (body.shape.kind == BenchShape::Kind::Box) {
        polygon.SetAsBox(0.5f * static_cast<float>(body.shape.size.x()) - skin,
                         0.5f * static_cast<float>(body.shape.size.y()) - skin);
        fixture.shape = &polygon;
      } else if (body.shape.kind == BenchShape::Kind::Circle) {
        circle.m_radius = static_cast<float>(body.shape.radius);
        fixture.shape = &circle;
      } else {
        // Regular polygon: moving every edge in by the skin scales it by (apothem - skin) /
        // apothem.
        const size_t n = body.shape.vertices.size();
        const double apothem =
            std::cos(impulse2d::kPi / static_cast<double>(n)) * body.shape.vertices[0].norm();
        const double scale = (apothem - skin) / apothem;
        b2Vec2 points[b2_maxPolygonVertices];
        for (size_t i = 0; i < n; ++i) points[i] = toB2(scale * body.shape.vertices[i]);
        polygon.Set(points, static_cast<int32>(n));
        fixture.shape = &polygon;
      }
      b->CreateFixture(&fixture);
      if (!body.isStatic) {
        double mass = 0.0, inertia = 0.0;
        nominalMass(body.shape, &mass, &inertia);
        b2MassData data;
        data.mass = static_cast<float>(mass);
        data.center.SetZero();
        data.I = static_cast<float>(inertia);
        b->SetMassData(&data);
      }
      bodies_.push_back(b);
    }
    for (const BenchJoint& joint : scene.joints) {
      b2RevoluteJointDef def;
      def.Initialize(bodies_[joint.bodyA], bodies_[joint.bodyB], toB2(joint.anchor));
      world_->CreateJoint(&def);
    }
  }
  void step() override {
    world_->Step(static_cast<float>(settings_.timeStep), settings_.velocityIterations,
                 settings_.positionIterations);
  }
  void read(std::vector<BodyState>* states) const override {
    states->resize(bodies_.size());
    for (size_t i = 0; i < bodies_.size(); ++i) {
      const b2Body* b = bodies_[i];
      const b2Vec2 p = b->GetWorldCenter();
      const b2Vec2 v = b->GetLinearVelocity();
      (*states)[i] = {Vec2(p.x, p.y), b->GetAngle(), Vec2(v.x, v.y), b->GetAngularVelocity()};
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
  EngineSettings settings_;
  std::unique_ptr<b2World> world_;
  std::vector<b2Body*> bodies_;
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
  return info;
}

}  // namespace impulse2d_bench
