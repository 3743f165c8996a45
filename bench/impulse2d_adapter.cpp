// impulse2d through its public API, and the one list of its solvers the benchmark sweeps.
#include <impulse2d/world.hpp>

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

class Impulse2dAdapter : public EngineAdapter {
 public:
  void build(const SceneSpec& scene, const EngineSettings& settings) override {
    WorldDef def;
    def.timeStep = settings.timeStep;
    def.velocityIterations = settings.velocityIterations;
    def.positionIterations = settings.positionIterations;
    def.enableSleep = false;
    for (const SolverEntry& entry : solvers()) {
      if (entry.name == settings.solver) def.solver = entry.type;
    }
    world_ = std::make_unique<World>(def);
    ids_.clear();
    for (const BenchBody& body : scene.bodies) {
      BodyDef bodyDef;
      bodyDef.type = body.isStatic ? BodyType::Static : BodyType::Dynamic;
      bodyDef.position = body.position;
      bodyDef.angle = body.angle;
      bodyDef.shapes.push_back(toShapeDef(body.shape));
      ids_.push_back(world_->createBody(bodyDef));
    }
    for (const BenchJoint& joint : scene.joints) {
      JointDef jointDef;
      jointDef.type = JointType::Revolute;
      jointDef.bodyA = ids_[joint.bodyA];
      jointDef.bodyB = ids_[joint.bodyB];
      jointDef.anchor = joint.anchor;
      world_->createJoint(jointDef);
    }
  }
  void step() override { world_->step(); }
  void read(std::vector<BodyState>* states) const override {
    states->resize(ids_.size());
    for (size_t i = 0; i < ids_.size(); ++i) {
      const Body& body = world_->body(ids_[i]);
      (*states)[i] = {body.center, body.angle, body.linearVelocity, body.angularVelocity};
    }
  }
  size_t contactCount() const override { return world_->contactCount(); }

 private:
  std::unique_ptr<World> world_;
  std::vector<BodyId> ids_;
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
  return engines;
}

}  // namespace impulse2d_bench
