// Definitions used to create worlds, bodies and joints. Units are SI: metres, kilograms,
// seconds, radians (counter-clockwise). Every field has a usable default.
#pragma once

#include <impulse2d/math.hpp>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace impulse2d {

/// Handles to world objects. A handle stays valid until its object is destroyed; a destroyed
/// object's slot may be reused, and the generation tells an old handle from a new one.
struct BodyId {
  int32_t index = -1;
  uint32_t generation = 0;
  bool valid() const { return index >= 0; }
  bool operator==(const BodyId& o) const { return index == o.index && generation == o.generation; }
  bool operator!=(const BodyId& o) const { return !(*this == o); }
};

struct JointId {
  int32_t index = -1;
  uint32_t generation = 0;
  bool valid() const { return index >= 0; }
  bool operator==(const JointId& o) const { return index == o.index && generation == o.generation; }
  bool operator!=(const JointId& o) const { return !(*this == o); }
};

/// Which velocity/position solver the world runs; see README "Solvers".
enum class SolverType {
  /// Box2D Lite: velocity bias beta/dt * max(0, depth - slop) (Baumgarte); position_iterations
  /// are not used.
  Baumgarte,
  /// Post-stabilisation: the velocity pass has no position bias (no momentum is added), then
  /// `position_iterations` non-linear Gauss-Seidel passes push overlapping bodies apart.
  NonlinearGaussSeidel,
  /// Sub-stepping with soft constraints (Catto's "soft step", Box2D v3): `velocity_iterations`
  /// sub-steps, each integrating gravity, solving once with a soft position bias (contacts and
  /// joints are stiff damped springs), moving the bodies and relaxing once without bias (taking
  /// back the velocity the bias added); restitution after the last. position_iterations are not
  /// used.
  SoftStep,
  /// Sub-stepping with post-stabilisation: `velocity_iterations` sub-steps, each integrating
  /// gravity, solving once without position bias (rigid: no energy is added), moving the bodies
  /// and solving once more (relax); restitution after the last, then `position_iterations` NGS
  /// passes as in NonlinearGaussSeidel. The default: it holds every hard case (README "Solvers").
  SubstepNgs,
};

/// Every solver, in the order tests and benchmarks run them.
constexpr SolverType kAllSolvers[] = {SolverType::Baumgarte, SolverType::NonlinearGaussSeidel,
                                      SolverType::SoftStep, SolverType::SubstepNgs};

/// Solvers that split the step into velocity_iterations sub-steps.
constexpr bool usesSubsteps(SolverType solver) {
  return solver == SolverType::SoftStep || solver == SolverType::SubstepNgs;
}

/// The solver's name in scenes and on the command line: baumgarte, ngs, soft, substep.
inline const char* solverName(SolverType solver) {
  switch (solver) {
    case SolverType::Baumgarte:
      return "baumgarte";
    case SolverType::NonlinearGaussSeidel:
      return "ngs";
    case SolverType::SoftStep:
      return "soft";
    case SolverType::SubstepNgs:
      return "substep";
  }
  return "unknown";
}

/// Every solver's name for messages: "baumgarte, ngs, soft or substep".
inline std::string solverNameList() {
  std::string list;
  const size_t count = sizeof(kAllSolvers) / sizeof(kAllSolvers[0]);
  for (size_t i = 0; i < count; ++i) {
    list += i == 0 ? "" : i + 1 == count ? " or " : ", ";
    list += solverName(kAllSolvers[i]);
  }
  return list;
}

/// The inverse of solverName; false for an unknown name.
inline bool solverFromName(const std::string& name, SolverType* solver) {
  for (SolverType s : kAllSolvers) {
    if (name == solverName(s)) {
      *solver = s;
      return true;
    }
  }
  return false;
}

struct WorldDef {
  Vec2 gravity = Vec2(0.0, -9.81);  ///< m/s^2
  double timeStep = 0.01;           ///< s, the fixed step of World::step()
  int velocityIterations = 8;
  int positionIterations = 3;
  SolverType solver = SolverType::SubstepNgs;
  double baumgarte = 0.2;             ///< fraction of the penetration removed per step
  double linearSlop = 0.005;          ///< m, penetration left alone so contacts persist
  double speculativeDistance = 0.02;  ///< m, contacts are kept this far before touching
  double restitutionThreshold = 1.0;  ///< m/s, slower impacts do not bounce
  double maxPushVelocity = 3.0;       ///< m/s, the fastest Baumgarte pushes overlaps apart
  bool warmStarting = true;
  /// m/s, the fastest a dynamic body moves (as Box2D v3's maximumLinearSpeed): whatever a joint,
  /// a contact or a force asks, its centre of mass never crosses more than this times the step.
  /// Valid edits of a running world (joints anchored anywhere, teleports into piles, forces on
  /// light bodies) thus stay bounded instead of throwing bodies out of the world.
  double maxLinearSpeed = 400.0;
  /// rad, the most a dynamic body turns in one solver step (a sub-step for the sub-stepping
  /// solvers): 0.25 pi, as Box2D v3, so that a turn never aliases (a body spun half a turn per
  /// step would seem to stand still) and contacts found before the step stay meaningful. A body
  /// with a joint anchored r m from its centre of mass turns at most maxLinearSpeed / r too, so
  /// that the anchor moves no faster than a centre may (src/core/motion_limits.hpp, TurnCaps).
  double maxRotation = 0.25 * kPi;
  /// Soft step only: contacts push out of overlaps as damped springs of this frequency, capped
  /// at 0.15 x the sub-step rate (stiffer ones were measured to shake large pyramids apart) and
  /// twice as stiff against static and kinematic bodies; joints hold as springs of jointHertz,
  /// capped at 0.25 x the sub-step rate.
  double contactHertz = 120.0;        ///< Hz
  double contactDampingRatio = 10.0;  ///< strongly over-damped: no bounce from the push
  double jointHertz = 60.0;           ///< Hz
  double jointDampingRatio = 2.0;
  /// Threads that step the sub-stepping solvers (substep, soft): 1 runs on the calling thread;
  /// more share each colour of contacts among oneTBB tasks. The result is bit-identical for
  /// any number.
  int threads = 1;
  bool enableSleep = true;               ///< still islands stop costing anything
  double timeToSleep = 0.5;              ///< s an island must be still before it sleeps
  double sleepLinearTolerance = 0.01;    ///< m/s, slower counts as still
  double sleepAngularTolerance = 0.035;  ///< rad/s (2 degrees/s)
  /// Remove a dynamic body as soon as it is lost for good (World::takeLostBodies: fallen below
  /// every static body by more than their extent along gravity, with nothing to catch or hold
  /// it) instead of only reporting it and letting it fall until it leaves kWorldExtent.
  bool removeLostBodies = false;
};

/// Why a step removed a body.
enum class RemovalCause {
  LeftWorldExtent,  ///< its centre of mass left kWorldExtent (limits.hpp)
  Overflow,         ///< its state stopped being finite (the last guard: the motion limits
                    ///< keep every valid edit from reaching it)
  LostForGood,      ///< lost for good below the static bodies, with WorldDef::removeLostBodies
};

enum class ShapeKind { Box, Circle, Polygon };

/// Which shapes may touch, as in Box2D: two shapes of the same non-zero group always collide
/// (positive group) or never do (negative group); otherwise they collide only when each one's
/// mask has a bit of the other's category. The defaults collide with everything.
struct CollisionFilter {
  uint64_t categoryBits = 1;         ///< what this shape is
  uint64_t maskBits = ~uint64_t(0);  ///< what it collides with
  int32_t groupIndex = 0;
};

/// Whether two shapes with these filters may touch.
inline bool filtersAllowContact(const CollisionFilter& a, const CollisionFilter& b) {
  if (a.groupIndex == b.groupIndex && a.groupIndex != 0) return a.groupIndex > 0;
  return (a.maskBits & b.categoryBits) != 0 && (b.maskBits & a.categoryBits) != 0;
}

struct ShapeDef {
  ShapeKind kind = ShapeKind::Box;
  Vec2 size = Vec2(1.0, 1.0);  ///< box: full width and height (m)
  double radius = 0.5;         ///< circle (m)
  std::vector<Vec2> vertices;  ///< polygon: convex, any winding, body frame before `offset`
  Vec2 offset = Vec2::Zero();  ///< m, shape origin in the body frame
  double angle = 0.0;          ///< rad, shape rotation in the body frame
  double density = 1.0;        ///< kg/m^2
  double friction = 0.6;
  double restitution = 0.0;
  double reflectance = 0.0;  ///< a laser's intensity of a hit on this shape, >= 0
  CollisionFilter filter;
};

enum class BodyType { Static, Kinematic, Dynamic };

struct BodyDef {
  std::string name;  ///< unique in the world; may be empty for anonymous bodies
  BodyType type = BodyType::Dynamic;
  Vec2 position = Vec2::Zero();  ///< m, the body origin in the world
  double angle = 0.0;            ///< rad
  Vec2 linearVelocity =
      Vec2::Zero();              ///< m/s of the centre of mass (the origin for symmetric bodies)
  double angularVelocity = 0.0;  ///< rad/s
  double linearDamping = 0.0;    ///< 1/s
  double angularDamping = 0.0;   ///< 1/s
  bool bullet = false;           ///< continuous collision against every body, not only static ones
  /// false: a dynamic body is created asleep, as if it had come to rest, and costs nothing until
  /// something touches it or a method wakes it (a world that does not sleep wakes it at once).
  bool awake = true;
  double mass = 0.0;  ///< kg; > 0 overrides the shapes' densities (inertia scales with it)
  /// kg m^2 about the centre of mass; > 0 overrides what the shapes give (e.g. a URDF inertial).
  double inertia = 0.0;
  /// When set, the centre of mass is `localCenter` (body frame) instead of the shapes' centroid;
  /// without an `inertia` the shapes' inertia is moved there by the parallel axis theorem.
  bool useLocalCenter = false;
  Vec2 localCenter = Vec2::Zero();
  std::vector<ShapeDef> shapes;
};

enum class JointType { Revolute, Prismatic, Weld, Distance };

struct JointDef {
  std::string name;
  JointType type = JointType::Revolute;
  BodyId bodyA;
  BodyId bodyB;
  Vec2 anchor = Vec2::Zero();  ///< m, world point at creation
  Vec2 axis = Vec2(1.0, 0.0);  ///< prismatic: world direction at creation
  bool enableLimit = false;
  double lower = 0.0;  ///< rad (revolute) or m (prismatic)
  double upper = 0.0;
  bool enableMotor = false;
  double motorSpeed = 0.0;      ///< rad/s or m/s
  double maxMotorTorque = 0.0;  ///< N m (revolute) or N (prismatic)
  double length = 0.0;          ///< distance joint rest length (m); <= 0: current distance
  /// Distance joint: the anchor on body B is `anchorB` (m, world point at creation) when
  /// `useAnchorB` is set, otherwise body B's origin. `anchor` is then the anchor on body A.
  Vec2 anchorB = Vec2::Zero();
  bool useAnchorB = false;
  double frequency = 0.0;     ///< Hz, weld/distance spring; 0 = rigid
  double dampingRatio = 0.0;  ///< weld/distance spring: 0 = undamped, 1 = critically damped
  /// m, distance joint with frequency > 0: hard limits on the spring's length.
  double minLength = 0.0;
  double maxLength = std::numeric_limits<double>::infinity();
  bool collideConnected = false;
};

}  // namespace impulse2d
