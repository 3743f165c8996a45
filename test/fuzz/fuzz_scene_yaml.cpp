// The YAML scene loader end to end: any text is either refused with one line of message and the
// world left as it was, or added whole and then stepped without a crash, a leak or a NaN.
#include "fuzz_input.hpp"

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
  for (int i = 0; i < kSteps; ++i) {
    world.step();
    // Whatever left the world was removed and reported; what is left is finite.
    IMPULSE2D_FUZZ_CHECK(finiteState(world));
  }
  return 0;
}
