// One interface for every engine the benchmark drives: build a SceneSpec, step it, read the bodies
// back. The peers' adapters are compiled in only when their libraries were found (Box2D 2.4,
// Chipmunk) or pointed at (Box2D v3).
#pragma once

#include "bench_scene.hpp"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace impulse2d_bench {

struct EngineSettings {
  std::string solver;  ///< one of EngineInfo::solvers
  double timeStep = 1.0 / 60.0;
  int velocityIterations = 8;  ///< sub-steps for the sub-stepping solvers and Box2D v3
  int positionIterations = 3;  ///< ignored by engines without a position pass (Chipmunk, v3)
  int threads = 1;             ///< worker threads (Box2D v3's workerCount)
};

/// A body's state as the metrics read it: the centre of mass and its velocities.
struct BodyState {
  Vec2 position = Vec2::Zero();
  double angle = 0.0;
  Vec2 velocity = Vec2::Zero();
  double angularVelocity = 0.0;
  bool alive = true;  ///< false: a body of an event group that does not exist now
};

class EngineAdapter {
 public:
  virtual ~EngineAdapter() = default;
  /// Builds the scene with its gravity and sleeping setting: every body outside the event groups
  /// and every joint between them.
  virtual void build(const SceneSpec& scene, const EngineSettings& settings) = 0;
  /// Creates the bodies of an event group (at the scene's poses) and the joints whose bodyB is
  /// one of them; destroys them again.
  virtual void createGroup(int group) = 0;
  virtual void destroyGroup(int group) = 0;
  virtual void step() = 0;
  /// One state per SceneSpec body, in the scene's order.
  virtual void read(std::vector<BodyState>* states) const = 0;
  /// Contact points the engine holds as touching now.
  virtual size_t contactCount() const = 0;
  /// One body's position as read() reports it, and a new linear velocity for it (a kinematic
  /// body's steering, SceneSpec::steering).
  virtual Vec2 position(int body) const = 0;
  virtual void setVelocity(int body, const Vec2& velocity) = 0;
};

struct EngineInfo {
  std::string name;
  std::vector<std::string> solvers;  ///< the first is the engine's default
  bool hasPositionIterations = true;
  std::vector<std::string> solversWithoutPositionIterations;
  EngineSettings defaults;  ///< the engine's own defaults at 60 Hz
  std::function<std::unique_ptr<EngineAdapter>()> make;
  /// Empty when the engine can run the scene at these settings, else why not (the row is
  /// skipped with this message, never run with other settings).
  std::function<std::string(const SceneSpec&, const EngineSettings&)> refuses;
};

/// impulse2d first, then whichever peers were compiled in.
std::vector<EngineInfo> availableEngines();

EngineInfo impulse2dEngine();
#ifdef IMPULSE2D_BENCH_BOX2D
EngineInfo box2dEngine();
#endif
#ifdef IMPULSE2D_BENCH_CHIPMUNK
EngineInfo chipmunkEngine();
#endif
#ifdef IMPULSE2D_BENCH_BOX2D_V3
EngineInfo box2dV3Engine();
#endif

/// The refusal every single-threaded engine gives for threads != 1.
std::string singleThreadOnly(const std::string& engine, const EngineSettings& settings);

/// Which bodies and joints each event group holds (group -1: those there from the start), found
/// once before the timed run.
class SceneGroups {
 public:
  explicit SceneGroups(const SceneSpec& scene);
  const std::vector<int>& bodies(int group) const { return bodies_[group + 1]; }
  const std::vector<int>& joints(int group) const { return joints_[group + 1]; }

 private:
  std::vector<std::vector<int>> bodies_, joints_;
};

/// The part of an adapter that is the same for every engine: the scene's event groups created
/// and destroyed through the engine's own createBody, createJoint and destroyBody (and
/// destroyJoint, for engines whose bodies do not take their joints along). `Handle` names a body.
template <typename Handle>
class GroupedAdapter : public EngineAdapter {
 public:
  void createGroup(int group) final {
    for (const int i : groups_->bodies(group)) bodies_[i] = createBody(i);
    for (const int j : groups_->joints(group)) createJoint(j);
  }
  void destroyGroup(int group) final {
    for (const int j : groups_->joints(group)) destroyJoint(j);
    for (const int i : groups_->bodies(group)) {
      destroyBody(i);
      bodies_[i] = none_;
    }
  }

 protected:
  /// Called first by build(): no body exists yet; `none` marks an absent one.
  void startScene(const SceneSpec& scene, const Handle& none) {
    scene_ = &scene;
    groups_ = std::make_unique<SceneGroups>(scene);
    none_ = none;
    bodies_.assign(scene.bodies.size(), none);
  }
  /// Scene body and joint indices; the bodies a joint names exist.
  virtual Handle createBody(int body) = 0;
  virtual void createJoint(int joint) = 0;
  virtual void destroyBody(int body) = 0;
  virtual void destroyJoint(int /*joint*/) {}

  const SceneSpec* scene_ = nullptr;
  std::unique_ptr<SceneGroups> groups_;
  std::vector<Handle> bodies_;  ///< per scene body
  Handle none_{};
};

}  // namespace impulse2d_bench
