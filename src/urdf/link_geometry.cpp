// Collision geometry onto the plane: a box keeps its two in-plane extents, a sphere and a
// cylinder standing on the plane become circles, a cylinder lying in the plane becomes its
// side-view rectangle. Anything tilted in between cannot be drawn in 2D and is refused.
#include "link_geometry.hpp"

#include "mesh_footprint.hpp"

#include <cmath>

namespace impulse2d {
namespace urdf_detail {
namespace {

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

std::string collisionContext(const urdf::Link& link, size_t index) {
  return "link " + quotedName(link.name) + ": collision[" + std::to_string(index) + "]: ";
}

bool positiveFinite(double v) { return std::isfinite(v) && v > 0.0; }

ShapeDef placedShape(const PlaneAxes& plane, const Eigen::Isometry3d& shapeInBody) {
  ShapeDef shape;
  shape.offset = project(plane, shapeInBody.translation());
  return shape;
}

std::string boxShape(const PlaneAxes& plane, const urdf::Box& box,
                     const Eigen::Isometry3d& shapeInBody, ShapeDef* out) {
  const Eigen::Vector3d size(box.dim.x, box.dim.y, box.dim.z);
  if (!positiveFinite(size.x()) || !positiveFinite(size.y()) || !positiveFinite(size.z())) {
    return "box size " + describe(size) + ": every extent must be finite and > 0";
  }
  // One of the box's axes must stand on the plane; the other two span its rectangle.
  const Eigen::Matrix3d r = shapeInBody.linear();
  for (int normalAxis = 0; normalAxis < 3; ++normalAxis) {
    if (!isNormal(plane, r.col(normalAxis))) continue;
    const int first = normalAxis == 0 ? 1 : 0;  // the lower remaining axis gives the width
    const int second = normalAxis == 2 ? 1 : 2;
    *out = placedShape(plane, shapeInBody);
    out->kind = ShapeKind::Box;
    out->size = Vec2(size[first], size[second]);
    out->angle = angleOf(plane, r.col(first));
    return "";
  }
  return "box is turned out of the " + plane.name + " plane; one of its axes must be along the " +
         "plane normal (" + plane.normalName + ")";
}

std::string cylinderShape(const PlaneAxes& plane, const urdf::Cylinder& cylinder,
                          const Eigen::Isometry3d& shapeInBody, ShapeDef* out) {
  if (!positiveFinite(cylinder.radius) || !positiveFinite(cylinder.length)) {
    return "cylinder radius and length must be finite and > 0";
  }
  const Eigen::Vector3d axis = shapeInBody.linear().col(2);  // a URDF cylinder's axis is its z
  *out = placedShape(plane, shapeInBody);
  if (isNormal(plane, axis)) {
    out->kind = ShapeKind::Circle;
    out->radius = cylinder.radius;
    return "";
  }
  if (isInPlane(plane, axis)) {  // seen from the side: a rectangle along the axis
    out->kind = ShapeKind::Box;
    out->size = Vec2(cylinder.length, 2.0 * cylinder.radius);
    out->angle = angleOf(plane, axis);
    return "";
  }
  return "cylinder axis " + describe(axis) + " is neither along the plane normal (" +
         plane.normalName + ") nor in the " + plane.name + " plane";
}

}  // namespace

std::string quotedName(const std::string& name) {
  constexpr size_t kMaxShown = 64;
  std::string out = "'";
  for (char c : name) {
    if (out.size() > kMaxShown) {
      out += "...";
      break;
    }
    const unsigned char u = static_cast<unsigned char>(c);
    out += (u < 0x20 || u == 0x7f) ? '?' : c;
  }
  return out + "'";
}

bool toIsometry(const urdf::Pose& pose, Eigen::Isometry3d* out) {
  const Eigen::Vector3d p(pose.position.x, pose.position.y, pose.position.z);
  const Eigen::Quaterniond q(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z);
  if (!finite(p) || !q.coeffs().allFinite() || q.norm() < 0.5) return false;
  *out = Eigen::Isometry3d::Identity();
  out->linear() = q.normalized().toRotationMatrix();
  out->translation() = p;
  return true;
}

std::string addCollisionShapes(
    const PlaneAxes& plane, const urdf::Link& link, const Eigen::Isometry3d& linkInBody,
    std::vector<ShapeDef>* shapes, std::vector<std::string>* warnings,
    const std::function<std::string(const std::string&, std::string*)>& findPackage) {
  for (size_t i = 0; i < link.collision_array.size(); ++i) {
    const urdf::CollisionSharedPtr& collision = link.collision_array[i];
    if (!collision || !collision->geometry) continue;
    const std::string where = collisionContext(link, i);
    Eigen::Isometry3d origin;
    if (!toIsometry(collision->origin, &origin)) return where + "origin: must be finite";
    const Eigen::Isometry3d shapeInBody = linkInBody * origin;
    ShapeDef shape;
    std::string why;
    const urdf::Geometry& geometry = *collision->geometry;
    switch (geometry.type) {
      case urdf::Geometry::SPHERE: {
        const double radius = static_cast<const urdf::Sphere&>(geometry).radius;
        if (!positiveFinite(radius)) {
          why = "sphere radius must be finite and > 0";
          break;
        }
        shape = placedShape(plane, shapeInBody);
        shape.kind = ShapeKind::Circle;
        shape.radius = radius;
        break;
      }
      case urdf::Geometry::BOX:
        why = boxShape(plane, static_cast<const urdf::Box&>(geometry), shapeInBody, &shape);
        break;
      case urdf::Geometry::CYLINDER:
        why =
            cylinderShape(plane, static_cast<const urdf::Cylinder&>(geometry), shapeInBody, &shape);
        break;
      case urdf::Geometry::MESH: {
        const urdf::Mesh& mesh = static_cast<const urdf::Mesh&>(geometry);
        const std::string scheme = "package://";
        if (!findPackage || mesh.filename.compare(0, scheme.size(), scheme) != 0) {
          // Only package:// names are read: a description must not open arbitrary files.
          warnings->push_back(where + "mesh " + quotedName(mesh.filename) + " skipped (" +
                              (findPackage ? "only package:// meshes are read"
                                           : "no package finder to read meshes with") +
                              "; or use a box, cylinder or sphere for 2D collision)");
          continue;
        }
        const std::string rest = mesh.filename.substr(scheme.size());
        const size_t slash = rest.find('/');
        std::string folder;
        if (slash != std::string::npos && slash > 0)
          folder = findPackage(rest.substr(0, slash), &why);
        if (folder.empty()) {
          return where + "mesh " + quotedName(mesh.filename) + ": " +
                 (why.empty() ? "must be package://PACKAGE/PATH" : why);
        }
        std::vector<std::vector<Vec2>> polygons;
        why = meshFootprint(folder + rest.substr(slash),
                            Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z), shapeInBody,
                            plane, &polygons);
        if (!why.empty()) return where + "mesh " + quotedName(mesh.filename) + ": " + why;
        for (const std::vector<Vec2>& polygon : polygons) {
          ShapeDef piece;
          piece.kind = ShapeKind::Polygon;
          piece.vertices = polygon;
          shapes->push_back(piece);
        }
        continue;
      }
      default:
        why = "unknown geometry type";
        break;
    }
    if (!why.empty()) return where + why;
    shapes->push_back(shape);
  }
  return "";
}

std::string addInertial(const PlaneAxes& plane, const urdf::Link& link,
                        const Eigen::Isometry3d& linkInBody, MassSum* sum) {
  if (!link.inertial) return "";
  const urdf::Inertial& inertial = *link.inertial;
  const std::string where = "link " + quotedName(link.name) + ": inertial: ";
  if (!std::isfinite(inertial.mass) || inertial.mass < 0.0) {
    return where + "mass must be finite and >= 0";
  }
  if (inertial.mass == 0.0) return "";
  Eigen::Isometry3d origin;
  if (!toIsometry(inertial.origin, &origin)) return where + "origin: must be finite";
  Eigen::Matrix3d tensor;
  tensor << inertial.ixx, inertial.ixy, inertial.ixz, inertial.ixy, inertial.iyy, inertial.iyz,
      inertial.ixz, inertial.iyz, inertial.izz;
  if (!tensor.allFinite()) return where + "inertia must be finite";
  const Eigen::Isometry3d frame = linkInBody * origin;
  // The tensor is given in the inertial frame; the plane normal seen from that frame:
  const Eigen::Vector3d normalInFrame = frame.linear().transpose() * plane.normal;
  const double aboutNormal = normalInFrame.dot(tensor * normalInFrame);
  if (!(aboutNormal >= 0.0)) {
    return where + "the inertia about the plane normal (" + plane.normalName + ") is negative";
  }
  const Vec2 center = project(plane, frame.translation());
  sum->mass += inertial.mass;
  sum->moment += inertial.mass * center;
  sum->inertiaAtOrigin += aboutNormal + inertial.mass * center.squaredNorm();
  return "";
}

}  // namespace urdf_detail
}  // namespace impulse2d
