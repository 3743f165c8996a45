// The YAML scene loader end to end: any text is either refused with one line of message and the
// world left as it was, or added whole and then stepped without a crash, a leak or a NaN, its
// devices running (drives commanded, lasers scanning, bumpers read) as in the node.
#include "fuzz_input.hpp"

#include <impulse2d/devices.hpp>
#include <impulse2d/scene.hpp>
#include <impulse2d/world.hpp>

#include <cmath>
#include <string>

namespace {

using impulse2d::fuzz::fail;

// A few steps are enough to reach the solver with every body and joint; more would only slow
// the search down.
constexpr int kSteps = 3;

bool finiteState(const impulse2d::World& world) {
  for (const impulse2d::BodyId id : world.bodies()) {
    const impulse2d::Body& body = world.body(id);
    if (!impulse2d::isFinite(body.xf.p) || !std::isfinite(body.angle) ||
        !impulse2d::isFinite(body.linearVelocity) || !std::isfinite(body.angularVelocity)) {
      return false;
    }
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  impulse2d::Scene scene;
  std::string error;
  if (!impulse2d::parseScene(text, &scene, &error)) {
    IMPULSE2D_FUZZ_CHECK(!error.empty());
    IMPULSE2D_FUZZ_CHECK(error.find('\n') == std::string::npos);
    return 0;
  }
  IMPULSE2D_FUZZ_CHECK(impulse2d::World::validate(scene.world).empty());
  // A world that already holds a body, so that name clashes with the world are reached too.
  impulse2d::World world(scene.world);
  impulse2d::BodyDef ground;
  ground.name = "ground";
  ground.type = impulse2d::BodyType::Static;
  ground.shapes.resize(1);
  ground.shapes[0].size = impulse2d::Vec2(20.0, 1.0);
  if (!world.createBody(ground).valid()) fail("the fixed ground body was refused");
  const uint64_t before = world.hash();
  if (!impulse2d::addScene(scene, world, &error)) {
    IMPULSE2D_FUZZ_CHECK(!error.empty());
    IMPULSE2D_FUZZ_CHECK(world.bodyCount() == 1 && world.jointCount() == 0);
    IMPULSE2D_FUZZ_CHECK(world.hash() == before);
    return 0;
  }
  IMPULSE2D_FUZZ_CHECK(world.bodyCount() == 1 + scene.bodies.size());
  IMPULSE2D_FUZZ_CHECK(world.jointCount() == scene.joints.size());
  impulse2d::DeviceSet devices;
  impulse2d::DeviceContext context;
  context.plane = scene.plane;
  context.worldFrame = scene.frameId;
  if (!devices.add(scene.devices, world, context, 0.0, &error)) {
    IMPULSE2D_FUZZ_CHECK(!error.empty() && devices.devices().empty());
  }
  for (impulse2d::Device& device : devices.devices()) {
    device.active = true;
    if (device.drive) device.drive->command(1.0, -2.0, 0.0);
  }
  for (int i = 0; i < kSteps; ++i) {
    devices.beforeStep(world, world.time());
    world.step();
    devices.afterStep(world, world.time());
    devices.dropDetached(world);
    // Whatever left the world was removed and reported; what is left is finite.
    IMPULSE2D_FUZZ_CHECK(finiteState(world));
    for (const impulse2d::Device& device : devices.devices()) {
      if (device.drive) {
        IMPULSE2D_FUZZ_CHECK(std::isfinite(device.drive->odometry().angle) &&
                             impulse2d::isFinite(device.drive->odometry().position));
      }
      for (const float range : device.ranges) IMPULSE2D_FUZZ_CHECK(!std::isnan(range));
    }
  }
  return 0;
}
