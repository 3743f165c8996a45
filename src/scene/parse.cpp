// Reads the contract's scene YAML into a Scene, refusing it whole at the first problem with one
// line that names the key and the body or joint.
#include <impulse2d/limits.hpp>
#include <impulse2d/scene.hpp>

#include "names.hpp"
#include "scene_parsers.hpp"
#include "yaml_document.hpp"
#include "yaml_fields.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>

namespace impulse2d {
namespace scene_detail {
namespace {

// "bodies[3] 'box3'" when the entry has a usable name, else "bodies[3]".
std::string entryContext(const char* list, size_t index, const YAML::Node& node) {
  std::string context = std::string(list) + "[" + std::to_string(index) + "]";
  if (node.IsMap()) {
    const YAML::Node name = node["name"];
    if (name && name.IsScalar() && !name.Scalar().empty()) context += " " + quoted(name.Scalar());
  }
  return context;
}

const std::string& nameOf(const BodyDef& body) { return body.name; }
const std::string& nameOf(const SceneJoint& joint) { return joint.def.name; }
const std::string& nameOf(const DeviceDef& device) { return device.name; }

template <typename Item>
void parseList(const Fields& top, const char* key, Item (*parse)(const YAML::Node&),
               std::vector<Item>* out) {
  if (!top.has(key)) return;
  const YAML::Node& list = top.node(key);
  if (!list.IsNull() && !list.IsSequence()) throw SceneError(key, "must be a list");
  std::map<std::string, size_t> seen;
  size_t i = 0;
  for (const YAML::Node& node : list) {
    try {
      Item item = parse(node);
      const auto clash = seen.find(nameOf(item));
      if (clash != seen.end()) {
        throw SceneError("name", "already used by " + std::string(key) + "[" +
                                     std::to_string(clash->second) + "]");
      }
      seen.emplace(nameOf(item), i);
      out->push_back(std::move(item));
    } catch (const SceneError& e) {
      throw SceneError("", entryContext(key, i, node) + ": " + e.what());
    }
    ++i;
  }
}

Scene parseDocument(const YAML::Node& doc) {
  if (doc.IsNull()) {
    throw SceneError("", "the scene is empty (expected world, bodies, joints, devices)");
  }
  const Fields top(doc, "a scene (keys world, bodies, joints, devices)",
                   {"world", "bodies", "joints", "devices"});
  Scene scene;
  if (top.has("world")) {
    try {
      parseWorld(top.node("world"), &scene);
    } catch (const SceneError& e) {
      throw SceneError("", std::string("world: ") + e.what());
    }
  }
  parseList(top, "bodies", parseBody, &scene.bodies);
  parseList(top, "joints", parseJoint, &scene.joints);
  parseList(top, "devices", parseDevice, &scene.devices);
  return scene;
}

bool fail(std::string* error, const std::string& message) {
  if (error != nullptr) {
    *error = message;
    // One line, whatever yaml-cpp or the input put in it.
    for (char& c : *error) {
      if (c == '\n' || c == '\r' || c == '\t') c = ' ';
    }
  }
  return false;
}

}  // namespace
}  // namespace scene_detail

bool parseScene(const std::string& yamlText, Scene* out, std::string* error) {
  using scene_detail::fail;
  // yaml-cpp's node tree costs tens of times the text: refuse before parsing.
  if (yamlText.size() > kMaxSceneBytes) {
    return fail(error, "the scene is " + std::to_string(yamlText.size()) + " bytes; at most " +
                           std::to_string(kMaxSceneBytes) + " are accepted");
  }
  try {
    Scene scene = scene_detail::parseDocument(scene_detail::loadSingleDocument(yamlText));
    if (out != nullptr) *out = std::move(scene);
    return true;
  } catch (const YAML::ParserException& e) {
    if (e.mark.is_null()) return fail(error, "YAML syntax error: " + e.msg);
    return fail(error, "YAML syntax error at line " + std::to_string(e.mark.line + 1) +
                           ", column " + std::to_string(e.mark.column + 1) + ": " + e.msg);
  } catch (const scene_detail::SceneError& e) {
    return fail(error, e.what());
  } catch (const std::exception& e) {
    return fail(error, std::string("cannot read the scene: ") + e.what());
  } catch (...) {
    return fail(error, "cannot read the scene");
  }
}

bool loadSceneFile(const std::string& path, Scene* out, std::string* error) {
  using scene_detail::fail;
  std::ifstream file(path, std::ios::binary);
  if (!file) return fail(error, path + ": cannot open (" + std::strerror(errno) + ")");
  std::string text;
  char chunk[1 << 16];
  while (file.read(chunk, sizeof chunk) || file.gcount() > 0) {
    text.append(chunk, static_cast<size_t>(file.gcount()));
    // A file larger than this is surely not a scene (or is /dev/zero): reading stops there.
    if (text.size() > kMaxSceneBytes) {
      return fail(error, path + ": larger than " + std::to_string(kMaxSceneBytes >> 20) +
                             " MiB, too large for a scene");
    }
  }
  if (file.bad()) return fail(error, path + ": cannot read (" + std::strerror(errno) + ")");
  std::string why;
  if (!parseScene(text, out, &why)) return fail(error, path + ": " + why);
  return true;
}

}  // namespace impulse2d
