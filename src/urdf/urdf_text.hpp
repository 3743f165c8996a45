// urdfdom's parser with its complaints captured: urdfdom reports why it refused a document only
// through console_bridge, which would print it to stderr.
#pragma once

#include <urdf_model/model.h>
#include <urdf_world/types.h>

#include <string>
#include <utility>

namespace impulse2d {
namespace urdf_detail {

/// The parsed model, or null with `error` set to urdfdom's last complaint ("bad XML" at least).
urdf::ModelInterfaceSharedPtr parseUrdfText(const std::string& xml, std::string* error);

/// urdfdom links hold their children by shared_ptr, so a joint whose child is its own parent
/// (which urdfdom accepts) makes a cycle that would leak. Clears the links' child lists when the
/// model is no longer needed.
class ModelReleaser {
 public:
  explicit ModelReleaser(urdf::ModelInterfaceSharedPtr model) : model_(std::move(model)) {}
  ~ModelReleaser();
  ModelReleaser(const ModelReleaser&) = delete;
  ModelReleaser& operator=(const ModelReleaser&) = delete;

 private:
  urdf::ModelInterfaceSharedPtr model_;
};

}  // namespace urdf_detail
}  // namespace impulse2d
