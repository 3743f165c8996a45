// The engine side of the ROS node: one World with its start scene, timed wrenches and plain
// snapshots for publishing.
//
// This header deliberately includes only defs.hpp. The generated messages impulse2d/Body.h and
// impulse2d/Shape.h declare impulse2d::Body and impulse2d::Shape, which clash with the engine's
// structs of the same names in body.hpp and shape.hpp, so no translation unit may include both.
// sim_world.cpp sees the engine; everything that sees messages sees only this header.
#pragma once

#include <impulse2d/defs.hpp>
#include <impulse2d/device_defs.hpp>
#include <impulse2d/model.hpp>
#include <impulse2d/occupancy_map.hpp>
#include <impulse2d/profile.hpp>

#include <Eigen/Geometry>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace impulse2d {

struct Scene;  // scene.hpp, which the node's headers leave out (see ImuReading)

class World;
class DeviceSet;
struct DeviceContext;
struct ContactInfo;

namespace bridge {

/// A name in single quotes, for one-line errors.
inline std::string quoted(const std::string& name) { return "'" + name + "'"; }

/// A shape's outline in its body's frame: a circle, or a convex polygon counter-clockwise.
struct ShapeOutline {
  bool circle = false;
  Vec2 center = Vec2::Zero();
  double radius = 0.0;
  std::vector<Vec2> vertices;
};

/// A shape as the world holds it, with its material (~get_body_properties).
struct ShapeProperties : ShapeOutline {
  double density = 0.0;
  double friction = 0.0;
  double restitution = 0.0;
};

/// What the world made of a body besides its state, every default applied.
struct BodyProperties {
  BodyType type = BodyType::Dynamic;
  double mass = 0.0, inertia = 0.0;  ///< 0 for static and kinematic bodies
  Vec2 localCenter = Vec2::Zero();   ///< centre of mass in the body frame
  double linearDamping = 0.0, angularDamping = 0.0;
  bool bullet = false;
  std::vector<ShapeProperties> shapes;
};

struct BodySnapshot {
  int index = -1;  ///< the body's slot: stable while it lives, used as a marker id
  std::string name;
  BodyType type = BodyType::Dynamic;
  Vec2 position = Vec2::Zero();  ///< body origin in the world
  double angle = 0.0;            ///< rad, continuous (not wrapped)
  Vec2 linearVelocity = Vec2::Zero();
  double angularVelocity = 0.0;
  bool awake = true;
  std::vector<ShapeOutline> shapes;  ///< filled only when asked for
};

struct ContactSnapshot {
  std::string bodyA, bodyB;
  Vec2 point = Vec2::Zero();
  Vec2 normal = Vec2::Zero();  ///< from body A to body B
  double separation = 0.0;
  double normalImpulse = 0.0;
  double tangentImpulse = 0.0;
};

struct JointSnapshot {
  int index = -1;
  std::string name;
  JointType type = JointType::Revolute;
  Vec2 originA = Vec2::Zero();  ///< body A's origin
  Vec2 originB = Vec2::Zero();
  Vec2 anchorA = Vec2::Zero();  ///< the anchor as carried by body A
  Vec2 anchorB = Vec2::Zero();
};

/// A URDF model's revolute or prismatic joint as joint_states reports it (URDF convention).
struct JointReading {
  std::string name;  ///< "model_name/joint"
  double position = 0.0;
  double velocity = 0.0;
};

/// A frame fixed to a body or to the world, for /tf_static: a URDF link merged into a body, a
/// URDF world link, a laser's frame.
struct FixedFrame {
  std::string name;
  std::string parent;  ///< a body's frame; empty: the world's frame_id
  std::string owner;   ///< the body whose removal removes the frame (its parent, or its model's)
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< in the parent's 3D frame
  /// Lasers and IMUs: the 2D offset in the body frame instead of `pose` (the plane mapping is
  /// the node's).
  bool laser = false;
  Vec2 offset = Vec2::Zero();
  double offsetAngle = 0.0;
  bool flip = false;  ///< an upside-down laser: rolled half a turn about its x axis
};

/// A drive's odometry and its body's true pose, for ~odom and tf (sim_world_devices.cpp).
struct OdometryReading {
  std::string device;
  std::string body;
  DriveDef def;
  Vec2 position = Vec2::Zero();  ///< the odometry, in the odom frame
  double angle = 0.0;
  double speed = 0.0;                ///< m/s along the body's x
  double sideSpeed = 0.0;            ///< m/s along the body's y (omni)
  double turnRate = 0.0;             ///< rad/s
  Vec2 truePosition = Vec2::Zero();  ///< the body in the world
  double trueAngle = 0.0;
  Vec2 trueVelocity = Vec2::Zero();  ///< m/s of the body's origin, world frame
  double trueTurnRate = 0.0;         ///< rad/s
};

/// One scan of a laser, taken after the step that ended at stampNs.
struct ScanReading {
  std::string device;
  std::string frame;  ///< "<body>/<device>"
  LaserDef def;
  int beams = 0;
  int64_t stampNs = 0;
  std::vector<float> ranges;
  std::vector<float> intensities;
};

/// One reading of an IMU, taken after the step that ended at stampNs.
struct ImuReading {
  std::string device;
  std::string frame;  ///< "<body>/<device>"
  ImuDef def;
  int64_t stampNs = 0;
  // As the unit reads them (ImuSample in imu.hpp, which the node's headers leave out: its
  // impulse2d::Shape would meet the message of that name).
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d angularVelocity = Eigen::Vector3d::Zero();     ///< rad/s
  Eigen::Vector3d linearAcceleration = Eigen::Vector3d::Zero();  ///< m/s^2
};

/// A bumper's contacts after a change, body_a always its body.
struct BumperReading {
  std::string device;
  int64_t stampNs = 0;
  std::vector<ContactSnapshot> contacts;
};

/// What ~ray_cast answers (sim_world_queries.cpp).
struct RayCastAnswer {
  bool hit = false;
  std::string body;
  Vec2 point = Vec2::Zero();
  Vec2 normal = Vec2::Zero();
  double fraction = 0.0;
};

/// A body the world lost by itself: removed by a step (it left the world extent, its velocity
/// overflowed, or it was lost for good with world.remove_lost_bodies), or found lost for good
/// and left to fall.
struct BodyLoss {
  std::string name;
  RemovalCause cause = RemovalCause::LeftWorldExtent;
  bool removed = true;
  std::string reason;            ///< "it left the world extent of 1e7 m", "lost for good: ..."
  Vec2 position = Vec2::Zero();  ///< its origin then
  int64_t simTimeNs = 0;         ///< the simulated time after the step that found it
  /// The node's warning: "removed body 'b': it left the world extent of 1e7 m", or "body 'b' is
  /// lost for good: ...; world.remove_lost_bodies: true removes such bodies at once".
  std::string describe() const;
};

/// What ~spawn_urdf asks for and answers (sim_world_urdf.cpp).
struct UrdfRequest {
  std::string modelName;
  std::string xml;
  Vec2 position = Vec2::Zero();
  double angle = 0.0;
  /// Top-down worlds: refuse a wheel's joint (an axis in the floor) instead of folding it.
  bool strict = false;
};
struct UrdfSpawned {
  std::vector<std::string> bodies, joints, warnings;
  std::vector<std::string> devices;  ///< from its gazebo plugins and sensors
};

/// What ~spawn_model asks for and answers (sim_world_models.cpp): a model file (absolute or
/// package://) or its YAML text, and where it goes.
struct ModelRequest {
  ModelPlacement where;
  std::string file;  ///< one of file and yaml
  std::string yaml;
};
struct ModelSpawned {
  std::vector<std::string> bodies, joints, devices;
};

/// An occupancy map the world's walls came from (a scene's `maps:`), for ~map.
struct LoadedMap {
  std::string name;
  OccupancyGrid grid;
};

/// Not thread-safe: the node serialises every call with its own mutex.
/// Every mutating call either succeeds or leaves the world unchanged and sets `error` to one
/// line naming the request field.
class SimWorld {
 public:
  SimWorld();
  ~SimWorld();
  SimWorld(const SimWorld&) = delete;
  SimWorld& operator=(const SimWorld&) = delete;

  /// Replaces everything by the scene and remembers it for reset(). On a bad scene the world is
  /// left empty with default settings, and reset() restores that empty world. The scene's
  /// devices wait for attachStartDevices(), so that they may name the bodies of URDF models
  /// spawned at start in between.
  bool loadStartScene(const std::string& yamlText, std::string* error);
  /// Attaches the start scene's devices. When they are refused the whole start scene is: the
  /// world keeps only the start URDF models, and so does reset().
  bool attachStartDevices(std::string* error);
  /// Back to the start scene: bodies, joints and settings; pending wrenches are dropped.
  /// The step count (simulated time) keeps running, so stamps never go backwards.
  void reset();
  /// Steps on this many threads from now on, whatever the scenes say (0: as the start scene
  /// says, 1 by default); kept across reset().
  void setThreads(int threads);
  int threads() const;
  /// Adds the scene's bodies, joints and devices (all or nothing); its `world:` settings are not
  /// applied.
  bool addScene(const std::string& yamlText, std::string* error);

  bool spawnBody(const BodyDef& def, std::string* error);
  bool deleteBody(const std::string& name, std::string* error);
  /// `def.bodyA` and `def.bodyB` are ignored; the bodies are named.
  bool createJoint(const JointDef& def, const std::string& bodyA, const std::string& bodyB,
                   std::string* error);
  bool deleteJoint(const std::string& name, std::string* error);
  /// `force` (N) at the world point `point`, which then moves with the body, plus `torque`
  /// (N m), for ceil(duration / time_step) steps; duration 0 means one step.
  /// A force at the point (0, 0) (a point left out) away from the body's centre of mass also
  /// turns it: `notes` gets a line that says so.
  bool applyWrench(const std::string& body, const Vec2& force, double torque, const Vec2& point,
                   double duration, std::string* error, std::vector<std::string>* notes = nullptr);
  bool setBodyState(const std::string& name, const Vec2& position, double angle,
                    const Vec2& linearVelocity, double angularVelocity, std::string* error);
  bool getBodyState(const std::string& name, BodySnapshot* out, std::string* error) const;
  bool getBodyProperties(const std::string& name, BodyProperties* out, std::string* error) const;

  // URDF models (sim_world_urdf.cpp). A model spawned with `atStart` is part of the start state
  // that reset() restores.
  bool spawnUrdf(const UrdfRequest& request, bool atStart, UrdfSpawned* out, std::string* error);
  /// Motor of a revolute or prismatic joint: target speed (rad/s or m/s) and max effort (N m or
  /// N). For URDF joints both are in the URDF's sense, max_effort 0 means the URDF effort limit,
  /// and the URDF velocity and effort limits clamp them. `release` switches the motor off.
  bool setJointMotor(const std::string& name, double speed, double maxEffort, bool release,
                     std::string* error);
  /// The URDF models' joints: the world's revolute and prismatic ones, then those a top-down
  /// world folded into bodies (wheels, at the angle they rolled to; others at 0).
  std::vector<JointReading> urdfJointStates() const;
  /// The folded joints' child links (wheels) at their joint positions, for /tf: they turn.
  std::vector<FixedFrame> rollingFrames() const;

  // Models (sim_world_models.cpp): a scene's `models:` and those spawned since. A model spawned
  // here is gone after reset(), as a spawned body is; the start scene's come back.
  bool spawnModel(const ModelRequest& request, ModelSpawned* out, std::string* error);
  /// Removes the model's bodies (the joints and devices on them go along).
  bool deleteModel(const std::string& name, std::string* error);
  /// Moves the model rigidly so that it stands at `position`, `angle` as if spawned there (its
  /// first body still in the world is placed as the file places it, the others keep their pose
  /// relative to it), and stops it: velocities zero, drives halted.
  bool moveModel(const std::string& name, const Vec2& position, double angle, std::string* error);
  std::vector<std::string> modelNames() const;

  // Queries (sim_world_queries.cpp): points within 1e7 m of the origin, named bodies to skip.
  bool rayCast(const Vec2& start, const Vec2& end, const std::vector<std::string>& ignore,
               RayCastAnswer* out, std::string* error) const;
  bool queryPoint(const Vec2& point, std::vector<std::string>* bodies, std::string* error) const;

  // Devices (sim_world_devices.cpp).
  /// Maps a device's topic as a scene gives it to the name it is checked by, so that the
  /// relative "scan" and the node's absolute "/impulse2d/scan" are seen as one; and names the
  /// node's own topics, which devices may not take. Identity and none by default.
  void setTopicRules(std::function<std::string(const std::string&)> resolve,
                     std::vector<std::string> reserved);
  std::vector<DeviceDef> devices() const;
  /// Changes whenever devices are added or removed.
  uint64_t deviceVersion() const;
  /// A cmd_vel for the drive named `device` (v m/s forward, w rad/s), at the current simulated
  /// time; false with a message when there is no such drive or a number is not finite.
  /// A command to the named drive: vx, vy (omni only) m/s and w rad/s in its body's frame.
  bool commandDrive(const std::string& device, double vx, double vy, double w, std::string* error);
  /// Lasers, bumpers and IMUs are read only while active (someone subscribes).
  void setDeviceActive(const std::string& device, bool active);
  std::vector<OdometryReading> odometry() const;
  /// The scans, IMU readings and bumper changes of the steps since the last call, oldest first
  /// (at most 64 of each are kept).
  std::vector<ScanReading> takeScans();
  std::vector<ImuReading> takeImuReadings();
  std::vector<BumperReading> takeBumperChanges();
  /// URDF link frames and laser and IMU frames whose bodies exist.
  std::vector<FixedFrame> fixedFrames() const;

  /// One fixed step, with the wrenches that are due and the devices.
  void step();
  /// Each stage's time of the last step (World::profile).
  const StepProfile& lastProfile() const;
  /// The bodies that steps removed, or found lost for good, since the last call, oldest first
  /// (at most 1024 are kept between calls).
  std::vector<BodyLoss> takeBodyLosses();
  /// Since this SimWorld was made, across resets.
  uint64_t removedBodyCount() const { return removedCount_; }
  uint64_t lostBodyCount() const { return lostCount_; }
  uint64_t stepCount() const { return steps_; }
  /// Simulated time as steps * time_step summed in nanoseconds, so it never drifts.
  int64_t simTimeNs() const { return simTimeNs_; }
  double timeStep() const;

  const std::string& frameId() const { return frameId_; }
  const std::string& plane() const { return plane_; }
  /// Changes whenever static bodies may have been added, moved or removed.
  uint64_t staticVersion() const { return staticVersion_; }
  /// How scenes find package://PACKAGE/... files: the package's folder, or "" with `error` set.
  /// Unset, such names are refused.
  void setPackageFinder(std::function<std::string(const std::string&, std::string*)> find);
  /// The maps of the start scene and of the scenes added since, in that order.
  const std::vector<LoadedMap>& maps() const { return maps_; }
  /// What ~map shows: the followed map (followMap) if there is one, else the last of maps(), or
  /// null.
  const LoadedMap* latestMap() const;
  /// Changes whenever latestMap() may have.
  uint64_t mapVersion() const { return mapVersion_; }
  /// Walls from an occupancy grid (a map topic), static bodies named `name`, `name/1`, ...:
  /// they replace the last grid's, and are put back after reset(). A grid that is malformed,
  /// too large, or whose walls cannot join the world (a name taken, a limit) leaves the world as
  /// it was.
  bool followMap(const std::string& name, OccupancyGrid grid, std::string* error);

  size_t bodyCount() const;
  size_t contactCount() const;
  std::vector<BodySnapshot> bodies(bool withShapes) const;
  std::vector<ContactSnapshot> contacts() const;
  std::vector<JointSnapshot> joints() const;

 private:
  /// A wrench held for a number of steps; the point is kept in the body frame.
  struct Wrench {
    BodyId body;
    Vec2 force = Vec2::Zero();
    Vec2 localPoint = Vec2::Zero();
    double torque = 0.0;
    uint64_t stepsLeft = 0;
  };
  void restoreStart();
  /// Adds the followed map's walls (after a reset); forgets the map if they cannot be added.
  void addFollowedWalls();
  /// parseScene with the package finder.
  bool parse(const std::string& yamlText, impulse2d::Scene* scene, std::string* error) const;
  /// A contact point with its bodies named (the ~contacts topic and the bumpers).
  ContactSnapshot snapshotOf(const ContactInfo& contact) const;
  /// A URDF joint in the world with what converts between the URDF's and the world's sense.
  struct UrdfJoint {
    JointId id;
    std::string name;
    double sign = 1.0;
    double maxEffort = 0.0;
    double maxVelocity = 0.0;
  };
  void respawnStartUrdfs();
  /// A joint folded into a body (UrdfFoldedJoint in urdf.hpp, which the node's headers leave
  /// out), with the position its wheel rolled to.
  struct FoldedJoint {
    std::string name, link;
    BodyId body;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
    Vec2 center = Vec2::Zero(), planeAxis = Vec2::UnitY();
    double wheelRadius = 0.0;
    double position = 0.0, velocity = 0.0;
  };
  /// After a step: the folded wheels roll with their bodies (or with the body's drive).
  void rollFoldedWheels();
  /// A model in the world: its bodies by id, so that a user's body that took the name of one
  /// removed since is never taken for it.
  struct PlacedModel {
    SceneModel def;
    std::vector<BodyId> bodies;  ///< def.bodies' ids when placed
  };
  /// Records the models just added with their bodies (names are unique then).
  void recordModels(const std::vector<SceneModel>& models);
  /// Empty when none of `models` takes the name of a model here, else the error.
  std::string checkModelNames(const std::vector<SceneModel>& models) const;
  DeviceContext deviceContext() const;
  /// Adds `devices` (checked against the world and the devices here) or nothing.
  bool addDevices(const std::vector<DeviceDef>& devices, std::string* error);
  /// After a step: queues the devices' fresh readings; drops the devices and frames of bodies
  /// the step removed.
  void collectDeviceReadings(bool bodiesRemoved);
  /// Forgets the URDF frames whose owner body is gone.
  void pruneUrdfFrames();

  std::unique_ptr<World> world_;
  std::string startYaml_;  ///< empty when the start scene was missing or bad
  int threads_ = 0;        ///< setThreads(); 0: the start scene's world.threads
  std::string frameId_ = "world";
  std::string plane_ = "xz";
  std::vector<Wrench> wrenches_;
  std::vector<UrdfJoint> urdfJoints_;
  std::vector<UrdfRequest> startUrdfs_;
  std::vector<FixedFrame> urdfFrames_;  ///< of the models spawned since the last restoreStart
  std::vector<FoldedJoint> foldedJoints_;
  std::unique_ptr<DeviceSet> devices_;
  std::vector<DeviceDef> startDevices_;  ///< the start scene's devices
  bool startDevicesAttached_ = false;
  std::function<std::string(const std::string&)> resolveTopic_;
  std::vector<std::string> reservedTopics_;
  std::vector<ScanReading> scans_;
  std::vector<ImuReading> imuReadings_;
  std::vector<BumperReading> bumperChanges_;
  uint64_t steps_ = 0;
  int64_t simTimeNs_ = 0;
  uint64_t staticVersion_ = 0;
  std::function<std::string(const std::string&, std::string*)> findPackage_;
  std::vector<LoadedMap> maps_;
  std::unique_ptr<LoadedMap> followed_;  ///< followMap's last grid
  std::vector<BodyId> followedWalls_;    ///< its walls in the world
  uint64_t mapVersion_ = 0;
  std::vector<PlacedModel> models_;
  std::vector<BodyLoss> losses_;
  uint64_t removedCount_ = 0;
  uint64_t lostCount_ = 0;
};

}  // namespace bridge
}  // namespace impulse2d
