// The contact part of the one-pass solvers (baumgarte, ngs; the sub-stepping ones are in
// contact_bundles.hpp): effective masses and biases computed once
// per step (pre-step), then Gauss-Seidel iterations over the points with accumulated impulses
// clamped (normal >= 0, friction inside the cone |t| <= mu * n).
//
// Every iteration reads and writes all constraints, so what an iteration needs is kept apart
// from what only the pre-step, restitution and the position pass read (ContactConstraintExtra),
// and the lever arms enter as the scalars cross(r, n) and cross(r, t) the rows use:
//   normal speed   vn = n . (vB - vA) + wB cross(rB, n) - wA cross(rA, n)
//   impulse P n:   vA -= mA P n,  wA -= iA P cross(rA, n),  and + for B.
#pragma once

#include "contact.hpp"
#include "crushed_bodies.hpp"
#include "feedback.hpp"
#include "solver_body.hpp"

#include <impulse2d/defs.hpp>

#include <vector>

namespace impulse2d {

// These three are built only by ContactSolver::prepare, which writes every field; their
// constructors leave them unset on purpose: zeroing them first cost a `rep stos` per contact,
// 4 % of a small scene's step (docs/benchmarks.md, "Profile and optimisations").
struct ContactConstraintPoint {
  ContactConstraintPoint() {}       // prepare() sets every field
  double normalArmA, normalArmB;    // cross(rA, n), cross(rB, n)
  double tangentArmA, tangentArmB;  // cross(rA, t), cross(rB, t), t = perp(n)
  double normalImpulse, tangentImpulse;
  double normalMass, tangentMass;
  double targetVelocity;  // the normal velocity the point must reach
};

struct ContactConstraint {
  ContactConstraint() {}  // prepare() sets every field
  int a, b;               // entries in the step's SolverBodies
  int pointCount;
  // Two-point manifolds whose points are not (nearly) redundant solve both normal impulses at
  // once (two_point_block-inl.h): k12 couples the rows of their 2x2 effective-mass matrix K,
  // inverse is K^-1 (both used when set).
  bool blockSolve;
  Vec2 normal;
  double friction, restitution;
  double k12;
  double inverse11, inverse12, inverse22;
  ContactConstraintPoint points[2];  // the first pointCount are set
};

/// What only the pre-step, restitution, storing and the position pass read, by constraint.
struct ContactConstraintExtra {
  ContactConstraintExtra() {}  // prepare() sets every field
  Contact* contact;
  Vec2 localNormal;            // in A's frame, for NGS
  Vec2 localA[2];              // surface points, body frames, for NGS (the first pointCount)
  Vec2 localB[2];              //
  double approachVelocity[2];  // normal velocity before solving (the first pointCount)
};

class ContactSolver {
 public:
  /// Builds the constraints of the touching (or about to touch) contacts of bodies the step moves;
  /// adds read-only entries to `bodies` for the others they touch.
  void prepare(std::vector<Contact>& contacts, SolverBodies& bodies, const WorldDef& def,
               double dt);
  /// Baumgarte: the body in `slot` gets no push out of its overlaps this step (its joints are
  /// solved without bias too: world_step.cpp, splitStressedJoints). Cleared by prepare().
  void withholdPush(int slot);
  void warmStart();
  void solveVelocities();
  /// Bounces points that approached faster than the threshold, once, after the iterations.
  void applyRestitution(double threshold);
  /// Copies accumulated impulses back into the arbiters for the next step's warm start.
  void storeImpulses();
  /// One non-linear Gauss-Seidel pass on positions; returns true when every overlap is within
  /// a small multiple of the slop (then further passes are skipped).
  bool solvePositions(const WorldDef& def);
  size_t size() const { return constraints_.size(); }

 private:
  /// Friction rows of one contact, clamped to the cone of its current normal impulses.
  static void solveFriction(ContactConstraint& c, SolverBody& a, SolverBody& b);
  /// Both normal rows of a two-point manifold, rigid, aiming at the given normal velocities.
  static void solveNormalBlock(ContactConstraint& c, SolverBody& a, SolverBody& b, double target1,
                               double target2);
  SolverBodies* bodies_ = nullptr;  // this step's; entries may be added until the solve starts

  /// Whether the contact gets no push out of its overlap: it presses a crushed body
  /// (crushed_bodies.hpp), or touches a body whose push is withheld (withholdPush).
  bool getsNoPush(const Contact& contact, const SolverBodies& bodies) const;

  std::vector<ContactConstraint> constraints_;
  std::vector<ContactConstraintExtra> extras_;  // by constraint
  CrushedBodies crushed_;                       // this step (baumgarte)
  CrushedBodies::SlotMarks unpushed_;           // this step (withholdPush)
};

}  // namespace impulse2d
