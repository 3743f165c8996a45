// Projection of URDF frames and directions onto the world's plane.
#include "plane_projection.hpp"

#include <cmath>
#include <cstdio>

namespace impulse2d {
namespace urdf_detail {

bool planeAxes(const std::string& plane, PlaneAxes* out) {
  if (plane == "xz") {
    *out = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ(), -Eigen::Vector3d::UnitY(), "xz",
            "3D y"};
    return true;
  }
  if (plane == "xy") {
    *out = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(), "xy",
            "3D z"};
    return true;
  }
  return false;
}

bool isNormal(const PlaneAxes& plane, const Eigen::Vector3d& unitDirection) {
  return std::abs(unitDirection.dot(plane.normal)) >= std::cos(kAngleTolerance);
}

bool isInPlane(const PlaneAxes& plane, const Eigen::Vector3d& unitDirection) {
  return std::abs(unitDirection.dot(plane.normal)) <= std::sin(kAngleTolerance);
}

bool keepsNormal(const PlaneAxes& plane, const Eigen::Matrix3d& rotation) {
  return (rotation * plane.normal).dot(plane.normal) >= std::cos(kAngleTolerance);
}

Vec2 project(const PlaneAxes& plane, const Eigen::Vector3d& point) {
  return Vec2(point.dot(plane.e1), point.dot(plane.e2));
}

double angleOf(const PlaneAxes& plane, const Eigen::Vector3d& direction) {
  return std::atan2(direction.dot(plane.e2), direction.dot(plane.e1));
}

std::string describe(const Eigen::Vector3d& v) {
  char text[96];
  std::snprintf(text, sizeof(text), "(%.6g %.6g %.6g)", v.x(), v.y(), v.z());
  return text;
}

}  // namespace urdf_detail
}  // namespace impulse2d
