// The IMU (imu.hpp): the body's motion at the mount point, as an accelerometer and a gyroscope
// read it.
#include <impulse2d/imu.hpp>

#include <cmath>

namespace impulse2d {
namespace {

Eigen::Quaterniond fromRollPitchYaw(double roll, double pitch, double yaw) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()));
}

}  // namespace

Imu::Motion Imu::motionOf(const Body& body) {
  return Motion{body.linearVelocity, body.angularVelocity, body.angle};
}

Imu::Imu(const ImuDef& def, BodyId body, uint32_t seed, const World& world)
    : def_(def), body_(body), noise_(seed) {
  if (!world.isValid(body)) return;
  const Body& b = world.body(body);
  last_ = motionOf(b);
  truth_.orientation = fromRollPitchYaw(0.0, 0.0, b.angle + def_.offsetAngle);
  truth_.angularVelocity.z() = b.angularVelocity;
  const Vec2 support = -Rot(b.angle + def_.offsetAngle).applyInverse(world.settings().gravity);
  truth_.linearAcceleration = Eigen::Vector3d(support.x(), support.y(), kFloorGravity);
}

void Imu::follow(const World& world) {
  if (!world.isValid(body_)) return;
  const Body& b = world.body(body_);
  const double dt = world.settings().timeStep;
  const Motion now = motionOf(b);
  //   mount o          r: from the centre of mass to the mount point, body frame
  //          /           a_mount = a_center + alpha x r - w^2 r
  //         / r    w
  //        *  <--.       (-w^2 r points back at the centre: the turn's pull)
  //   centre of mass
  const Vec2 centerAcceleration =
      Rot(0.5 * (last_.angle + now.angle)).applyInverse(Vec2((now.velocity - last_.velocity) / dt));
  const double angularAcceleration = (now.angularVelocity - last_.angularVelocity) / dt;
  const Vec2 r = def_.offset - b.localCenter;
  const Vec2 mount = centerAcceleration + cross(angularAcceleration, r) -
                     now.angularVelocity * now.angularVelocity * r;
  // What the unit feels is the acceleration less gravity's, in its own frame.
  const Vec2 felt =
      Rot(def_.offsetAngle)
          .applyInverse(Vec2(mount - Rot(now.angle).applyInverse(world.settings().gravity)));
  truth_.orientation = fromRollPitchYaw(0.0, 0.0, now.angle + def_.offsetAngle);
  truth_.angularVelocity = Eigen::Vector3d(0.0, 0.0, now.angularVelocity);
  truth_.linearAcceleration = Eigen::Vector3d(felt.x(), felt.y(), kFloorGravity);
  last_ = now;
}

ImuSample Imu::read() {
  auto noisy = [&](const Eigen::Vector3d& stddev) {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (int i = 0; i < 3; ++i) {
      if (stddev[i] > 0.0) n[i] = stddev[i] * noise_.next();
    }
    return n;
  };
  ImuSample out;
  const Eigen::Vector3d tilt = noisy(def_.orientationNoise);
  out.orientation = truth_.orientation * fromRollPitchYaw(tilt.x(), tilt.y(), tilt.z());
  out.angularVelocity =
      truth_.angularVelocity + def_.angularVelocityBias + noisy(def_.angularVelocityNoise);
  out.linearAcceleration =
      truth_.linearAcceleration + def_.linearAccelerationBias + noisy(def_.linearAccelerationNoise);
  return out;
}

}  // namespace impulse2d
