// Where a scene's files are: names resolved against the scene's folder or a ROS package, and
// files read with a bound.
#include <impulse2d/limits.hpp>
#include <impulse2d/scene.hpp>

#include "names.hpp"
#include "scene_parsers.hpp"
#include "yaml_fields.hpp"

#include <sys/stat.h>

#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>

namespace impulse2d {
namespace scene_detail {

std::string resolveFile(const std::string& name, const ScenePaths& paths) {
  const std::string scheme = "package://";
  if (name.compare(0, scheme.size(), scheme) == 0) {
    const std::string rest = name.substr(scheme.size());
    const size_t slash = rest.find('/');
    if (slash == std::string::npos || slash == 0) {
      throw SceneError("file", "must be package://PACKAGE/PATH, not " + quoted(name));
    }
    const std::string package = rest.substr(0, slash);
    for (const char c : package) {
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) {
        throw SceneError("file", "package://" + package + ": not a ROS package name (REP 144)");
      }
    }
    if (!paths.findPackage) {
      throw SceneError("file",
                       "package:// names need a package finder (the node and "
                       "impulse2d_sim have one)");
    }
    std::string why;
    const std::string folder = paths.findPackage(package, &why);
    if (folder.empty()) throw SceneError("file", why);
    return folder + rest.substr(slash);
  }
  if (!name.empty() && name[0] == '/') return name;
  if (paths.folder.empty()) return name;
  return paths.folder + (paths.folder.back() == '/' ? "" : "/") + name;
}

std::string whyNotAFile(const std::string& path) {
  struct stat info {};
  if (stat(path.c_str(), &info) != 0) return std::strerror(errno);
  if (S_ISDIR(info.st_mode)) return "a directory, not a file";
  if (!S_ISREG(info.st_mode)) return "not a regular file";
  return "";
}

bool readSceneText(const std::string& path, std::string* text, std::string* error) {
  auto fail = [&](const std::string& why) {
    if (error != nullptr) *error = path + ": " + why;
    return false;
  };
  std::ifstream file(path, std::ios::binary);
  if (!file) return fail(std::string("cannot open (") + std::strerror(errno) + ")");
  text->clear();
  char chunk[1 << 16];
  while (file.read(chunk, sizeof chunk) || file.gcount() > 0) {
    text->append(chunk, static_cast<size_t>(file.gcount()));
    // A file larger than this is surely not a scene (or is /dev/zero): reading stops there.
    if (text->size() > kMaxSceneBytes) {
      return fail("larger than " + std::to_string(kMaxSceneBytes >> 20) +
                  " MiB, too large for a scene");
    }
  }
  if (file.bad()) return fail(std::string("cannot read (") + std::strerror(errno) + ")");
  return true;
}

}  // namespace scene_detail

std::string resolveSceneFile(const std::string& name, const ScenePaths& paths, std::string* error) {
  try {
    return scene_detail::resolveFile(name, paths);
  } catch (const scene_detail::SceneError& e) {
    if (error != nullptr) *error = e.what();
    return "";
  }
}

std::string findPackageOnPath(const std::string& package, std::string* error) {
  const char* list = std::getenv("ROS_PACKAGE_PATH");
  std::string entries = list == nullptr ? "" : list;
  size_t start = 0;
  while (start <= entries.size()) {
    size_t end = entries.find(':', start);
    if (end == std::string::npos) end = entries.size();
    std::string entry = entries.substr(start, end - start);
    while (entry.size() > 1 && entry.back() == '/') entry.pop_back();
    start = end + 1;
    if (entry.empty()) continue;
    const std::string inside = entry + "/" + package;
    if (std::ifstream(inside + "/package.xml").good()) return inside;
    // The entry may be the package's own folder, whatever its name: its package.xml says.
    std::ifstream own(entry + "/package.xml");
    const std::string xml((std::istreambuf_iterator<char>(own)), std::istreambuf_iterator<char>());
    if (xml.find("<name>" + package + "</name>") != std::string::npos) return entry;
  }
  if (error != nullptr) {
    *error = "no package named '" + package + "' on ROS_PACKAGE_PATH (" +
             (list == nullptr ? "not set: source a workspace's devel/setup.bash" : entries) + ")";
  }
  return "";
}

}  // namespace impulse2d
