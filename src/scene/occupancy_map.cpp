// Occupancy maps as walls (occupancy_map.hpp): map_server's files, the trinary reading, the
// merge of occupied cells into blocks, and the blocks as static bodies.
#include <impulse2d/limits.hpp>
#include <impulse2d/occupancy_map.hpp>

#include "scene_parsers.hpp"

#include <stb_image.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>

namespace impulse2d {
namespace {

constexpr int8_t kOccupied = 100, kFree = 0, kUnknown = -1;
constexpr size_t kMaxMapYamlBytes = 1u << 20;

// Only regular files are read: a FIFO or a device named by a request would block or never end.
std::string folderOf(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

}  // namespace

OccupancyGrid gridFromPixels(const uint8_t* pixels, int width, int height, int channels,
                             const MapImageRules& rules) {
  OccupancyGrid grid;
  grid.width = width;
  grid.height = height;
  grid.data.resize(static_cast<size_t>(width) * static_cast<size_t>(height));
  // Grey, grey + alpha, RGB or RGBA: the colour channels are all but a trailing alpha.
  const bool alpha = channels == 2 || channels == 4;
  const int colours = alpha ? channels - 1 : channels;
  for (int row = 0; row < height; ++row) {
    const uint8_t* pixel = pixels + static_cast<size_t>(row) * width * channels;
    // The image's top row is the map's last.
    int8_t* cell = grid.data.data() + static_cast<size_t>(height - 1 - row) * width;
    for (int x = 0; x < width; ++x, pixel += channels) {
      if (alpha && pixel[channels - 1] == 0) {
        cell[x] = kUnknown;
        continue;
      }
      int sum = 0;
      for (int c = 0; c < colours; ++c) sum += pixel[c];
      const double mean = static_cast<double>(sum) / colours;
      const double occupancy = rules.negate ? mean / 255.0 : (255.0 - mean) / 255.0;
      cell[x] = occupancy > rules.occupiedThresh ? kOccupied
                : occupancy < rules.freeThresh   ? kFree
                                                 : kUnknown;
    }
  }
  return grid;
}

bool loadMapFile(const std::string& yamlPath, OccupancyGrid* out, std::string* error) {
  auto fail = [&](const std::string& why) {
    if (error != nullptr) *error = yamlPath + ": " + why;
    return false;
  };
  // Read with a bound first: a map's YAML is a few lines, and the path may name anything.
  const std::string notYaml = scene_detail::whyNotAFile(yamlPath);
  if (!notYaml.empty()) return fail("cannot open the map's YAML file (" + notYaml + ")");
  std::ifstream file(yamlPath, std::ios::binary);
  if (!file)
    return fail(std::string("cannot open the map's YAML file (") + std::strerror(errno) + ")");
  std::string text;
  char chunk[4096];
  while (file.read(chunk, sizeof chunk) || file.gcount() > 0) {
    text.append(chunk, static_cast<size_t>(file.gcount()));
    if (text.size() > kMaxMapYamlBytes) return fail("too large for a map_server YAML file");
  }
  YAML::Node doc;
  try {
    doc = YAML::Load(text);
  } catch (const std::exception& e) {
    return fail(std::string("not a map_server YAML file: ") + e.what());
  }
  if (!doc.IsMap()) return fail("not a map_server YAML file (a map of image, resolution, origin)");
  MapImageRules rules;
  std::string image;
  double resolution = 0.0;
  std::vector<double> origin;
  try {
    if (!doc["image"] || !doc["image"].IsScalar()) return fail("image: must be given, a file name");
    image = doc["image"].as<std::string>();
    if (!doc["resolution"]) return fail("resolution: must be given, m per cell");
    resolution = doc["resolution"].as<double>();
    if (!doc["origin"]) return fail("origin: must be given, [x, y, yaw]");
    origin = doc["origin"].as<std::vector<double>>();
    if (doc["negate"]) rules.negate = doc["negate"].as<int>() != 0;
    if (doc["occupied_thresh"]) rules.occupiedThresh = doc["occupied_thresh"].as<double>();
    if (doc["free_thresh"]) rules.freeThresh = doc["free_thresh"].as<double>();
    if (doc["mode"] && doc["mode"].as<std::string>() != "trinary") {
      return fail("mode: only trinary is read (scale and raw keep costs that walls do not have)");
    }
  } catch (const YAML::Exception& e) {
    return fail(std::string("a key has the wrong type: ") + e.msg);
  }
  if (!(std::isfinite(resolution) && resolution > 0.0 && resolution <= 1e3)) {
    return fail("resolution: must be finite, > 0 and at most 1000 m");
  }
  if (origin.size() != 3 || !std::all_of(origin.begin(), origin.end(), [](double v) {
        return std::isfinite(v) && std::abs(v) <= kMaxCoordinate;
      })) {
    return fail("origin: must be three finite numbers [x, y, yaw], x and y within 1e6 m");
  }
  if (!(rules.freeThresh >= 0.0 && rules.freeThresh <= rules.occupiedThresh &&
        rules.occupiedThresh <= 1.0)) {
    return fail(
        "free_thresh, occupied_thresh: must satisfy 0 <= free_thresh <= occupied_thresh <= 1");
  }
  const std::string imagePath =
      !image.empty() && image[0] == '/' ? image : folderOf(yamlPath) + image;
  int width = 0, height = 0, channels = 0;
  const std::string notImage = scene_detail::whyNotAFile(imagePath);
  if (!notImage.empty()) return fail("image: cannot read " + imagePath + " (" + notImage + ")");
  if (stbi_info(imagePath.c_str(), &width, &height, &channels) == 0) {
    return fail("image: cannot read " + imagePath + " (" + stbi_failure_reason() + ")");
  }
  if (static_cast<double>(width) * height > static_cast<double>(kMaxMapCells)) {
    return fail("image: " + std::to_string(width) + " x " + std::to_string(height) +
                " cells; at most " + std::to_string(kMaxMapCells) + " are read");
  }
  const std::unique_ptr<uint8_t, void (*)(void*)> pixels(
      stbi_load(imagePath.c_str(), &width, &height, &channels, 0), stbi_image_free);
  if (!pixels) {
    return fail("image: cannot read " + imagePath + " (" + stbi_failure_reason() + ")");
  }
  if (static_cast<double>(width) * resolution > 2.0 * kMaxCoordinate ||
      static_cast<double>(height) * resolution > 2.0 * kMaxCoordinate) {
    return fail("the map is larger than 2e6 m across");
  }
  OccupancyGrid grid = gridFromPixels(pixels.get(), width, height, channels, rules);
  grid.resolution = resolution;
  grid.origin = Vec2(origin[0], origin[1]);
  grid.originYaw = origin[2];
  if (out != nullptr) *out = std::move(grid);
  return true;
}

std::vector<CellBlock> mergeOccupiedCells(const OccupancyGrid& grid) {
  std::vector<CellBlock> blocks;
  // The blocks still open, by the columns [x0, x1) they span: each ends in the row below.
  std::map<std::pair<int, int>, size_t> open, next;
  for (int y = 0; y < grid.height; ++y) {
    const int8_t* row = grid.data.data() + static_cast<size_t>(y) * grid.width;
    next.clear();
    for (int x = 0; x < grid.width;) {
      if (row[x] != kOccupied) {
        ++x;
        continue;
      }
      const int x0 = x;
      while (x < grid.width && row[x] == kOccupied) ++x;
      const auto below = open.find({x0, x});
      if (below != open.end()) {
        blocks[below->second].y1 = y + 1;
        next.emplace(below->first, below->second);
      } else {
        blocks.push_back(CellBlock{x0, y, x, y + 1});
        next.emplace(std::make_pair(x0, x), blocks.size() - 1);
      }
    }
    open.swap(next);
  }
  return blocks;
}

std::vector<BodyDef> mapBodies(const std::string& name, const OccupancyGrid& grid,
                               const std::vector<CellBlock>& blocks, const ShapeDef& shape) {
  // Neighbours share a body: blocks sorted by the 64-cell tile their corner lies in.
  constexpr int kTile = 64;
  std::vector<size_t> order(blocks.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  auto tileOf = [&](size_t i) {
    return std::make_pair(blocks[i].y0 / kTile, blocks[i].x0 / kTile);
  };
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return tileOf(a) < tileOf(b); });
  std::vector<BodyDef> bodies;
  for (size_t start = 0; start < order.size(); start += kMaxShapesPerBody) {
    BodyDef body;
    body.name = bodies.empty() ? name : name + "/" + std::to_string(bodies.size());
    body.type = BodyType::Static;
    body.position = grid.origin;
    body.angle = grid.originYaw;
    const size_t end = std::min(order.size(), start + kMaxShapesPerBody);
    for (size_t k = start; k < end; ++k) {
      const CellBlock& b = blocks[order[k]];
      ShapeDef box = shape;
      box.kind = ShapeKind::Box;
      box.size = grid.resolution * Vec2(b.x1 - b.x0, b.y1 - b.y0);
      box.offset = grid.resolution * Vec2(0.5 * (b.x0 + b.x1), 0.5 * (b.y0 + b.y1));
      box.angle = 0.0;
      body.shapes.push_back(box);
    }
    bodies.push_back(std::move(body));
  }
  return bodies;
}

}  // namespace impulse2d
