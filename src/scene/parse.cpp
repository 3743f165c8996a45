// Reads the contract's scene YAML into a Scene, refusing it whole at the first problem with one
// line that names the key and the body or joint.
#include <impulse2d/limits.hpp>
#include <impulse2d/scene.hpp>

#include "names.hpp"
#include "scene_parsers.hpp"
#include "yaml_document.hpp"
#include "yaml_fields.hpp"

#include <cstring>
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

// `maps:`: each map's walls join the scene's bodies, after its own; their names may not clash.
void parseMaps(const Fields& top, const ScenePaths& paths, Scene* scene) {
  if (!top.has("maps")) return;
  const YAML::Node& list = top.node("maps");
  if (!list.IsNull() && !list.IsSequence()) throw SceneError("maps", "must be a list");
  std::map<std::string, std::string> taken;  // body name -> who has it
  for (size_t b = 0; b < scene->bodies.size(); ++b) {
    taken.emplace(scene->bodies[b].name, "bodies[" + std::to_string(b) + "]");
  }
  size_t i = 0;
  for (const YAML::Node& node : list) {
    const std::string context = entryContext("maps", i, node);
    try {
      std::vector<BodyDef> walls;
      SceneMap map = parseMap(node, paths, &walls);
      for (const BodyDef& wall : walls) {
        const auto clash = taken.emplace(wall.name, context);
        if (!clash.second) {
          throw SceneError("name", "its body " + quoted(wall.name) + " is already " +
                                       clash.first->second + "'s");
        }
      }
      scene->maps.push_back(std::move(map));
      for (BodyDef& wall : walls) scene->bodies.push_back(std::move(wall));
    } catch (const SceneError& e) {
      throw SceneError("", context + ": " + e.what());
    }
    ++i;
  }
}

// `models:`: each model file's bodies, joints and devices, placed and named in its namespace.
void parseModels(const Fields& top, const ScenePaths& paths, Scene* scene) {
  if (!top.has("models")) return;
  const YAML::Node& list = top.node("models");
  if (!list.IsNull() && !list.IsSequence()) throw SceneError("models", "must be a list");
  size_t i = 0;
  for (const YAML::Node& node : list) {
    const std::string context = entryContext("models", i, node);
    try {
      const Fields f(node, "a model entry", {"name", "file", "namespace", "position", "angle"});
      ModelPlacement where;
      where.name = f.name("name");
      where.ns = f.string("namespace", "");
      where.position = f.vec2("position", where.position);
      where.angle = f.number("angle", where.angle);
      if (!f.has("file")) throw SceneError("file", "must be given: a model's YAML file");
      const std::string file = resolveFile(f.string("file", ""), paths);
      Scene model;
      std::string why;
      if (!loadModelFile(file, &model, &why)) throw SceneError("file", why);
      if (!placeModel(model, where, scene, &why, file)) throw SceneError("", why);
    } catch (const SceneError& e) {
      throw SceneError("", context + ": " + e.what());
    }
    ++i;
  }
}

Scene parseDocument(const YAML::Node& doc, const ScenePaths& paths) {
  if (doc.IsNull()) {
    throw SceneError("",
                     "the scene is empty (expected world, bodies, joints, devices, maps, models)");
  }
  const Fields top(doc, "a scene (keys world, bodies, joints, devices, maps, models)",
                   {"world", "bodies", "joints", "devices", "maps", "models"});
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
  parseMaps(top, paths, &scene);
  parseModels(top, paths, &scene);
  return scene;
}

Scene parseModelDocument(const YAML::Node& doc) {
  if (doc.IsNull()) throw SceneError("", "the model is empty (expected bodies, joints, devices)");
  const Fields top(doc, "a model", {"bodies", "joints", "devices"});
  Scene model;
  parseList(top, "bodies", parseBody, &model.bodies);
  parseList(top, "joints", parseJoint, &model.joints);
  parseList(top, "devices", parseDevice, &model.devices);
  return model;
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

// Parses one YAML document with `parse`, turning every exception into one line.
template <typename Parse>
bool parseText(const std::string& yamlText, const char* what, Parse parse, Scene* out,
               std::string* error) {
  // yaml-cpp's node tree costs tens of times the text: refuse before parsing.
  if (yamlText.size() > kMaxSceneBytes) {
    return fail(error, "the " + std::string(what) + " is " + std::to_string(yamlText.size()) +
                           " bytes; at most " + std::to_string(kMaxSceneBytes) + " are accepted");
  }
  try {
    Scene scene = parse(loadSingleDocument(yamlText));
    if (out != nullptr) *out = std::move(scene);
    return true;
  } catch (const YAML::ParserException& e) {
    if (e.mark.is_null()) return fail(error, "YAML syntax error: " + e.msg);
    return fail(error, "YAML syntax error at line " + std::to_string(e.mark.line + 1) +
                           ", column " + std::to_string(e.mark.column + 1) + ": " + e.msg);
  } catch (const SceneError& e) {
    return fail(error, e.what());
  } catch (const std::exception& e) {
    return fail(error, "cannot read the " + std::string(what) + ": " + e.what());
  } catch (...) {
    return fail(error, "cannot read the " + std::string(what));
  }
}

}  // namespace
}  // namespace scene_detail

bool parseScene(const std::string& yamlText, Scene* out, std::string* error) {
  return parseScene(yamlText, ScenePaths(), out, error);
}

bool parseScene(const std::string& yamlText, const ScenePaths& paths, Scene* out,
                std::string* error) {
  return scene_detail::parseText(
      yamlText, "scene",
      [&](const YAML::Node& doc) { return scene_detail::parseDocument(doc, paths); }, out, error);
}

bool parseModel(const std::string& yamlText, Scene* out, std::string* error) {
  return scene_detail::parseText(yamlText, "model", scene_detail::parseModelDocument, out, error);
}

bool loadModelFile(const std::string& path, Scene* out, std::string* error) {
  using scene_detail::fail;
  // The node opens these for ~spawn_model's callers: only regular files (a FIFO would hang it)
  // named as YAML (nothing else is read, and no other file's lines end up in an error).
  const bool yaml = [&] {
    for (const char* ext : {".yaml", ".yml"}) {
      const size_t n = std::strlen(ext);
      if (path.size() > n && path.compare(path.size() - n, n, ext) == 0) return true;
    }
    return false;
  }();
  if (!yaml) return fail(error, path + ": a model file's name ends in .yaml or .yml");
  const std::string notAFile = scene_detail::whyNotAFile(path);
  if (!notAFile.empty()) return fail(error, path + ": cannot open (" + notAFile + ")");
  std::string text, why;
  if (!scene_detail::readSceneText(path, &text, error)) return false;
  if (!parseModel(text, out, &why)) return scene_detail::fail(error, path + ": " + why);
  return true;
}

bool loadSceneFile(const std::string& path, Scene* out, std::string* error) {
  return loadSceneFile(path, ScenePaths(), out, error);
}

bool loadSceneFile(const std::string& path, const ScenePaths& base, Scene* out,
                   std::string* error) {
  using scene_detail::fail;
  std::string text;
  if (!scene_detail::readSceneText(path, &text, error)) return false;
  ScenePaths paths = base;
  paths.folder.clear();
  const size_t slash = path.find_last_of('/');
  if (slash != std::string::npos) paths.folder = path.substr(0, slash + 1);
  std::string why;
  if (!parseScene(text, paths, out, &why)) return fail(error, path + ": " + why);
  return true;
}

}  // namespace impulse2d
