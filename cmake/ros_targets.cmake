# ROS executables, plugins, rostests and install rules (after core.cmake).

# ROS headers are not ours to fix: keep their warnings out of -Werror.
# The generated message headers (devel/include) too: gencpp adds that folder, but not as SYSTEM.
#catkin_lint: ignore_once external_directory
include_directories(SYSTEM ${catkin_INCLUDE_DIRS} ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_INCLUDE_DESTINATION})

# The world node's logic, shared by impulse2d_node and the nodelet.
add_library(impulse2d_ros STATIC
  src/ros/conversions.cpp
  src/ros/device_endpoints.cpp
  src/ros/device_messages.cpp
  src/ros/markers.cpp
  src/ros/scene_param.cpp
  src/ros/sim_world.cpp
  src/ros/sim_world_devices.cpp
  src/ros/sim_world_maps.cpp
  src/ros/sim_world_models.cpp
  src/ros/sim_world_queries.cpp
  src/ros/world_devices.cpp
  src/ros/world_maps.cpp
  src/ros/world_node.cpp
  src/ros/world_publish.cpp
  src/ros/world_services.cpp)
target_link_libraries(impulse2d_ros PUBLIC impulse2d_scene impulse2d_devices ${catkin_LIBRARIES})
set_target_properties(impulse2d_ros PROPERTIES POSITION_INDEPENDENT_CODE ON)
add_dependencies(impulse2d_ros ${PROJECT_NAME}_generate_messages_cpp ${catkin_EXPORTED_TARGETS})

# The nodelet plugin impulse2d/WorldNodelet (nodelet_plugins.xml names lib/libimpulse2d_nodelet).
add_library(impulse2d_nodelet SHARED src/ros/world_nodelet.cpp)
target_link_libraries(impulse2d_nodelet PRIVATE impulse2d_ros)

add_executable(impulse2d_node src/ros/node_main.cpp)
target_link_libraries(impulse2d_node PRIVATE impulse2d_ros)

# The fleet demo's reactive wanderer (scan in, cmd_vel out); it needs nothing of the engine.
add_executable(impulse2d_wanderer src/ros/wanderer_main.cpp)
target_link_libraries(impulse2d_wanderer PRIVATE ${catkin_LIBRARIES})
add_dependencies(impulse2d_wanderer ${catkin_EXPORTED_TARGETS})

if(CATKIN_ENABLE_TESTING)
  find_package(rostest REQUIRED)
  find_package(roslaunch REQUIRED)

  # Conversions, the ~scene parameter and the markers, without a master.
  catkin_add_gtest(impulse2d_ros_unit_tests test/ros/conversions_test.cpp
    test/ros/device_messages_test.cpp test/ros/markers_test.cpp test/ros/sim_world_devices_test.cpp
    test/ros/sim_world_maps_test.cpp test/ros/sim_world_models_test.cpp
    test/ros/sim_world_wheels_test.cpp)
  target_link_libraries(impulse2d_ros_unit_tests impulse2d_ros GTest::gtest_main)
  target_compile_definitions(impulse2d_ros_unit_tests PRIVATE
    IMPULSE2D_SOURCE_DIR="${PROJECT_SOURCE_DIR}")

  # The rostests' gtest clients share their main() and helpers: compiled once here, not once per
  # client (eight of them; under the sanitizers each copy took 20-25 s of compiling).
  add_library(impulse2d_world_test_common STATIC test/ros/world_test_main.cpp
    test/ros/world_test_util.cpp)
  target_link_libraries(impulse2d_world_test_common PUBLIC ${catkin_LIBRARIES} ${GTEST_LIBRARIES})
  add_dependencies(impulse2d_world_test_common ${PROJECT_NAME}_generate_messages_cpp)

  # A gtest node run twice: by test/ros/NAME.test against impulse2d_node and by
  # test/ros/NAME_nodelet.test against the nodelet (one pipeline, both ways, as velodyne's).
  function(impulse2d_add_node_and_nodelet_rostest name)
    add_rostest_gtest(impulse2d_${name}_tests test/ros/${name}.test ${ARGN})
    target_link_libraries(impulse2d_${name}_tests impulse2d_world_test_common ${catkin_LIBRARIES}
      Eigen3::Eigen)
    add_dependencies(impulse2d_${name}_tests impulse2d_node impulse2d_nodelet
      ${PROJECT_NAME}_generate_messages_cpp)
    add_rostest(test/ros/${name}_nodelet.test DEPENDENCIES impulse2d_${name}_tests)
  endfunction()

  # Services, topics and defaults (world_node.test and world_nodelet.test).
  add_rostest_gtest(impulse2d_world_tests test/ros/world_node.test
    test/ros/services_test.cpp
    test/ros/topics_test.cpp
    test/ros/defaults_test.cpp)
  target_link_libraries(impulse2d_world_tests impulse2d_world_test_common ${catkin_LIBRARIES})
  add_dependencies(impulse2d_world_tests impulse2d_node impulse2d_nodelet
    ${PROJECT_NAME}_generate_messages_cpp)
  add_rostest(test/ros/world_nodelet.test DEPENDENCIES impulse2d_world_tests)

  # Robots in the loop: drives, lasers, bumpers, ~ray_cast and ~query_point.
  add_rostest_gtest(impulse2d_robot_tests test/ros/robot.test test/ros/robot_test.cpp)
  target_link_libraries(impulse2d_robot_tests impulse2d_world_test_common ${catkin_LIBRARIES})
  add_dependencies(impulse2d_robot_tests impulse2d_node ${PROJECT_NAME}_generate_messages_cpp)

  # The other devices (omni, ackermann, imu, mounted lasers).
  impulse2d_add_node_and_nodelet_rostest(devices test/ros/devices_test.cpp)
  # Occupancy maps: a scene's, ~map, ~map_topic.
  impulse2d_add_node_and_nodelet_rostest(maps test/ros/maps_test.cpp)
  # Models in namespaces: a scene's, ~spawn_model, ~move_model, ~delete_model; /clock.
  impulse2d_add_node_and_nodelet_rostest(models test/ros/models_test.cpp)

  # The fleet demo as launched, without RViz: every robot wanders.
  add_rostest_gtest(impulse2d_fleet_tests test/ros/fleet.test test/ros/fleet_test.cpp)
  target_link_libraries(impulse2d_fleet_tests impulse2d_world_test_common ${catkin_LIBRARIES})
  add_dependencies(impulse2d_fleet_tests impulse2d_node impulse2d_wanderer
    ${PROJECT_NAME}_generate_messages_cpp)

  roslaunch_add_file_check(launch/world.launch)
  roslaunch_add_file_check(launch/robot_demo.launch rviz:=false)
  roslaunch_add_file_check(launch/demo.launch rviz:=false)
  roslaunch_add_file_check(launch/fleet_demo.launch rviz:=false)
endif()

install(TARGETS impulse2d_core impulse2d_devices impulse2d_scene impulse2d_sim
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
install(TARGETS impulse2d_node impulse2d_nodelet impulse2d_wanderer
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
install(DIRECTORY include/impulse2d/ DESTINATION ${CATKIN_PACKAGE_INCLUDE_DESTINATION})
install(DIRECTORY config launch DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})
install(DIRECTORY rviz DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})
install(FILES nodelet_plugins.xml DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})
