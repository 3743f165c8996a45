// Loading the one YAML document of a scene, safe from yaml-cpp 0.7's endless loops.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>

namespace impulse2d {
namespace scene_detail {

/// The text's only YAML document (a null node when there is none). Throws YAML::ParserException
/// for a syntax error and SceneError when the text holds more than one document.
YAML::Node loadSingleDocument(const std::string& text);

}  // namespace scene_detail
}  // namespace impulse2d
