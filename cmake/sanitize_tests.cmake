# -DIMPULSE2D_SANITIZE=ON instruments the product (libraries, node, nodelet, CLI, wanderer) and
# not the test programs' own code: gtest programs and rostest clients are compiled without
# ASan/UBSan and linked with their runtimes, so the libraries they link stay checked. The test
# code was half of the sanitizer build (a gtest source compiles in 8 s instrumented, 4 s not;
# a rostest client took 12-26 s) and is not what the stage is for; ThreadSanitizer's build
# (thread_sanitizer.cmake) draws the same line.
# Called once every target exists (CMakeLists.txt defers it): the test programs are the targets
# named impulse2d_*_test, impulse2d_*_tests and impulse2d_world_test_common.
function(impulse2d_uninstrument_tests)
  get_property(targets DIRECTORY ${PROJECT_SOURCE_DIR} PROPERTY BUILDSYSTEM_TARGETS)
  foreach(target ${targets})
    if(target MATCHES "^impulse2d_.*_tests?$" OR target STREQUAL "impulse2d_world_test_common")
      target_compile_options(${target} PRIVATE -fno-sanitize=all)
    endif()
  endforeach()
endfunction()
