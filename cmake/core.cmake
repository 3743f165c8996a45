# The ROS-free parts: the engine (Eigen only), the YAML scene loader, the devices (drives, lasers,
# bumpers) and the headless simulator.
file(GLOB IMPULSE2D_CORE_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/core/*.cpp)
add_library(impulse2d_core ${IMPULSE2D_CORE_SOURCES})
target_include_directories(impulse2d_core PUBLIC ${PROJECT_SOURCE_DIR}/include
  PRIVATE ${PROJECT_SOURCE_DIR}/src/core)
# Highway: the contact kernels' SIMD, compiled for every x86 instruction set and chosen when the
# program starts (src/core/contact_kernels.cpp); oneTBB: the step's threads (step_workers.cpp).
find_package(HWY REQUIRED)
# catkin_lint knows a FindTBB module of ROS's cmake_modules package; Debian's libtbb-dev ships
# its own TBBConfig.cmake, which this finds.
#catkin_lint: ignore_once missing_cmake_modules
find_package(TBB REQUIRED)
target_link_libraries(impulse2d_core PUBLIC Eigen3::Eigen PRIVATE hwy::hwy TBB::tbb)
# Bit-identical results on every instruction set: no multiply-add contracted into one rounding.
target_compile_options(impulse2d_core PRIVATE -ffp-contract=off)
target_compile_definitions(impulse2d_core PRIVATE HWY_COMPILE_ALL_ATTAINABLE)
set_target_properties(impulse2d_core PROPERTIES POSITION_INDEPENDENT_CODE ON)
# The solver's rows are written on scalars (src/core/contact_math.hpp): GCC's SLP vectorizer
# would pair two scalar updates of a velocity into one 16-byte load that the CPU cannot forward
# from the two 8-byte stores just before it, a stall that cost a fifth of the step.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  target_compile_options(impulse2d_core PRIVATE -fno-tree-slp-vectorize)
endif()

file(GLOB IMPULSE2D_SCENE_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/scene/*.cpp)
add_library(impulse2d_scene ${IMPULSE2D_SCENE_SOURCES})
# stb_image (libstb-dev) reads the occupancy maps' images.
find_package(PkgConfig REQUIRED)
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)
target_link_libraries(impulse2d_scene PUBLIC impulse2d_core PRIVATE yaml-cpp PkgConfig::STB)
set_target_properties(impulse2d_scene PROPERTIES POSITION_INDEPENDENT_CODE ON)

file(GLOB IMPULSE2D_DEVICE_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/devices/*.cpp)
add_library(impulse2d_devices ${IMPULSE2D_DEVICE_SOURCES})
target_link_libraries(impulse2d_devices PUBLIC impulse2d_core)
set_target_properties(impulse2d_devices PROPERTIES POSITION_INDEPENDENT_CODE ON)

file(GLOB IMPULSE2D_SIM_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/sim/*.cpp)
add_executable(impulse2d_sim ${IMPULSE2D_SIM_SOURCES})
target_link_libraries(impulse2d_sim PRIVATE impulse2d_scene impulse2d_devices)
