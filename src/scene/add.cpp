// Adding a parsed scene to a world, all or nothing: everything that can be checked is checked
// before the world changes, and what was created is destroyed again if creation still fails.
#include <impulse2d/scene.hpp>

#include "names.hpp"

#include <map>

namespace impulse2d {

using scene_detail::checkName;
using scene_detail::printable;

namespace {

std::string context(const char* list, size_t index, const std::string& name) {
  return std::string(list) + "[" + std::to_string(index) + "] '" + printable(name) + "': ";
}

// A joint's body: one of the scene's (by index, created later) or one already in the world.
struct BodyRef {
  size_t sceneIndex = 0;
  BodyId worldId;
};

class SceneAdder {
 public:
  SceneAdder(const Scene& scene, World& world) : scene_(scene), world_(world) {}
  ~SceneAdder() {
    if (!done_) rollBack();
  }

  std::string add() {
    std::string why = checkBodies();
    if (why.empty()) why = checkJointNames();
    if (why.empty()) why = checkDeviceBodies();
    if (why.empty()) why = createBodies();
    if (why.empty()) why = createJoints();
    done_ = why.empty();
    if (!done_) rollBack();
    return why;
  }

  const std::vector<BodyId>& bodies() const { return bodies_; }
  const std::vector<JointId>& joints() const { return joints_; }

 private:
  std::string checkBodies() {
    for (size_t i = 0; i < scene_.bodies.size(); ++i) {
      const BodyDef& def = scene_.bodies[i];
      const std::string where = context("bodies", i, def.name);
      std::string why = checkName(def.name);
      if (!why.empty()) return where + "name: " + why;
      const auto clash = sceneBodies_.find(def.name);
      if (clash != sceneBodies_.end()) {
        return where + "name: already used by bodies[" + std::to_string(clash->second) + "]";
      }
      if (world_.findBody(def.name).valid()) {
        return where + "name: the world already has a body of that name";
      }
      why = World::validate(def);
      if (!why.empty()) return where + why;
      sceneBodies_.emplace(def.name, i);
    }
    return "";
  }

  std::string resolve(const std::string& name, const char* key, const std::string& where,
                      BodyRef* out) const {
    const auto inScene = sceneBodies_.find(name);
    if (inScene != sceneBodies_.end()) {
      out->sceneIndex = inScene->second;
      return "";
    }
    out->worldId = world_.findBody(name);
    if (out->worldId.valid()) return "";
    return where + key + ": no body named '" + printable(name) + "' in the scene or the world";
  }

  std::string checkJointNames() {
    std::map<std::string, size_t> seen;
    for (size_t j = 0; j < scene_.joints.size(); ++j) {
      const SceneJoint& joint = scene_.joints[j];
      const std::string where = context("joints", j, joint.def.name);
      const std::string why = checkName(joint.def.name);
      if (!why.empty()) return where + "name: " + why;
      const auto clash = seen.find(joint.def.name);
      if (clash != seen.end()) {
        return where + "name: already used by joints[" + std::to_string(clash->second) + "]";
      }
      if (world_.findJoint(joint.def.name).valid()) {
        return where + "name: the world already has a joint of that name";
      }
      seen.emplace(joint.def.name, j);
      if (joint.bodyA == joint.bodyB) {
        return where + "body_b: joins body '" + printable(joint.bodyA) + "' to itself";
      }
      BodyRef a, b;
      std::string missing = resolve(joint.bodyA, "body_a", where, &a);
      if (missing.empty()) missing = resolve(joint.bodyB, "body_b", where, &b);
      if (!missing.empty()) return missing;
      refs_.emplace_back(a, b);
    }
    return "";
  }

  std::string checkDeviceBodies() const {
    for (size_t d = 0; d < scene_.devices.size(); ++d) {
      const DeviceDef& device = scene_.devices[d];
      const std::string where = context("devices", d, device.name);
      BodyRef ref;
      const std::string missing = resolve(device.body, "body", where, &ref);
      if (!missing.empty()) return missing;
      const BodyType type =
          ref.worldId.valid() ? world_.body(ref.worldId).type : scene_.bodies[ref.sceneIndex].type;
      if (isDrive(device.type) && type != BodyType::Dynamic) {
        return where + "body: '" + printable(device.body) + "' is not dynamic; " +
               deviceTypeWithArticle(device.type) + " moves its body with forces";
      }
    }
    return "";
  }

  std::string createBodies() {
    for (size_t i = 0; i < scene_.bodies.size(); ++i) {
      std::string why;
      const BodyId id = world_.createBody(scene_.bodies[i], &why);
      if (!id.valid()) {
        return context("bodies", i, scene_.bodies[i].name) + (why.empty() ? "not created" : why);
      }
      bodies_.push_back(id);
    }
    return "";
  }

  BodyId idOf(const BodyRef& ref) const {
    return ref.worldId.valid() ? ref.worldId : bodies_[ref.sceneIndex];
  }

  // Joints are checked only now because the world checks them against bodies that exist.
  std::string createJoints() {
    std::vector<JointDef> defs;
    for (size_t j = 0; j < scene_.joints.size(); ++j) {
      const SceneJoint& joint = scene_.joints[j];
      JointDef def = joint.def;
      def.bodyA = idOf(refs_[j].first);
      def.bodyB = idOf(refs_[j].second);
      if (!joint.hasLength) def.length = 0.0;  // the world measures the current distance
      const std::string why = world_.validate(def);
      if (!why.empty()) return context("joints", j, def.name) + why;
      defs.push_back(def);
    }
    for (size_t j = 0; j < defs.size(); ++j) {
      std::string why;
      const JointId id = world_.createJoint(defs[j], &why);
      if (!id.valid())
        return context("joints", j, defs[j].name) + (why.empty() ? "not created" : why);
      joints_.push_back(id);
    }
    return "";
  }

  void rollBack() {
    for (auto it = joints_.rbegin(); it != joints_.rend(); ++it) world_.destroyJoint(*it);
    for (auto it = bodies_.rbegin(); it != bodies_.rend(); ++it) world_.destroyBody(*it);
    joints_.clear();
    bodies_.clear();
  }

  const Scene& scene_;
  World& world_;
  std::map<std::string, size_t> sceneBodies_;
  std::vector<std::pair<BodyRef, BodyRef>> refs_;
  std::vector<BodyId> bodies_;
  std::vector<JointId> joints_;
  bool done_ = false;
};

}  // namespace

bool addScene(const Scene& scene, World& world, std::string* error,
              std::vector<BodyId>* createdBodies, std::vector<JointId>* createdJoints) {
  SceneAdder adder(scene, world);
  const std::string why = adder.add();
  if (createdBodies != nullptr)
    *createdBodies = why.empty() ? adder.bodies() : std::vector<BodyId>();
  if (createdJoints != nullptr) {
    *createdJoints = why.empty() ? adder.joints() : std::vector<JointId>();
  }
  if (error != nullptr) *error = why;
  return why.empty();
}

}  // namespace impulse2d
