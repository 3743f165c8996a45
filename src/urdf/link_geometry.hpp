// One link's collision geometry and inertial, expressed in the frame of the body it joins.
#pragma once

#include "plane_projection.hpp"

#include <impulse2d/defs.hpp>

#include <urdf_model/link.h>
#include <urdf_model/pose.h>

#include <functional>
#include <string>
#include <vector>

namespace impulse2d {
namespace urdf_detail {

/// A URDF pose as an isometry; false when a number is not finite.
bool toIsometry(const urdf::Pose& pose, Eigen::Isometry3d* out);

/// Mass properties summed over the links of one body, in the body frame.
struct MassSum {
  double mass = 0.0;
  Vec2 moment = Vec2::Zero();  ///< sum of mass * centre
  /// Sum over links of (inertia about the normal through the link's centre + mass * |centre|^2),
  /// i.e. the inertia about the body origin.
  double inertiaAtOrigin = 0.0;
};

/// Appends the link's collision elements as shapes; `linkInBody` places the link frame in the
/// body frame. Meshes are skipped with a warning. Returns "" or the reason naming the link.
/// `findPackage` resolves package:// mesh names (UrdfPlacement::findPackage); without it meshes
/// are skipped with a warning.
std::string addCollisionShapes(
    const PlaneAxes& plane, const urdf::Link& link, const Eigen::Isometry3d& linkInBody,
    std::vector<ShapeDef>* shapes, std::vector<std::string>* warnings,
    const std::function<std::string(const std::string&, std::string*)>& findPackage = nullptr);

/// Adds the link's <inertial>, if any, to `sum`. Returns "" or the reason naming the link.
std::string addInertial(const PlaneAxes& plane, const urdf::Link& link,
                        const Eigen::Isometry3d& linkInBody, MassSum* sum);

/// The link's name in single quotes, shortened and on one line, for messages.
std::string quotedName(const std::string& name);

}  // namespace urdf_detail
}  // namespace impulse2d
