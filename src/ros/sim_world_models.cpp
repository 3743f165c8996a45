// SimWorld's models: spawned from a file or YAML text under a name and namespace, deleted whole,
// moved rigidly. A scene's `models:` are recorded when the scene is added (sim_world.cpp).
#include "sim_world.hpp"

#include <impulse2d/devices.hpp>
#include <impulse2d/drive.hpp>
#include <impulse2d/limits.hpp>
#include <impulse2d/scene.hpp>

#include <algorithm>
#include <cmath>

namespace impulse2d {
namespace bridge {

std::string SimWorld::checkModelNames(const std::vector<SceneModel>& models) const {
  for (const SceneModel& model : models) {
    for (const PlacedModel& placed : models_) {
      if (placed.def.name == model.name) {
        return "a model named " + quoted(model.name) + " already exists";
      }
    }
  }
  return "";
}

void SimWorld::recordModels(const std::vector<SceneModel>& models) {
  for (const SceneModel& model : models) {
    PlacedModel placed;
    placed.def = model;
    for (const std::string& body : model.bodies) placed.bodies.push_back(world_->findBody(body));
    models_.push_back(std::move(placed));
  }
}

std::vector<std::string> SimWorld::modelNames() const {
  std::vector<std::string> names;
  for (const PlacedModel& model : models_) names.push_back(model.def.name);
  return names;
}

bool SimWorld::spawnModel(const ModelRequest& request, ModelSpawned* out, std::string* error) {
  if (request.file.empty() == request.yaml.empty()) {
    *error = request.file.empty() ? "file, model_yaml: give one (a model file or its YAML text)"
                                  : "file, model_yaml: give one, not both";
    return false;
  }
  Scene model;
  std::string file;
  if (!request.file.empty()) {
    // The node's working directory means little to a caller: names must say where they are.
    if (request.file[0] != '/' && request.file.compare(0, 10, "package://") != 0) {
      *error = "file: must be absolute or package://PACKAGE/PATH, not " + quoted(request.file);
      return false;
    }
    ScenePaths paths;
    paths.findPackage = findPackage_;
    file = resolveSceneFile(request.file, paths, error);
    if (file.empty() || !loadModelFile(file, &model, error)) {
      *error = "file: " + *error;
      return false;
    }
  } else if (!parseModel(request.yaml, &model, error)) {
    *error = "model_yaml: " + *error;
    return false;
  }
  Scene placed;
  if (!placeModel(model, request.where, &placed, error, file)) return false;
  const std::string taken = checkModelNames(placed.models);
  if (!taken.empty()) {
    *error = "model_name: " + taken;
    return false;
  }
  // The devices are checked against the devices here before anything is added.
  *error = devices_->check(placed.devices, deviceContext());
  if (!error->empty()) return false;
  if (!impulse2d::addScene(placed, *world_, error)) return false;
  addDevices(placed.devices, error);  // checked above: cannot fail
  recordModels(placed.models);
  ++staticVersion_;  // its static bodies and sensor frames join tf_static
  const SceneModel& def = placed.models.front();
  if (out != nullptr) *out = ModelSpawned{def.bodies, def.joints, def.devices};
  return true;
}

bool SimWorld::deleteModel(const std::string& name, std::string* error) {
  const auto model = std::find_if(models_.begin(), models_.end(),
                                  [&](const PlacedModel& m) { return m.def.name == name; });
  if (name.empty() || model == models_.end()) {
    *error = name.empty() ? "model_name: must not be empty"
                          : "model_name: no model named " + quoted(name);
    return false;
  }
  for (const BodyId body : model->bodies) {
    if (!world_->isValid(body)) continue;  // deleted or removed by the world since
    wrenches_.erase(std::remove_if(wrenches_.begin(), wrenches_.end(),
                                   [&](const Wrench& w) { return w.body == body; }),
                    wrenches_.end());
    world_->destroyBody(body);  // its joints go with it
  }
  devices_->dropDetached(*world_);
  pruneUrdfFrames();
  models_.erase(model);
  ++staticVersion_;
  return true;
}

bool SimWorld::moveModel(const std::string& name, const Vec2& position, double angle,
                         std::string* error) {
  const auto model = std::find_if(models_.begin(), models_.end(),
                                  [&](const PlacedModel& m) { return m.def.name == name; });
  if (name.empty() || model == models_.end()) {
    *error = name.empty() ? "model_name: must not be empty"
                          : "model_name: no model named " + quoted(name);
    return false;
  }
  if (!position.allFinite() || position.cwiseAbs().maxCoeff() > kMaxCoordinate ||
      !std::isfinite(angle)) {
    *error = "pose: must be finite and within 1e6 m of the origin";
    return false;
  }
  // The first body still here is put where the file puts it in a model at the pose; the rest
  // turn and move with it:
  //
  //       now                       after
  //    B . . . A(first)   --->   target = pose * local(A)
  //    every body b:  b' = target * now(A)^-1 * b
  const std::vector<BodyId>& bodies = model->bodies;
  const auto first =
      std::find_if(bodies.begin(), bodies.end(), [&](BodyId id) { return world_->isValid(id); });
  if (first == bodies.end()) {
    *error = "model_name: " + quoted(name) + " has no body left in the world";
    return false;
  }
  const size_t k = static_cast<size_t>(first - bodies.begin());
  const Body& anchor = world_->body(*first);
  const Vec2 anchorAt = anchor.xf.p;
  const double turn = angle + model->def.localAngles[k] - anchor.angle;
  const Vec2 target = Rot(angle).apply(model->def.localPositions[k]) + position;
  const Rot rotation(turn);
  std::vector<Vec2> moved;
  for (const BodyId id : bodies) {
    if (!world_->isValid(id)) continue;
    moved.push_back(rotation.apply(world_->body(id).xf.p - anchorAt) + target);
    if (moved.back().cwiseAbs().maxCoeff() > kMaxCoordinate) {
      *error = "pose: would put a body of the model beyond 1e6 m of the origin";
      return false;
    }
  }
  size_t next = 0;
  for (const BodyId id : bodies) {
    if (!world_->isValid(id)) continue;
    const Body& body = world_->body(id);
    const bool isStatic = body.type == BodyType::Static;
    world_->setTransform(id, moved[next++], body.angle + turn);
    if (!isStatic) world_->setVelocity(id, Vec2::Zero(), 0.0);
    if (isStatic) ++staticVersion_;
    wrenches_.erase(std::remove_if(wrenches_.begin(), wrenches_.end(),
                                   [&](const Wrench& w) { return w.body == id; }),
                    wrenches_.end());
  }
  for (Device& device : devices_->devices()) {
    if (device.drive && std::find(bodies.begin(), bodies.end(), device.body) != bodies.end()) {
      device.drive->halt();
    }
  }
  return true;
}

}  // namespace bridge
}  // namespace impulse2d
