// The parsers of one scene entry each; they throw SceneError naming the key within the entry.
#pragma once

#include <impulse2d/scene.hpp>

#include <yaml-cpp/yaml.h>

namespace impulse2d {
namespace scene_detail {

/// The `world:` map into scene->world, plane and frameId.
void parseWorld(const YAML::Node& node, Scene* scene);
/// One entry of `bodies:`, checked with World::validate(BodyDef).
BodyDef parseBody(const YAML::Node& node);
/// One entry of `joints:`; bodies are resolved by name only when the scene is added.
SceneJoint parseJoint(const YAML::Node& node);
/// One entry of `devices:`; its body is resolved by name only when the scene is added.
DeviceDef parseDevice(const YAML::Node& node);
/// A file name of a scene: absolute, relative to paths.folder, or package://PACKAGE/PATH;
/// throws SceneError("file", ...) when it cannot be resolved.
std::string resolveFile(const std::string& name, const ScenePaths& paths);
/// Empty when `path` names a regular file, else why it cannot be read as one: "No such file or
/// directory", "a directory, not a file", "not a regular file" (a FIFO or a device would block
/// or never end).
std::string whyNotAFile(const std::string& path);
/// Reads a scene's or a model's text, at most kMaxSceneBytes; false with "PATH: why" otherwise.
bool readSceneText(const std::string& path, std::string* text, std::string* error);
/// One entry of `maps:`: reads its files and appends its walls to `walls`.
SceneMap parseMap(const YAML::Node& node, const ScenePaths& paths, std::vector<BodyDef>* walls);

}  // namespace scene_detail
}  // namespace impulse2d
