// The drives' model (diff_drive, omni, ackermann): wheel speeds ramped towards the command, the
// forces that move the body at those speeds through the physics, and odometry integrated from
// the wheel speeds as encoders measure them. ROS-free; the node feeds it cmd_vel and publishes
// what it reads.
#pragma once

#include <impulse2d/device_defs.hpp>
#include <impulse2d/world.hpp>

namespace impulse2d {

/// `current` moved towards `target` by at most maxRate * dt.
double rampTowards(double current, double target, double maxRate, double dt);
/// `current` moved towards `target` by at most maxRate * dt in length.
Vec2 rampTowards(const Vec2& current, const Vec2& target, double maxRate, double dt);

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
/// The same for a velocity `v` in the body frame (forward, sideways): the integral of R(a) v
/// over the turn, (R(a + w dt - pi/2) - R(a - pi/2)) v / w.
Pose2 integrateArc(const Pose2& pose, const Vec2& v, double w, double dt);

/// The steering angle (rad) at which a car of wheelbase L (m) turns at rate w (rad/s) when its
/// rear axle moves at v (m/s): atan(w L / v), the bicycle model's w = v tan(angle) / L; within
/// +-maxAngle. At v = 0 no angle gives a turn: `current` is kept.
double steeringFor(double v, double w, double wheelbase, double maxAngle, double current);

/// A dynamic body driven like a wheeled robot (top-down worlds, plane xy). The type says how:
///   - diff_drive: forward speed v and turn rate w, no sideways slip;
///   - omni (holonomic): forward and sideways speed and turn rate, each its own;
///   - ackermann (car-like, the body's origin at the rear axle's middle): forward speed v of the
///     rear axle, no sideways slip there, and the turn rate w = v tan(steering) / wheelbase of a
///     steering angle that turns towards the one the command's turn rate asks for
///     (steeringFor) at steering_rate, never beyond max_steering_angle. So the tightest turn has
///     radius wheelbase / tan(max_steering_angle), and a car at rest cannot turn.
///
/// Each step, before the world steps: the wheel speeds move towards the command at most
/// max_linear_accel (forward and sideways together) and max_angular_accel (diff_drive, omni); a
/// command older than cmd_timeout counts as zero. The drive then applies the force and torque
/// that give the body exactly those speeds at the end of the step if nothing else acts: along
/// the heading half a step ahead (so the chords follow the odometry's arc), with gravity, damping
/// and the forces already applied for the step (World::applyForce, the node's wrenches) made up
/// for. They are capped at max_force (forward and sideways together) and max_torque, so
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
  /// `type` is one of diff_drive, omni and ackermann.
  Drive(const DriveDef& def, BodyId body, const World& world,
        DeviceType type = DeviceType::DiffDrive);

  const DriveDef& def() const { return def_; }
  DeviceType type() const { return type_; }
  BodyId body() const { return body_; }

  /// A command at simulated time `now`: vx m/s along the body's x axis, vy m/s along its y axis
  /// (omni; the other drives ignore it), w rad/s counter-clockwise. Non-finite values are ignored
  /// (the caller reports them).
  void command(double vx, double vy, double w, double now);
  void command(double v, double w, double now) { command(v, 0.0, w, now); }
  /// The wheels stop at once and the last command is forgotten, as when the robot is picked up
  /// and set down elsewhere (a model moved): it stays still until the next command.
  void halt();
  /// Whether the last command (if any) is older than cmd_timeout at `now`.
  bool timedOut(double now) const;

  /// Before the world steps from time `now`.
  void beforeStep(World& world, double now);
  /// After the world stepped dt.
  void afterStep(double dt);

  /// The odometry: the pose in the odom frame and the twist (forward, sideways, turn) in the body
  /// frame.
  const Pose2& odometry() const { return odometry_; }
  double speed() const { return speed_; }
  double sideSpeed() const { return sideSpeed_; }
  double turnRate() const { return turnRate_; }
  /// ackermann: the steering angle now (rad, counter-clockwise), 0 for the other drives.
  double steeringAngle() const { return steering_; }

 private:
  // The target speeds of this step: forward, sideways and turning.
  void rampSpeeds(bool live, double dt);

  DriveDef def_;
  DeviceType type_;
  BodyId body_;
  double commandVx_ = 0.0, commandVy_ = 0.0, commandW_ = 0.0;
  bool hasCommand_ = false;
  double commandTime_ = 0.0;
  // The wheels' speeds as the step began, and as it ends.
  double startSpeed_ = 0.0, startSideSpeed_ = 0.0, startTurnRate_ = 0.0;
  double speed_ = 0.0, sideSpeed_ = 0.0, turnRate_ = 0.0;
  double steering_ = 0.0;
  Pose2 odometry_;
};

}  // namespace impulse2d
