// The bodies of a scene file in the order the world creates them (its slot order), for tests
// that must not include the engine's headers next to the messages (see sim_world.hpp).
#pragma once

#include <string>
#include <vector>

namespace impulse2d_test {

/// Empty when the file cannot be read as a scene.
std::vector<std::string> sceneBodyNames(const std::string& path);

}  // namespace impulse2d_test
