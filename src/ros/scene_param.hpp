// Reading the ~scene parameter, which may hold YAML text (<param textfile=...>) or the scene as a
// dictionary (<rosparam command="load" ...>).
#pragma once

#include <ros/node_handle.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <string>

namespace impulse2d {
namespace bridge {

/// A parameter value as YAML text (flow style, i.e. JSON-like) that parses back to the same
/// values: strings are quoted, doubles keep all 17 digits, non-finite doubles become .inf/.nan.
std::string toYaml(XmlRpc::XmlRpcValue& value);

enum class SceneParam { Missing, Ok, Bad };

/// Reads `name` from `nh` as scene YAML text. Bad: `error` says why (not text nor a dictionary).
SceneParam readSceneParam(const ros::NodeHandle& nh, const std::string& name, std::string* yaml,
                          std::string* error);

}  // namespace bridge
}  // namespace impulse2d
