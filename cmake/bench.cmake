# impulse2d_bench: speed against error, with Box2D and Chipmunk side by side when they are
# installed (libbox2d-dev, libchipmunk-dev). The package never depends on them: each adapter is
# compiled in only when its library is found, and a compile definition says so.
add_executable(impulse2d_bench
  bench/bench_human.cpp
  bench/bench_main.cpp
  bench/bench_scenes.cpp
  bench/bench_scenes_v3.cpp
  bench/bench_shapes.cpp
  bench/engine_common.cpp
  bench/impulse2d_adapter.cpp
  bench/memory_probe.cpp
  bench/metrics.cpp)
target_link_libraries(impulse2d_bench PRIVATE impulse2d_core)

find_path(IMPULSE2D_BOX2D_INCLUDE_DIR box2d/box2d.h)
find_library(IMPULSE2D_BOX2D_LIBRARY box2d)
if(IMPULSE2D_BOX2D_INCLUDE_DIR AND IMPULSE2D_BOX2D_LIBRARY)
  message(STATUS "impulse2d_bench: with Box2D (${IMPULSE2D_BOX2D_LIBRARY})")
  target_sources(impulse2d_bench PRIVATE bench/box2d_adapter.cpp)
  target_include_directories(impulse2d_bench SYSTEM PRIVATE ${IMPULSE2D_BOX2D_INCLUDE_DIR})
  target_link_libraries(impulse2d_bench PRIVATE ${IMPULSE2D_BOX2D_LIBRARY})
  target_compile_definitions(impulse2d_bench PRIVATE IMPULSE2D_BENCH_BOX2D)
else()
  message(STATUS "impulse2d_bench: Box2D not found (libbox2d-dev), benchmarking without it")
endif()

find_path(IMPULSE2D_CHIPMUNK_INCLUDE_DIR chipmunk/chipmunk.h)
find_library(IMPULSE2D_CHIPMUNK_LIBRARY chipmunk)
if(IMPULSE2D_CHIPMUNK_INCLUDE_DIR AND IMPULSE2D_CHIPMUNK_LIBRARY)
  message(STATUS "impulse2d_bench: with Chipmunk (${IMPULSE2D_CHIPMUNK_LIBRARY})")
  target_sources(impulse2d_bench PRIVATE bench/chipmunk_adapter.cpp)
  target_include_directories(impulse2d_bench SYSTEM PRIVATE ${IMPULSE2D_CHIPMUNK_INCLUDE_DIR})
  target_link_libraries(impulse2d_bench PRIVATE ${IMPULSE2D_CHIPMUNK_LIBRARY})
  target_compile_definitions(impulse2d_bench PRIVATE IMPULSE2D_BENCH_CHIPMUNK)
else()
  message(STATUS "impulse2d_bench: Chipmunk not found (libchipmunk-dev), benchmarking without it")
endif()

# What the robot devices cost (a scan, a step with and without them), ROS-free.
add_executable(impulse2d_device_bench bench/device_cost.cpp)
target_link_libraries(impulse2d_device_bench PRIVATE impulse2d_devices)

# Box2D v3 is not packaged: point IMPULSE2D_BENCH_BOX2D_V3_DIR at a v3 install tree (a folder
# with include/box2d/box2d.h and libbox2d.a in lib/, lib64/ or src/). Its workers run on oneTBB
# (libtbb-dev, which the core needs anyway). Off unless set; CI never sets it. Its headers share
# Box2D 2.4's <box2d/box2d.h>, so only its adapter sees them.
set(IMPULSE2D_BENCH_BOX2D_V3_DIR "" CACHE PATH
  "A Box2D v3 build or install to benchmark against (include/box2d and libbox2d.a); empty: none")
if(IMPULSE2D_BENCH_BOX2D_V3_DIR)
  find_path(IMPULSE2D_BOX2D_V3_INCLUDE_DIR box2d/box2d.h
    PATHS ${IMPULSE2D_BENCH_BOX2D_V3_DIR}/include NO_DEFAULT_PATH)
  find_library(IMPULSE2D_BOX2D_V3_LIBRARY NAMES libbox2d.a
    PATHS ${IMPULSE2D_BENCH_BOX2D_V3_DIR}
    PATH_SUFFIXES lib lib64 src NO_DEFAULT_PATH)
  if(NOT IMPULSE2D_BOX2D_V3_INCLUDE_DIR OR NOT IMPULSE2D_BOX2D_V3_LIBRARY)
    message(FATAL_ERROR "IMPULSE2D_BENCH_BOX2D_V3_DIR=${IMPULSE2D_BENCH_BOX2D_V3_DIR} holds no "
      "include/box2d/box2d.h and libbox2d.a (a Box2D v3 build or install)")
  endif()
  # TBB::tbb: found by cmake/core.cmake (the core's threads run on oneTBB too; v3.1's workers).
  message(STATUS "impulse2d_bench: with Box2D v3 (${IMPULSE2D_BOX2D_V3_LIBRARY})")
  target_sources(impulse2d_bench PRIVATE bench/box2d_v3_adapter.cpp)
  set_source_files_properties(bench/box2d_v3_adapter.cpp PROPERTIES
    COMPILE_OPTIONS "-isystem;${IMPULSE2D_BOX2D_V3_INCLUDE_DIR}")
  target_link_libraries(impulse2d_bench PRIVATE ${IMPULSE2D_BOX2D_V3_LIBRARY} TBB::tbb)
  target_compile_definitions(impulse2d_bench PRIVATE IMPULSE2D_BENCH_BOX2D_V3)
  # Master (2026) gave every joint definition a b2JointDef base: the adapter takes either API.
  file(STRINGS ${IMPULSE2D_BOX2D_V3_INCLUDE_DIR}/box2d/types.h IMPULSE2D_BOX2D_V3_JOINT_BASE
    REGEX "b2JointDef base;")
  if(IMPULSE2D_BOX2D_V3_JOINT_BASE)
    message(STATUS "impulse2d_bench: Box2D v3 master's API (joint bases; v3's own worker threads)")
    target_compile_definitions(impulse2d_bench PRIVATE IMPULSE2D_BOX2D_V3_MASTER)
  endif()
endif()

if(NOT IMPULSE2D_CORE_ONLY)
  install(TARGETS impulse2d_bench impulse2d_device_bench
    RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
endif()
