// The 3D-to-plane geometry of URDF import: which 3D directions span the world's plane, and
// whether a URDF frame, axis or shape can be represented in it.
#pragma once

#include <impulse2d/math.hpp>

#include <Eigen/Geometry>

#include <string>

namespace impulse2d {
namespace urdf_detail {

/// The plane's 2D axes in 3D and its counter-clockwise normal e1 x e2.
/// xz: e1 = x, e2 = z, normal = -y. xy: e1 = x, e2 = y, normal = z.
struct PlaneAxes {
  Eigen::Vector3d e1, e2, normal;
  std::string name;        ///< "xz" or "xy"
  std::string normalName;  ///< the normal's 3D axis as users know it: "3D y" or "3D z"
};

/// False for anything but "xz" and "xy".
bool planeAxes(const std::string& plane, PlaneAxes* out);

/// Directions within this angle of the normal count as normal, within it of the plane as in it
/// (URDF files write pi/2 as 1.5708).
constexpr double kAngleTolerance = 1e-3;  // rad

bool isNormal(const PlaneAxes& plane, const Eigen::Vector3d& unitDirection);
bool isInPlane(const PlaneAxes& plane, const Eigen::Vector3d& unitDirection);

/// A rotation that keeps the plane's normal, i.e. one about the normal only.
bool keepsNormal(const PlaneAxes& plane, const Eigen::Matrix3d& rotation);

/// The point's in-plane coordinates (its offset along the normal is dropped).
Vec2 project(const PlaneAxes& plane, const Eigen::Vector3d& point);
/// The angle (counter-clockwise about the normal) of an in-plane direction.
double angleOf(const PlaneAxes& plane, const Eigen::Vector3d& direction);

/// "(x y z)" with short numbers, for messages.
std::string describe(const Eigen::Vector3d& v);

}  // namespace urdf_detail
}  // namespace impulse2d
