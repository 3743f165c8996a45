// The world as a nodelet (impulse2d/WorldNodelet): the same WorldNode as impulse2d_node, on the
// manager's multi-threaded callback queue so concurrent service calls are answered in parallel.
#include "world_node.hpp"

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include <memory>

namespace impulse2d {

class WorldNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    node_ =
        std::make_unique<bridge::WorldNode>(getMTNodeHandle(), getMTPrivateNodeHandle(), getName());
  }

  std::unique_ptr<bridge::WorldNode> node_;
};

}  // namespace impulse2d

PLUGINLIB_EXPORT_CLASS(impulse2d::WorldNodelet, nodelet::Nodelet)
