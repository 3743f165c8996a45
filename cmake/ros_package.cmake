# The catkin side: dependencies, message generation and the package declaration.
find_package(catkin REQUIRED)
catkin_package(
  INCLUDE_DIRS include
  LIBRARIES impulse2d_core impulse2d_scene
)
