// A collision mesh seen from along the plane normal: its projected convex hull, as few convex
// polygons as the engine takes (at most 16 vertices each), never more than 1 mm outside the hull.
#pragma once

#include "plane_projection.hpp"

#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace impulse2d {
namespace urdf_detail {

/// m: how far a simplified footprint may reach outside the mesh's hull.
constexpr double kFootprintTolerance = 1e-3;

/// The convex hull of `points`, counter-clockwise, without collinear points; empty when the
/// points span no area.
std::vector<Vec2> convexHull(std::vector<Vec2> points);

/// Covers the convex polygon `hull` (counter-clockwise) with convex polygons of at most
/// `maxVertices` vertices: first an outer simplification (an edge is dropped by extending its
/// neighbours to meet) while that stays within `tolerance` of the hull; if more vertices remain,
/// the polygon is cut into a fan of pieces that share the first vertex, whose union is it exactly.
std::vector<std::vector<Vec2>> footprintPolygons(const std::vector<Vec2>& hull, int maxVertices,
                                                 double tolerance);

/// Reads the mesh file (STL, COLLADA, OBJ, ... with assimp), scales it (URDF `scale`), places it
/// with `meshInBody` and projects it onto the plane: its footprint, as footprintPolygons() gives
/// it. Returns "" or why the file cannot be used (unreadable, empty, too large, no area).
std::string meshFootprint(const std::string& path, const Eigen::Vector3d& scale,
                          const Eigen::Isometry3d& meshInBody, const PlaneAxes& plane,
                          std::vector<std::vector<Vec2>>* polygons);

}  // namespace urdf_detail
}  // namespace impulse2d
