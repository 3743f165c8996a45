# impulse2d_core_soak: seeded random edits of a running world, invariants after every step
# (test/soak/soak_run.hpp; the unit tests compile soak_run.cpp too, for the seeds that once
# failed). CI runs it short (scripts/test.d/45-core-soak.sh); a flag runs it long.
add_executable(impulse2d_core_soak ${PROJECT_SOURCE_DIR}/test/soak/core_soak_main.cpp
  ${PROJECT_SOURCE_DIR}/test/soak/soak_run.cpp)
target_link_libraries(impulse2d_core_soak PRIVATE impulse2d_core)
if(NOT IMPULSE2D_CORE_ONLY)
  install(TARGETS impulse2d_core_soak RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
endif()
