# Tests of reliability (after ros_targets.cmake, with testing enabled): the node reaches the
# CLI's exact state (hash.test, ~5 s), the load test (load.test, ~75 s) and issue 14's recipe.
add_rostest_gtest(impulse2d_hash_test test/ros/hash.test
  test/ros/hash_test.cpp test/ros/scene_names.cpp)
target_link_libraries(impulse2d_hash_test impulse2d_scene ${catkin_LIBRARIES})
target_compile_definitions(impulse2d_hash_test PRIVATE
  IMPULSE2D_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
  IMPULSE2D_SIM_EXECUTABLE="$<TARGET_FILE:impulse2d_sim>")
add_dependencies(impulse2d_hash_test impulse2d_node impulse2d_sim ${PROJECT_NAME}_generate_messages_cpp)
# The same on three threads (~threads): the state does not depend on them.
add_rostest(test/ros/hash_threads.test DEPENDENCIES impulse2d_hash_test)

add_rostest_gtest(impulse2d_load_test test/ros/load.test test/ros/load_test.cpp)
target_link_libraries(impulse2d_load_test ${catkin_LIBRARIES})
add_dependencies(impulse2d_load_test impulse2d_node ${PROJECT_NAME}_generate_messages_cpp)

# Issue 14's recipe at ~rate 0: a URDF arm and 50 boxes with friction left out, none lost
# (recipe.test, ~20 s).
add_rostest_gtest(impulse2d_recipe_test test/ros/recipe.test test/ros/recipe_test.cpp)
target_link_libraries(impulse2d_recipe_test impulse2d_world_test_common ${catkin_LIBRARIES})
add_dependencies(impulse2d_recipe_test impulse2d_node ${PROJECT_NAME}_generate_messages_cpp)

# SimWorld's and the conversions' limits, without a master.
catkin_add_gtest(impulse2d_sim_world_limits_tests test/ros/sim_world_limits_test.cpp)
target_link_libraries(impulse2d_sim_world_limits_tests impulse2d_ros GTest::gtest_main)
