// The ROS face of one world: parameters, the stepping timer, publishers, diagnostics and the
// private services. impulse2d_node and the impulse2d/WorldNodelet both run exactly this class.
#pragma once

#include "conversions.hpp"
#include "device_endpoints.hpp"
#include "sim_world.hpp"

#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/TransformStamped.h>
#include <impulse2d/ApplyWrench.h>
#include <impulse2d/CreateJoint.h>
#include <impulse2d/DeleteBody.h>
#include <impulse2d/DeleteJoint.h>
#include <impulse2d/DeleteModel.h>
#include <impulse2d/GetBodyProperties.h>
#include <impulse2d/GetBodyState.h>
#include <impulse2d/JointCommand.h>
#include <impulse2d/LoadScene.h>
#include <impulse2d/MoveModel.h>
#include <impulse2d/QueryPoint.h>
#include <impulse2d/RayCast.h>
#include <impulse2d/RemovedBodies.h>
#include <impulse2d/SetBodyState.h>
#include <impulse2d/SetJointMotor.h>
#include <impulse2d/SpawnBody.h>
#include <impulse2d/SpawnModel.h>
#include <impulse2d/SpawnUrdf.h>
#include <impulse2d/Step.h>
#include <nav_msgs/OccupancyGrid.h>
#include <ros/ros.h>
#include <std_srvs/Empty.h>

#include <atomic>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace impulse2d {
namespace bridge {

class WorldNode {
 public:
  /// `nh` is for the global topics (/tf, /tf_static, /clock, /diagnostics), `pnh` the private
  /// namespace for the parameters, services and ~contacts / ~markers; `name` is used in logs.
  /// Callbacks may run on several threads at once: every world access takes one mutex.
  WorldNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh, const std::string& name);
  ~WorldNode();
  WorldNode(const WorldNode&) = delete;
  WorldNode& operator=(const WorldNode&) = delete;

 private:
  /// Holds the world mutex. While a caller waits for it, the free-running step loop yields.
  class Lock {
   public:
    explicit Lock(WorldNode& node);
    ~Lock();
    Lock(const Lock&) = delete;
    Lock& operator=(const Lock&) = delete;

   private:
    WorldNode& node_;
  };

  void loadStartScene();
  void readParams();
  void advertise();
  void advertiseServices();  // world_services.cpp

  // Stepping (world_node.cpp).
  void onStepTimer(const ros::WallTimerEvent& event);
  void stepLocked();    ///< one step plus its statistics; the caller holds the Lock
  void recordLosses();  ///< logs what the step lost, keeps the removals for ~removed_bodies
  void restartSchedule();
  ros::Time stampFor(int64_t simTimeNs) const;
  void publishClock(int64_t simTimeNs);

  // Publishing (world_publish.cpp).
  void onPublishTimer(const ros::WallTimerEvent& event);
  /// ~removed_bodies again when something was removed since it was last sent (or never sent).
  void publishRemovedBodies();
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);

  // Services (world_services.cpp).
  bool spawnBody(SpawnBody::Request& req, SpawnBody::Response& res);
  bool deleteBody(DeleteBody::Request& req, DeleteBody::Response& res);
  bool createJoint(CreateJoint::Request& req, CreateJoint::Response& res);
  bool deleteJoint(DeleteJoint::Request& req, DeleteJoint::Response& res);
  bool loadScene(LoadScene::Request& req, LoadScene::Response& res);
  bool applyWrench(ApplyWrench::Request& req, ApplyWrench::Response& res);
  bool getBodyState(GetBodyState::Request& req, GetBodyState::Response& res);
  bool getBodyProperties(GetBodyProperties::Request& req, GetBodyProperties::Response& res);
  bool setBodyState(SetBodyState::Request& req, SetBodyState::Response& res);
  bool step(Step::Request& req, Step::Response& res);
  bool pause(std_srvs::Empty::Request& req, std_srvs::Empty::Response& res);
  bool unpause(std_srvs::Empty::Request& req, std_srvs::Empty::Response& res);
  bool reset(std_srvs::Empty::Request& req, std_srvs::Empty::Response& res);

  // Devices and queries (world_devices.cpp).
  /// Tells the world which topic names devices may take, before any scene is loaded.
  void setUpDevices();
  /// Opens and closes the devices' topics to match the world's devices. Takes the Lock briefly;
  /// never call it holding the Lock (see DeviceEndpoints::sync).
  void syncDevices();
  /// Publishes the scans and bumper changes of the last step; the caller holds the Lock.
  void publishDeviceReadings();
  /// Lasers and bumpers run only while someone subscribes.
  void updateDeviceDemand();
  void onCmdVel(const std::string& device, const geometry_msgs::Twist& twist);
  /// Odometry messages of the drives, and their tf: odom -> body, world -> odom. `driven` gets
  /// the bodies that hang under an odom frame on tf instead of under the world frame.
  void publishOdometry(Plane plane, const std::string& worldFrame, const ros::Time& stamp,
                       const std::vector<OdometryReading>& odometry,
                       std::vector<geometry_msgs::TransformStamped>* tf,
                       std::vector<std::string>* driven);
  bool rayCast(RayCast::Request& req, RayCast::Response& res);
  bool queryPoint(QueryPoint::Request& req, QueryPoint::Response& res);

  // Maps (world_maps.cpp): package:// for scenes, ~map, ~map_topic.
  void setUpMaps();
  void advertiseMaps();
  void onMap(const nav_msgs::OccupancyGrid::ConstPtr& msg);
  /// Publishes ~map when the maps changed; takes the Lock.
  void publishMap();

  // URDF models, joint_states and joint motors (urdf_services.cpp).
  // Models (model_services.cpp).
  void advertiseModels();
  bool spawnModel(SpawnModel::Request& req, SpawnModel::Response& res);
  bool deleteModel(DeleteModel::Request& req, DeleteModel::Response& res);
  bool moveModel(MoveModel::Request& req, MoveModel::Response& res);

  void loadStartUrdf();
  void advertiseUrdf();
  bool spawnUrdf(SpawnUrdf::Request& req, SpawnUrdf::Response& res);
  bool setJointMotor(SetJointMotor::Request& req, SetJointMotor::Response& res);
  void onJointCommand(const JointCommand::ConstPtr& command);
  void publishJointStates(const ros::Time& stamp, const std::vector<JointReading>& joints);

  ros::NodeHandle nh_, pnh_;
  std::string name_;

  std::mutex mutex_;
  std::atomic<int> waiters_{0};

  // Guarded by mutex_.
  SimWorld sim_;
  bool paused_ = false;
  ros::WallTime scheduleStart_;  ///< when the timer's step count was last restarted
  uint64_t scheduledSteps_ = 0;  ///< steps the timer made since scheduleStart_
  ros::WallTime statsStart_;     ///< diagnostics window
  int64_t statsSimStartNs_ = 0;
  uint64_t statsSteps_ = 0;
  double statsStepSeconds_ = 0.0;
  StepProfile statsProfile_;                             // the window's steps' stage times, summed
  uint64_t statsRemovedStart_ = 0, statsLostStart_ = 0;  ///< counts at the window's start
  // What ~removed_bodies sends: the latest removals (RemovedBodies.msg says how many).
  std::deque<impulse2d::RemovedBody> removedBodies_;

  // /clock never goes back, even when a timer tick and a step call publish out of order. It is
  // also sent at ~publish_rate while paused, so sim-time nodes see the clock (as gazebo does).
  std::mutex clockMutex_;
  int64_t lastClockNs_ = -1;

  // Set once by readParams().
  double rate_ = 100.0;  ///< steps per wall second; 0: as fast as possible
  double publishRate_ = 30.0;
  bool publishClock_ = false;

  // Only the publish timer touches these (a timer's callbacks never overlap).
  uint64_t publishedStaticVersion_ = 0;
  uint64_t publishedRemovedCount_ = 0;
  bool removedPublished_ = false;
  bool staticPublished_ = false;
  bool tfPublished_ = false;
  ros::Time lastTfStamp_;
  uint64_t publishedMapVersion_ = 0;
  bool mapPublished_ = false;
  std::string followedMapName_ = "map";  ///< ~map_name, set once before the subscriber starts

  ros::Publisher tfPub_, tfStaticPub_, clockPub_, contactsPub_, markersPub_, removedBodiesPub_;
  ros::Publisher jointStatesPub_, mapPub_;
  ros::Subscriber jointCommandSub_, mapSub_;
  std::unique_ptr<DeviceEndpoints> deviceEndpoints_;
  std::mutex deviceSyncMutex_;        // one syncDevices() at a time
  uint64_t syncedDeviceVersion_ = 0;  // guarded by deviceSyncMutex_
  bool devicesSynced_ = false;
  std::unique_ptr<diagnostic_updater::Updater> diagnostics_;
  std::vector<ros::ServiceServer> services_;
  ros::WallTimer stepTimer_, publishTimer_;
};

}  // namespace bridge
}  // namespace impulse2d
