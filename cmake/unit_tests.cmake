# gtest unit tests of the ROS-free parts; no ROS master is involved.
file(GLOB IMPULSE2D_UNIT_TEST_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/unit/*.cpp)
list(APPEND IMPULSE2D_UNIT_TEST_SOURCES ${PROJECT_SOURCE_DIR}/test/soak/soak_run.cpp)
set(IMPULSE2D_TEST_DEFINES
  IMPULSE2D_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
  IMPULSE2D_SIM_EXECUTABLE="$<TARGET_FILE:impulse2d_sim>")

if(IMPULSE2D_CORE_ONLY)
  enable_testing()
  # catkin_lint counts catkin's own search for GTest; this branch builds without catkin.
  #catkin_lint: ignore_once duplicate_find
  find_package(GTest REQUIRED)
  include(GoogleTest)
  add_executable(impulse2d_unit_tests ${IMPULSE2D_UNIT_TEST_SOURCES})
  target_link_libraries(impulse2d_unit_tests PRIVATE impulse2d_scene impulse2d_devices
    GTest::gtest_main)
  gtest_discover_tests(impulse2d_unit_tests DISCOVERY_TIMEOUT 60)
elseif(CATKIN_ENABLE_TESTING)  # always true here: CMakeLists.txt includes us only then
  catkin_add_gtest(impulse2d_unit_tests ${IMPULSE2D_UNIT_TEST_SOURCES} TIMEOUT 600)
  target_link_libraries(impulse2d_unit_tests impulse2d_scene impulse2d_devices
    ${GTEST_MAIN_LIBRARIES})
endif()
target_include_directories(impulse2d_unit_tests PRIVATE ${PROJECT_SOURCE_DIR}/src/core
  ${PROJECT_SOURCE_DIR}/src/scene ${PROJECT_SOURCE_DIR}/test/soak)
target_compile_definitions(impulse2d_unit_tests PRIVATE ${IMPULSE2D_TEST_DEFINES})
# The headers nearly every test source reads: parsing them was most of each source's compile
# (gtest, Eigen and world.hpp alone 3.7 s of test_world.cpp's 4-5 s), now done once.
target_precompile_headers(impulse2d_unit_tests PRIVATE <gtest/gtest.h> <impulse2d/world.hpp>
  <impulse2d/scene.hpp> <algorithm> <cmath> <random> <string> <vector>)
add_dependencies(impulse2d_unit_tests impulse2d_sim)
