// urdfdom's parser with its complaints captured: urdfdom reports why it refused a document only
// through console_bridge, which would print it to stderr.
#pragma once

#include <urdf_model/model.h>
#include <urdf_world/types.h>

#include <string>

namespace impulse2d {
namespace urdf_detail {

/// The parsed model, or null with `error` set to urdfdom's last complaint ("bad XML" at least).
urdf::ModelInterfaceSharedPtr parseUrdfText(const std::string& xml, std::string* error);

}  // namespace urdf_detail
}  // namespace impulse2d
