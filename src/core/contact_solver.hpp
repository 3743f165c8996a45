// The contact part of the sequential-impulse solver: effective masses and biases computed once
// per step (pre-step), then Gauss-Seidel iterations over the points with accumulated impulses
// clamped (normal >= 0, friction inside the cone |t| <= mu * n).
#pragma once

#include "contact.hpp"
#include "feedback.hpp"
#include "solver_body.hpp"

#include <impulse2d/defs.hpp>

#include <vector>

namespace impulse2d {

struct ContactConstraintPoint {
  Vec2 rA = Vec2::Zero(), rB = Vec2::Zero();          // from each centre of mass to the point
  Vec2 localA = Vec2::Zero(), localB = Vec2::Zero();  // surface points, body frames, for NGS
  double normalImpulse = 0.0, tangentImpulse = 0.0;
  double normalMass = 0.0, tangentMass = 0.0;
  double targetVelocity = 0.0;    // the normal velocity the point must at least reach
  double approachVelocity = 0.0;  // normal velocity before solving, for restitution
  double separation = 0.0;
  // Soft step: the contact point fixed in each body (body frame, from the centre of mass), so
  // the separation can be followed through the sub-steps without a new narrow phase.
  Vec2 anchorA = Vec2::Zero(), anchorB = Vec2::Zero();
  double maxNormalImpulse = 0.0;  // largest of any sub-step: did the point push at all?
  double totalNormalImpulse = 0.0, totalTangentImpulse = 0.0;  // summed over the sub-steps
};

struct ContactConstraint {
  Contact* contact = nullptr;
  int a = -1, b = -1;  // entries in the step's SolverBodies
  Vec2 normal = Vec2::Zero();
  Vec2 localNormal = Vec2::Zero();  // in A's frame, for NGS
  double friction = 0.0, restitution = 0.0;
  int pointCount = 0;
  ContactConstraintPoint points[2];
  // Two-point manifolds whose points are not (nearly) redundant solve both normal impulses at
  // once; k is their 2x2 effective-mass matrix, used when `blockSolve` is set.
  bool blockSolve = false;
  double k11 = 0.0, k12 = 0.0, k22 = 0.0;
  Feedback soft;  // soft step: the contact spring (stiffer against static bodies)
};

class ContactSolver {
 public:
  /// Builds the constraints of the touching (or about to touch) contacts of bodies the step moves;
  /// adds read-only entries to `bodies` for the others they touch.
  void prepare(std::vector<Contact>& contacts, SolverBodies& bodies, const WorldDef& def,
               double dt);
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

  // --- sub-stepping solvers (contact_solver_substeps.cpp) ---
  /// After prepare(): sets the soft step's springs for sub-steps of h and turns the arbiters'
  /// whole-step impulses into one sub-step's warm start.
  void prepareSubsteps(const WorldDef& def, int substeps, double h);
  /// One iteration at the current poses; useBias: the soft step's push out of overlaps.
  void solveSubstep(double h, bool useBias, double maxPushVelocity);
  /// After each sub-step's relax pass: adds what the sub-step applied to the step's totals.
  void addSubstepImpulses();

 private:
  /// Friction rows of one contact, clamped to the cone of its current normal impulses.
  static void solveFriction(ContactConstraint& c, SolverBody& a, SolverBody& b);
  static void solveNormalBlock(ContactConstraint& c, SolverBody& a, SolverBody& b);
  static void solveSoftNormalBlock(ContactConstraint& c, SolverBody& a, SolverBody& b,
                                   const double bias[2], const Feedback fb[2]);

  int substeps_ = 0;                // 0: a one-pass solver (Baumgarte or NGS)
  SolverBodies* bodies_ = nullptr;  // this step's; entries may be added until the solve starts

  std::vector<ContactConstraint> constraints_;
};

}  // namespace impulse2d
