#include "contact_solver.hpp"

#include "contact_math.hpp"
#include "position_pass.hpp"
#include "two_point_block-inl.h"

#include <algorithm>
#include <cmath>

namespace impulse2d {

// The two-point block (two_point_block-inl.h) on doubles, as the kernels run it in lanes.
using HWY_NAMESPACE::blockInverse;
using HWY_NAMESPACE::positionCorrection;
using HWY_NAMESPACE::positionPushes;
using HWY_NAMESPACE::ScalarLanes;
using HWY_NAMESPACE::solveTwoPointBlock;
using HWY_NAMESPACE::TwoPointBlock;
using HWY_NAMESPACE::wellConditioned;

void ContactSolver::withholdPush(int slot) { unpushed_.mark(slot); }

bool ContactSolver::getsNoPush(const Contact& contact, const SolverBodies& bodies) const {
  if (unpushed_.has(contact.bodyA) || unpushed_.has(contact.bodyB)) return true;
  return crushed_.pressesCrushed(contact, [&](int slot) { return bodies.dynamicEntryOf(slot); });
}

void ContactSolver::prepare(std::vector<Contact>& contacts, SolverBodies& bodies,
                            const WorldDef& def, double dt) {
  constraints_.clear();
  extras_.clear();
  bodies_ = &bodies;
  const bool baumgarte = def.solver == SolverType::Baumgarte;
  if (baumgarte) crushed_.find(contacts, [&](int slot) { return bodies.dynamicEntryOf(slot); });
  const double inverseDt = 1.0 / dt;
  for (Contact& contact : contacts) {
    const Manifold& m = contact.manifold;
    if (m.pointCount == 0) continue;
    // Asleep, or resting on something that cannot move.
    if (!bodies.isActive(contact.bodyA) && !bodies.isActive(contact.bodyB)) continue;
    const int entryA = bodies.ensureEntryOf(contact.bodyA),
              entryB = bodies.ensureEntryOf(contact.bodyB);
    if (entryA == entryB) continue;                      // two members of one welded cluster
    ContactConstraint& c = constraints_.emplace_back();  // built in place: no copies
    ContactConstraintExtra& extra = extras_.emplace_back();
    extra.contact = &contact;
    c.a = entryA;
    c.b = entryB;
    const SolverBody& a = bodies[c.a];
    const SolverBody& b = bodies[c.b];
    c.blockSolve = false;
    c.k12 = 0.0;
    c.inverse11 = c.inverse12 = c.inverse22 = 0.0;
    c.normal = m.normal;
    extra.localNormal = a.q.applyInverse(m.normal);
    c.friction = contact.friction;
    c.restitution = contact.restitution;
    c.pointCount = m.pointCount;
    const Vec2 tangent = perp(m.normal);
    const bool push = baumgarte && !getsNoPush(contact, bodies);
    for (int i = 0; i < m.pointCount; ++i) {
      const ManifoldPoint& mp = m.points[i];
      ContactConstraintPoint& p = c.points[i];
      const Vec2 rA = mp.point - a.center;
      const Vec2 rB = mp.point - b.center;
      p.normalArmA = cross(rA, m.normal);
      p.normalArmB = cross(rB, m.normal);
      p.tangentArmA = cross(rA, tangent);
      p.tangentArmB = cross(rB, tangent);
      const Vec2 halfGap = 0.5 * mp.separation * m.normal;
      extra.localA[i] = a.q.applyInverse(mp.point - halfGap - a.center);
      extra.localB[i] = b.q.applyInverse(mp.point + halfGap - b.center);
      p.normalImpulse = contact.normalImpulse[i];
      p.tangentImpulse = contact.tangentImpulse[i];
      p.normalMass = rowMass(a, b, p.normalArmA, p.normalArmB);
      p.tangentMass = rowMass(a, b, p.tangentArmA, p.tangentArmB);
      extra.approachVelocity[i] =
          rowSpeed(a, b, m.normal.x(), m.normal.y(), p.normalArmA, p.normalArmB);
      if (mp.separation > 0.0) {
        // Speculative: not touching yet, so the bodies may close the gap within this step.
        p.targetVelocity = -mp.separation * inverseDt;
      } else if (push) {
        // Capped, so that bodies spawned deep inside each other separate instead of exploding.
        p.targetVelocity =
            std::min(def.baumgarte / dt * std::max(0.0, -mp.separation - def.linearSlop),
                     def.maxPushVelocity);
      } else {
        p.targetVelocity = 0.0;  // the position pass removes the overlap without adding momentum
      }
    }
    if (c.pointCount == 2) {
      const ContactConstraintPoint& p1 = c.points[0];
      const ContactConstraintPoint& p2 = c.points[1];
      const double m = a.invMass + b.invMass;
      const double k11 = m + a.invInertia * p1.normalArmA * p1.normalArmA +
                         b.invInertia * p1.normalArmB * p1.normalArmB;
      const double k22 = m + a.invInertia * p2.normalArmA * p2.normalArmA +
                         b.invInertia * p2.normalArmB * p2.normalArmB;
      c.k12 = m + a.invInertia * p1.normalArmA * p2.normalArmA +
              b.invInertia * p1.normalArmB * p2.normalArmB;
      const double det = k11 * k22 - c.k12 * c.k12;
      c.blockSolve = wellConditioned(ScalarLanes{}, k11, det);
      if (c.blockSolve) {
        blockInverse(ScalarLanes{}, k11, c.k12, k22, det, &c.inverse11, &c.inverse12, &c.inverse22);
      }
    }
  }
  unpushed_.clear();
}

void ContactSolver::warmStart() {
  SolverBody* bodies = bodies_->data();
  for (const ContactConstraint& c : constraints_) {
    SolverBody& a = bodies[c.a];
    SolverBody& b = bodies[c.b];
    // All impulses of the manifold at once: P = sum of (normal n + tangent t) over the points.
    const double nx = c.normal.x(), ny = c.normal.y();
    double normal = 0.0, tangent = 0.0, angularA = 0.0, angularB = 0.0;
    for (int i = 0; i < c.pointCount; ++i) {
      const ContactConstraintPoint& p = c.points[i];
      normal += p.normalImpulse;
      tangent += p.tangentImpulse;
      angularA += p.normalImpulse * p.normalArmA + p.tangentImpulse * p.tangentArmA;
      angularB += p.normalImpulse * p.normalArmB + p.tangentImpulse * p.tangentArmB;
    }
    const double px = normal * nx - tangent * ny, py = normal * ny + tangent * nx;
    applyImpulse(a, b, px, py, angularA, angularB);
  }
}

void ContactSolver::solveFriction(ContactConstraint& c, SolverBody& a, SolverBody& b) {
  const double tx = -c.normal.y(), ty = c.normal.x();  // perp(normal)
  for (int i = 0; i < c.pointCount; ++i) {
    ContactConstraintPoint& p = c.points[i];
    const double vt = rowSpeed(a, b, tx, ty, p.tangentArmA, p.tangentArmB);
    const double maxFriction = c.friction * p.normalImpulse;
    const double total =
        std::clamp(p.tangentImpulse - p.tangentMass * vt, -maxFriction, maxFriction);
    applyRowImpulse(a, b, tx, ty, p.tangentArmA, p.tangentArmB, total - p.tangentImpulse);
    p.tangentImpulse = total;
  }
}

void ContactSolver::solveVelocities() {
  SolverBody* bodies = bodies_->data();
  for (ContactConstraint& c : constraints_) {
    SolverBody& a = bodies[c.a];
    SolverBody& b = bodies[c.b];
    // Friction first: non-penetration matters more, so the normal impulse gets the last word.
    solveFriction(c, a, b);
    if (c.blockSolve) {
      solveNormalBlock(c, a, b, c.points[0].targetVelocity, c.points[1].targetVelocity);
      continue;
    }
    for (int i = 0; i < c.pointCount; ++i) {
      ContactConstraintPoint& p = c.points[i];
      const double vn = rowSpeed(a, b, c.normal.x(), c.normal.y(), p.normalArmA, p.normalArmB);
      // Clamp the accumulated impulse, not the increment: an iteration may take back what an
      // earlier one pushed too hard, as long as the total still only pushes.
      const double total = std::max(p.normalImpulse - p.normalMass * (vn - p.targetVelocity), 0.0);
      applyRowImpulse(a, b, c.normal.x(), c.normal.y(), p.normalArmA, p.normalArmB,
                      total - p.normalImpulse);
      p.normalImpulse = total;
    }
  }
}

// Both normal impulses of a two-point manifold at once. Solving the pair exactly removes the
// left-right bias of one-by-one Gauss-Seidel that makes stacks lean.
void ContactSolver::solveNormalBlock(ContactConstraint& c, SolverBody& a, SolverBody& b,
                                     double target1, double target2) {
  ContactConstraintPoint& p1 = c.points[0];
  ContactConstraintPoint& p2 = c.points[1];
  const double nx = c.normal.x(), ny = c.normal.y();
  const double x1Old = p1.normalImpulse, x2Old = p2.normalImpulse;
  // Both points share the bodies' linear velocities; only the turning differs.
  const double linear = nx * (b.linearVelocity.x() - a.linearVelocity.x()) +
                        ny * (b.linearVelocity.y() - a.linearVelocity.y());
  const double vn1 = linear + b.angularVelocity * p1.normalArmB - a.angularVelocity * p1.normalArmA;
  const double vn2 = linear + b.angularVelocity * p2.normalArmB - a.angularVelocity * p2.normalArmA;
  const TwoPointBlock<ScalarLanes> k{c.k12,       c.inverse11,   c.inverse12,
                                     c.inverse22, p1.normalMass, p2.normalMass};
  double x1 = 0.0, x2 = 0.0;
  if (!solveTwoPointBlock(ScalarLanes{}, k, vn1 - target1, vn2 - target2, x1Old, x2Old, &x1, &x2)) {
    return;  // no case fits: round-off on a degenerate pair
  }
  applyTwoRowImpulses(a, b, nx, ny, p1.normalArmA, p1.normalArmB, x1 - x1Old, p2.normalArmA,
                      p2.normalArmB, x2 - x2Old);
  p1.normalImpulse = x1;
  p2.normalImpulse = x2;
}

void ContactSolver::applyRestitution(double threshold) {
  SolverBody* bodies = bodies_->data();
  for (size_t k = 0; k < constraints_.size(); ++k) {
    ContactConstraint& c = constraints_[k];
    if (c.restitution == 0.0) continue;
    for (int i = 0; i < c.pointCount; ++i) {
      ContactConstraintPoint& p = c.points[i];
      const double approach = extras_[k].approachVelocity[i];
      // Only points that pushed: a speculative point the bodies never reached does not bounce.
      if (approach > -threshold || p.normalImpulse == 0.0) continue;
      SolverBody& a = bodies[c.a];
      SolverBody& b = bodies[c.b];
      const double vn = rowSpeed(a, b, c.normal.x(), c.normal.y(), p.normalArmA, p.normalArmB);
      const double target = -c.restitution * approach;
      const double total = std::max(p.normalImpulse - p.normalMass * (vn - target), 0.0);
      const double delta = total - p.normalImpulse;
      p.normalImpulse = total;
      applyRowImpulse(a, b, c.normal.x(), c.normal.y(), p.normalArmA, p.normalArmB, delta);
    }
  }
}

void ContactSolver::storeImpulses() {
  for (size_t k = 0; k < constraints_.size(); ++k) {
    const ContactConstraint& c = constraints_[k];
    Contact& contact = *extras_[k].contact;
    for (int i = 0; i < c.pointCount; ++i) {
      contact.normalImpulse[i] = c.points[i].normalImpulse;
      contact.tangentImpulse[i] = c.points[i].tangentImpulse;
    }
  }
}

bool ContactSolver::solvePositions(const WorldDef& def) {
  SolverBody* bodies = bodies_->data();
  double deepest = 0.0;
  for (size_t k = 0; k < constraints_.size(); ++k) {
    const ContactConstraint& c = constraints_[k];
    const ContactConstraintExtra& extra = extras_[k];
    SolverBody& a = bodies[c.a];
    SolverBody& b = bodies[c.b];
    // Each point at the current poses: its separation, and its normal arms cross(r, n) at the
    // point midway between the two anchors. In scalars: math.hpp says why.
    const Vec2 normal = a.q.apply(extra.localNormal);
    const double nx = normal.x(), ny = normal.y();
    double armA[2] = {0.0, 0.0}, armB[2] = {0.0, 0.0}, correction[2] = {0.0, 0.0};
    for (int i = 0; i < c.pointCount; ++i) {
      const Vec2 anchorA = a.q.apply(extra.localA[i]), anchorB = b.q.apply(extra.localB[i]);
      const double pointAx = a.center.x() + anchorA.x(), pointAy = a.center.y() + anchorA.y();
      const double pointBx = b.center.x() + anchorB.x(), pointBy = b.center.y() + anchorB.y();
      const double separation = (pointBx - pointAx) * nx + (pointBy - pointAy) * ny;
      const double midX = 0.5 * (pointAx + pointBx), midY = 0.5 * (pointAy + pointBy);
      armA[i] = (midX - a.center.x()) * ny - (midY - a.center.y()) * nx;
      armB[i] = (midX - b.center.x()) * ny - (midY - b.center.y()) * nx;
      deepest = std::min(deepest, separation);
      correction[i] = positionCorrection(ScalarLanes{}, separation, def.baumgarte, def.linearSlop,
                                         kMaxLinearCorrection);
    }
    if (correction[0] == 0.0 && correction[1] == 0.0) continue;  // every point within the slop
    // Both points together, as in the velocity pass: one after the other would tilt the body a
    // little every pass, and a tall stack leans over.
    double x1 = 0.0, x2 = 0.0;
    positionPushes(ScalarLanes{}, a.invMass + b.invMass, a.invInertia, b.invInertia, armA, armB,
                   correction, c.pointCount == 2, &x1, &x2);
    const double sum = x1 + x2;
    a.center.x() -= a.invMass * sum * nx;
    a.center.y() -= a.invMass * sum * ny;
    b.center.x() += b.invMass * sum * nx;
    b.center.y() += b.invMass * sum * ny;
    turnBy(a, -(a.invInertia * (armA[0] * x1 + armA[1] * x2)));
    turnBy(b, b.invInertia * (armB[0] * x1 + armB[1] * x2));
  }
  return overlapsResolved(deepest, def.linearSlop);
}

}  // namespace impulse2d
