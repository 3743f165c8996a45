// The drives (drive.hpp): ramps, steering, forces and odometry.
#include <impulse2d/drive.hpp>

#include <algorithm>
#include <cmath>

namespace impulse2d {

namespace {
constexpr double kStandardGravity = 9.81;  // m/s^2, for the default traction: the body's weight
}  // namespace

double rampTowards(double current, double target, double maxRate, double dt) {
  const double step = maxRate * dt;
  return current + std::clamp(target - current, -step, step);
}

Vec2 rampTowards(const Vec2& current, const Vec2& target, double maxRate, double dt) {
  const Vec2 change = target - current;
  const double step = maxRate * dt;
  const double length = change.norm();
  return length <= step ? target : Vec2(current + change * (step / length));
}

Pose2 integrateArc(const Pose2& pose, double v, double w, double dt) {
  Pose2 out;
  const double turn = w * dt;
  if (std::abs(turn) < 1e-6) {
    const double mid = pose.angle + 0.5 * turn;
    out.position = pose.position + v * dt * Vec2(std::cos(mid), std::sin(mid));
  } else {
    const double r = v / w;
    const double a0 = pose.angle, a1 = pose.angle + turn;
    out.position =
        pose.position + r * Vec2(std::sin(a1) - std::sin(a0), std::cos(a0) - std::cos(a1));
  }
  out.angle = pose.angle + turn;
  return out;
}

Pose2 integrateArc(const Pose2& pose, const Vec2& v, double w, double dt) {
  Pose2 out;
  const double turn = w * dt;
  if (std::abs(turn) < 1e-6) {
    out.position = pose.position + dt * Rot(pose.angle + 0.5 * turn).apply(v);
  } else {
    // d/da R(a) = R(a + pi/2), so R(a - pi/2) is R's integral: [[sin, cos], [-cos, sin]].
    auto integral = [](double a) {
      const double s = std::sin(a), c = std::cos(a);
      Eigen::Matrix2d m;
      m << s, c, -c, s;
      return m;
    };
    out.position = pose.position + (integral(pose.angle + turn) - integral(pose.angle)) * v / w;
  }
  out.angle = pose.angle + turn;
  return out;
}

double steeringFor(double v, double w, double wheelbase, double maxAngle, double current) {
  if (v == 0.0) return current;
  return std::clamp(std::atan(w * wheelbase / v), -maxAngle, maxAngle);
}

Drive::Drive(const DriveDef& def, BodyId body, const World& world, DeviceType type)
    : def_(def), type_(type), body_(body) {
  const Body& b = world.body(body);
  if (!(def_.maxForce > 0.0)) def_.maxForce = b.mass * kStandardGravity;
  if (!(def_.maxTorque > 0.0)) def_.maxTorque = def_.maxForce * b.maxExtent;
}

void Drive::command(double vx, double vy, double w, double now) {
  if (!std::isfinite(vx) || !std::isfinite(vy) || !std::isfinite(w)) return;
  commandVx_ = vx;
  commandVy_ = type_ == DeviceType::Omni ? vy : 0.0;
  commandW_ = w;
  commandTime_ = now;
  hasCommand_ = true;
}

void Drive::halt() {
  commandVx_ = commandVy_ = commandW_ = 0.0;
  hasCommand_ = false;
  startSpeed_ = startSideSpeed_ = startTurnRate_ = 0.0;
  speed_ = sideSpeed_ = turnRate_ = 0.0;
  steering_ = 0.0;
}

bool Drive::timedOut(double now) const {
  return hasCommand_ && def_.cmdTimeout > 0.0 && now - commandTime_ > def_.cmdTimeout;
}

void Drive::rampSpeeds(bool live, double dt) {
  const double vx = live ? commandVx_ : 0.0, w = live ? commandW_ : 0.0;
  switch (type_) {
    case DeviceType::Omni: {
      const Vec2 v = rampTowards(Vec2(speed_, sideSpeed_), Vec2(vx, live ? commandVy_ : 0.0),
                                 def_.maxLinearAccel, dt);
      speed_ = v.x();
      sideSpeed_ = v.y();
      turnRate_ = rampTowards(turnRate_, w, def_.maxAngularAccel, dt);
      break;
    }
    case DeviceType::Ackermann: {
      speed_ = rampTowards(speed_, vx, def_.maxLinearAccel, dt);
      // Timed out: the car rolls to a stop with the wheels where they are.
      const double target =
          live ? steeringFor(vx, w, def_.wheelbase, def_.maxSteeringAngle, steering_) : steering_;
      steering_ = rampTowards(steering_, target, def_.steeringRate, dt);
      turnRate_ = speed_ * std::tan(steering_) / def_.wheelbase;
      break;
    }
    default:
      speed_ = rampTowards(speed_, vx, def_.maxLinearAccel, dt);
      turnRate_ = rampTowards(turnRate_, w, def_.maxAngularAccel, dt);
      break;
  }
}

void Drive::beforeStep(World& world, double now) {
  const double dt = world.settings().timeStep;
  startSpeed_ = speed_;
  startSideSpeed_ = sideSpeed_;
  startTurnRate_ = turnRate_;
  rampSpeeds(hasCommand_ && !timedOut(now), dt);
  if (!world.isValid(body_)) return;
  const Body& body = world.body(body_);

  // The origin's velocity along the heading half a step ahead, and the centre of mass's that
  // goes with it at the new turn rate.
  const double heading = body.angle + 0.5 * turnRate_ * dt;
  Vec2 originVelocity = speed_ * Vec2(std::cos(heading), std::sin(heading));
  if (type_ == DeviceType::Omni) {
    originVelocity += sideSpeed_ * Vec2(-std::sin(heading), std::cos(heading));
  }
  const Vec2 centerVelocity = originVelocity + cross(turnRate_, Vec2(body.center - body.xf.p));
  // The step gives v' = (v + dt (g + (F + F_applied) / m)) / (1 + dt c) (world_step.cpp,
  // integrateVelocities), F_applied being the forces already applied for this step (a wrench);
  // solved for F with v' = the target, likewise for the torque.
  const double m = body.mass, dampLinear = 1.0 + dt * body.linearDamping;
  Vec2 force = m * (dampLinear * centerVelocity - body.linearVelocity) / dt -
               m * world.settings().gravity - body.force;
  double torque =
      body.inertia * ((1.0 + dt * body.angularDamping) * turnRate_ - body.angularVelocity) / dt -
      body.torque;
  if (force.norm() > def_.maxForce) force *= def_.maxForce / force.norm();
  torque = std::clamp(torque, -def_.maxTorque, def_.maxTorque);
  // A stopped drive on level ground leaves the rounding residue of its last stop alone, so the
  // body can fall asleep.
  constexpr double kNegligible = 1e-9;  // of the caps
  if (force.norm() <= kNegligible * def_.maxForce &&
      std::abs(torque) <= kNegligible * def_.maxTorque) {
    return;
  }
  world.applyForce(body_, force, body.center);
  world.applyTorque(body_, torque);
}

void Drive::afterStep(double dt) {
  const double turn = 0.5 * (startTurnRate_ + turnRate_);
  if (type_ == DeviceType::Omni) {
    const Vec2 v(0.5 * (startSpeed_ + speed_), 0.5 * (startSideSpeed_ + sideSpeed_));
    odometry_ = integrateArc(odometry_, v, turn, dt);
  } else {
    odometry_ = integrateArc(odometry_, 0.5 * (startSpeed_ + speed_), turn, dt);
  }
}

}  // namespace impulse2d
