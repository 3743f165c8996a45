// WorldNode: start-up, parameters and stepping. Publishing is in world_publish.cpp, the
// services in world_services.cpp.
#include "world_node.hpp"

#include "conversions.hpp"
#include "scene_param.hpp"

#include <impulse2d/limits.hpp>
#include <impulse2d/simd.hpp>

#include <impulse2d/ContactArray.h>
#include <rosgraph_msgs/Clock.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace impulse2d {
namespace bridge {
namespace {

// A free-running (rate 0) timer callback steps for at most this long before it lets the
// publish timer and the services in.
constexpr double kFreeRunSlice = 0.02;  // s
// Behind by more than this, the timer drops the backlog instead of stepping it all at once.
constexpr double kMaxBacklog = 0.25;  // s of wall time
// The timer never fires more often than this; higher rates step several times per tick.
constexpr double kMinTimerPeriod = 0.001;  // s

}  // namespace

WorldNode::Lock::Lock(WorldNode& node) : node_(node) {
  ++node_.waiters_;
  node_.mutex_.lock();
  --node_.waiters_;
}

WorldNode::Lock::~Lock() { node_.mutex_.unlock(); }

WorldNode::WorldNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh, const std::string& name)
    : nh_(nh), pnh_(pnh), name_(name) {
  const std::string simd = useSimdTargetFromEnvironment();  // before the first step
  if (!simd.empty()) ROS_WARN("[%s] %s", name_.c_str(), simd.c_str());
  setUpDevices();
  setUpMaps();
  loadStartScene();
  loadStartUrdf();
  // The scene's devices come last: they may name the URDF model's bodies.
  std::string error;
  if (!sim_.attachStartDevices(&error)) {
    ROS_ERROR("[%s] ~scene: %s; starting without the scene", name_.c_str(), error.c_str());
  }
  readParams();
  restartSchedule();
  statsStart_ = ros::WallTime::now();
  advertise();
  if (publishClock_) publishClock(sim_.simTimeNs());
  ROS_INFO(
      "[%s] %zu bodies, time_step %g s, rate %g steps/s (0: as fast as possible), %d thread%s, "
      "%s",
      name_.c_str(), sim_.bodyCount(), sim_.timeStep(), rate_, sim_.threads(),
      sim_.threads() == 1 ? "" : "s", paused_ ? "paused" : "running");

  // From here on callbacks may run on other threads, and they take the lock.
  advertiseServices();
  syncDevices();
  const double period = rate_ > 0.0 ? std::max(1.0 / rate_, kMinTimerPeriod) : kMinTimerPeriod;
  // Wall timers: the step rate is per wall second, and a ros::Timer would wait on the very
  // /clock this node publishes.
  stepTimer_ = nh_.createWallTimer(ros::WallDuration(period), &WorldNode::onStepTimer, this);
  publishTimer_ =
      nh_.createWallTimer(ros::WallDuration(1.0 / publishRate_), &WorldNode::onPublishTimer, this);
}

WorldNode::~WorldNode() {
  // Stop the callbacks first: shutting a timer or service down waits for a running callback.
  stepTimer_.stop();
  publishTimer_.stop();
  for (ros::ServiceServer& s : services_) s.shutdown();
  jointCommandSub_.shutdown();
  mapSub_.shutdown();
  deviceEndpoints_->shutdown();
}

void WorldNode::loadStartScene() {
  std::string yaml, error;
  switch (readSceneParam(pnh_, "scene", &yaml, &error)) {
    case SceneParam::Missing:
      ROS_WARN("[%s] no ~scene parameter: starting with an empty world", name_.c_str());
      return;
    case SceneParam::Bad:
      ROS_ERROR("[%s] ~scene: %s; starting with an empty world", name_.c_str(), error.c_str());
      return;
    case SceneParam::Ok:
      break;
  }
  if (!sim_.loadStartScene(yaml, &error)) {
    ROS_ERROR("[%s] ~scene: %s; starting with an empty world", name_.c_str(), error.c_str());
    return;
  }
  Plane plane;
  if (!parsePlane(sim_.plane(), &plane)) {
    ROS_ERROR("[%s] ~scene: world.plane: '%s' is neither xz nor xy", name_.c_str(),
              sim_.plane().c_str());
  }
}

void WorldNode::readParams() {
  const double defaultRate = 1.0 / sim_.timeStep();
  pnh_.param("rate", rate_, defaultRate);
  if (!std::isfinite(rate_) || rate_ < 0.0) {
    ROS_WARN("[%s] ~rate must be >= 0 (0: as fast as possible); using %g", name_.c_str(),
             defaultRate);
    rate_ = defaultRate;
  }
  pnh_.param("publish_rate", publishRate_, 30.0);
  if (!std::isfinite(publishRate_) || publishRate_ <= 0.0) {
    ROS_WARN("[%s] ~publish_rate must be > 0; using 30", name_.c_str());
    publishRate_ = 30.0;
  }
  // Unset, it follows /use_sim_time: a user who sets that for the navigation stack wants the
  // simulator to be the clock (as stage_ros and flatland are).
  if (!pnh_.getParam("publish_clock", publishClock_)) {
    publishClock_ = false;
    ros::param::get("/use_sim_time", publishClock_);
  }
  pnh_.param("paused", paused_, false);
  int threads = 0;
  if (pnh_.getParam("threads", threads)) {
    if (threads >= 1 && threads <= kMaxThreads) {
      sim_.setThreads(threads);
    } else {
      ROS_WARN("[%s] ~threads must be in [1, %d]; using the scene's %d", name_.c_str(), kMaxThreads,
               sim_.threads());
    }
  }
}

void WorldNode::advertise() {
  tfPub_ = nh_.advertise<tf2_msgs::TFMessage>("/tf", 100);
  tfStaticPub_ = nh_.advertise<tf2_msgs::TFMessage>("/tf_static", 1, true);
  if (publishClock_) clockPub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
  contactsPub_ = pnh_.advertise<impulse2d::ContactArray>("contacts", 10);
  markersPub_ = pnh_.advertise<visualization_msgs::MarkerArray>("markers", 10);
  removedBodiesPub_ = pnh_.advertise<impulse2d::RemovedBodies>("removed_bodies", 1, true);
  diagnostics_ = std::make_unique<diagnostic_updater::Updater>(nh_, pnh_, name_);
  diagnostics_->setHardwareID("impulse2d");
  diagnostics_->add("world", this, &WorldNode::diagnose);
  advertiseMaps();
}

void WorldNode::restartSchedule() {
  scheduleStart_ = ros::WallTime::now();
  scheduledSteps_ = 0;
}

void WorldNode::stepLocked() {
  const auto start = std::chrono::steady_clock::now();
  sim_.step();
  recordLosses();
  publishDeviceReadings();
  statsStepSeconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  statsProfile_ += sim_.lastProfile();
  ++statsSteps_;
}

void WorldNode::recordLosses() {
  // ~removed_bodies keeps this many; its count field says how many there were in all.
  constexpr size_t kMaxRemovedKept = 1000;
  for (const BodyLoss& loss : sim_.takeBodyLosses()) {
    ROS_WARN("[%s] %s", name_.c_str(), loss.describe().c_str());
    if (!loss.removed) continue;
    impulse2d::RemovedBody msg;
    msg.name = loss.name;
    switch (loss.cause) {
      case RemovalCause::LeftWorldExtent:
        msg.cause = impulse2d::RemovedBody::LEFT_WORLD;
        break;
      case RemovalCause::Overflow:
        msg.cause = impulse2d::RemovedBody::OVERFLOW;
        break;
      case RemovalCause::LostForGood:
        msg.cause = impulse2d::RemovedBody::LOST_FOR_GOOD;
        break;
    }
    msg.reason = loss.reason;
    msg.position.x = loss.position.x();
    msg.position.y = loss.position.y();
    msg.stamp = stampFor(loss.simTimeNs);
    removedBodies_.push_back(std::move(msg));
    if (removedBodies_.size() > kMaxRemovedKept) removedBodies_.pop_front();
  }
}

void WorldNode::onStepTimer(const ros::WallTimerEvent&) {
  const ros::WallTime tickStart = ros::WallTime::now();
  bool stepped = false;
  int64_t simTimeNs = 0;
  for (;;) {
    {
      Lock lock(*this);
      if (paused_) break;
      if (rate_ > 0.0) {
        // Step k of the schedule is due at scheduleStart_ + k / rate: counting steps against
        // the wall clock keeps the average rate exact whatever the timer's jitter.
        const double elapsed = (ros::WallTime::now() - scheduleStart_).toSec();
        const uint64_t due = static_cast<uint64_t>(std::floor(elapsed * rate_)) + 1;
        if (scheduledSteps_ >= due) break;
        if (static_cast<double>(due - scheduledSteps_) > std::max(1.0, kMaxBacklog * rate_)) {
          ROS_WARN_THROTTLE(10.0, "[%s] stepping cannot keep up with ~rate %g; dropping backlog",
                            name_.c_str(), rate_);
          scheduledSteps_ = due - 1;
        }
      } else if ((ros::WallTime::now() - tickStart).toSec() > kFreeRunSlice) {
        break;
      }
      stepLocked();
      ++scheduledSteps_;
      stepped = true;
      simTimeNs = sim_.simTimeNs();
    }
    // Someone (a service, the publisher) waits for the world: let them in, the schedule makes
    // up for it on the next tick.
    if (waiters_.load() > 0) break;
  }
  if (stepped && publishClock_) publishClock(simTimeNs);
}

ros::Time WorldNode::stampFor(int64_t simTimeNs) const {
  if (!publishClock_) return ros::Time::now();
  ros::Time t;
  t.fromNSec(static_cast<uint64_t>(simTimeNs));
  return t;
}

void WorldNode::publishClock(int64_t simTimeNs) {
  std::lock_guard<std::mutex> lock(clockMutex_);
  if (simTimeNs < lastClockNs_) return;
  lastClockNs_ = simTimeNs;
  rosgraph_msgs::Clock clock;
  clock.clock.fromNSec(static_cast<uint64_t>(simTimeNs));
  clockPub_.publish(clock);
}

}  // namespace bridge
}  // namespace impulse2d
