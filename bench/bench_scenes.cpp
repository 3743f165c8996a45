// The project's named scenes. Sizes, gaps and materials match scripts/make_hard_scenes.py, so a
// figure here can be read next to the hard-case tests of the same scene.
#include "bench_scene.hpp"

#include <cmath>
#include <cstdint>

namespace impulse2d_bench {
namespace {

BenchBody box(double x, double y, double w, double h, bool isStatic = false, double density = 1.0) {
  BenchBody body;
  body.isStatic = isStatic;
  body.position = Vec2(x, y);
  BenchShape shape;
  shape.kind = BenchShape::Kind::Box;
  shape.size = Vec2(w, h);
  shape.density = density;
  body.shapes.push_back(shape);
  return body;
}

// The ground as in the hard cases: 1 m thick, its top at y = 0.
BenchBody ground(double width) { return box(0.0, -0.5, width, 1.0, true); }

void addPyramid(SceneSpec& scene, int rows, double topDensity = 1.0) {
  for (int row = 0; row < rows; ++row) {
    const int count = rows - row;
    for (int i = 0; i < count; ++i) {
      const double density = row == rows - 1 ? topDensity : 1.0;
      scene.bodies.push_back(box((i - 0.5 * (count - 1)), row + 0.5, 1.0, 1.0, false, density));
    }
  }
}

SceneSpec pyramid(const std::string& name, int rows, double duration) {
  SceneSpec scene;
  scene.name = name;
  scene.duration = duration;
  scene.tolerance = 0.10;  // test_hard_cases: largest sideways < 10 cm
  scene.bodies.push_back(ground(rows > 60 ? 3.0 * rows : 200.0));
  addPyramid(scene, rows);
  return scene;
}

SceneSpec stack(double duration) {
  SceneSpec scene;
  scene.name = "stack20";
  scene.duration = duration;
  scene.tolerance = 0.05;  // test_hard_cases: top drifts < 5 cm sideways
  scene.bodies.push_back(ground(200.0));
  for (int i = 0; i < 20; ++i) scene.bodies.push_back(box(0.0, 0.5 + i, 1.0, 1.0));
  return scene;
}

SceneSpec massRatio(double duration) {
  SceneSpec scene;
  scene.name = "mass_ratio";  // mass_ratio_pyramid.yaml: 10 rows, the top box 100 times heavier
  scene.duration = duration;
  scene.tolerance = 0.10;
  scene.bodies.push_back(ground(200.0));
  addPyramid(scene, 10, 100.0);
  return scene;
}

// bridge20.yaml: 20 planks (1 m x 12.5 cm, 20 kg/m^2) pinned end to end between two static posts,
// a 1 m box of 10 planks' mass in the middle.
SceneSpec bridge(double duration) {
  SceneSpec scene;
  scene.name = "bridge20";
  scene.kind = SceneKind::Jointed;
  scene.duration = duration;
  scene.tolerance = 0.05;
  const double plank = 1.0, deckY = 5.0 - 0.0625;
  scene.bodies.push_back(ground(200.0));
  scene.bodies.push_back(box(-0.5, 4.75, 1.0, 0.5, true));
  const int left = 1;
  scene.bodies.push_back(box(20 * plank + 0.5, 4.75, 1.0, 0.5, true));
  const int right = 2;
  const int first = static_cast<int>(scene.bodies.size());
  for (int i = 0; i < 20; ++i)
    scene.bodies.push_back(box((i + 0.5) * plank, deckY, plank, 0.125, false, 20.0));
  const double plankMass = plank * 0.125 * 20.0;
  scene.bodies.push_back(box(10.0 * plank, 5.5, 1.0, 1.0, false, 10.0 * plankMass));
  for (int i = 0; i <= 20; ++i) {
    const int a = i == 0 ? left : first + i - 1;
    const int b = i == 20 ? right : first + i;
    scene.joints.push_back({a, b, Vec2(i * plank, deckY)});
  }
  return scene;
}

// A 50 x 50 grid of circles (r = 0.4 m, 1 m apart), each pinned to its left and upper neighbour
// midway between them; the middle seven of the top row are static, the rest hangs from them.
SceneSpec jointGrid(double duration) {
  SceneSpec scene;
  scene.name = "joint_grid";
  scene.kind = SceneKind::Jointed;
  scene.duration = duration;
  scene.tolerance = 0.10;
  const int n = 50;
  for (int row = 0; row < n; ++row) {
    for (int col = 0; col < n; ++col) {
      BenchBody body;
      body.isStatic = row == 0 && std::abs(col - n / 2) <= 3;
      body.position = Vec2(col - 0.5 * (n - 1), 50.0 - row);
      BenchShape circle;
      circle.kind = BenchShape::Kind::Circle;
      circle.radius = 0.4;
      body.shapes.push_back(circle);
      scene.bodies.push_back(body);
      const int index = row * n + col;
      // Two static neighbours need no joint (Chipmunk aborts on one: its mass matrix is zero).
      const bool bothStatic = body.isStatic && scene.bodies[index - (col > 0 ? 1 : 0)].isStatic;
      if (col > 0 && !bothStatic) {
        scene.joints.push_back({index - 1, index, body.position - Vec2(0.5, 0.0)});
      }
      if (row > 0) scene.joints.push_back({index - n, index, body.position + Vec2(0.0, 0.5)});
    }
  }
  return scene;
}

// A fixed pseudo-random sequence (the scene must be the same everywhere, every run).
struct Lcg {
  uint64_t state = 0x9e3779b97f4a7c15ULL;
  double uniform(double lo, double hi) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return lo + (hi - lo) * static_cast<double>(state >> 11) / 9007199254740992.0;
  }
};

std::vector<Vec2> regularPolygon(int sides, double circumradius) {
  std::vector<Vec2> vertices;
  for (int k = 0; k < sides; ++k) {
    const double a = 2.0 * impulse2d::kPi * k / sides;
    vertices.emplace_back(circumradius * std::cos(a), circumradius * std::sin(a));
  }
  return vertices;
}

// 500 boxes, circles and regular polygons (3, 5, 6 sides) dropped in a 20 x 25 grid into a
// container 20 m wide with 30 m walls.
SceneSpec fallingShapes(double duration) {
  SceneSpec scene;
  scene.name = "falling_shapes";
  scene.kind = SceneKind::Contained;
  scene.duration = duration;
  scene.bodies.push_back(box(0.0, -0.5, 24.0, 1.0, true));
  scene.bodies.push_back(box(-10.5, 15.0, 1.0, 30.0, true));
  scene.bodies.push_back(box(10.5, 15.0, 1.0, 30.0, true));
  scene.container.lower = Vec2(-10.0, 0.0);
  scene.container.upper = Vec2(10.0, 60.0);
  Lcg random;
  const int sides[3] = {3, 5, 6};
  for (int row = 0; row < 25; ++row) {
    for (int col = 0; col < 20; ++col) {
      BenchBody body;
      body.position = Vec2(-9.5 + col, 2.0 + 1.05 * row);
      body.angle = random.uniform(-0.5, 0.5);
      BenchShape shape;
      switch ((row + col) % 3) {
        case 0:
          shape.kind = BenchShape::Kind::Box;
          shape.size = Vec2(random.uniform(0.4, 0.9), random.uniform(0.4, 0.9));
          break;
        case 1:
          shape.kind = BenchShape::Kind::Circle;
          shape.radius = random.uniform(0.2, 0.45);
          break;
        default:
          shape.kind = BenchShape::Kind::Polygon;
          shape.radius = 0.0;
          shape.vertices = regularPolygon(sides[(row + 2 * col) % 3], random.uniform(0.3, 0.45));
          break;
      }
      body.shapes.push_back(shape);
      scene.bodies.push_back(body);
    }
  }
  return scene;
}

}  // namespace

std::vector<SceneSpec> makeScenes(bool quick) {
  const double q = quick ? 0.1 : 1.0;  // quick runs a tenth of the simulated time
  std::vector<SceneSpec> scenes;
  scenes.push_back(pyramid("pyramid100", 100, quick ? 0.25 : 2.0));
  scenes.push_back(pyramid("pyramid20", 20, 10.0 * q));
  scenes.push_back(stack(10.0 * q));
  scenes.push_back(massRatio(10.0 * q));
  scenes.push_back(bridge(10.0 * q));
  scenes.push_back(jointGrid(quick ? 0.25 : 5.0));
  scenes.push_back(fallingShapes(quick ? 0.5 : 6.0));
  // Scaling series: bases 14 .. 200 (105 .. 20,100 boxes), one simulated second each, timed.
  const std::vector<int> bases =
      quick ? std::vector<int>{14, 32} : std::vector<int>{14, 20, 32, 45, 63, 100, 141, 200};
  for (const int base : bases) {
    SceneSpec scene =
        pyramid("scaling_" + std::to_string(base * (base + 1) / 2), base, quick ? 0.25 : 1.0);
    scene.scaling = true;
    scenes.push_back(scene);
  }
  for (SceneSpec& scene : makeV3Scenes(quick)) scenes.push_back(std::move(scene));
  return scenes;
}

}  // namespace impulse2d_bench
