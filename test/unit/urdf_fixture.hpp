// The URDF fixtures of test/urdf/ as text, for the URDF loader's tests.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace impulse2d {
namespace test {

inline std::string urdfFixture(const std::string& name) {
  std::ifstream in(std::string(IMPULSE2D_SOURCE_DIR) + "/test/urdf/" + name);
  EXPECT_TRUE(in.good()) << name;
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace test
}  // namespace impulse2d
