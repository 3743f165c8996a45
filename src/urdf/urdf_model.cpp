// URDF onto the plane: links joined by fixed joints become one body, revolute/continuous joints
// about the plane normal and prismatic joints along the plane become world joints, floating and
// planar joints leave their child free. A root link named "world" is the ground (gazebo's
// convention): what is fixed to it becomes static. Seen from above (plane xy), a revolute or
// continuous joint about an axis in the floor (a wheel's) is folded: its child joins its parent's
// body as if fixed, and the joint is kept aside for joint_states (UrdfFoldedJoint).
//
//        side view                      top view (xy)
//     base ====O==== base           +-----------+
//              ^ wheel_joint         |   base    |   the wheel's cylinder lying down is a
//         axis into the page       [=]         [=]  rectangle 2r x length of the base body
#include <impulse2d/urdf.hpp>

#include "gazebo_devices.hpp"
#include "link_geometry.hpp"
#include "plane_projection.hpp"
#include "urdf_text.hpp"

#include "names.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace impulse2d {
namespace urdf_detail {
namespace {

// Bounds the work one request can cause; far above real robots.
constexpr size_t kMaxLinks = 1000;

const char* kWorldLink = "world";

// Links joined by fixed joints: one rigid body named after its top link.
struct Group {
  const urdf::Link* top = nullptr;
  const urdf::Joint* parentJoint = nullptr;  ///< the joint above the top link, if any
  BodyType type = BodyType::Dynamic;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< top link frame in the model
  std::vector<ShapeDef> shapes;
  MassSum mass;
  std::vector<const urdf::Joint*> movingChildren;
  /// The links merged into the top link, each with its frame in the top link's.
  std::vector<std::pair<std::string, Eigen::Isometry3d>> mergedFrames;
  bool skipped = false;
};

struct MovingJoint {
  const urdf::Joint* joint = nullptr;
  size_t parentGroup = 0;
  size_t childGroup = 0;
};

// A joint folded into its parent's body (top-down worlds).
struct Fold {
  const urdf::Joint* joint = nullptr;
  size_t group = 0;
  const urdf::Link* child = nullptr;
  Eigen::Isometry3d childPose;  ///< the child link's frame in the model at position 0
};

struct Pending {
  const urdf::Link* link;
  size_t group;
  Eigen::Isometry3d pose;
};

std::string jointName(const urdf::Joint& joint) { return "joint " + quotedName(joint.name); }

class Projector {
 public:
  Projector(const urdf::ModelInterface& model, const PlaneAxes& plane,
            const UrdfPlacement& placement, UrdfModel* out)
      : model_(model), plane_(plane), placement_(placement), out_(out) {}

  std::string run() {
    if (model_.links_.size() > kMaxLinks) {
      return "the model has " + std::to_string(model_.links_.size()) + " links; at most " +
             std::to_string(kMaxLinks) + " are accepted";
    }
    std::string why = walk();
    if (why.empty()) why = makeBodies();
    if (why.empty()) why = makeJoints();
    if (why.empty()) why = makeFolded();
    return why;
  }

  // Where a link went (gazebo_devices.hpp): false for a link without a body.
  bool locate(const std::string& link, LinkPlace* out) const {
    const auto it = linkPlaces_.find(link);
    if (it == linkPlaces_.end() || groups_[it->second.first].skipped) return false;
    out->body = placement_.modelName + "/" + groups_[it->second.first].top->name;
    out->inBody = it->second.second;
    return true;
  }

 private:
  std::string walk() {
    const urdf::LinkConstSharedPtr root = model_.getRoot();
    if (!root) return "the model has no root link";
    std::vector<Pending> stack;
    if (root->name == kWorldLink) {
      addFrame(kWorldLink, "", placementPose());
      if (!root->collision_array.empty()) {
        out_->warnings.push_back("link 'world': collision skipped (the world link is the ground)");
      }
      for (const urdf::JointSharedPtr& joint : root->child_joints) {
        std::string why = startFromWorld(*joint, &stack);
        if (!why.empty()) return why;
      }
    } else {
      groups_.push_back(Group());
      groups_.back().top = root.get();
      stack.push_back({root.get(), 0, Eigen::Isometry3d::Identity()});
    }
    size_t visited = 0;
    while (!stack.empty()) {
      const Pending next = stack.back();
      stack.pop_back();
      if (++visited > model_.links_.size()) return "the links do not form a tree";
      const std::string why = visit(next, &stack);
      if (!why.empty()) return why;
    }
    return "";
  }

  std::string childOf(const urdf::Joint& joint, const Eigen::Isometry3d& parentPose,
                      const urdf::Link** child, Eigen::Isometry3d* childPose) const {
    const urdf::LinkConstSharedPtr link = model_.getLink(joint.child_link_name);
    if (!link) return jointName(joint) + ": no child link " + quotedName(joint.child_link_name);
    Eigen::Isometry3d origin;
    if (!toIsometry(joint.parent_to_joint_origin_transform, &origin)) {
      return jointName(joint) + ": origin: must be finite";
    }
    *child = link.get();
    *childPose = parentPose * origin;
    return "";
  }

  size_t startGroup(const urdf::Link* top, const urdf::Joint* parentJoint, BodyType type) {
    groups_.push_back(Group());
    groups_.back().top = top;
    groups_.back().parentJoint = parentJoint;
    groups_.back().type = type;
    return groups_.size() - 1;
  }

  std::string startFromWorld(const urdf::Joint& joint, std::vector<Pending>* stack) {
    const urdf::Link* child = nullptr;
    Eigen::Isometry3d pose;
    std::string why = childOf(joint, Eigen::Isometry3d::Identity(), &child, &pose);
    if (!why.empty()) return why;
    switch (joint.type) {
      case urdf::Joint::FIXED:
        stack->push_back({child, startGroup(child, &joint, BodyType::Static), pose});
        return "";
      case urdf::Joint::FLOATING:
      case urdf::Joint::PLANAR:
        stack->push_back({child, startGroup(child, &joint, BodyType::Dynamic), pose});
        return "";
      default:
        return jointName(joint) + ": a moving joint needs a body on both sides, and the 'world' " +
               "link is none; fix a base link to 'world' and hang the joint from it";
    }
  }

  std::string visit(const Pending& at, std::vector<Pending>* stack) {
    const urdf::Link& link = *at.link;
    Group& group = groups_[at.group];
    // A group's top link is visited before the links fixed to it, so its pose is known here.
    if (at.link == group.top) group.pose = at.pose;
    const Eigen::Isometry3d inBody =
        at.link == group.top ? Eigen::Isometry3d::Identity() : group.pose.inverse() * at.pose;
    if (at.link != group.top) group.mergedFrames.emplace_back(link.name, inBody);
    linkPlaces_.emplace(link.name, std::make_pair(at.group, inBody));
    std::string why = addCollisionShapes(plane_, link, inBody, &group.shapes, &out_->warnings,
                                         placement_.findPackage);
    if (why.empty() && group.type == BodyType::Dynamic) {
      why = addInertial(plane_, link, inBody, &group.mass);
    }
    if (!why.empty()) return why;

    for (const urdf::JointSharedPtr& joint : link.child_joints) {
      const urdf::Link* child = nullptr;
      Eigen::Isometry3d childPose;
      why = childOf(*joint, at.pose, &child, &childPose);
      if (!why.empty()) return why;
      if (joint->mimic) {
        out_->warnings.push_back(jointName(*joint) + ": mimic ignored (the joint moves freely)");
      }
      switch (joint->type) {
        case urdf::Joint::FIXED:
          stack->push_back({child, at.group, childPose});
          break;
        case urdf::Joint::REVOLUTE:
        case urdf::Joint::CONTINUOUS:
          if (folds(*joint, childPose)) {
            folds_.push_back({joint.get(), at.group, child, childPose});
            foldedLinks_.push_back(child->name);
            stack->push_back({child, at.group, childPose});
            break;
          }
          [[fallthrough]];
        case urdf::Joint::PRISMATIC: {
          const size_t childGroup = startGroup(child, joint.get(), BodyType::Dynamic);
          groups_[at.group].movingChildren.push_back(joint.get());
          moving_.push_back({joint.get(), at.group, childGroup});
          stack->push_back({child, childGroup, childPose});
          break;
        }
        case urdf::Joint::FLOATING:
        case urdf::Joint::PLANAR:
          stack->push_back({child, startGroup(child, joint.get(), BodyType::Dynamic), childPose});
          break;
        default:
          return jointName(*joint) + ": unknown joint type";
      }
    }
    return "";
  }

  // Whether a top-down world folds the joint: its axis, in the model, lies off the vertical.
  bool folds(const urdf::Joint& joint, const Eigen::Isometry3d& childPose) const {
    if (plane_.name != "xy" || placement_.strict) return false;
    const Eigen::Vector3d localAxis(joint.axis.x, joint.axis.y, joint.axis.z);
    if (!localAxis.allFinite() || localAxis.norm() < 1e-9) return false;  // makeJoints says so
    return !isNormal(plane_, childPose.linear() * localAxis.normalized());
  }

  bool isFolded(const std::string& link) const {
    return std::find(foldedLinks_.begin(), foldedLinks_.end(), link) != foldedLinks_.end();
  }

  // The radius of a cylinder of `link` whose axis is the joint's (a wheel), or 0.
  static double wheelRadius(const urdf::Link& link, const Eigen::Vector3d& jointAxis) {
    for (const urdf::CollisionSharedPtr& collision : link.collision_array) {
      if (!collision || !collision->geometry ||
          collision->geometry->type != urdf::Geometry::CYLINDER) {
        continue;
      }
      Eigen::Isometry3d origin;
      if (!toIsometry(collision->origin, &origin)) continue;
      const double radius = static_cast<const urdf::Cylinder&>(*collision->geometry).radius;
      if (std::abs(origin.linear().col(2).dot(jointAxis)) > 1.0 - 1e-6 && radius > 0.0) {
        return radius;
      }
    }
    return 0.0;
  }

  std::string makeFolded() {
    for (const Fold& fold : folds_) {
      const Group& group = groups_[fold.group];
      const urdf::Joint& joint = *fold.joint;
      if (group.skipped) continue;  // no body to fold into: the link went with it
      std::string why = prefixed(joint.name, "joint");
      if (!why.empty()) return why;
      UrdfFoldedJoint folded;
      folded.name = placement_.modelName + "/" + joint.name;
      folded.body = placement_.modelName + "/" + group.top->name;
      // A link whose name cannot be a frame is not on tf (addFrame warns of such links too).
      if (scene_detail::checkName(fold.child->name).empty()) {
        folded.link = placement_.modelName + "/" + fold.child->name;
      }
      folded.pose = group.pose.inverse() * fold.childPose;
      folded.axis = Eigen::Vector3d(joint.axis.x, joint.axis.y, joint.axis.z).normalized();
      folded.center = project(plane_, folded.pose.translation());
      const Vec2 planeAxis = project(plane_, folded.pose.linear() * folded.axis);
      folded.planeAxis = planeAxis.norm() > 1e-9 ? Vec2(planeAxis.normalized()) : Vec2::UnitY();
      folded.wheelRadius = wheelRadius(*fold.child, folded.axis);
      out_->folded.push_back(folded);
      out_->warnings.push_back(
          jointName(joint) + ": folded into body " + quotedName(folded.body) + " (its axis " +
          describe(fold.childPose.linear() * folded.axis) +
          " lies off the vertical: a wheel seen from above); strict refuses such models");
    }
    return "";
  }

  std::string prefixed(const std::string& name, const std::string& what) const {
    const std::string why = scene_detail::checkName(name);
    if (!why.empty()) {
      return what + " " + quotedName(name) + ": name " + why + " (names become tf frames)";
    }
    return "";
  }

  // The model's root frame in the world frame, in 3D.
  Eigen::Isometry3d placementPose() const {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = plane_.e1 * placement_.position.x() + plane_.e2 * placement_.position.y();
    pose.linear() = Eigen::AngleAxisd(placement_.angle, plane_.normal).toRotationMatrix();
    return pose;
  }

  // A link frame for tf. A name that cannot be a frame leaves the link off tf with a warning:
  // merged links never had to be named as frames.
  void addFrame(const std::string& link, const std::string& body, const Eigen::Isometry3d& pose) {
    if (!scene_detail::checkName(link).empty()) {
      out_->warnings.push_back("link " + quotedName(link) + ": not on tf, its name " +
                               scene_detail::checkName(link) + " (names become tf frames)");
      return;
    }
    out_->frames.push_back({placement_.modelName + "/" + link, body, pose});
  }

  // The frames of a group's links: fixed to its body, or, for a static group left without a
  // body, to the world (from the world link, which lies at the placement).
  void addGroupFrames(const Group& group) {
    if (!group.skipped) {
      const std::string body = placement_.modelName + "/" + group.top->name;
      for (const auto& [link, inBody] : group.mergedFrames) {
        if (!isFolded(link)) addFrame(link, body, inBody);  // a folded one turns: on /tf
      }
    } else if (group.type == BodyType::Static) {
      const Eigen::Isometry3d top = placementPose() * group.pose;
      addFrame(group.top->name, "", top);
      for (const auto& [link, inBody] : group.mergedFrames) addFrame(link, "", top * inBody);
    }
  }

  Vec2 worldPoint(const Vec2& modelPoint) const {
    return placement_.position + Rot(placement_.angle).apply(modelPoint);
  }

  std::string makeBodies() {
    for (Group& group : groups_) {
      const std::string& linkName = group.top->name;
      if (group.shapes.empty()) {
        if (!group.movingChildren.empty()) {
          return "link " + quotedName(linkName) + ": has no collision geometry (meshes are " +
                 "skipped), but " + jointName(*group.movingChildren.front()) +
                 " hangs from it; give it a box, cylinder or sphere collision";
        }
        group.skipped = true;
        out_->warnings.push_back("link " + quotedName(linkName) +
                                 " skipped with the links fixed to it: no collision geometry");
        addGroupFrames(group);
        continue;
      }
      std::string why = prefixed(linkName, "link");
      if (!why.empty()) return why;
      if (!keepsNormal(plane_, group.pose.linear())) {
        const std::string culprit = group.parentJoint
                                        ? jointName(*group.parentJoint) + ": its origin turns link "
                                        : "link ";
        return culprit + quotedName(linkName) + " out of the " + plane_.name +
               " plane (a roll or pitch); only a rotation about the plane normal (" +
               plane_.normalName + ") can be represented";
      }
      BodyDef def;
      def.name = placement_.modelName + "/" + linkName;
      def.type = group.type;
      def.position = worldPoint(project(plane_, group.pose.translation()));
      def.angle = placement_.angle + angleOf(plane_, group.pose.linear() * plane_.e1);
      def.shapes = group.shapes;
      if (group.type == BodyType::Dynamic && group.mass.mass > 0.0) {
        const double mass = group.mass.mass;
        def.mass = mass;
        def.useLocalCenter = true;
        def.localCenter = group.mass.moment / mass;
        const double inertia = group.mass.inertiaAtOrigin - mass * def.localCenter.squaredNorm();
        // Point masses give no inertia: the shapes' inertia, scaled to the mass, stands in.
        def.inertia = inertia > 1e-12 * mass ? inertia : 0.0;
      }
      out_->scene.bodies.push_back(def);
      addGroupFrames(group);
    }
    return "";
  }

  std::string limits(const urdf::Joint& joint, JointDef* def, UrdfJointInfo* info) const {
    if (!joint.limits) {
      if (joint.type == urdf::Joint::CONTINUOUS) return "";
      return jointName(joint) + ": <limit> is required for revolute and prismatic joints";
    }
    const urdf::JointLimits& limit = *joint.limits;
    if (!std::isfinite(limit.effort) || limit.effort < 0.0 || !std::isfinite(limit.velocity) ||
        limit.velocity < 0.0) {
      return jointName(joint) + ": limit effort and velocity must be finite and >= 0";
    }
    info->maxEffort = limit.effort;
    info->maxVelocity = limit.velocity;
    def->maxMotorTorque = limit.effort;
    if (joint.type == urdf::Joint::CONTINUOUS) return "";
    if (!std::isfinite(limit.lower) || !std::isfinite(limit.upper) || limit.lower > limit.upper) {
      return jointName(joint) + ": limit lower and upper must be finite with lower <= upper";
    }
    def->enableLimit = true;
    // The world measures along the plane's counter-clockwise normal; the URDF along its axis.
    def->lower = info->sign > 0.0 ? limit.lower : -limit.upper;
    def->upper = info->sign > 0.0 ? limit.upper : -limit.lower;
    return "";
  }

  std::string makeJoints() {
    for (const MovingJoint& moving : moving_) {
      const urdf::Joint& joint = *moving.joint;
      const Group& parent = groups_[moving.parentGroup];
      const Group& child = groups_[moving.childGroup];
      if (child.skipped) {
        out_->warnings.push_back(jointName(joint) + " skipped: its child link has no body");
        continue;
      }
      std::string why = prefixed(joint.name, "joint");
      if (!why.empty()) return why;
      const Eigen::Vector3d localAxis(joint.axis.x, joint.axis.y, joint.axis.z);
      if (!localAxis.allFinite() || localAxis.norm() < 1e-9) {
        return jointName(joint) + ": axis must be a finite, non-zero vector";
      }
      // The joint frame is the child link's frame.
      const Eigen::Vector3d axis = child.pose.linear() * localAxis.normalized();
      JointDef def;
      UrdfJointInfo info;
      def.name = placement_.modelName + "/" + joint.name;
      def.anchor = worldPoint(project(plane_, child.pose.translation()));
      if (joint.type == urdf::Joint::PRISMATIC) {
        if (!isInPlane(plane_, axis)) {
          return jointName(joint) + ": axis " + describe(localAxis) + " is not in the " +
                 plane_.name + " plane; a prismatic joint must slide along the plane";
        }
        def.type = info.type = JointType::Prismatic;
        def.axis = Rot(placement_.angle).apply(project(plane_, axis).normalized());
      } else {
        if (!isNormal(plane_, axis)) {
          return jointName(joint) + ": axis " + describe(localAxis) + " is not along the " +
                 plane_.name + " plane's normal (" + plane_.normalName +
                 "); a revolute joint must turn in the plane";
        }
        def.type = info.type = JointType::Revolute;
        info.sign = axis.dot(plane_.normal) > 0.0 ? 1.0 : -1.0;
      }
      why = limits(joint, &def, &info);
      if (!why.empty()) return why;
      info.name = def.name;
      SceneJoint sceneJoint;
      sceneJoint.def = def;
      sceneJoint.bodyA = placement_.modelName + "/" + parent.top->name;
      sceneJoint.bodyB = placement_.modelName + "/" + child.top->name;
      out_->scene.joints.push_back(sceneJoint);
      out_->joints.push_back(info);
    }
    return "";
  }

  const urdf::ModelInterface& model_;
  const PlaneAxes& plane_;
  const UrdfPlacement& placement_;
  UrdfModel* out_;
  std::vector<Group> groups_;
  std::vector<MovingJoint> moving_;
  std::vector<Fold> folds_;
  std::vector<std::string> foldedLinks_;
  std::map<std::string, std::pair<size_t, Eigen::Isometry3d>> linkPlaces_;  // group, in its body
};

}  // namespace
}  // namespace urdf_detail

bool parseUrdf(const std::string& urdfXml, const UrdfPlacement& placement, UrdfModel* out,
               std::string* error) {
  using namespace urdf_detail;
  std::string why;
  *out = UrdfModel();
  PlaneAxes plane;
  if (!planeAxes(placement.plane, &plane)) {
    why = "plane: must be xz or xy";
  } else if (!scene_detail::checkName(placement.modelName).empty()) {
    why = "model_name: " + scene_detail::checkName(placement.modelName);
  } else if (!placement.position.allFinite() || !std::isfinite(placement.angle)) {
    why = "pose: must be finite";
  }
  if (why.empty()) {
    const urdf::ModelInterfaceSharedPtr model = parseUrdfText(urdfXml, &why);
    const ModelReleaser releaser(model);
    if (model) {
      out->scene.plane = placement.plane;
      Projector projector(*model, plane, placement, out);
      why = projector.run();
      if (why.empty()) {
        why = gazeboDevices(
            urdfXml, plane, placement.modelName,
            [&](const std::string& link, LinkPlace* place) {
              return projector.locate(link, place);
            },
            &out->scene.devices, &out->warnings);
      }
      // A sensor's frame named after its link is the sensor's, at the sensor's pose: the link's
      // own frame leaves tf_static, which would otherwise have two places for it.
      for (const DeviceDef& device : out->scene.devices) {
        out->frames.erase(
            std::remove_if(out->frames.begin(), out->frames.end(),
                           [&](const UrdfFrame& f) { return f.name == device.frame; }),
            out->frames.end());
      }
      if (why.empty() && out->scene.bodies.empty()) {
        why = "the model has no link with collision geometry (meshes are skipped)";
      }
    }
  }
  if (!why.empty()) *out = UrdfModel();
  if (error != nullptr) *error = why;
  return why.empty();
}

}  // namespace impulse2d
