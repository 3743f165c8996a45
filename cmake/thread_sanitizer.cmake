# -DIMPULSE2D_TSAN=ON: ThreadSanitizer on the node and the libraries it is built from, not on the
# test clients, so that reports come from the node only (scripts/test.d/40-tsan.sh). -g1: line
# tables, all a report's stack needs.
foreach(target impulse2d_core impulse2d_scene impulse2d_devices impulse2d_ros impulse2d_node)
  target_compile_options(${target} PRIVATE -fsanitize=thread -fno-omit-frame-pointer -g1)
  target_link_options(${target} PRIVATE -fsanitize=thread)
endforeach()
