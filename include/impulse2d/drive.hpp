// The differential drive's model: wheel speeds ramped towards the command, the forces that move
// the body at those speeds through the physics, and odometry integrated from the wheel speeds as
// encoders measure them. ROS-free; the node feeds it cmd_vel and publishes what it reads.
#pragma once

#include <impulse2d/device_defs.hpp>
#include <impulse2d/world.hpp>

namespace impulse2d {

/// `current` moved towards `target` by at most maxRate * dt.
double rampTowards(double current, double target, double maxRate, double dt);

/// A pose in the plane.
struct Pose2 {
  Vec2 position = Vec2::Zero();  ///< m
  double angle = 0.0;            ///< rad, continuous
};

/// Dead reckoning over dt at forward speed v (along the heading) and turn rate w: the exact arc,
///
///   x += v/w (sin(a + w dt) - sin a),  y -= v/w (cos(a + w dt) - cos a),  a += w dt
///
/// and, for turns under 1e-6 rad a step, the chord along the mid-step heading.
Pose2 integrateArc(const Pose2& pose, double v, double w, double dt);

/// A dynamic body driven like a differential-drive robot (top-down worlds, plane xy).
///
/// Each step, before the world steps: the wheel speeds (v forward, w turning) move towards the
/// command at most max_linear_accel and max_angular_accel; a command older than cmd_timeout
/// counts as zero. The drive then applies the force and torque that give the body exactly those
/// speeds at the end of the step if nothing else acts: forward along the heading half a step
/// ahead (so the chords follow the odometry's arc), no sideways slip, with gravity, damping and
/// the forces already applied for the step (World::applyForce, the node's wrenches) made up for.
/// They are capped at max_force (forward and sideways together) and max_torque, so
///   - blocked (a wall, a heavy crate): the body pushes with max_force and stays; the wheels keep
///     turning, so the odometry runs on and drifts from the ground truth;
///   - pushed by a body, which the drive learns of only from the speed it lost: it gives way at
///     push x dt / mass m/s (a speed controller's droop), and freely to pushes beyond max_force;
///     likewise a crate it pushes slows it by its drag x dt / mass;
///   - on a slope (gravity in the plane): it holds its speed, and stands still when stopped, while
///     the force that takes is within max_force; beyond that it slides, unseen by the odometry.
/// The wheel speeds change linearly through a step, as a ramp does; after the step the odometry
/// integrates their mean over it (integrateArc). Its frame is the body's pose when the drive was
/// created.
class Drive {
 public:
  /// `def.maxForce` and `def.maxTorque` <= 0 are resolved from the body (device_defs.hpp).
  Drive(const DriveDef& def, BodyId body, const World& world);

  const DriveDef& def() const { return def_; }
  BodyId body() const { return body_; }

  /// A command at simulated time `now`: v m/s along the body's x axis, w rad/s counter-clockwise.
  /// Non-finite values are ignored (the caller reports them).
  void command(double v, double w, double now);
  /// Whether the last command (if any) is older than cmd_timeout at `now`.
  bool timedOut(double now) const;

  /// Before the world steps from time `now`.
  void beforeStep(World& world, double now);
  /// After the world stepped dt.
  void afterStep(double dt);

  /// The odometry: the pose in the odom frame and the twist (v, w) in the body frame.
  const Pose2& odometry() const { return odometry_; }
  double speed() const { return speed_; }
  double turnRate() const { return turnRate_; }

 private:
  DriveDef def_;
  BodyId body_;
  double commandV_ = 0.0, commandW_ = 0.0;
  bool hasCommand_ = false;
  double commandTime_ = 0.0;
  double startSpeed_ = 0.0, startTurnRate_ = 0.0;  // the wheels' speeds as the step began
  double speed_ = 0.0, turnRate_ = 0.0;            // and as it ends
  Pose2 odometry_;
};

}  // namespace impulse2d
