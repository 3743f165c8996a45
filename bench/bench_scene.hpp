// The benchmark's scenes as engine-neutral data, so every engine builds exactly the same bodies,
// shapes and joints. The project's own scenes follow test/scenes/*.yaml
// (scripts/make_hard_scenes.py); the v3_ scenes follow Box2D v3.1.1's shared/benchmarks.c.
#pragma once

#include <impulse2d/defs.hpp>
#include <impulse2d/math.hpp>

#include <string>
#include <vector>

namespace impulse2d_bench {

using impulse2d::Vec2;

struct BenchShape {
  /// Polygon: convex, counter-clockwise, in the body frame, rounded by `radius` when it is > 0
  /// (Box2D v3's rounded polygons). Capsule: the segment vertices[0]-vertices[1] swept by
  /// `radius`. Engines without rounded shapes get the outline as a polygon (outlinePolygon).
  enum class Kind { Box, Circle, Polygon, Capsule };
  Kind kind = Kind::Box;
  Vec2 size = Vec2(1.0, 1.0);  ///< box: full width and height (m)
  Vec2 center = Vec2::Zero();  ///< box and circle: centre in the body frame (m)
  double radius = 0.5;         ///< circle, capsule; polygon rounding (0: sharp corners)
  std::vector<Vec2> vertices;  ///< polygon corners; capsule segment ends
  double density = 1.0;        ///< kg/m^2
  double friction = 0.6;
  double restitution = 0.0;
  impulse2d::CollisionFilter filter;  ///< Box2D's categories, masks and groups
};

struct BenchBody {
  bool isStatic = false;
  /// Moves at `velocity` and `angularVelocity` whatever touches it (Box2D's kinematic body); it
  /// has no mass of its own and is driven, so the error figures leave it out as a static one.
  bool isKinematic = false;
  Vec2 position = Vec2::Zero();  ///< m, the body origin, which is its centre of mass
  double angle = 0.0;
  Vec2 velocity = Vec2::Zero();  ///< m/s at the start
  double angularVelocity = 0.0;  ///< rad/s at the start
  double linearDamping = 0.0;    ///< 1/s
  bool awake = true;             ///< false: created asleep (scenes that sleep)
  double sleepThreshold = 0.0;   ///< m/s, Box2D v3's per-body threshold; 0: the engine's own
  bool canSleep = true;          ///< false: never sleeps (Box2D's enableSleep / allowSleep)
  int group = -1;                ///< >= 0: created and destroyed by the scene's events
  std::vector<BenchShape> shapes;
  /// Static or kinematic: no mass, nothing the solver moves.
  bool isDriven() const { return isStatic || isKinematic; }
};

/// A revolute joint at a world point; bodies index SceneSpec::bodies. Angles as in Box2D v3: the
/// joint angle is angleB - angleA - referenceAngle; limits bound it and the spring pulls it to 0.
struct BenchJoint {
  int bodyA = 0;
  int bodyB = 0;
  Vec2 anchor = Vec2::Zero();
  double referenceAngle = 0.0;
  bool enableLimit = false;
  double lower = 0.0, upper = 0.0;  ///< rad
  bool enableMotor = false;
  double motorSpeed = 0.0;      ///< rad/s
  double maxMotorTorque = 0.0;  ///< N m; at speed 0 the motor is joint friction
  double springHertz = 0.0;     ///< 0: no spring
  double springDampingRatio = 0.0;
};

/// Before step `step` (0-based), the bodies of `group` (BenchBody::group) are created, or
/// destroyed with their joints. Joints belong to the group of their bodyB.
struct SceneEvent {
  int step = 0;
  int group = 0;
  bool create = true;
};

/// What the error figures mean for a scene (see docs/benchmarks.md).
enum class SceneKind {
  Resting,    ///< should not move: drift, sink and penetration; stood = drift < tolerance
  Jointed,    ///< held by joints: joint gaps; stood = largest gap < tolerance
  Contained,  ///< moves inside a container: penetration, escapes; stood = none escaped
  Impact,     ///< free bodies colliding without gravity: momentum; stood = momentum kept
};

/// Where the bodies of a Contained scene must stay (their centres of mass).
struct Container {
  enum class Kind { Box, Disc, BodyBox };
  Kind kind = Kind::Box;
  Vec2 lower = Vec2::Zero(), upper = Vec2::Zero();  ///< Box (world) or BodyBox (its frame)
  Vec2 center = Vec2::Zero();                       ///< Disc
  double radius = 0.0;                              ///< Disc
  int body = -1;  ///< BodyBox: the container body (it is not counted itself)
};

/// A kinematic body steered along x: before step s (0-based) its velocity is set to carry its
/// centre in that step to (amplitude sin(rate s dt), y0), y0 where the scene puts it, as Box2D
/// v3's b2Body_SetTargetTransform does for master's junkyard.
struct Steering {
  int body = -1;           ///< -1: none
  double amplitude = 0.0;  ///< m
  double rate = 0.0;       ///< rad/s
};

struct SceneSpec {
  std::string name;
  SceneKind kind = SceneKind::Resting;
  std::vector<BenchBody> bodies;
  std::vector<BenchJoint> joints;
  std::vector<SceneEvent> events;  ///< sorted by step
  Vec2 gravity = Vec2(0.0, -9.81);
  /// Whether still bodies may sleep. The project's scenes never do (every engine does the same
  /// work each step); the v3_ scenes sleep where Box2D v3's benchmark lets them.
  bool sleep = false;
  /// false: the first step (which finds every contact) is run but not timed, as v3's app does.
  bool timeFirstStep = true;
  double duration = 10.0;   ///< s of simulated time per run
  double tolerance = 0.05;  ///< drift (Resting), joint gap (Jointed, m) or momentum (Impact)
  Container container;      ///< Contained
  bool scaling = false;     ///< a member of the scaling series (timed, fewer figures of interest)
  Steering steering;
  /// Whether a kinematic body moves: it does work on what it touches.
  bool hasMovingKinematic() const {
    if (steering.body >= 0) return true;
    for (const BenchBody& body : bodies) {
      if (body.isKinematic && (body.velocity.norm() > 0.0 || body.angularVelocity != 0.0)) {
        return true;
      }
    }
    return false;
  }
};

/// Mass (kg), rotational inertia about the centroid (kg m^2) and centroid (body frame) of one
/// shape from its density, on its true outline (capsules and rounded polygons included).
void shapeMass(const BenchShape& shape, double* mass, double* inertia, Vec2* centroid);

/// Mass and rotational inertia about the body origin of all the body's shapes; every engine is
/// given these, so all move the same bodies.
void nominalMass(const BenchBody& body, double* mass, double* inertia);

/// Moves the body's origin to its centre of mass (the shapes shift the other way), so that every
/// engine, whatever it takes as the body's origin, moves the same point.
void centreOnMass(BenchBody* body);

/// The outline of a capsule or rounded polygon as a convex polygon of at most `maxVertices`
/// points lying on the true outline (so it fits inside it); other polygons as they are.
std::vector<Vec2> outlinePolygon(const BenchShape& shape, int maxVertices);

/// The same shape as impulse2d describes it (capsules and rounded polygons as 16-point outlines).
impulse2d::ShapeDef toShapeDef(const BenchShape& shape);

/// Whether the shape is a capsule or a rounded polygon.
bool isRounded(const BenchShape& shape);

/// Every named scene, in a fixed order. `quick` shortens durations and shrinks the scaling series
/// and the v3_ scenes (to Box2D's own debug sizes) so the whole set runs in seconds.
std::vector<SceneSpec> makeScenes(bool quick);

/// Box2D v3.1.1's seven benchmark scenes and master's washer, compounds and junkyard
/// (bench_scenes_v3.cpp).
std::vector<SceneSpec> makeV3Scenes(bool quick);

}  // namespace impulse2d_bench
