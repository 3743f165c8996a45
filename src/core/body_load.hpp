// What integrating a dynamic body's velocity over a time step adds: gravity, the applied force
// and torque, and implicit damping. One formula for both solver paths (the one-pass solvers over
// the step, the sub-stepping ones over each sub-step).
#pragma once

#include <impulse2d/math.hpp>

#include <cmath>

namespace impulse2d {

/// v = (v + dv) * damping over one (sub-)step.
struct BodyLoad {
  double dvx = 0.0, dvy = 0.0, dw = 0.0;
  double linearDamping = 1.0, angularDamping = 1.0;  // factors per (sub-)step
};

/// The load of a step h. Implicit damping, 1 / (1 + h c): stable for any coefficient and step.
inline BodyLoad loadOver(double h, const Vec2& gravity, double invMass, double invInertia,
                         const Vec2& force, double torque, double linearDamping,
                         double angularDamping) {
  BodyLoad load;
  load.dvx = h * (gravity.x() + invMass * force.x());
  load.dvy = h * (gravity.y() + invMass * force.y());
  load.dw = h * invInertia * torque;
  if (linearDamping > 0.0) load.linearDamping = 1.0 / (1.0 + h * linearDamping);
  if (angularDamping > 0.0) load.angularDamping = 1.0 / (1.0 + h * angularDamping);
  return load;
}

/// The last guard against non-finite impulses, in both solver paths: 0 x inf is NaN in the rows
/// of static and sleeping bodies, which every body touching them reads. A dynamic body whose
/// velocity or load this step is not finite stands still with infinite mass for the rest of the
/// step and is removed at its end (world_bounds.cpp, RemovalCause::Overflow). Finite but absurd
/// loads are bounded by the motion limits instead.
inline bool isFiniteMotion(double vx, double vy, double w) { return std::isfinite(vx + vy + w); }

/// Adds the load to a velocity.
inline void applyLoad(const BodyLoad& load, double& vx, double& vy, double& w) {
  vx = (vx + load.dvx) * load.linearDamping;
  vy = (vy + load.dvy) * load.linearDamping;
  w = (w + load.dw) * load.angularDamping;
}

}  // namespace impulse2d
