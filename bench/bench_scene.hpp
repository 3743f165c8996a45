// The benchmark's scenes as engine-neutral data, so every engine builds exactly the same bodies,
// shapes and joints. Geometry follows test/scenes/*.yaml (scripts/make_hard_scenes.py): unit
// boxes placed edge to edge without gaps, friction 0.6, density 1, the ground's top at y = 0.
#pragma once

#include <impulse2d/defs.hpp>
#include <impulse2d/math.hpp>

#include <string>
#include <vector>

namespace impulse2d_bench {

using impulse2d::Vec2;

struct BenchShape {
  enum class Kind { Box, Circle, Polygon };
  Kind kind = Kind::Box;
  Vec2 size = Vec2(1.0, 1.0);  ///< box: full width and height (m)
  double radius = 0.5;         ///< circle (m)
  /// polygon: counter-clockwise, centred on its centroid (so the body origin is the centre of
  /// mass in every engine); regular, so an engine's skin can be taken off by scaling.
  std::vector<Vec2> vertices;
  double density = 1.0;  ///< kg/m^2
  double friction = 0.6;
};

struct BenchBody {
  bool isStatic = false;
  Vec2 position = Vec2::Zero();  ///< m, the centre of mass
  double angle = 0.0;
  BenchShape shape;
};

/// A revolute joint at a world point; bodies index SceneSpec::bodies.
struct BenchJoint {
  int bodyA = 0;
  int bodyB = 0;
  Vec2 anchor = Vec2::Zero();
};

/// What the error figures mean for a scene (see docs/benchmarks.md).
enum class SceneKind {
  Resting,  ///< should not move: drift, sink and penetration; stood = drift < tolerance
  Jointed,  ///< held by joints: joint gaps; stood = largest gap < tolerance
  Falling,  ///< settles in a container: penetration; stood = every body still inside
};

struct SceneSpec {
  std::string name;
  SceneKind kind = SceneKind::Resting;
  std::vector<BenchBody> bodies;
  std::vector<BenchJoint> joints;
  double duration = 10.0;   ///< s of simulated time per run
  double tolerance = 0.05;  ///< m: drift (Resting) or joint gap (Jointed) that still "stood"
  /// Falling: the inside of the container (lower-left, upper-right corners; m).
  Vec2 boxLower = Vec2::Zero(), boxUpper = Vec2::Zero();
  bool scaling = false;  ///< a member of the scaling series (timed, fewer figures of interest)
};

/// Mass (kg) and rotational inertia about the centroid (kg m^2) of the scene shape, from its
/// density; every engine is given these, so all move the same bodies.
void nominalMass(const BenchShape& shape, double* mass, double* inertia);

/// The same shape as impulse2d describes it.
impulse2d::ShapeDef toShapeDef(const BenchShape& shape);

/// Every named scene, in a fixed order. `quick` shortens durations and shrinks the scaling series
/// so the whole set runs in seconds.
std::vector<SceneSpec> makeScenes(bool quick);

}  // namespace impulse2d_bench
