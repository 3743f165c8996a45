// The solver's working copy of the bodies for one step. Constraints reach their bodies through
// indices into one contiguous array of the few numbers an iteration needs, instead of through
// Body (about 300 bytes with its name, shapes and proxies), so a pass over the contacts touches
// one or two cache lines per body.
//
//   [ awake dynamic ... | awake kinematic ... | read-only: static or asleep, added on demand ]
//   0                   dynamicCount          movingCount                                  size
//
// Only the moving part is ever written back to the bodies, and only dynamic bodies take back a
// velocity: nothing the solver computes (not even a NaN from a non-finite impulse) can reach a
// static body, and a pile resting on a static ground never reads the ground's Body again.
#pragma once

#include <impulse2d/body.hpp>

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "weld_clusters.hpp"

namespace impulse2d {

/// What a velocity row reads and writes of a body: its velocities and masses. The joints' warm
/// start and velocity rows take only this, so the sub-stepping passes that read no pose copy no
/// pose (SubstepBodies::velocityView).
struct BodyVelocity {
  Vec2 linearVelocity = Vec2::Zero();  // m/s of the centre of mass
  double angularVelocity = 0.0;
  double invMass = 0.0, invInertia = 0.0;  // 0 for the read-only and kinematic entries
};

/// A body as a joint or contact row sees it: velocities, masses and pose.
struct SolverBody : BodyVelocity {
  Vec2 center = Vec2::Zero();  // centre of mass
  double angle = 0.0;
  Rot q;  // Rot(angle), to round-off (see turnBy)
  Vec2 localCenter = Vec2::Zero();
};

/// What integrating a dynamic body's velocity needs besides the SolverBody (read once a step),
/// and a kinematic body's prescribed velocity, which no impulse may change.
struct SolverBodyLoad {
  Vec2 force = Vec2::Zero();
  double torque = 0.0;
  double linearDamping = 0.0, angularDamping = 0.0;
  Vec2 linearVelocity = Vec2::Zero();
  double angularVelocity = 0.0;
};

/// A body as the solver sees it, velocity and masses included.
inline SolverBody solverView(const Body& body) {
  SolverBody e;
  e.linearVelocity = body.linearVelocity;
  e.angularVelocity = body.angularVelocity;
  e.invMass = body.invMass;
  e.invInertia = body.invInertia;
  e.center = body.center;
  e.angle = body.angle;
  e.q = body.xf.q;
  e.localCenter = body.localCenter;
  return e;
}

constexpr double kSmallTurn = 0.02;  // rad: below it rotationBy takes the series

/// Applies the impulse (px, py) between two bodies, plus the angular impulses; A takes the
/// reaction: vA -= mA p, wA -= iA angularA, vB += mB p, wB += iB angularB. Each coordinate is
/// written on its own, for rows computed in scalars (contact_solver.cpp, the joints): their
/// Vec2(px, py) was built on the stack from two stores and read back as one vector, which stalls
/// store forwarding; a velocity written so is read back as scalars.
inline void applyImpulse(BodyVelocity& a, BodyVelocity& b, double px, double py, double angularA,
                         double angularB) {
  a.linearVelocity.x() -= a.invMass * px;
  a.linearVelocity.y() -= a.invMass * py;
  a.angularVelocity -= a.invInertia * angularA;
  b.linearVelocity.x() += b.invMass * px;
  b.linearVelocity.y() += b.invMass * py;
  b.angularVelocity += b.invInertia * angularB;
}

/// The rotation by a small angle without calling sin and cos: their Taylor series to the seventh
/// power, whose next terms stay below round-off up to 0.02 rad (a sub-step of a body turning at
/// 10 rad/s); larger turns call them.
inline Rot rotationBy(double angle) {
  if (!(std::abs(angle) < kSmallTurn)) return Rot(angle);
  const double a2 = angle * angle;
  Rot r;
  r.c = 1.0 - a2 * (1.0 / 2.0 - a2 * (1.0 / 24.0 - a2 * (1.0 / 720.0)));
  r.s = angle * (1.0 - a2 * (1.0 / 6.0 - a2 * (1.0 / 120.0 - a2 * (1.0 / 5040.0))));
  return r;
}

/// Turns a body by a (usually small) angle. q follows angle to round-off within the step; the
/// poses written back take Rot(angle) afresh, so no error carries over.
inline void turnBy(SolverBody& body, double angle) {
  body.angle += angle;
  body.q = body.q * rotationBy(angle);
}

class SolverBodies {
 public:
  /// Starts a step: one entry for every living, awake, non-static body (dynamic first), in slot
  /// order, except that each welded cluster (weld_clusters.hpp) is one entry, its root's, which
  /// every member's slot maps to. Entries of other bodies are added by ensureEntryOf() as
  /// constraints need them.
  /// movableSlots: the living non-static bodies' slots, ascending (WorldImpl::movableSlots).
  void gather(const std::vector<Body>& bodies, const std::vector<int>& movableSlots,
              const WeldClusters& clusters);
  /// The entry of the body in `slot`, or -1 when the step does not move it.
  int movingEntryOf(int slot) const {
    return indexOfSlot_[slot] < movingCount_ ? indexOfSlot_[slot] : -1;
  }
  /// The entry of the body in `slot`, adding a read-only one (no velocity, infinite mass, its
  /// pose) for a body the step does not move.
  int ensureEntryOf(int slot);
  bool isDynamic(int entry) const { return entry < dynamicCount_; }
  /// Whether the step moves the body in `slot` as a dynamic body (awake).
  bool isActive(int slot) const { return indexOfSlot_[slot] < dynamicCount_; }
  /// The entry of the body in `slot` when the step moves it as a dynamic body, or -1.
  int dynamicEntryOf(int slot) const { return isActive(slot) ? indexOfSlot_[slot] : -1; }

  SolverBody& operator[](int entry) { return entries_[entry]; }
  const SolverBody& operator[](int entry) const { return entries_[entry]; }
  SolverBody* data() { return entries_.data(); }
  int dynamicCount() const { return dynamicCount_; }
  int movingCount() const { return movingCount_; }
  int slotOf(int entry) const { return slots_[entry]; }
  const SolverBodyLoad& load(int entry) const { return loads_[entry]; }

  /// A joint's view of the body in `slot` (see entryOf): its entry, except that a member of a
  /// cluster sees its cluster's entry from its own frame (MemberStart::viewLocalCenter).
  SolverBody view(int slot);
  /// Writes a view back: the velocity of a dynamic entry, and its pose when `pose`.
  void store(int slot, const SolverBody& view, bool pose);
  /// The welded clusters' members, by entry (ClusterRows::ofRow, member).
  const ClusterRows& clusterRows() const { return clusterRows_; }

  /// Gives the kinematic entries their prescribed velocities back: impulses cannot change them
  /// (infinite mass) unless they are not finite, and then they must not move the body.
  void holdKinematicVelocities();
  /// Writes the poses of the moving entries, and the velocities of the dynamic ones, back; the
  /// members of a cluster rigidly with it.
  void storeMotion(std::vector<Body>& bodies) const;

 private:
  void add(const Body& body, int slot, bool readOnly);
  void addCluster(const WeldClusters& clusters, int cluster);

  const std::vector<Body>* bodies_ = nullptr;
  std::vector<SolverBody> entries_;
  std::vector<SolverBodyLoad> loads_;  // by entry, for the dynamic ones
  std::vector<int> slots_;             // by entry
  static constexpr int kNone = std::numeric_limits<int>::max();
  std::vector<int> indexOfSlot_;  // by body slot; kNone when the body has no entry
  int dynamicCount_ = 0, movingCount_ = 0;
  ClusterRows clusterRows_;  // the welded clusters' members, by dynamic entry
};

}  // namespace impulse2d
