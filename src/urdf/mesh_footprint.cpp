// Mesh footprints (mesh_footprint.hpp).
//
//   dropping edge (b, c): its neighbours' lines meet at p, outside the hull
//
//          p
//         / \          the added triangle b-p-c reaches dist(p, bc) outside;
//      a-b   c-d       allowed while that is within the tolerance
#include "mesh_footprint.hpp"

#include <impulse2d/limits.hpp>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>

namespace impulse2d {
namespace urdf_detail {
namespace {

// Bounds the work one mesh can cause; far above collision meshes.
constexpr size_t kMaxMeshBytes = 64u << 20;
constexpr size_t kMaxMeshVertices = 2000000;

double cross(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

// Where the lines through (a, b) and through (c, d) meet; false when they are parallel.
bool meet(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, Vec2* out) {
  const Vec2 r = b - a, s = d - c;
  const double denom = r.x() * s.y() - r.y() * s.x();
  if (std::abs(denom) < 1e-15) return false;
  const double t = ((c - a).x() * s.y() - (c - a).y() * s.x()) / denom;
  *out = a + t * r;
  return true;
}

double distanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

// The point that replaces edge (v[i], v[i+1]) when the edges before and after it are extended,
// and how far it lies outside that edge; infinity when they do not meet ahead of it.
double dropCost(const std::vector<Vec2>& v, size_t i, Vec2* point) {
  const size_t n = v.size();
  const Vec2& a = v[(i + n - 1) % n];
  const Vec2& b = v[i];
  const Vec2& c = v[(i + 1) % n];
  const Vec2& d = v[(i + 2) % n];
  Vec2 p = Vec2::Zero();
  if (!meet(a, b, d, c, &p)) return std::numeric_limits<double>::infinity();
  // p must lie beyond b along a->b and beyond c along d->c (outside the edge, not behind).
  if ((p - b).dot(b - a) < 0.0 || (p - c).dot(c - d) < 0.0) {
    return std::numeric_limits<double>::infinity();
  }
  *point = p;
  return distanceToSegment(p, b, c);
}

}  // namespace

std::vector<Vec2> convexHull(std::vector<Vec2> points) {
  std::sort(points.begin(), points.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return {};
  // Andrew's monotone chain: the lower hull left to right, then the upper hull back.
  std::vector<Vec2> hull(2 * points.size());
  size_t k = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  for (size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  if (hull.size() < 3) return {};
  return hull;
}

std::vector<std::vector<Vec2>> footprintPolygons(const std::vector<Vec2>& hull, int maxVertices,
                                                 double tolerance) {
  std::vector<Vec2> v = hull;
  const size_t limit = static_cast<size_t>(std::max(3, maxVertices));
  // Each step drops the edge that adds the least; every point added lies outside the current
  // polygon by at most that edge's cost, and the polygon only grows, so its distance to the hull
  // is at most the sum along one point's history: bounded by keeping the total spent per corner.
  std::vector<double> reach(v.size(), 0.0);  // how far outside the hull each vertex lies
  while (v.size() > limit) {
    size_t best = v.size();
    double bestReach = std::numeric_limits<double>::infinity();
    Vec2 bestPoint = Vec2::Zero();
    for (size_t i = 0; i < v.size(); ++i) {
      Vec2 p = Vec2::Zero();
      const double cost = dropCost(v, i, &p);
      const double r = cost + std::max(reach[i], reach[(i + 1) % v.size()]);
      if (r < bestReach) {
        bestReach = r;
        best = i;
        bestPoint = p;
      }
    }
    if (best == v.size() || bestReach > tolerance) break;
    const size_t next = (best + 1) % v.size();
    v[best] = bestPoint;
    reach[best] = bestReach;
    v.erase(v.begin() + static_cast<long>(next));
    reach.erase(reach.begin() + static_cast<long>(next));
  }
  if (v.size() <= limit) return {v};
  // A fan from v[0]: pieces v0, v[k], ..., v[k + limit - 2], each convex, sharing edges.
  std::vector<std::vector<Vec2>> pieces;
  for (size_t start = 1; start + 1 < v.size(); start += limit - 2) {
    std::vector<Vec2> piece{v[0]};
    for (size_t i = start; i < std::min(v.size(), start + limit - 1); ++i) piece.push_back(v[i]);
    pieces.push_back(piece);
  }
  return pieces;
}

std::string meshFootprint(const std::string& path, const Eigen::Vector3d& scale,
                          const Eigen::Isometry3d& meshInBody, const PlaneAxes& plane,
                          std::vector<std::vector<Vec2>>* polygons) {
  struct stat info {};
  if (stat(path.c_str(), &info) != 0)
    return std::string("cannot read (") + std::strerror(errno) + ")";
  if (!S_ISREG(info.st_mode)) return "cannot read (not a regular file)";
  if (static_cast<size_t>(info.st_size) > kMaxMeshBytes) {
    return "larger than " + std::to_string(kMaxMeshBytes >> 20) + " MiB";
  }
  if (!scale.allFinite() || (scale.array() <= 0.0).any()) return "scale must be finite and > 0";
  Assimp::Importer importer;
  // Node transforms baked in (COLLADA places its meshes with them), units as the file says.
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_PreTransformVertices | aiProcess_JoinIdenticalVertices);
  if (scene == nullptr || scene->mNumMeshes == 0) {
    const char* why = importer.GetErrorString();
    return std::string("cannot read (assimp: ") + (why && *why ? why : "no mesh in the file") + ")";
  }
  std::vector<Vec2> points;
  size_t count = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& mesh = *scene->mMeshes[m];
    count += mesh.mNumVertices;
    if (count > kMaxMeshVertices) {
      return "more than " + std::to_string(kMaxMeshVertices) + " vertices";
    }
    for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
      const aiVector3D& p = mesh.mVertices[i];
      const Eigen::Vector3d local(p.x * scale.x(), p.y * scale.y(), p.z * scale.z());
      if (!local.allFinite()) return "a vertex is not finite";
      points.push_back(project(plane, meshInBody * local));
    }
  }
  for (const Vec2& p : points) {
    if (p.cwiseAbs().maxCoeff() > kMaxCoordinate) return "a vertex lies beyond 1e6 m";
  }
  const std::vector<Vec2> hull = convexHull(std::move(points));
  if (hull.empty()) return "its footprint has no area (seen along the plane normal)";
  *polygons = footprintPolygons(hull, kMaxPolygonVertices, kFootprintTolerance);
  return "";
}

}  // namespace urdf_detail
}  // namespace impulse2d
