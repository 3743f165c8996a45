// libFuzzer harness: any bytes as URDF text. A model the loader accepts is added to a world,
// which then steps; nothing may crash, hang or trip the sanitizers.
#include <impulse2d/urdf.hpp>
#include <impulse2d/world.hpp>

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  for (const char* plane : {"xz", "xy"}) {
    impulse2d::UrdfPlacement placement;
    placement.modelName = "fuzz";
    placement.plane = plane;
    impulse2d::UrdfModel model;
    std::string error;
    if (!impulse2d::parseUrdf(xml, placement, &model, &error)) continue;
    impulse2d::World world;
    if (!impulse2d::addScene(model.scene, world, &error)) continue;
    for (int i = 0; i < 10; ++i) world.step();
  }
  return 0;
}
