// Occupancy maps as walls (issue 23): a map in map_server's format (a YAML file naming an image)
// read into an occupancy grid, its occupied cells merged into few boxes, and the boxes as static
// bodies. ROS-free; the scene loader reads `maps:` with it and the node publishes the grid.
#pragma once

#include <impulse2d/defs.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace impulse2d {

/// Cells as nav_msgs/OccupancyGrid has them.
struct OccupancyGrid {
  int width = 0;               ///< cells along the map's x
  int height = 0;              ///< cells along its y
  double resolution = 0.05;    ///< m per cell
  Vec2 origin = Vec2::Zero();  ///< m, the outer corner of the first cell (bottom left) in the world
  double originYaw = 0.0;      ///< rad, the map's x axis in the world
  /// Row by row from the bottom row (y = 0), each from x = 0: 100 occupied, 0 free, -1 unknown.
  std::vector<int8_t> data;
};

/// map_server's thresholds and how to read a pixel (its YAML keys).
struct MapImageRules {
  bool negate = false;           ///< false: black is occupied
  double occupiedThresh = 0.65;  ///< occupancy above it: occupied
  double freeThresh = 0.196;     ///< below it: free; between the two: unknown
};

/// A grid from an image's pixels as map_server's trinary mode reads them: the image's top row is
/// the map's top; each pixel's occupancy is (255 - mean of its colour channels) / 255 (negate:
/// mean / 255); a fully transparent pixel is unknown.
OccupancyGrid gridFromPixels(const uint8_t* pixels, int width, int height, int channels,
                             const MapImageRules& rules);

/// Reads a map_server YAML file (`image`, `resolution`, `origin`, `negate`, `occupied_thresh`,
/// `free_thresh`; `mode` must be trinary if given) and its image (PGM or PNG, through stb_image),
/// the image's path relative to the YAML's folder unless absolute. False with one line naming
/// the file and key otherwise.
bool loadMapFile(const std::string& yamlPath, OccupancyGrid* out, std::string* error);

/// An axis-aligned block of occupied cells: columns [x0, x1), rows [y0, y1) from the bottom.
struct CellBlock {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

/// The occupied cells as few blocks that cover exactly them: each row's runs of occupied cells,
/// a run extending the block of the row below that spans the same columns. Linear in the cells.
std::vector<CellBlock> mergeOccupiedCells(const OccupancyGrid& grid);

/// The walls of a map: static bodies of boxes, one per block, at most kMaxShapesPerBody each
/// (blocks near each other share a body), placed at the map's origin. The first is named
/// `name`, the others `name/1`, `name/2`, ... Every box is `shape`'s friction, restitution,
/// reflectance and filter.
std::vector<BodyDef> mapBodies(const std::string& name, const OccupancyGrid& grid,
                               const std::vector<CellBlock>& blocks, const ShapeDef& shape);

}  // namespace impulse2d
