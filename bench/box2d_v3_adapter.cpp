// Box2D v3 (single precision, graph-coloured SIMD solver), compiled in only when the build is
// pointed at a v3 build (IMPULSE2D_BENCH_BOX2D_V3_DIR, cmake/bench.cmake). It is driven as its own
// benchmark app drives it: b2DefaultWorldDef with the scene's gravity and sleeping, 4 sub-steps
// (velocityIterations) at 60 Hz, continuous collision on, native capsules and rounded polygons,
// revolute springs.
//
// Two APIs are taken: v3.1's (up to v3.1.1) and master's (from 2026: joint definitions share a
// b2JointDef base with local frames, positions are b2Pos, and v3 runs its own worker threads
// when given no task callbacks); cmake/bench.cmake tells them apart by that base in types.h and
// defines IMPULSE2D_BOX2D_V3_MASTER. With v3.1 the workers run on oneTBB (each task v3 enqueues is
// a parallel_for over its items in an arena of `threads` slots); with master they are v3's own
// scheduler, as its benchmark app runs them.
#include <box2d/box2d.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <deque>

#include "engine_adapter.hpp"

namespace impulse2d_bench {
namespace {

b2Vec2 toB2(const Vec2& v) { return {static_cast<float>(v.x()), static_cast<float>(v.y())}; }

#if !defined(IMPULSE2D_BOX2D_V3_MASTER)
// v3 calls enqueueTask for work it splits into [start, end) ranges (at least minRange items) and
// finishTask to wait for it; a worker index must be below workerCount, which the arena's slot
// indices are.
class TbbTasks {
 public:
  explicit TbbTasks(int workers) : arena_(workers) {}
  static void* enqueue(b2TaskCallback* task, int itemCount, int minRange, void* taskContext,
                       void* userContext) {
    TbbTasks& self = *static_cast<TbbTasks*>(userContext);
    if (self.used_ == self.groups_.size()) self.groups_.emplace_back();
    tbb::task_group* group = &self.groups_[self.used_++];
    self.arena_.execute([=] {
      group->run([=] {
        tbb::parallel_for(tbb::blocked_range<int>(0, itemCount, std::max(1, minRange)),
                          [=](const tbb::blocked_range<int>& range) {
                            const int slot = tbb::this_task_arena::current_thread_index();
                            task(range.begin(), range.end(), static_cast<uint32_t>(slot),
                                 taskContext);
                          });
      });
    });
    return group;
  }
  static void finish(void* userTask, void* userContext) {
    TbbTasks& self = *static_cast<TbbTasks*>(userContext);
    tbb::task_group* group = static_cast<tbb::task_group*>(userTask);
    self.arena_.execute([=] { group->wait(); });
  }
  /// After a step every task has been waited for: the groups can be reused.
  void reset() { used_ = 0; }

 private:
  tbb::task_arena arena_;
  std::deque<tbb::task_group> groups_;  // stable addresses
  size_t used_ = 0;
};
#else
struct TbbTasks {  // master: v3's own threads
  void reset() {}
};
#endif

class Box2dV3Adapter : public GroupedAdapter<b2BodyId> {
 public:
  ~Box2dV3Adapter() override {
    if (b2World_IsValid(world_)) b2DestroyWorld(world_);
  }
  void build(const SceneSpec& scene, const EngineSettings& settings) override {
    startScene(scene, b2_nullBodyId);
    settings_ = settings;
    b2WorldDef def = b2DefaultWorldDef();
    def.gravity = toB2(scene.gravity);
    def.enableSleep = scene.sleep;
    def.workerCount = settings.threads;
#if !defined(IMPULSE2D_BOX2D_V3_MASTER)
    if (settings.threads > 1) {
      tasks_ = std::make_unique<TbbTasks>(settings.threads);
      def.enqueueTask = TbbTasks::enqueue;
      def.finishTask = TbbTasks::finish;
      def.userTaskContext = tasks_.get();
    }
#endif
    world_ = b2CreateWorld(&def);
    createGroup(-1);
  }
  void step() override {
    b2World_Step(world_, static_cast<float>(settings_.timeStep), settings_.velocityIterations);
    if (tasks_) tasks_->reset();
  }
  Vec2 position(int body) const override {
#if defined(IMPULSE2D_BOX2D_V3_MASTER)
    const auto p = b2Body_GetWorldCenter(bodies_[body]);
#else
    const b2Vec2 p = b2Body_GetWorldCenterOfMass(bodies_[body]);
#endif
    return Vec2(p.x, p.y);
  }
  void setVelocity(int body, const Vec2& velocity) override {
    b2Body_SetLinearVelocity(bodies_[body], toB2(velocity));
  }
  void read(std::vector<BodyState>* states) const override {
    states->resize(bodies_.size());
    for (size_t i = 0; i < bodies_.size(); ++i) {
      const b2BodyId id = bodies_[i];
      if (B2_IS_NULL(id)) {
        (*states)[i].alive = false;
        continue;
      }
#if defined(IMPULSE2D_BOX2D_V3_MASTER)
      const auto p = b2Body_GetWorldCenter(id);
#else
      const b2Vec2 p = b2Body_GetWorldCenterOfMass(id);
#endif
      const b2Vec2 v = b2Body_GetLinearVelocity(id);
      (*states)[i] = {Vec2(p.x, p.y), b2Rot_GetAngle(b2Body_GetRotation(id)), Vec2(v.x, v.y),
                      b2Body_GetAngularVelocity(id), true};
    }
  }
  size_t contactCount() const override {
    size_t points = 0;
    std::vector<b2ContactData> contacts;
    for (size_t i = 0; i < bodies_.size(); ++i) {
      if (B2_IS_NULL(bodies_[i]) || scene_->bodies[i].isStatic) continue;
      contacts.resize(static_cast<size_t>(b2Body_GetContactCapacity(bodies_[i])));
      const int count =
          b2Body_GetContactData(bodies_[i], contacts.data(), static_cast<int>(contacts.size()));
      for (int k = 0; k < count; ++k) {
        // Each contact once: from its body A, or from the moving body when A is static.
        const b2BodyId a = b2Shape_GetBody(contacts[k].shapeIdA);
        if (B2_ID_EQUALS(a, bodies_[i]) || b2Body_GetType(a) == b2_staticBody) {
          points += static_cast<size_t>(contacts[k].manifold.pointCount);
        }
      }
    }
    return points;
  }

 private:
  b2BodyId createBody(int index) override {
    const BenchBody& body = scene_->bodies[index];
    b2BodyDef def = b2DefaultBodyDef();
    def.type = body.isStatic ? b2_staticBody : body.isKinematic ? b2_kinematicBody : b2_dynamicBody;
    def.position = toB2(body.position);
    def.rotation = b2MakeRot(static_cast<float>(body.angle));
    def.linearVelocity = toB2(body.velocity);
    def.angularVelocity = static_cast<float>(body.angularVelocity);
    def.linearDamping = static_cast<float>(body.linearDamping);
    def.isAwake = body.awake;
    def.enableSleep = body.canSleep;
    if (body.sleepThreshold > 0.0) def.sleepThreshold = static_cast<float>(body.sleepThreshold);
    const b2BodyId id = b2CreateBody(world_, &def);
    for (const BenchShape& shape : body.shapes) addShape(id, shape);
    if (!body.isDriven()) {
      double mass = 0.0, inertia = 0.0;
      nominalMass(body, &mass, &inertia);
      b2Body_SetMassData(id, {static_cast<float>(mass), {0.0f, 0.0f}, static_cast<float>(inertia)});
    }
    return id;
  }
  static void addShape(b2BodyId body, const BenchShape& shape) {
    b2ShapeDef def = b2DefaultShapeDef();
    def.density = static_cast<float>(shape.density);
    def.material.friction = static_cast<float>(shape.friction);
    def.material.restitution = static_cast<float>(shape.restitution);
    def.filter.categoryBits = shape.filter.categoryBits;
    def.filter.maskBits = shape.filter.maskBits;
    def.filter.groupIndex = shape.filter.groupIndex;
    switch (shape.kind) {
      case BenchShape::Kind::Box: {
        const b2Polygon box = b2MakeOffsetBox(0.5f * static_cast<float>(shape.size.x()),
                                              0.5f * static_cast<float>(shape.size.y()),
                                              toB2(shape.center), b2Rot_identity);
        b2CreatePolygonShape(body, &def, &box);
        return;
      }
      case BenchShape::Kind::Circle: {
        const b2Circle circle{toB2(shape.center), static_cast<float>(shape.radius)};
        b2CreateCircleShape(body, &def, &circle);
        return;
      }
      case BenchShape::Kind::Capsule: {
        const b2Capsule capsule{toB2(shape.vertices[0]), toB2(shape.vertices[1]),
                                static_cast<float>(shape.radius)};
        b2CreateCapsuleShape(body, &def, &capsule);
        return;
      }
      case BenchShape::Kind::Polygon: {
        std::vector<b2Vec2> points;
        for (const Vec2& v : shape.vertices) points.push_back(toB2(v));
        const b2Hull hull = b2ComputeHull(points.data(), static_cast<int>(points.size()));
        const b2Polygon polygon = b2MakePolygon(&hull, static_cast<float>(shape.radius));
        b2CreatePolygonShape(body, &def, &polygon);
        return;
      }
    }
  }
  void createJoint(int index) override {
    const BenchJoint& joint = scene_->joints[index];
    b2RevoluteJointDef def = b2DefaultRevoluteJointDef();
#if defined(IMPULSE2D_BOX2D_V3_MASTER)
    // The joint angle is B's frame's angle less A's: A's frame turned by the reference angle
    // makes it 0 at the reference, as v3.1's referenceAngle did.
    b2JointDef& base = def.base;
    base.bodyIdA = bodies_[joint.bodyA];
    base.bodyIdB = bodies_[joint.bodyB];
    base.localFrameA.p = b2Body_GetLocalPoint(base.bodyIdA, toB2(joint.anchor));
    base.localFrameA.q = b2MakeRot(static_cast<float>(joint.referenceAngle));
    base.localFrameB.p = b2Body_GetLocalPoint(base.bodyIdB, toB2(joint.anchor));
    base.localFrameB.q = b2Rot_identity;
#else
    def.bodyIdA = bodies_[joint.bodyA];
    def.bodyIdB = bodies_[joint.bodyB];
    def.localAnchorA = b2Body_GetLocalPoint(def.bodyIdA, toB2(joint.anchor));
    def.localAnchorB = b2Body_GetLocalPoint(def.bodyIdB, toB2(joint.anchor));
    def.referenceAngle = static_cast<float>(joint.referenceAngle);
#endif
    def.enableLimit = joint.enableLimit;
    def.lowerAngle = static_cast<float>(joint.lower);
    def.upperAngle = static_cast<float>(joint.upper);
    def.enableMotor = joint.enableMotor;
    def.motorSpeed = static_cast<float>(joint.motorSpeed);
    def.maxMotorTorque = static_cast<float>(joint.maxMotorTorque);
    def.enableSpring = joint.springHertz > 0.0;
    def.hertz = static_cast<float>(joint.springHertz);
    def.dampingRatio = static_cast<float>(joint.springDampingRatio);
    b2CreateRevoluteJoint(world_, &def);
  }

  void destroyBody(int index) override { b2DestroyBody(bodies_[index]); }  // and its joints

  EngineSettings settings_;
  std::unique_ptr<TbbTasks> tasks_;
  b2WorldId world_ = b2_nullWorldId;
};

}  // namespace

EngineInfo box2dV3Engine() {
  EngineInfo info;
  info.name = "box2d_v3";
  info.solvers = {"default"};
  info.hasPositionIterations = false;
  info.defaults.solver = "default";
  info.defaults.velocityIterations = 4;  // sub-steps, as v3's samples and benchmark app use
  info.defaults.positionIterations = 0;
  info.make = [] { return std::make_unique<Box2dV3Adapter>(); };
  info.refuses = [](const SceneSpec&, const EngineSettings& settings) -> std::string {
#if defined(IMPULSE2D_BOX2D_V3_MASTER)
    if (settings.threads > 32) return "Box2D v3 master takes at most 32 workers (B2_MAX_WORKERS)";
#else
    if (settings.threads > 64) return "Box2D v3.1 takes at most 64 workers (B2_MAX_WORKERS)";
#endif
    return "";
  };
  return info;
}

}  // namespace impulse2d_bench
