# URDF robot descriptions onto the plane (issue 5): the ROS-free loader impulse2d_urdf
# (urdfdom + the engine), and in the catkin build the node's ~spawn_urdf side with its
# rostests. Included from CMakeLists.txt after the unit tests and ROS targets are declared;
# test/unit/test_urdf.cpp is globbed into impulse2d_unit_tests, which links the loader here.
find_package(urdfdom REQUIRED)
# Collision meshes (STL, COLLADA, OBJ) for their footprints.
find_package(assimp REQUIRED)

file(GLOB IMPULSE2D_URDF_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/urdf/*.cpp)
add_library(impulse2d_urdf ${IMPULSE2D_URDF_SOURCES})
target_include_directories(impulse2d_urdf PRIVATE ${PROJECT_SOURCE_DIR}/src/scene)
target_link_libraries(impulse2d_urdf PUBLIC impulse2d_scene PRIVATE urdfdom::urdfdom_model
  assimp::assimp)
set_target_properties(impulse2d_urdf PROPERTIES POSITION_INDEPENDENT_CODE ON)

if(TARGET impulse2d_unit_tests)
  if(IMPULSE2D_CORE_ONLY)
    target_link_libraries(impulse2d_unit_tests PRIVATE impulse2d_urdf)
  else()
    target_link_libraries(impulse2d_unit_tests impulse2d_urdf)
  endif()
endif()

if(NOT IMPULSE2D_CORE_ONLY)
  # The node's URDF services, joint_states and joint commands.
  target_sources(impulse2d_ros PRIVATE ${PROJECT_SOURCE_DIR}/src/ros/sim_world_urdf.cpp
    ${PROJECT_SOURCE_DIR}/src/ros/urdf_services.cpp)
  target_link_libraries(impulse2d_ros PUBLIC impulse2d_urdf)
  install(TARGETS impulse2d_urdf
    ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
    LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
  # The demo arm lives with the fixtures; installed at the same relative path for the launch file.
  install(FILES test/urdf/two_link_arm.urdf
    DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}/test/urdf)

  if(CATKIN_ENABLE_TESTING)
    add_rostest_gtest(impulse2d_urdf_tests test/ros/urdf.test test/ros/urdf_test.cpp)
    target_link_libraries(impulse2d_urdf_tests impulse2d_world_test_common ${catkin_LIBRARIES})
    add_dependencies(impulse2d_urdf_tests impulse2d_node ${PROJECT_NAME}_generate_messages_cpp)
    roslaunch_add_file_check(launch/urdf_demo.launch rviz:=false)
  endif()
endif()
