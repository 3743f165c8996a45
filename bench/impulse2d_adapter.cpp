// impulse2d through its public API, and the one list of its solvers the benchmark sweeps.
#include <impulse2d/world.hpp>

#include <stdexcept>

#include "engine_adapter.hpp"

namespace impulse2d_bench {
namespace {

using namespace impulse2d;

struct SolverEntry {
  std::string name;  // as the CLI and scenes name it
  SolverType type;
  bool usesPositionIterations;  // else the position sweep is skipped for it
};

// Every solver the benchmark sweeps; the first is the default. A new SolverType is one more line.
const std::vector<SolverEntry>& solvers() {
  static const std::vector<SolverEntry> list = {
      {"substep", SolverType::SubstepNgs, true},
      {"ngs", SolverType::NonlinearGaussSeidel, true},
      {"soft", SolverType::SoftStep, false},
      {"baumgarte", SolverType::Baumgarte, false},
  };
  return list;
}

class Impulse2dAdapter : public GroupedAdapter<BodyId> {
 public:
  void build(const SceneSpec& scene, const EngineSettings& settings) override {
    startScene(scene, BodyId());
    WorldDef def;
    def.gravity = scene.gravity;
    def.timeStep = settings.timeStep;
    def.velocityIterations = settings.velocityIterations;
    def.positionIterations = settings.positionIterations;
    def.threads = settings.threads;  // the same result for every count
    def.enableSleep = scene.sleep;
    for (const SolverEntry& entry : solvers()) {
      if (entry.name == settings.solver) def.solver = entry.type;
    }
    world_ = std::make_unique<World>(def);
    createGroup(-1);
  }
  void step() override { world_->step(); }
  void read(std::vector<BodyState>* states) const override {
    states->resize(bodies_.size());
    for (size_t i = 0; i < bodies_.size(); ++i) {
      if (!bodies_[i].valid()) {
        (*states)[i].alive = false;
        continue;
      }
      const Body& body = world_->body(bodies_[i]);
      (*states)[i] = {body.center, body.angle, body.linearVelocity, body.angularVelocity, true};
    }
  }
  size_t contactCount() const override { return world_->contactCount(); }
  Vec2 position(int body) const override { return world_->body(bodies_[body]).center; }
  void setVelocity(int body, const Vec2& velocity) override {
    world_->setVelocity(bodies_[body], velocity, 0.0);
  }

 private:
  BodyId createBody(int index) override {
    const BenchBody& body = scene_->bodies[index];
    BodyDef def;
    def.type = body.isStatic      ? BodyType::Static
               : body.isKinematic ? BodyType::Kinematic
                                  : BodyType::Dynamic;
    def.position = body.position;
    def.angle = body.angle;
    def.linearVelocity = body.velocity;
    def.angularVelocity = body.angularVelocity;
    def.linearDamping = body.linearDamping;
    def.awake = body.awake;
    bool approximated = false;
    for (const BenchShape& shape : body.shapes) {
      def.shapes.push_back(toShapeDef(shape));
      approximated |= isRounded(shape);
    }
    if (def.shapes.empty()) {
      // impulse2d wants a shape on every body: a static anchor (the tumbler's ground) gets a 1 cm
      // box 100 km away, where nothing can touch it.
      ShapeDef far;
      far.size = Vec2(0.01, 0.01);
      far.offset = Vec2(1e5, 1e5);
      def.shapes.push_back(far);
    }
    if (approximated && !body.isDriven()) {
      // A rounded shape's polygon outline is a little smaller: give it the true shape's mass.
      nominalMass(body, &def.mass, &def.inertia);
      def.useLocalCenter = true;
    }
    std::string error;
    const BodyId id = world_->createBody(def, &error);
    if (!id.valid()) throw std::runtime_error("impulse2d refused a body: " + error);
    return id;
  }
  void createJoint(int index) override {
    const BenchJoint& joint = scene_->joints[index];
    JointDef def;
    def.type = JointType::Revolute;
    def.bodyA = bodies_[joint.bodyA];
    def.bodyB = bodies_[joint.bodyB];
    def.anchor = joint.anchor;
    // impulse2d's limits are relative to the angle between the bodies at creation.
    const double atCreation = scene_->bodies[joint.bodyB].angle - scene_->bodies[joint.bodyA].angle;
    def.enableLimit = joint.enableLimit;
    def.lower = joint.lower + joint.referenceAngle - atCreation;
    def.upper = joint.upper + joint.referenceAngle - atCreation;
    def.enableMotor = joint.enableMotor;
    def.motorSpeed = joint.motorSpeed;
    def.maxMotorTorque = joint.maxMotorTorque;
    // No revolute spring in impulse2d: springHertz is left out (docs/benchmarks.md).
    std::string error;
    if (!world_->createJoint(def, &error).valid()) {
      throw std::runtime_error("impulse2d refused a joint: " + error);
    }
  }

  void destroyBody(int index) override { world_->destroyBody(bodies_[index]); }  // and joints

  std::unique_ptr<World> world_;
};

}  // namespace

EngineInfo impulse2dEngine() {
  EngineInfo info;
  info.name = "impulse2d";
  for (const SolverEntry& entry : solvers()) {
    info.solvers.push_back(entry.name);
    if (!entry.usesPositionIterations) info.solversWithoutPositionIterations.push_back(entry.name);
  }
  info.defaults.solver = info.solvers.front();
  info.defaults.velocityIterations = WorldDef().velocityIterations;
  info.defaults.positionIterations = WorldDef().positionIterations;
  info.make = [] { return std::make_unique<Impulse2dAdapter>(); };
  return info;
}

std::vector<EngineInfo> availableEngines() {
  std::vector<EngineInfo> engines{impulse2dEngine()};
#ifdef IMPULSE2D_BENCH_BOX2D
  engines.push_back(box2dEngine());
#endif
#ifdef IMPULSE2D_BENCH_CHIPMUNK
  engines.push_back(chipmunkEngine());
#endif
#ifdef IMPULSE2D_BENCH_BOX2D_V3
  engines.push_back(box2dV3Engine());
#endif
  return engines;
}

}  // namespace impulse2d_bench
