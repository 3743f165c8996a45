# The catkin side: dependencies, message generation and the package declaration.
find_package(catkin REQUIRED COMPONENTS
  diagnostic_updater geometry_msgs message_generation nav_msgs nodelet pluginlib roscpp
  rosgraph_msgs roslib sensor_msgs std_msgs std_srvs tf2_msgs tf2_ros visualization_msgs)

add_message_files(DIRECTORY msg FILES
  Body.msg Contact.msg ContactArray.msg Joint.msg JointCommand.msg Shape.msg)
# ~removed_bodies
add_message_files(DIRECTORY msg FILES RemovedBodies.msg RemovedBody.msg)
add_service_files(DIRECTORY srv FILES
  ApplyWrench.srv CreateJoint.srv DeleteBody.srv DeleteJoint.srv GetBodyState.srv LoadScene.srv
  SetBodyState.srv SetJointMotor.srv SpawnBody.srv SpawnUrdf.srv Step.srv)
# ~get_body_properties
add_service_files(DIRECTORY srv FILES GetBodyProperties.srv)
# ~ray_cast, ~query_point
add_service_files(DIRECTORY srv FILES QueryPoint.srv RayCast.srv)
# ~spawn_model, ~delete_model, ~move_model
add_service_files(DIRECTORY srv FILES DeleteModel.srv MoveModel.srv SpawnModel.srv)
generate_messages(DEPENDENCIES geometry_msgs std_msgs)

catkin_package(
  INCLUDE_DIRS include
  LIBRARIES impulse2d_core impulse2d_devices impulse2d_scene impulse2d_urdf
  CATKIN_DEPENDS geometry_msgs message_runtime nav_msgs nodelet roscpp rosgraph_msgs sensor_msgs
    std_msgs std_srvs visualization_msgs
)
