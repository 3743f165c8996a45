// WorldNode: what the publish timer sends (tf, tf_static, ~contacts, ~markers) and diagnostics.
#include "conversions.hpp"
#include "device_messages.hpp"
#include "markers.hpp"
#include "world_node.hpp"

#include <impulse2d/ContactArray.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>

namespace impulse2d {
namespace bridge {
namespace {

geometry_msgs::TransformStamped bodyTransform(Plane plane, const std::string& frameId,
                                              const ros::Time& stamp, const BodySnapshot& body) {
  geometry_msgs::TransformStamped t;
  t.header.frame_id = frameId;
  t.header.stamp = stamp;
  t.child_frame_id = body.name;
  t.transform = toTransform(plane, body.position, body.angle);
  return t;
}

}  // namespace

void WorldNode::onPublishTimer(const ros::WallTimerEvent&) {
  // Devices a step removed (with their bodies) give up their topics; the listeners decide
  // which lasers and bumpers run.
  syncDevices();
  updateDeviceDemand();

  // Contacts and markers cost something to build, so only while someone listens.
  const bool wantContacts = contactsPub_.getNumSubscribers() > 0;
  const bool wantMarkers = markersPub_.getNumSubscribers() > 0;

  MarkerInput scene;
  std::vector<ContactSnapshot> contacts;
  uint64_t staticVersion = 0;
  int64_t simTimeNs = 0;
  std::vector<JointReading> jointReadings;
  std::vector<OdometryReading> odometry;
  std::vector<FixedFrame> fixedFrames;
  std::vector<FixedFrame> rollingFrames;
  {
    Lock lock(*this);
    simTimeNs = sim_.simTimeNs();
    scene.stamp = stampFor(simTimeNs);
    scene.frameId = sim_.frameId();
    if (!parsePlane(sim_.plane(), &scene.plane)) scene.plane = Plane::XZ;
    scene.timeStep = sim_.timeStep();
    scene.bodies = sim_.bodies(wantMarkers);
    if (wantContacts || wantMarkers) contacts = sim_.contacts();
    if (wantMarkers) scene.joints = sim_.joints();
    staticVersion = sim_.staticVersion();
    jointReadings = sim_.urdfJointStates();
    rollingFrames = sim_.rollingFrames();
    odometry = sim_.odometry();
    if (!staticPublished_ || staticVersion != publishedStaticVersion_) {
      fixedFrames = sim_.fixedFrames();
    }
  }

  if (publishClock_) publishClock(simTimeNs);

  // On simulated time a paused world keeps its stamp; tf2 would warn about repeated data.
  if (!tfPublished_ || scene.stamp != lastTfStamp_) {
    tf2_msgs::TFMessage tf;
    // A driven body hangs under its odom frame: world -> odom -> body.
    std::vector<std::string> driven;
    publishOdometry(scene.plane, scene.frameId, scene.stamp, odometry, &tf.transforms, &driven);
    for (const BodySnapshot& body : scene.bodies) {
      if (body.type == BodyType::Static || body.name.empty()) continue;
      if (std::find(driven.begin(), driven.end(), body.name) != driven.end()) continue;
      tf.transforms.push_back(bodyTransform(scene.plane, scene.frameId, scene.stamp, body));
    }
    // Wheels folded into their bodies turn with their joint positions.
    for (const FixedFrame& frame : rollingFrames) {
      tf.transforms.push_back(fixedTransform(scene.plane, scene.frameId, frame, scene.stamp));
    }
    if (!tf.transforms.empty()) tfPub_.publish(tf);
    tfPublished_ = true;
    lastTfStamp_ = scene.stamp;
  }

  // Latched, and always the full set, so that a removed static body leaves it.
  if (!staticPublished_ || staticVersion != publishedStaticVersion_) {
    tf2_msgs::TFMessage tf;
    for (const BodySnapshot& body : scene.bodies) {
      if (body.type != BodyType::Static || body.name.empty()) continue;
      tf.transforms.push_back(bodyTransform(scene.plane, scene.frameId, scene.stamp, body));
    }
    // Frames fixed to bodies: URDF links merged into them, lasers.
    for (const FixedFrame& frame : fixedFrames) {
      tf.transforms.push_back(fixedTransform(scene.plane, scene.frameId, frame, scene.stamp));
    }
    tfStaticPub_.publish(tf);
    staticPublished_ = true;
    publishedStaticVersion_ = staticVersion;
  }

  publishJointStates(scene.stamp, jointReadings);
  publishRemovedBodies();
  publishMap();

  if (wantContacts) {
    impulse2d::ContactArray msg;
    msg.header.frame_id = scene.frameId;
    msg.header.stamp = scene.stamp;
    msg.contacts.reserve(contacts.size());
    for (const ContactSnapshot& c : contacts) msg.contacts.push_back(toContactMsg(c));
    contactsPub_.publish(msg);
  }
  if (wantMarkers) {
    scene.contacts = std::move(contacts);
    markersPub_.publish(buildMarkers(scene));
  }
  diagnostics_->update();
}

void WorldNode::publishRemovedBodies() {
  impulse2d::RemovedBodies msg;
  {
    Lock lock(*this);
    const uint64_t count = sim_.removedBodyCount();
    if (removedPublished_ && count == publishedRemovedCount_) return;
    msg.header.stamp = stampFor(sim_.simTimeNs());
    msg.header.frame_id = sim_.frameId();
    msg.bodies.assign(removedBodies_.begin(), removedBodies_.end());
    msg.count = count;
    publishedRemovedCount_ = count;
    removedPublished_ = true;
  }
  removedBodiesPub_.publish(msg);
}

void WorldNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  Lock lock(*this);
  const ros::WallTime now = ros::WallTime::now();
  const double wall = (now - statsStart_).toSec();
  const double sim = 1e-9 * static_cast<double>(sim_.simTimeNs() - statsSimStartNs_);
  const double realTimeFactor = wall > 0.0 ? sim / wall : 0.0;
  const double meanStep = statsSteps_ > 0 ? statsStepSeconds_ / statsSteps_ : 0.0;
  // Running behind the requested rate by more than 10% is worth a warning.
  const double target = rate_ * sim_.timeStep();
  if (paused_) {
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "paused");
  } else if (rate_ > 0.0 && realTimeFactor < 0.9 * target) {
    status.summaryf(diagnostic_msgs::DiagnosticStatus::WARN,
                    "real-time factor %.3f below the requested %.3f", realTimeFactor, target);
  } else {
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "running");
  }
  // Losing bodies is worth a warning for the window it happened in.
  const uint64_t removed = sim_.removedBodyCount(), lost = sim_.lostBodyCount();
  if (removed > statsRemovedStart_) {
    status.mergeSummaryf(diagnostic_msgs::DiagnosticStatus::WARN,
                         "%llu bodies removed (see ~removed_bodies)",
                         static_cast<unsigned long long>(removed - statsRemovedStart_));
  }
  if (lost > statsLostStart_) {
    status.mergeSummaryf(diagnostic_msgs::DiagnosticStatus::WARN, "%llu bodies lost for good",
                         static_cast<unsigned long long>(lost - statsLostStart_));
  }
  status.add("real-time factor", realTimeFactor);
  status.add("mean step time (s)", meanStep);
  status.add("steps in window", statsSteps_);
  status.add("total steps", sim_.stepCount());
  status.add("simulated time (s)", 1e-9 * static_cast<double>(sim_.simTimeNs()));
  status.add("bodies", sim_.bodyCount());
  status.add("contacts", sim_.contactCount());
  status.add("bodies removed", removed);
  status.add("bodies lost for good", lost);
  status.add("requested rate (steps/s)", rate_);
  status.add("threads", sim_.threads());
  // Where the steps' time went, as impulse2d_sim --profile prints it: mean ms per step.
  const double steps = statsSteps_ > 0 ? static_cast<double>(statsSteps_) : 1.0;
  for (const auto& [stage, ms] : statsProfile_.stages()) {
    status.add(std::string("stage ms: ") + stage, ms / steps);
  }
  status.add("stage ms: step", statsProfile_.total / steps);
  statsProfile_ = StepProfile();
  statsStart_ = now;
  statsSimStartNs_ = sim_.simTimeNs();
  statsSteps_ = 0;
  statsStepSeconds_ = 0.0;
  statsRemovedStart_ = removed;
  statsLostStart_ = lost;
}

}  // namespace bridge
}  // namespace impulse2d
