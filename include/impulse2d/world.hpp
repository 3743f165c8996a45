// The public face of the engine: a world of bodies, shapes and joints stepped at a fixed rate.
#pragma once

#include <impulse2d/body.hpp>
#include <impulse2d/defs.hpp>
#include <impulse2d/profile.hpp>
#include <impulse2d/queries.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace impulse2d {

/// One contact point as users see it (ROS ~contacts, the CLI's --contacts).
struct ContactInfo {
  BodyId bodyA, bodyB;
  Vec2 point = Vec2::Zero();    ///< world, as found before the step moved the bodies
  Vec2 normal = Vec2::Zero();   ///< unit, from body A to body B
  double separation = 0.0;      ///< m, negative = penetration
  double normalImpulse = 0.0;   ///< N s applied by the last step
  double tangentImpulse = 0.0;  ///< N s, along perp(normal)
};

/// What a joint is now, for joint_states and drawing.
struct JointState {
  Vec2 anchorA = Vec2::Zero();  ///< world position of the anchor on body A
  Vec2 anchorB = Vec2::Zero();  ///< and on body B; they coincide when the joint holds
  double position = 0.0;        ///< revolute: angle B - A relative to creation (rad);
                                ///< prismatic: translation along the axis (m); distance: length
  double velocity = 0.0;        ///< rad/s or m/s
};

/// A body that a step removed because it left the world (limits.hpp, docs/security.md).
struct RemovedBody {
  BodyId id;  ///< no longer valid
  std::string name;
  Vec2 position = Vec2::Zero();  ///< its origin when removed (may be inf or NaN)
  std::string reason;            ///< e.g. "it left the world extent of 1e7 m"
  RemovalCause cause = RemovalCause::LeftWorldExtent;
};

/// A dynamic body that a step found lost for good: awake, below every static and kinematic body,
/// along gravity, by more than the static bodies' own extent along gravity (their bounding box),
/// joined by no joint to anything that is not as far down, and not rising with the bodies its
/// joints join it to. Nothing is left to stop it: it falls until it leaves kWorldExtent. See
/// WorldDef::removeLostBodies.
struct LostBody {
  BodyId id;  ///< still valid when reported by takeLostBodies()
  std::string name;
  Vec2 position = Vec2::Zero();  ///< its origin when found lost
  double depth = 0.0;            ///< m from the lowest static point down to the body's top
  std::string reason;            ///< e.g. "it fell 3.2 m below every static body ..."
};

struct WorldImpl;

class World {
 public:
  explicit World(const WorldDef& def = WorldDef());
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  /// Settings may be changed between steps (time step, iterations, solver, gravity).
  WorldDef& settings();
  const WorldDef& settings() const;
  /// Empty when the settings are usable, otherwise a reason naming the field.
  static std::string validate(const WorldDef& def);

  // --- creation and destruction; on bad input nothing changes and `error` says why ---
  /// Checks a body definition without creating it (shape geometry, finite numbers, mass...).
  static std::string validate(const BodyDef& def);
  /// Also checks that both bodies exist, differ, and the geometry makes sense.
  std::string validate(const JointDef& def) const;
  BodyId createBody(const BodyDef& def, std::string* error = nullptr);
  /// Destroys the body, its contacts and every joint attached to it.
  bool destroyBody(BodyId id);
  JointId createJoint(const JointDef& def, std::string* error = nullptr);
  bool destroyJoint(JointId id);
  /// Removes everything; settings are kept.
  void clear();

  // --- lookup ---
  bool isValid(BodyId id) const;
  bool isValid(JointId id) const;
  BodyId findBody(const std::string& name) const;    ///< invalid id when absent
  JointId findJoint(const std::string& name) const;  ///< invalid id when absent
  const Body& body(BodyId id) const;                 ///< precondition: isValid(id)
  const JointDef& jointDef(JointId id) const;        ///< as created (anchor in world at creation)
  JointState jointState(JointId id) const;
  std::vector<BodyId> bodies() const;  ///< in slot order (deterministic)
  std::vector<JointId> joints() const;
  size_t bodyCount() const;
  size_t jointCount() const;

  // --- changing state (each wakes the body) ---
  /// Places the body's origin. Dynamic bodies rigidly welded to it (weld joints of frequency 0,
  /// directly or through others) move with it, so the assembly stays whole; false, and nothing
  /// moves, when one of them would leave kMaxCoordinate.
  bool setTransform(BodyId id, const Vec2& position, double angle);
  /// Sets the velocity of the body's centre of mass and its turn rate; the dynamic bodies rigidly
  /// welded to it take the same rigid motion.
  bool setVelocity(BodyId id, const Vec2& linear, double angular);
  /// A force (N) at a world point, held until the end of the next step.
  bool applyForce(BodyId id, const Vec2& force, const Vec2& worldPoint);
  bool applyTorque(BodyId id, double torque);
  /// Motor of a revolute or prismatic joint.
  bool setJointMotor(JointId id, bool enable, double speed, double maxForceOrTorque);

  // --- queries (world_queries.cpp; queries.hpp says what a hit is) ---
  /// The nearest hit of the segment from -> to over every body's shapes, bodies in `filter`
  /// skipped; no hit when either end is not finite.
  RayHit rayCast(const Vec2& from, const Vec2& to, const RayFilter& filter = RayFilter()) const;
  /// A fan of segments from one origin, as a scanner casts them: (*hits)[i] is rayCast(origin,
  /// ends[i], filter), bit for bit, computed at once: the shapes within reach are gathered once
  /// and each segment tries only those in its direction, nearest first (ray_fan.cpp).
  void rayCastFan(const Vec2& origin, const std::vector<Vec2>& ends, const RayFilter& filter,
                  std::vector<RayHit>* hits) const;
  /// The bodies with a shape containing the point (boundary included), in slot order.
  std::vector<BodyId> queryPoint(const Vec2& point) const;
  /// The bodies with a shape overlapping the box (touching included; exact, not by bounding
  /// boxes), in slot order. Empty for a box that is not finite or whose lower corner exceeds its
  /// upper one.
  std::vector<BodyId> queryAabb(const Aabb& box) const;

  // --- simulation ---
  /// Advances one fixed step of settings().timeStep.
  void step();
  double time() const;
  uint64_t stepCount() const;
  /// Times each stage of every step from now on (off: no clock is read; the default).
  void setProfiling(bool on);
  bool profiling() const;
  /// The stages' times of the last step taken with profiling on (all 0 before one).
  const StepProfile& profile() const;

  /// Touching contact points of the last step (speculative points that never touched are left
  /// out), ordered deterministically.
  std::vector<ContactInfo> contacts() const;
  size_t contactCount() const;
  /// FNV-1a over the exact bits of every body's position, angle and velocities in slot order:
  /// equal hashes mean bit-identical states.
  uint64_t hash() const;

  /// Bodies that steps removed since the last call, oldest first: those whose centre of mass
  /// left kWorldExtent (limits.hpp) or whose state stopped being finite. At most 1024 are
  /// kept between calls; removedBodyCount() counts them all.
  std::vector<RemovedBody> takeRemovedBodies();
  uint64_t removedBodyCount() const;
  /// Bodies that steps found lost for good since the last call, oldest first, each once (again
  /// only after it came back), and left in the world because WorldDef::removeLostBodies is off
  /// (with it on they are removed and reported by takeRemovedBodies()). Needs a static body and
  /// non-zero gravity. At most 1024 are kept between calls; lostBodyCount() counts them all.
  std::vector<LostBody> takeLostBodies();
  uint64_t lostBodyCount() const;

 private:
  /// The step stage behind takeRemovedBodies() and takeLostBodies() (world_bounds.cpp).
  void removeEscapedBodies();
  /// Unit tests only (test/unit/test_limits.cpp): writes a state no World method accepts, to
  /// prove the last guard that no valid request reaches.
  friend struct WorldTestAccess;

  std::unique_ptr<WorldImpl> impl_;
};

}  // namespace impulse2d
