// A rigid body as users read it through World::body(): its pose, velocities, mass properties,
// shapes, name, type and whether it is awake. They change it only through World's methods, so the
// broad phase, islands and contacts stay consistent; that bookkeeping is the world's own
// (src/core/world_impl.hpp, BodyBookkeeping).
#pragma once

#include <impulse2d/defs.hpp>
#include <impulse2d/shape.hpp>

#include <string>
#include <vector>

namespace impulse2d {

struct alignas(64) Body {
  BodyType type = BodyType::Dynamic;
  bool awake = true;
  Transform xf;                        ///< body origin in the world
  Vec2 linearVelocity = Vec2::Zero();  ///< m/s of the centre of mass
  double angularVelocity = 0.0;        ///< rad/s

  std::vector<Shape> shapes;  ///< in the body frame (offsets already applied)
  double maxExtent = 0.0;     ///< m, farthest shape point from the centre of mass
  double minExtent = 0.0;     ///< m, the thinnest shape's inner radius: moving less cannot skip it

  BodyId id;
  std::string name;
  double angle = 0.0;               ///< rad, continuous (not wrapped), xf.q == Rot(angle)
  Vec2 localCenter = Vec2::Zero();  ///< centre of mass in the body frame
  Vec2 center = Vec2::Zero();       ///< centre of mass in the world

  Vec2 force = Vec2::Zero();  ///< N, accumulated until the end of the next step
  double torque = 0.0;        ///< N m

  double mass = 0.0, invMass = 0.0;        ///< kg; 0 for static and kinematic bodies
  double inertia = 0.0, invInertia = 0.0;  ///< kg m^2 about the centre of mass
  double linearDamping = 0.0, angularDamping = 0.0;
  bool bullet = false;

  double sleepTime = 0.0;  ///< s the body has been still

  /// Velocity of a world point attached to the body.
  Vec2 velocityAt(const Vec2& worldPoint) const {
    return linearVelocity + cross(angularVelocity, Vec2(worldPoint - center));
  }
};

}  // namespace impulse2d
