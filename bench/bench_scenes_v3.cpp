// Box2D v3.1.1's benchmark scenes and three of master's (shared/benchmarks.c, its benchmark app's
// step counts), built as the release build builds them; `quick` takes Box2D's debug sizes and a
// tenth of the steps.
// Geometry Box2D has and impulse2d has not is described as Box2D has it (capsules, rounded
// polygons: BenchShape), or by its closest equivalent, each noted where it is built and in
// docs/benchmarks.md: segments and chains as thin static boxes whose face is the segment.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "bench_human.hpp"
#include "bench_scene.hpp"

namespace impulse2d_bench {
namespace {

constexpr double kPi = impulse2d::kPi;

SceneSpec v3Scene(const std::string& name, SceneKind kind, int steps) {
  SceneSpec scene;
  scene.name = "v3_" + name;
  scene.kind = kind;
  scene.gravity = Vec2(0.0, -10.0);  // b2DefaultWorldDef
  scene.sleep = true;                // likewise; three scenes turn it off
  scene.timeFirstStep = false;       // the app times steps 2..N
  scene.duration = steps / 60.0;     // at the app's 60 Hz: exactly its step count
  return scene;
}

BenchShape box(double halfWidth, double halfHeight, const Vec2& center = Vec2::Zero()) {
  BenchShape shape;
  shape.kind = BenchShape::Kind::Box;
  shape.size = Vec2(2.0 * halfWidth, 2.0 * halfHeight);
  shape.center = center;
  return shape;
}

BenchShape circle(double radius) {
  BenchShape shape;
  shape.kind = BenchShape::Kind::Circle;
  shape.radius = radius;
  return shape;
}

BenchBody body(const Vec2& position, bool isStatic, const BenchShape& shape) {
  BenchBody b;
  b.isStatic = isStatic;
  b.position = position;
  b.shapes.push_back(shape);
  return b;
}

int add(SceneSpec& scene, const BenchBody& b) {
  scene.bodies.push_back(b);
  return static_cast<int>(scene.bodies.size()) - 1;
}

BenchJoint pin(int a, int b, const Vec2& anchor) {
  BenchJoint joint;
  joint.bodyA = a;
  joint.bodyB = b;
  joint.anchor = anchor;
  return joint;
}

// The motor that turns the tumbler's drum about `anchor`: 25 degrees/s, with all the torque it
// needs.
BenchJoint drumMotor(int ground, int drum, const Vec2& anchor) {
  BenchJoint motor = pin(ground, drum, anchor);
  motor.enableMotor = true;
  motor.motorSpeed = (kPi / 180.0) * 25.0;
  motor.maxMotorTorque = 1e8;
  return motor;
}

// Boxes of half-width `extent` in rows of base .. 1, as CreateLargePyramid and
// CreateSmallPyramid place them: row i at y = (2i + 1) extent + baseY, its first box at
// x = (i + 1) extent + left.
void addPyramid(SceneSpec& scene, int base, double extent, double left, double baseY) {
  for (int i = 0; i < base; ++i) {
    const double y = (2.0 * i + 1.0) * extent + baseY;
    for (int j = i; j < base; ++j) {
      const double x = (i + 1.0) * extent + 2.0 * (j - i) * extent + left;
      add(scene, body(Vec2(x, y), false, box(extent, extent)));
    }
  }
}

// CreateJointGrid: N x N circles 1 m apart in columns k (x = k) and rows i (y = -i), each pinned
// to the one above and the one to its left midway between them; the middle seven of the top row
// are static. The circles' filter (category 2, mask ~2) keeps them from ever touching each other.
// v3 also pins the six pairs of static neighbours to each other; those joints do nothing and are
// left out (Chipmunk aborts on a joint between two static bodies).
SceneSpec jointGrid(bool quick) {
  SceneSpec scene = v3Scene("joint_grid", SceneKind::Jointed, quick ? 50 : 500);
  scene.sleep = false;
  scene.tolerance = 0.10;
  const int n = quick ? 10 : 100;
  BenchShape shape = circle(0.4);
  shape.filter.categoryBits = 2;
  shape.filter.maskBits = ~2u;  // a 32-bit complement in uint64 maskBits, as in benchmarks.c
  for (int k = 0; k < n; ++k) {
    for (int i = 0; i < n; ++i) {
      const bool isStatic = k >= n / 2 - 3 && k <= n / 2 + 3 && i == 0;
      const int index = add(scene, body(Vec2(k, -i), isStatic, shape));
      if (i > 0) scene.joints.push_back(pin(index - 1, index, Vec2(k, -i + 0.5)));
      if (k > 0 && !(isStatic && scene.bodies[index - n].isStatic)) {
        scene.joints.push_back(pin(index - n, index, Vec2(k - 0.5, -i)));
      }
    }
  }
  return scene;
}

// CreateLargePyramid: unit boxes, base 100, on a 200 m x 2 m ground whose top is y = 0.
SceneSpec largePyramid(bool quick) {
  SceneSpec scene = v3Scene("large_pyramid", SceneKind::Resting, quick ? 50 : 500);
  scene.sleep = false;
  scene.tolerance = 0.10;
  const int base = quick ? 20 : 100;
  add(scene, body(Vec2(0.0, -1.0), true, box(100.0, 1.0)));
  addPyramid(scene, base, 0.5, -0.5 * base, 0.0);
  return scene;
}

// CreateManyPyramids: rows of small pyramids (base 10, unit boxes), each row on a segment 11 m
// above the last. A segment is a static box 10 cm thick whose top face is the segment (the row
// of pyramids below ends 1 m under it).
SceneSpec manyPyramids(bool quick) {
  SceneSpec scene = v3Scene("many_pyramids", SceneKind::Resting, quick ? 20 : 200);
  scene.sleep = false;
  scene.tolerance = 0.10;
  const int baseCount = 10, rowCount = quick ? 5 : 20, columnCount = quick ? 5 : 20;
  const double extent = 0.5, thickness = 0.1;
  const double groundDeltaY = 2.0 * extent * (baseCount + 1.0);
  const double groundWidth = 2.0 * extent * columnCount * (baseCount + 1.0);
  BenchBody ground;
  ground.isStatic = true;
  for (int i = 0; i < rowCount; ++i) {
    ground.shapes.push_back(
        box(groundWidth, 0.5 * thickness, Vec2(0.0, i * groundDeltaY - 0.5 * thickness)));
  }
  add(scene, ground);
  const double baseWidth = 2.0 * extent * baseCount;
  double baseY = 0.0;
  for (int row = 0; row < rowCount; ++row) {
    for (int column = 0; column < columnCount; ++column) {
      const double centerX =
          -0.5 * groundWidth + column * (baseWidth + 2.0 * extent) + extent;  // CreateSmallPyramid
      addPyramid(scene, baseCount, extent, centerX - 0.5, baseY);
    }
    baseY += groundDeltaY;
  }
  return scene;
}

// CreateRain / StepRain: rows of ground 45 m apart made of 0.5 m boxes (each its own static body
// here; v3 puts them all on one), and every eighth step a column of groups of ragdolls (one group
// per row) appears 40 m above its ground; once every column has one, each eighth step destroys
// the oldest column and creates it again.
SceneSpec rain(bool quick) {
  // Quick: 200 steps, so the first ragdolls (falling 40 m, about 170 steps) land.
  const int steps = quick ? 200 : 1000;
  SceneSpec scene = v3Scene("rain", SceneKind::Jointed, steps);
  scene.tolerance = 0.05;
  const int rowCount = quick ? 3 : 5, columnCount = quick ? 10 : 40, groupSize = quick ? 2 : 5;
  const int gridCount = quick ? 200 : 500, delay = quick ? 0x1F : 0x7;
  const double gridSize = 0.5;
  for (int i = 0; i < rowCount; ++i) {
    double x = -0.5 * gridCount * gridSize;
    for (int j = 0; j <= gridCount; ++j) {
      add(scene, body(Vec2(x, 45.0 * i), true, box(0.5 * gridSize, 0.5 * gridSize)));
      x += gridSize;
    }
  }
  // One group per (row, column), as v3's g_rainData.groups.
  const double span = gridCount * gridSize, groupDistance = span / columnCount;
  for (int row = 0; row < rowCount; ++row) {
    for (int column = 0; column < columnCount; ++column) {
      Vec2 position(-0.5 * span + groupDistance * (column + 0.5), 40.0 + 45.0 * row);
      for (int i = 0; i < groupSize; ++i) {
        addHuman(scene, row * columnCount + column, position, i + 1);
        position.x() += 0.5;
      }
    }
  }
  int columnsFilled = 0, nextColumn = 0;
  for (int step = 0; step < steps; ++step) {
    if ((step & delay) != 0) continue;
    if (columnsFilled < columnCount) {
      for (int row = 0; row < rowCount; ++row) {
        scene.events.push_back({step, row * columnCount + columnsFilled, true});
      }
      ++columnsFilled;
    } else {
      for (int row = 0; row < rowCount; ++row) {
        scene.events.push_back({step, row * columnCount + nextColumn, false});
        scene.events.push_back({step, row * columnCount + nextColumn, true});
      }
      nextColumn = (nextColumn + 1) % columnCount;
    }
  }
  return scene;
}

// CreateSmash: no gravity; an 8 m box of density 8 at 40 m/s hits a block of 0.4 m boxes that
// touch edge to edge and start asleep.
SceneSpec smash(bool quick) {
  // Quick: 90 steps, so the impact (at 1.15 s) happens.
  SceneSpec scene = v3Scene("smash", SceneKind::Impact, quick ? 90 : 300);
  scene.gravity = Vec2::Zero();
  scene.tolerance = 1e-3;
  BenchBody ram = body(Vec2(-20.0, 0.0), false, box(4.0, 4.0));
  ram.velocity = Vec2(40.0, 0.0);
  ram.shapes[0].density = 8.0;
  add(scene, ram);
  const double d = 0.4;
  const int columns = quick ? 20 : 120, rows = quick ? 10 : 80;
  for (int i = 0; i < columns; ++i) {
    for (int j = 0; j < rows; ++j) {
      BenchBody block =
          body(Vec2(i * d + 30.0, (j - rows / 2.0) * d), false, box(0.5 * d, 0.5 * d));
      block.awake = false;
      add(scene, block);
    }
  }
  return scene;
}

// CreateSpinner: a 40 m drum (a chain loop of 360 segments) and a 40.4 m rounded blade turned by
// a motor at 5 rad/s through a pile of capsules, circles and squares. Pinned 20 m below the
// drum's centre, the blade reaches 0.2 m past the chain; in v3 it grinds through the chain once a
// turn (its continuous collision leaves out a one-sided chain the blade's centre never crosses,
// and its soft contact gives). Each segment here is a static box 1 m thick outside the drum,
// which continuous collision would stop the blade at, in v3 and impulse2d alike: the boxes' inner
// faces lie on a circle of 40.25 m, so the blade turns as in v3, just clear of the drum.
SceneSpec spinner(bool quick) {
  SceneSpec scene = v3Scene("spinner", SceneKind::Contained, quick ? 140 : 1400);
  const double drumRadius = 40.25;
  scene.container.kind = Container::Kind::Disc;
  scene.container.center = Vec2(0.0, 32.0);
  scene.container.radius = drumRadius;
  const int pointCount = 360;
  const double thickness = 1.0;
  std::vector<Vec2> points;
  const impulse2d::Rot turn(-2.0 * kPi / pointCount);
  Vec2 p(drumRadius, 0.0);
  for (int i = 0; i < pointCount; ++i) {
    points.emplace_back(p.x(), p.y() + 32.0);
    p = turn.apply(p);
  }
  int ground = -1;
  for (int i = 0; i < pointCount; ++i) {
    const Vec2 a = points[i], b = points[(i + 1) % pointCount];
    const Vec2 along = (b - a).normalized();
    const Vec2 outward(-along.y(), along.x());  // the points run clockwise: left is outside
    BenchBody segment = body(0.5 * (a + b) + 0.5 * thickness * outward, true,
                             box(0.5 * (b - a).norm(), 0.5 * thickness));
    segment.angle = std::atan2(along.y(), along.x());
    segment.shapes[0].friction = 0.1;
    const int index = add(scene, segment);
    if (ground < 0) ground = index;
  }

  BenchShape blade;
  blade.kind = BenchShape::Kind::Polygon;
  blade.vertices = {Vec2(-0.4, -20.0), Vec2(0.4, -20.0), Vec2(0.4, 20.0), Vec2(-0.4, 20.0)};
  blade.radius = 0.2;  // b2MakeRoundedBox(0.4, 20, 0.2)
  blade.friction = 0.0;
  BenchBody rotor = body(Vec2(0.0, 12.0), false, blade);
  rotor.canSleep = false;
  const int spinner = add(scene, rotor);
  BenchJoint motor = pin(ground, spinner, Vec2(0.0, 12.0));
  motor.enableMotor = true;
  motor.motorSpeed = 5.0;
  motor.maxMotorTorque = 40000.0;
  scene.joints.push_back(motor);

  BenchShape capsule;
  capsule.kind = BenchShape::Kind::Capsule;
  capsule.vertices = {Vec2(-0.25, 0.0), Vec2(0.25, 0.0)};
  capsule.radius = 0.25;
  const BenchShape shapes[3] = {capsule, circle(0.35), box(0.35, 0.35)};
  const int bodyCount = quick ? 499 : 3038;
  double x = -24.0, y = 2.0;
  for (int i = 0; i < bodyCount; ++i) {
    BenchShape shape = shapes[i % 3];
    shape.friction = 0.1;
    shape.restitution = 0.1;
    shape.density = 0.25;
    add(scene, body(Vec2(x, y), false, shape));
    x += 1.0;
    if (x > 24.0) {
      x = -24.0;
      y += 1.0;
    }
  }
  return scene;
}

// CreateTumbler: a 20 m square drum of four walls (density 50) turned at 25 degrees/s by a motor
// about its centre, holding a grid of 0.25 m boxes. The ground body has no shape: it only
// anchors the motor.
SceneSpec tumbler(bool quick) {
  SceneSpec scene = v3Scene("tumbler", SceneKind::Contained, quick ? 75 : 750);
  BenchBody ground;
  ground.isStatic = true;
  const int groundIndex = add(scene, ground);
  BenchBody drum;
  drum.position = Vec2(0.0, 10.0);
  for (const auto& [half, center] : {std::make_pair(Vec2(0.5, 10.0), Vec2(10.0, 0.0)),
                                     std::make_pair(Vec2(0.5, 10.0), Vec2(-10.0, 0.0)),
                                     std::make_pair(Vec2(10.0, 0.5), Vec2(0.0, 10.0)),
                                     std::make_pair(Vec2(10.0, 0.5), Vec2(0.0, -10.0))}) {
    BenchShape wall = box(half.x(), half.y(), center);
    wall.density = 50.0;
    drum.shapes.push_back(wall);
  }
  const int drumIndex = add(scene, drum);
  scene.joints.push_back(drumMotor(groundIndex, drumIndex, Vec2(0.0, 10.0)));
  scene.container.kind = Container::Kind::BodyBox;
  scene.container.body = drumIndex;
  scene.container.lower = Vec2(-9.5, -9.5);
  scene.container.upper = Vec2(9.5, 9.5);

  const int gridCount = quick ? 20 : 45;
  double y = -0.2 * gridCount + 10.0;
  for (int i = 0; i < gridCount; ++i) {
    double x = -0.2 * gridCount;
    for (int j = 0; j < gridCount; ++j) {
      add(scene, body(Vec2(x, y), false, box(0.125, 0.125)));
      x += 0.4;
    }
    y += 0.4;
  }
  return scene;
}

// CreateWasher (master): a kinematic drum of 36 wall segments 16-18 m out, each a tenth of its
// arc longer at both ends, and four paddles 14-16 m out, turning at 25 degrees/s about (0, 10) and
// drifting at (1, -2) mm/s as master's does, holding a grid of 0.2 m boxes.
SceneSpec washer(bool quick) {
  SceneSpec scene = v3Scene("washer", SceneKind::Contained, quick ? 50 : 500);
  const Vec2 center(0.0, 10.0);
  BenchBody drum;
  drum.isKinematic = true;
  drum.position = center;
  drum.velocity = Vec2(0.001, -0.002);
  drum.angularVelocity = (kPi / 180.0) * 25.0;
  const double r0 = 14.0, r1 = 16.0, r2 = 18.0, step = kPi / 18.0;
  auto quad = [](double inner, double outer, double from, double to) {
    BenchShape shape;  // counter-clockwise: out along `from`, round the outer arc, back in
    shape.kind = BenchShape::Kind::Polygon;
    shape.radius = 0.0;
    shape.vertices = {
        inner * Vec2(std::cos(from), std::sin(from)), outer * Vec2(std::cos(from), std::sin(from)),
        outer * Vec2(std::cos(to), std::sin(to)), inner * Vec2(std::cos(to), std::sin(to))};
    return shape;
  };
  for (int i = 0; i < 36; ++i) {
    drum.shapes.push_back(quad(r1, r2, i * step - 0.1 * step, (i + 1) * step + 0.1 * step));
    if (i % 9 == 0) drum.shapes.push_back(quad(r0, r1, i * step, (i + 1) * step));
  }
  add(scene, drum);
  scene.container.kind = Container::Kind::Disc;
  scene.container.center = center;
  scene.container.radius = r1;

  const int gridCount = quick ? 20 : 90;
  const double a = 0.1;
  double y = -1.1 * a * gridCount + 10.0;
  for (int i = 0; i < gridCount; ++i) {
    double x = -1.1 * a * gridCount;
    for (int j = 0; j < gridCount; ++j) {
      add(scene, body(Vec2(x, y), false, box(a, a)));
      x += 2.1 * a;
    }
    y += 2.1 * a;
  }
  return scene;
}

// Master's compounds and junkyard stand on one static body of a few hundred boxes: a floor of
// `floorCount` boxes 1 m apart from x = -halfWidth and two walls of `wallCount` at +-halfWidth.
// impulse2d takes at most 64 shapes a body, so each row goes into static bodies of at most 50
// boxes, split evenly (compounds: the floor and each wall in halves).
void addBoxGround(SceneSpec& scene, double halfWidth, int floorCount, int wallCount) {
  std::vector<BenchShape> floor, left, right;
  for (int i = 0; i < floorCount; ++i) floor.push_back(box(0.55, 0.5, Vec2(-halfWidth + i, 0.0)));
  for (int i = 0; i < wallCount; ++i) {
    left.push_back(box(0.5, 0.55, Vec2(-halfWidth, 1.0 + i)));
    right.push_back(box(0.5, 0.55, Vec2(halfWidth, 1.0 + i)));
  }
  for (const std::vector<BenchShape>* row : {&floor, &left, &right}) {
    const size_t count = row->size(), chunks = (count + 49) / 50;
    for (size_t k = 0; k < chunks; ++k) {
      BenchBody ground;
      ground.isStatic = true;
      ground.shapes.assign(row->begin() + static_cast<std::ptrdiff_t>(k * count / chunks),
                           row->begin() + static_cast<std::ptrdiff_t>((k + 1) * count / chunks));
      add(scene, ground);
    }
  }
}

// CreateCompounds (master, from its samples' barrel): 3,000 bodies of two overlapping triangles
// each (friction 0.5) dropped in columns into a box 80 m wide with 100 m walls. Master's ground
// is one body of 281 boxes and a segment 80 m below; here the boxes are six static bodies
// (addBoxGround) and the segment a 2 cm static box.
SceneSpec compounds(bool quick) {
  SceneSpec scene = v3Scene("compounds", SceneKind::Contained, quick ? 50 : 500);
  addBoxGround(scene, 40.0, 81, 100);
  add(scene, body(Vec2(0.0, -80.0), true, box(800.0, 0.01)));
  scene.container.kind = Container::Kind::Box;
  scene.container.lower = Vec2(-40.0, 0.0);
  scene.container.upper = Vec2(40.0, 400.0);

  BenchShape leftTriangle, rightTriangle;
  leftTriangle.kind = rightTriangle.kind = BenchShape::Kind::Polygon;
  leftTriangle.radius = rightTriangle.radius = 0.0;
  leftTriangle.vertices = {Vec2(-1.0, 0.0), Vec2(0.5, 1.0), Vec2(0.0, 2.0)};
  rightTriangle.vertices = {Vec2(1.0, 0.0), Vec2(0.0, 2.0), Vec2(-0.5, 1.0)};
  leftTriangle.friction = rightTriangle.friction = 0.5;
  const int columnCount = quick ? 10 : 20, rowCount = quick ? 40 : 150;
  const double shift = 2.0, extraY = 0.25, centerX = shift * columnCount / 2.0 - 1.0;
  const double centerY = 1.15 / 2.0, yStart = 5.0;
  double side = 0.25;
  for (int i = 0; i < columnCount; ++i) {
    const double x = i * shift - centerX;
    for (int j = 0; j < rowCount; ++j) {
      BenchBody compound =
          body(Vec2(x + side, j * (shift + extraY) + centerY + yStart), false, leftTriangle);
      compound.shapes.push_back(rightTriangle);
      centreOnMass(&compound);  // every engine then reports the same point (metrics.cpp)
      side = -side;
      add(scene, compound);
    }
  }
  return scene;
}

// CreateJunkyard (master): 8,000 pentagons (a hull of 5 points of the Fibonacci spiral on a
// circle of 0.25 m) dropped in 200 columns of 40 into a box 160 m wide with 50 m walls, and a
// kinematic 4 x 8 m pusher steered along the floor to x = 60 sin(0.2 t). Master's ground is one
// body of 261 boxes: here seven static bodies (addBoxGround). Master's pusher has its box 4 m
// above its origin; here the body is at the box's centre, steered the same way.
SceneSpec junkyard(bool quick) {
  SceneSpec scene = v3Scene("junkyard", SceneKind::Contained, quick ? 100 : 800);
  addBoxGround(scene, 80.0, 161, 50);
  scene.container.kind = Container::Kind::Box;
  scene.container.lower = Vec2(-80.0, 0.0);
  scene.container.upper = Vec2(80.0, 400.0);

  const double radius = 0.25, phi = kPi * (std::sqrt(5.0) - 1.0);
  std::vector<std::pair<double, Vec2>> points;  // by angle: the hull, counter-clockwise
  for (int i = 0; i < 5; ++i) {
    const double theta = phi * i;
    const Vec2 p = radius * Vec2(std::cos(theta), std::sin(theta));
    points.emplace_back(std::atan2(p.y(), p.x()), p);
  }
  std::sort(points.begin(), points.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  BenchShape pentagon;
  pentagon.kind = BenchShape::Kind::Polygon;
  pentagon.radius = 0.0;
  for (const auto& [angle, p] : points) pentagon.vertices.push_back(p);

  const int columnCount = 200, rowCount = quick ? 2 : 40;
  double side = -0.1;
  for (int i = 0; i < columnCount; ++i) {
    const double x = 1.5 * (2.0 * i - columnCount) * radius;
    for (int j = 0; j < rowCount; ++j) {
      BenchBody piece = body(Vec2(x + side, 4.0 * j * radius + 15.0), false, pentagon);
      centreOnMass(&piece);  // every engine then reports the same point (metrics.cpp)
      side = -side;
      add(scene, piece);
    }
  }
  BenchBody pusher = body(Vec2(0.0, 4.0), false, box(2.0, 4.0));
  pusher.isKinematic = true;
  scene.steering.body = add(scene, pusher);
  scene.steering.amplitude = 60.0;
  scene.steering.rate = 0.2;
  return scene;
}

}  // namespace

std::vector<SceneSpec> makeV3Scenes(bool quick) {
  std::vector<SceneSpec> scenes;
  scenes.push_back(jointGrid(quick));
  scenes.push_back(largePyramid(quick));
  scenes.push_back(manyPyramids(quick));
  scenes.push_back(rain(quick));
  scenes.push_back(smash(quick));
  scenes.push_back(spinner(quick));
  scenes.push_back(tumbler(quick));
  scenes.push_back(washer(quick));
  scenes.push_back(compounds(quick));
  scenes.push_back(junkyard(quick));
  return scenes;
}

}  // namespace impulse2d_bench
