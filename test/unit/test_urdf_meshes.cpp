// Collision meshes in URDFs (issue 25): read with assimp from package:// names, projected along
// the plane normal, their convex hull covered by polygons of at most 16 vertices that reach at
// most 1 mm outside it; an unreadable mesh refuses the model with a message naming it.
#include <impulse2d/limits.hpp>
#include <impulse2d/urdf.hpp>
#include <impulse2d/world.hpp>

#include "../../src/urdf/mesh_footprint.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace impulse2d {
namespace {

using urdf_detail::convexHull;
using urdf_detail::footprintPolygons;
using urdf_detail::kFootprintTolerance;

constexpr double kPi = 3.14159265358979323846;

std::vector<Vec2> regularPolygon(int n, double radius) {
  std::vector<Vec2> v;
  for (int k = 0; k < n; ++k) {
    v.emplace_back(radius * std::cos(2 * kPi * k / n), radius * std::sin(2 * kPi * k / n));
  }
  return v;
}

double area(const std::vector<Vec2>& p) {
  double a = 0.0;
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec2& u = p[i];
    const Vec2& w = p[(i + 1) % p.size()];
    a += u.x() * w.y() - u.y() * w.x();
  }
  return 0.5 * a;
}

// How far `point` lies outside the convex polygon `hull` (0 inside), counter-clockwise.
double outside(const Vec2& point, const std::vector<Vec2>& hull) {
  double worst = 0.0;
  for (size_t i = 0; i < hull.size(); ++i) {
    const Vec2 edge = hull[(i + 1) % hull.size()] - hull[i];
    const Vec2 normal = Vec2(edge.y(), -edge.x()).normalized();
    worst = std::max(worst, (point - hull[i]).dot(normal));
  }
  return worst;
}

void expectCovers(const std::vector<std::vector<Vec2>>& pieces, const std::vector<Vec2>& hull) {
  double total = 0.0;
  for (const std::vector<Vec2>& piece : pieces) {
    EXPECT_LE(piece.size(), static_cast<size_t>(kMaxPolygonVertices));
    EXPECT_GE(piece.size(), 3u);
    EXPECT_GT(area(piece), 0.0);  // counter-clockwise and convex (checked by the world below)
    for (const Vec2& v : piece) EXPECT_LE(outside(v, hull), kFootprintTolerance + 1e-12);
    total += area(piece);
  }
  EXPECT_GE(total, area(hull) * (1.0 - 1e-12));  // the pieces cover the hull
}

TEST(MeshFootprint, HullsAreCounterClockwiseWithoutInnerOrCollinearPoints) {
  const std::vector<Vec2> hull = convexHull({Vec2(0, 0), Vec2(1, 0), Vec2(0.5, 0), Vec2(1, 1),
                                             Vec2(0, 1), Vec2(0.5, 0.5), Vec2(0.2, 0.7)});
  ASSERT_EQ(hull.size(), 4u);
  EXPECT_NEAR(area(hull), 1.0, 1e-12);
  EXPECT_TRUE(convexHull({Vec2(0, 0), Vec2(1, 1), Vec2(2, 2)}).empty());  // no area
}

TEST(MeshFootprint, FewVerticesWithinAMillimetreOrAnExactFan) {
  // A small round part: one polygon of at most 16 vertices, at most 1 mm outside.
  const std::vector<Vec2> small = regularPolygon(40, 0.02);
  const auto one = footprintPolygons(small, kMaxPolygonVertices, kFootprintTolerance);
  ASSERT_EQ(one.size(), 1u);
  expectCovers(one, small);
  // A 1 m drum: 16 vertices would reach 2 cm out, so the simplified hull is cut into a fan of
  // pieces whose union is it.
  const std::vector<Vec2> big = regularPolygon(64, 1.0);
  const auto fan = footprintPolygons(big, kMaxPolygonVertices, kFootprintTolerance);
  EXPECT_GT(fan.size(), 1u);
  expectCovers(fan, big);
  // A hull already within the limit is kept as it is.
  const std::vector<Vec2> square = regularPolygon(4, 1.0);
  EXPECT_EQ(footprintPolygons(square, kMaxPolygonVertices, kFootprintTolerance).front(), square);
}

std::string findImpulse2d(const std::string& package, std::string* error) {
  if (package == "impulse2d") return IMPULSE2D_SOURCE_DIR;
  *error = "no package named '" + package + "'";
  return "";
}

std::string robotWithMesh(const std::string& mesh, const std::string& extra = "") {
  return R"(<robot name="r"><link name="base"><collision>)" + extra +
         R"(<geometry><mesh filename=")" + mesh + R"(" scale="2 2 1"/></geometry></collision>
         <inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link></robot>)";
}

bool parse(const std::string& xml, UrdfModel* out, std::string* error, bool finder = true) {
  UrdfPlacement placement;
  placement.modelName = "m";
  placement.plane = "xy";
  if (finder) placement.findPackage = findImpulse2d;
  return parseUrdf(xml, placement, out, error);
}

TEST(UrdfMeshes, AMeshsFootprintSeenFromAboveIsItsScaledHull) {
  // The drum (r 0.1 m, 32 sides) scaled by 2 across: a 0.2 m disc from above.
  UrdfModel model;
  std::string error;
  ASSERT_TRUE(parse(robotWithMesh("package://impulse2d/test/urdf/meshes/drum.obj"), &model, &error))
      << error;
  ASSERT_EQ(model.scene.bodies.size(), 1u);
  const std::vector<ShapeDef>& shapes = model.scene.bodies[0].shapes;
  ASSERT_GE(shapes.size(), 1u);
  const std::vector<Vec2> drum = regularPolygon(32, 0.2);
  std::vector<std::vector<Vec2>> pieces;
  for (const ShapeDef& s : shapes) {
    EXPECT_EQ(s.kind, ShapeKind::Polygon);
    pieces.push_back(s.vertices);
  }
  expectCovers(pieces, drum);
  World world;  // the pieces are shapes the world takes (convex, at most 16 vertices)
  ASSERT_TRUE(addScene(model.scene, world, &error)) << error;
  // The plate STL (0.3 x 0.2 m), scaled to 0.6 x 0.4 and turned a quarter about z.
  ASSERT_TRUE(parse(robotWithMesh("package://impulse2d/test/urdf/meshes/plate.stl",
                                  R"(<origin rpy="0 0 1.5707963267948966"/>)"),
                    &model, &error))
      << error;
  ASSERT_EQ(model.scene.bodies[0].shapes.size(), 1u);
  const std::vector<Vec2>& plate = model.scene.bodies[0].shapes[0].vertices;
  ASSERT_EQ(plate.size(), 4u);
  EXPECT_NEAR(area(plate), 0.6 * 0.4, 1e-6);
  double maxY = 0.0;
  for (const Vec2& v : plate) maxY = std::max(maxY, v.y());
  EXPECT_NEAR(maxY, 0.3, 1e-6);
}

TEST(UrdfMeshes, UnreadableMeshesRefuseAndOthersAreSkippedWithAWord) {
  struct Case {
    std::string mesh;
    std::string error;
  };
  const Case cases[] = {
      {"package://impulse2d/test/urdf/meshes/missing.stl", "cannot read (No such file"},
      {"package://impulse2d/package.xml", "cannot read (assimp:"},
      {"package://impulse2d/test/urdf/meshes", "cannot read (not a regular file)"},
      {"package://no_such_package/m.stl", "no package named 'no_such_package'"},
  };
  for (const Case& c : cases) {
    UrdfModel model;
    std::string error;
    EXPECT_FALSE(parse(robotWithMesh(c.mesh), &model, &error)) << c.mesh;
    EXPECT_NE(error.find("link 'base': collision[0]: mesh '" + c.mesh.substr(0, 50)),
              std::string::npos)
        << error;
    EXPECT_NE(error.find(c.error), std::string::npos) << error;
  }
  // file:// and relative names are never opened; without a package finder nothing is.
  for (const std::string& mesh : {std::string("file:///etc/passwd"), std::string("m.stl")}) {
    UrdfModel model;
    std::string error;
    EXPECT_FALSE(parse(robotWithMesh(mesh), &model, &error));  // no other geometry: no body
    EXPECT_NE(error.find("no link with collision geometry"), std::string::npos) << error;
  }
  UrdfModel model;
  std::string error;
  EXPECT_FALSE(parse(robotWithMesh("package://impulse2d/test/urdf/meshes/drum.obj"), &model, &error,
                     /*finder=*/false));
}

}  // namespace
}  // namespace impulse2d
