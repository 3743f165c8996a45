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

if(NOT IMPULSE2D_CORE_ONLY)
  install(TARGETS impulse2d_bench RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
endif()
