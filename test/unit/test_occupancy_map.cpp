// Occupancy maps as walls (issue 23) without ROS: map_server's reading of pixels, the merge of
// occupied cells into blocks that cover exactly them, map_server files (PGM and the YAML), and a
// scene's `maps:` whose walls rays and bodies meet where the cells are.
#include <gtest/gtest.h>

#include <impulse2d/limits.hpp>
#include <impulse2d/occupancy_map.hpp>
#include <impulse2d/scene.hpp>

#include "temp_folder.hpp"

#include <random>
#include <string>

namespace impulse2d {
namespace {

// A binary PGM (P5) of `rows`, top row first, '#' black (occupied), '.' white (free), '?' grey.
std::string pgm(const std::vector<std::string>& rows) {
  std::string out =
      "P5\n" + std::to_string(rows[0].size()) + " " + std::to_string(rows.size()) + "\n255\n";
  for (const std::string& row : rows) {
    for (const char c : row) out.push_back(static_cast<char>(c == '#' ? 0 : c == '.' ? 255 : 205));
  }
  return out;
}

TEST(OccupancyMap, PixelsReadAsMapServersTrinaryMode) {
  // Grey + alpha: black, white, map_server's unknown grey 205, a transparent black.
  const uint8_t pixels[] = {0, 255, 255, 255, 205, 255, 0, 0};
  const OccupancyGrid grid = gridFromPixels(pixels, 4, 1, 2, MapImageRules());
  ASSERT_EQ(grid.data.size(), 4u);
  EXPECT_EQ(grid.data[0], 100);
  EXPECT_EQ(grid.data[1], 0);
  EXPECT_EQ(grid.data[2], -1);  // (255 - 205) / 255 = 0.196: not below free_thresh 0.196
  EXPECT_EQ(grid.data[3], -1);
  MapImageRules negate;
  negate.negate = true;
  const OccupancyGrid flipped = gridFromPixels(pixels, 4, 1, 2, negate);
  EXPECT_EQ(flipped.data[0], 0);
  EXPECT_EQ(flipped.data[1], 100);
  // RGB: the mean of the channels; the image's top row is the map's last.
  const uint8_t rgb[] = {0, 0, 0, /* top */ 255, 255, 255 /* bottom */};
  const OccupancyGrid tall = gridFromPixels(rgb, 1, 2, 3, MapImageRules());
  EXPECT_EQ(tall.data[0], 0);    // row 0, the bottom: white
  EXPECT_EQ(tall.data[1], 100);  // row 1, the top: black
}

// Paints the blocks: each occupied cell exactly once, nothing else.
void expectExactCover(const OccupancyGrid& grid, const std::vector<CellBlock>& blocks) {
  std::vector<int> painted(grid.data.size(), 0);
  for (const CellBlock& b : blocks) {
    ASSERT_LT(b.x0, b.x1);
    ASSERT_LT(b.y0, b.y1);
    for (int y = b.y0; y < b.y1; ++y) {
      for (int x = b.x0; x < b.x1; ++x) ++painted[static_cast<size_t>(y) * grid.width + x];
    }
  }
  for (size_t i = 0; i < painted.size(); ++i) {
    ASSERT_EQ(painted[i], grid.data[i] == 100 ? 1 : 0) << "cell " << i;
  }
}

TEST(OccupancyMap, BlocksCoverExactlyTheOccupiedCellsAndMergeRuns) {
  OccupancyGrid room;
  room.width = 10;
  room.height = 8;
  room.data.assign(80, 0);
  for (int x = 0; x < 10; ++x) room.data[x] = room.data[70 + x] = 100;          // floor and ceiling
  for (int y = 0; y < 8; ++y) room.data[10 * y] = room.data[10 * y + 9] = 100;  // sides
  const std::vector<CellBlock> blocks = mergeOccupiedCells(room);
  expectExactCover(room, blocks);
  EXPECT_EQ(blocks.size(), 4u);  // the bottom row, two side columns, the top row
  // Random grids, a third occupied: still exact.
  std::mt19937 random(3);
  OccupancyGrid noisy;
  noisy.width = 97;
  noisy.height = 61;
  for (int i = 0; i < noisy.width * noisy.height; ++i) {
    noisy.data.push_back(random() % 3 == 0 ? 100 : (random() % 2 ? 0 : -1));
  }
  expectExactCover(noisy, mergeOccupiedCells(noisy));
}

TEST(OccupancyMap, BodiesHoldAtMostTheShapeLimitAndTakeTheShapesKeys) {
  OccupancyGrid checker;  // every other cell: nothing merges
  checker.width = 40;
  checker.height = 20;
  for (int y = 0; y < 20; ++y) {
    for (int x = 0; x < 40; ++x) checker.data.push_back((x + y) % 2 ? 100 : 0);
  }
  checker.resolution = 0.1;
  checker.origin = Vec2(-2.0, 1.0);
  ShapeDef shape;
  shape.friction = 0.3;
  shape.reflectance = 0.7;
  const std::vector<CellBlock> blocks = mergeOccupiedCells(checker);
  ASSERT_EQ(blocks.size(), 400u);
  const std::vector<BodyDef> bodies = mapBodies("plan", checker, blocks, shape);
  ASSERT_EQ(bodies.size(), (400 + kMaxShapesPerBody - 1) / kMaxShapesPerBody);
  EXPECT_EQ(bodies[0].name, "plan");
  EXPECT_EQ(bodies[1].name, "plan/1");
  size_t boxes = 0;
  for (const BodyDef& body : bodies) {
    EXPECT_EQ(body.type, BodyType::Static);
    EXPECT_LE(body.shapes.size(), kMaxShapesPerBody);
    EXPECT_EQ(body.position, checker.origin);
    for (const ShapeDef& s : body.shapes) {
      EXPECT_EQ(s.friction, 0.3);
      EXPECT_EQ(s.reflectance, 0.7);
      EXPECT_NEAR(s.size.x(), 0.1, 1e-15);
    }
    boxes += body.shapes.size();
  }
  EXPECT_EQ(boxes, 400u);
}

TEST(OccupancyMap, MapServerFilesAndTheirMistakes) {
  TempFolder folder;
  folder.write("room.pgm", pgm({"#####", "#...#", "#.?.#", "#####"}));
  const std::string yaml =
      folder.write("room.yaml",
                   "image: room.pgm\nresolution: 0.5\norigin: [-1.0, -2.0, 0.0]\nnegate: 0\n"
                   "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  OccupancyGrid grid;
  std::string error;
  ASSERT_TRUE(loadMapFile(yaml, &grid, &error)) << error;
  EXPECT_EQ(grid.width, 5);
  EXPECT_EQ(grid.height, 4);
  EXPECT_EQ(grid.resolution, 0.5);
  EXPECT_EQ(grid.origin, Vec2(-1.0, -2.0));
  EXPECT_EQ(grid.data[1 * 5 + 2], -1);  // the grey cell, second row from the bottom
  EXPECT_EQ(grid.data[2 * 5 + 2], 0);
  EXPECT_EQ(grid.data[0], 100);

  const struct {
    const char* yaml;
    const char* error;
  } refused[] = {
      {"resolution: 0.5\norigin: [0, 0, 0]\n", "image: must be given"},
      {"image: room.pgm\nresolution: -1\norigin: [0, 0, 0]\n", "resolution: must be finite, > 0"},
      {"image: room.pgm\nresolution: 0.5\norigin: [0, 0]\n", "origin: must be three finite"},
      {"image: room.pgm\nresolution: 0.5\norigin: [0, 0, 0]\nmode: scale\n", "mode: only trinary"},
      {"image: nothing.pgm\nresolution: 0.5\norigin: [0, 0, 0]\n", "image: cannot read"},
      {"image: room.pgm\nresolution: 0.5\norigin: [0, 0, 0]\nfree_thresh: 0.9\n",
       "free_thresh, occupied_thresh"},
      {"[1, 2", "not a map_server YAML file"},
  };
  for (const auto& r : refused) {
    const std::string bad = folder.write("bad.yaml", r.yaml);
    error.clear();
    EXPECT_FALSE(loadMapFile(bad, &grid, &error)) << r.yaml;
    EXPECT_NE(error.find(r.error), std::string::npos) << error;
    EXPECT_EQ(error.find(bad + ": "), 0u) << error;
  }
  EXPECT_FALSE(loadMapFile(folder.path() + "missing.yaml", &grid, &error));
  EXPECT_NE(error.find("cannot open the map's YAML file (No such file or directory)"),
            std::string::npos)
      << error;
  // Only regular files: a folder (or a FIFO, a device) would block or never end.
  EXPECT_FALSE(loadMapFile(folder.path(), &grid, &error));
  EXPECT_NE(error.find("(a directory, not a file)"), std::string::npos) << error;
  EXPECT_FALSE(loadMapFile("/dev/null", &grid, &error));
  EXPECT_NE(error.find("(not a regular file)"), std::string::npos) << error;
  const std::string folderImage =
      folder.write("folder.yaml", "image: /tmp\nresolution: 0.5\norigin: [0, 0, 0]\n");
  EXPECT_FALSE(loadMapFile(folderImage, &grid, &error));
  EXPECT_NE(error.find("image: cannot read /tmp (a directory, not a file)"), std::string::npos)
      << error;
}

TEST(OccupancyMap, ASceneMapsWallsThatRaysAndBodiesMeetAtTheCells) {
  TempFolder folder;
  // A room 8 x 6 cells of 0.25 m, walls one cell thick, the map's corner at (-1, -1).
  folder.write("room.pgm",
               pgm({"########", "#......#", "#......#", "#......#", "#......#", "########"}));
  folder.write("room.yaml", "image: room.pgm\nresolution: 0.25\norigin: [-1.0, -1.0, 0.0]\n");
  const std::string scenePath = folder.write(
      "scene.yaml",
      "world: {plane: xy, gravity: [0.0, -5.0], time_step: 0.01}\n"
      "bodies: [{name: ball, position: [0.0, -0.2], shapes: [{type: circle, radius: 0.1}]}]\n"
      "maps: [{name: room, file: room.yaml, reflectance: 0.4}]\n");
  Scene scene;
  std::string error;
  ASSERT_TRUE(loadSceneFile(scenePath, &scene, &error)) << error;
  ASSERT_EQ(scene.maps.size(), 1u);
  EXPECT_EQ(scene.maps[0].name, "room");
  EXPECT_EQ(scene.maps[0].bodies, 1u);
  ASSERT_EQ(scene.bodies.size(), 2u);  // the ball, then the room's walls
  EXPECT_EQ(scene.bodies[1].name, "room");
  World world(scene.world);
  ASSERT_TRUE(addScene(scene, world, &error)) << error;
  // The inside spans x (-0.75, 0.75), y (-0.75, 0.25): a ray from the middle meets the east
  // wall's face at x = 0.75 exactly, whatever box the cells merged into.
  const RayHit east = world.rayCast(Vec2(0.0, 0.0), Vec2(3.0, 0.0));
  ASSERT_TRUE(east.hit());
  EXPECT_NEAR(east.point.x(), 0.75, 1e-12);
  const RayHit north = world.rayCast(Vec2(0.3, 0.0), Vec2(0.3, 3.0));
  EXPECT_NEAR(north.point.y(), 0.25, 1e-12);
  // The ball falls onto the floor's top face, y = -0.75, and rests there within the slop.
  const BodyId ball = world.findBody("ball");
  for (int i = 0; i < 200; ++i) world.step();
  EXPECT_NEAR(world.body(ball).xf.p.y(), -0.75 + 0.1, 0.01);
  // Names: the map's body may not take a name the scene's bodies have.
  const std::string clash =
      folder.write("clash.yaml",
                   "bodies: [{name: room, shapes: [{}]}]\nmaps: [{name: room, file: room.yaml}]\n");
  EXPECT_FALSE(loadSceneFile(clash, &scene, &error));
  EXPECT_NE(error.find("maps[0] 'room': name: its body 'room' is already bodies[0]'s"),
            std::string::npos)
      << error;
  // package:// needs ROS to find the package.
  EXPECT_FALSE(
      parseScene("maps: [{name: m, file: package://impulse2d/maps/x.yaml}]", &scene, &error));
  EXPECT_NE(error.find("package:// names need a package finder"), std::string::npos) << error;
  ScenePaths paths;
  paths.findPackage = [&](const std::string& package, std::string* why) -> std::string {
    if (package == "floors") return folder.path() + "sub";
    *why = "no package named " + package;
    return "";
  };
  EXPECT_FALSE(
      parseScene("maps: [{name: m, file: package://nowhere/x.yaml}]", paths, &scene, &error));
  EXPECT_NE(error.find("maps[0] 'm': file: no package named nowhere"), std::string::npos) << error;
  EXPECT_FALSE(
      parseScene("maps: [{name: m, file: package://../etc/x.yaml}]", paths, &scene, &error));
  EXPECT_NE(error.find("not a ROS package name"), std::string::npos) << error;
  paths.folder = folder.path();
  ASSERT_TRUE(parseScene("maps: [{name: m, file: room.yaml}]", paths, &scene, &error)) << error;
}

TEST(OccupancyMap, PackagesAreFoundOnRosPackagePathWithoutRos) {
  TempFolder folder;
  folder.write("package.xml", "<package><name>my_maps</name></package>");
  const char* saved = std::getenv("ROS_PACKAGE_PATH");
  const std::string before = saved == nullptr ? "" : saved;
  setenv("ROS_PACKAGE_PATH", ("/nonexistent:" + folder.path()).c_str(), 1);
  std::string error;
  // The entry is the package itself (its package.xml names it).
  EXPECT_EQ(findPackageOnPath("my_maps", &error) + "/", folder.path());
  EXPECT_EQ(findPackageOnPath("other", &error), "");
  EXPECT_NE(error.find("no package named 'other' on ROS_PACKAGE_PATH"), std::string::npos) << error;
  if (saved == nullptr) {
    unsetenv("ROS_PACKAGE_PATH");
  } else {
    setenv("ROS_PACKAGE_PATH", before.c_str(), 1);
  }
}

}  // namespace
}  // namespace impulse2d
