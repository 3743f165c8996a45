# The catkin side: dependencies, message generation and the package declaration.
set(IMPULSE2D_ROS_DEPENDS
  roscpp nodelet pluginlib std_msgs std_srvs geometry_msgs sensor_msgs visualization_msgs
  rosgraph_msgs tf2_msgs tf2_ros diagnostic_updater)
find_package(catkin REQUIRED COMPONENTS message_generation ${IMPULSE2D_ROS_DEPENDS})

add_message_files(DIRECTORY msg FILES
  Shape.msg Body.msg Joint.msg Contact.msg ContactArray.msg)
add_service_files(DIRECTORY srv FILES
  SpawnBody.srv DeleteBody.srv CreateJoint.srv DeleteJoint.srv SpawnUrdf.srv LoadScene.srv
  ApplyWrench.srv SetBodyState.srv GetBodyState.srv Step.srv)
# URDF joints (cmake/urdf.cmake): commands to a joint motor.
add_message_files(DIRECTORY msg FILES JointCommand.msg)
add_service_files(DIRECTORY srv FILES SetJointMotor.srv)
generate_messages(DEPENDENCIES std_msgs geometry_msgs)

catkin_package(
  INCLUDE_DIRS include
  LIBRARIES impulse2d_core impulse2d_scene impulse2d_urdf
  CATKIN_DEPENDS message_runtime std_msgs geometry_msgs
)
