# libFuzzer harnesses: one executable per test/fuzz/fuzz_*.cpp, in a separate core-only clang
# build (scripts/test.d/30-fuzz.sh):
#   CC=clang CXX=clang++ cmake -S . -B build_fuzz -DIMPULSE2D_CORE_ONLY=ON -DIMPULSE2D_FUZZ=ON
# Everything, the libraries included, is built with ASan + UBSan and libFuzzer's coverage
# instrumentation; harnesses link the libraries and whatever ROS-free loaders exist.
if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "IMPULSE2D_FUZZ needs clang (CC=clang CXX=clang++)")
endif()
if(NOT IMPULSE2D_CORE_ONLY)
  message(FATAL_ERROR "IMPULSE2D_FUZZ needs IMPULSE2D_CORE_ONLY=ON")
endif()

# Applies to every target defined after this file is included (core.cmake comes after it).
add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all
  -fno-omit-frame-pointer -g)
# The SIMD kernels for this machine's instruction set only: the one that runtime dispatch would
# pick here, and the only one a harness runs (built and run on the same machine, in CI too). The
# two kernel sources took 41 s and 30 s to compile for all five, and the build 157 s instead of
# about 200 on two cores. The unit tests check every instruction set, also under ASan.
add_compile_options(-march=native)
add_compile_definitions(HWY_COMPILE_ONLY_STATIC)
add_link_options(-fsanitize=address,undefined)

# Defines the harness targets; called once core.cmake's libraries exist.
function(impulse2d_add_fuzzers)
  # The node's request path without ROS (sim_world.cpp includes no ROS header by design).
  # sim_world_urdf.cpp holds its URDF models and sim_world_devices.cpp its devices (also
  # ROS-free), so it needs impulse2d_urdf and impulse2d_devices.
  if(NOT TARGET impulse2d_urdf)
    message(FATAL_ERROR "fuzzers: the node's request path needs the impulse2d_urdf library")
  endif()
  add_library(impulse2d_fuzz_sim_world STATIC ${PROJECT_SOURCE_DIR}/src/ros/sim_world.cpp
    ${PROJECT_SOURCE_DIR}/src/ros/sim_world_devices.cpp
    ${PROJECT_SOURCE_DIR}/src/ros/sim_world_maps.cpp
    ${PROJECT_SOURCE_DIR}/src/ros/sim_world_models.cpp
    ${PROJECT_SOURCE_DIR}/src/ros/sim_world_queries.cpp
    ${PROJECT_SOURCE_DIR}/src/ros/sim_world_urdf.cpp)
  target_include_directories(impulse2d_fuzz_sim_world PUBLIC ${PROJECT_SOURCE_DIR}/src/ros)
  target_link_libraries(impulse2d_fuzz_sim_world PUBLIC impulse2d_scene impulse2d_devices
    impulse2d_urdf)

  file(GLOB harnesses CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/fuzz/fuzz_*.cpp)
  set(IMPULSE2D_FUZZERS "")
  foreach(source ${harnesses})
    get_filename_component(name ${source} NAME_WE)
    add_executable(${name} ${source})
    target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/test/fuzz
      ${PROJECT_SOURCE_DIR}/src/core ${PROJECT_SOURCE_DIR}/src/scene)
    target_link_libraries(${name} PRIVATE impulse2d_core impulse2d_scene impulse2d_devices
      impulse2d_urdf impulse2d_fuzz_sim_world)
    target_link_options(${name} PRIVATE -fsanitize=fuzzer)
    list(APPEND IMPULSE2D_FUZZERS ${name})
  endforeach()
  add_custom_target(fuzzers DEPENDS ${IMPULSE2D_FUZZERS})
endfunction()
