// The sub-stepping solvers' bodies. Everything a contact row reads and writes of a body sits in
// one 64-byte BodyState, kept as the motion since the step began rather than as a pose:
//
//   [ vx vy w | turned | dx dy | qc qs ]    velocity, angle turned, centre moved, rotation turned
//
// so a body the step does not move (static, asleep) is the identity state, shared by all of them
// in one read-only row, and a contact needs no pose of it. The rows are laid out
//
//   [ awake dynamic ... | awake kinematic ... | identity | one sink per worker ]
//   0                   dynamicCount          movingCount
//
// A constraint writes a body back only when it is dynamic; the lanes of other bodies write into
// their worker's sink, which nothing reads, so no two threads ever write one line.
#pragma once

#include <impulse2d/body.hpp>

#include <cstdint>
#include <utility>
#include <vector>

#include "body_load.hpp"
#include "motion_limits.hpp"
#include "solver_body.hpp"
#include "step_workers.hpp"
#include "weld_clusters.hpp"

namespace impulse2d {

struct alignas(64) BodyState {
  double vx = 0.0, vy = 0.0, w = 0.0;  // m/s of the centre of mass, rad/s
  double turned = 0.0;                 // rad since the step began (continuous)
  double dx = 0.0, dy = 0.0;           // m the centre of mass moved since the step began
  double qc = 1.0, qs = 0.0;           // Rot(turned), to round-off
};
static_assert(sizeof(BodyState) == 64, "one cache line per body");

/// Field offsets of BodyState in doubles, for gathers.
enum BodyStateField : int64_t { kVx = 0, kVy, kW, kTurned, kDx, kDy, kQc, kQs, kStateDoubles };

/// What contacts read of a moving body as the step begins (fill: 32 bytes a body).
struct BodySim {
  Vec2 center0 = Vec2::Zero();  // centre of mass when the step began
  double invMass = 0.0, invInertia = 0.0;
};

/// The rest, read once or twice a step: where the body began, and a kinematic body's velocity.
struct BodyStart {
  int slot = -1;
  double angle0 = 0.0;
  Rot q0;
  Vec2 localCenter = Vec2::Zero();
  Vec2 kinematicVelocity = Vec2::Zero();
  double kinematicAngularVelocity = 0.0;
};

class SubstepBodies {
 public:
  /// Starts a step of sub-steps of h: a row for every awake body of `movableSlots` (the living
  /// non-static ones, ascending; dynamic first, in slot order), then the identity row and
  /// `workers` sinks.
  /// Dynamic bodies move within `limits` (motion_limits.hpp). A body whose velocity or load is
  /// not finite is held still with infinite mass instead, and listed in overflowed().
  /// Each welded cluster gets one row, its root's, which every member's slot reads and writes.
  void gather(const std::vector<Body>& bodies, const std::vector<int>& movableSlots,
              const Vec2& gravity, double h, const MotionLimits& limits,
              const WeldClusters& clusters, StepWorkers& workers);
  const std::vector<int>& overflowed() const { return overflowed_; }
  /// The dynamic bodies' own turn-rate limits (empty after gather; WorldImpl fills them).
  TurnCaps& turnCaps() { return turnCaps_; }
  /// An entry's centre of mass as the step began.
  const Vec2& center0(int entry) const { return sims_[entry].center0; }

  /// The row a constraint reads for the body in `slot` (the identity row when it is not moving).
  int64_t readRow(int slot) const {
    const int entry = entryOfSlot_[slot];
    return entry < 0 ? identityRow() : entry;
  }
  /// The row it writes, or -1 (write into the worker's sink) when the body is not dynamic.
  int64_t writeRow(int slot) const {
    const int entry = entryOfSlot_[slot];
    return entry >= 0 && entry < dynamicCount_ ? entry : -1;
  }
  /// The moving entry of the body in `slot`, or -1.
  int entryOf(int slot) const { return entryOfSlot_[slot]; }
  /// Asks for what a joint's view of the body in `slot` reads (view(), or velocityView() when
  /// not `poses`), ahead of the view; a hint only.
  void prefetchView(int slot, bool poses) const {
    const int entry = entryOfSlot_[slot];
    if (entry < 0) return;
    __builtin_prefetch(&states_[entry]);
    __builtin_prefetch(&sims_[entry]);
    if (!poses) return;
    const char* start = reinterpret_cast<const char*>(&starts_[entry]);
    __builtin_prefetch(start);
    __builtin_prefetch(start + sizeof(BodyStart) - 1);  // it may straddle two lines
  }
  bool isDynamicEntry(int entry) const { return entry >= 0 && entry < dynamicCount_; }
  /// Whether the body in `slot` is dynamic and awake: the step moves it by impulses.
  bool isDynamicSlot(int slot) const { return isDynamicEntry(entryOfSlot_[slot]); }
  /// The entry of the body in `slot` when it is dynamic and awake, or -1.
  int dynamicEntryOf(int slot) const { return isDynamicSlot(slot) ? entryOfSlot_[slot] : -1; }

  int dynamicCount() const { return dynamicCount_; }
  int movingCount() const { return movingCount_; }
  int64_t identityRow() const { return movingCount_; }
  int64_t sinkRow(int worker) const { return movingCount_ + 1 + worker; }
  BodyState* states() { return states_.data(); }
  const BodyState* states() const { return states_.data(); }
  BodyState& state(int entry) { return states_[entry]; }
  const BodySim& sim(int entry) const { return sims_[entry]; }
  const BodyStart& start(int entry) const { return starts_[entry]; }

  /// Gravity, forces and damping over one sub-step, for the entries [begin, end).
  void integrateVelocities(int begin, int end);
  /// Moves the entries [begin, end) with their velocities over h (kinematic ones at their
  /// prescribed velocities, whatever an impulse did).
  void integratePositions(int begin, int end, double h);

  /// A joint's scalar view of a body: its pose now, velocities and masses. Bodies that do not
  /// move this step read as static (no velocity, infinite mass).
  SolverBody view(int slot) const;
  /// Only the velocities and masses, for the passes that read no pose (v3_joint_grid spent a
  /// fifth of its joint passes on poses, and a tenth more on copying views with unread poses).
  BodyVelocity velocityView(int slot) const;
  /// Where view(slot) began the step: view() is this moved by the row's motion since (centre
  /// moved by (dx, dy), angle and rotation turned), unless the body does not move this step.
  struct ViewStart {
    Vec2 center0;
    double angle0;
    Rot q0;
    Vec2 localCenter;
    bool moves;
  };
  ViewStart viewStart(int slot) const;
  /// view(slot).angle alone.
  double viewAngle(int slot) const {
    const ViewStart start = viewStart(slot);
    return start.moves ? start.angle0 + states_[entryOfSlot_[slot]].turned : start.angle0;
  }
  /// Writes back what a joint's velocity rows changed, to a dynamic entry.
  void store(int slot, const BodyVelocity& view);
  /// Writes back what a joint changed: velocities of a dynamic entry, and its pose when
  /// `pose` (position passes).
  void store(int slot, const SolverBody& view, bool pose);

  /// The welded clusters' members, by entry (ClusterRows::ofRow, member).
  const ClusterRows& clusterRows() const { return clusterRows_; }

  /// Writes the moved poses and (dynamic) velocities, within the limits, of the entries [begin,
  /// end) back to the bodies.
  void finish(std::vector<Body>& bodies, int begin, int end) const;

 private:
  static constexpr int kSlotsPerBlock = 1024;  // movable slots per block of gather's stages
  /// Fills the entry's rows; false for a body held still (see gather()).
  bool add(const Body& body, int slot, int entry, const Vec2& gravity, double h);
  /// Fills a cluster's row (its root's entry) and its members' starts.
  void addCluster(const WeldClusters& clusters, int cluster, const Vec2& gravity, double h);
  /// A member's pose and velocity from its cluster's row.
  void finishMember(std::vector<Body>& bodies, int entry, const MemberStart& m) const;

  const std::vector<Body>* bodies_ = nullptr;
  std::vector<BodyState> states_;
  std::vector<BodySim> sims_;
  std::vector<BodyLoad> loads_;  // dynamic entries only
  std::vector<BodyStart> starts_;
  std::vector<int> entryOfSlot_;  // -1 when the body has no row
  std::vector<int> blockFirst_;   // gather(): each block's first dynamic and kinematic row
  std::vector<std::vector<int>> overflowedOfBlock_;
  std::vector<int> overflowed_;  // slots, in slot order
  int dynamicCount_ = 0, movingCount_ = 0;
  MotionLimits limits_;
  TurnCaps turnCaps_;
  ClusterRows clusterRows_;  // the welded clusters' members, by entry
};

// Inline: the joint passes call these twice per joint visit. The views copy each pair of
// doubles as one 16-byte vector: the joints' rows read a view's Vec2 so, and a Vec2 stored as two
// scalars and read back at once as one vector stalls the processor's store forwarding (`perf` put
// a fifth of the joints' warm start on that first load).
inline SolverBody SubstepBodies::view(int slot) const {
  const int entry = entryOfSlot_[slot];
  if (entry < 0) {
    SolverBody e = solverView((*bodies_)[slot]);
    e.linearVelocity.setZero();
    e.angularVelocity = e.invMass = e.invInertia = 0.0;
    return e;
  }
  const BodyState& s = states_[entry];
  const ViewStart start = viewStart(slot);
  SolverBody e;
  static_cast<BodyVelocity&>(e) = velocityView(slot);
  e.center = start.center0 + Eigen::Map<const Vec2>(&s.dx);
  e.angle = start.angle0 + s.turned;
  e.q = start.q0 * Rot::fromCosSin(s.qc, s.qs);
  e.localCenter = start.localCenter;
  return e;
}

inline SubstepBodies::ViewStart SubstepBodies::viewStart(int slot) const {
  const int entry = entryOfSlot_[slot];
  if (entry < 0) {
    const Body& body = (*bodies_)[slot];
    return {body.center, body.angle, body.xf.q, body.localCenter, false};
  }
  const BodyStart& start = starts_[entry];
  if (const MemberStart* m = clusterRows_.ofSlot(slot)) {  // its cluster, seen from it
    return {sims_[entry].center0, m->angle0, m->q0, m->viewLocalCenter, true};
  }
  return {sims_[entry].center0, start.angle0, start.q0, start.localCenter, true};
}

inline BodyVelocity SubstepBodies::velocityView(int slot) const {
  BodyVelocity e;  // a body that does not move this step: no velocity, infinite mass
  const int entry = entryOfSlot_[slot];
  if (entry < 0) return e;
  const BodyState& s = states_[entry];
  const BodySim& sim = sims_[entry];
  e.linearVelocity = Eigen::Map<const Vec2>(&s.vx);
  e.angularVelocity = s.w;
  e.invMass = sim.invMass;
  e.invInertia = sim.invInertia;
  return e;
}

inline void SubstepBodies::store(int slot, const BodyVelocity& view) {
  const int entry = entryOfSlot_[slot];
  if (entry < 0 || entry >= dynamicCount_) return;
  BodyState& s = states_[entry];
  s.vx = view.linearVelocity.x();
  s.vy = view.linearVelocity.y();
  s.w = view.angularVelocity;
}

inline void SubstepBodies::store(int slot, const SolverBody& view, bool pose) {
  store(slot, static_cast<const BodyVelocity&>(view));
  const int entry = entryOfSlot_[slot];
  if (!pose || entry < 0 || entry >= dynamicCount_) return;
  BodyState& s = states_[entry];
  const BodySim& sim = sims_[entry];
  double angle0 = starts_[entry].angle0;
  Rot q0 = starts_[entry].q0;
  if (const MemberStart* m = clusterRows_.ofSlot(slot)) {
    angle0 = m->angle0;
    q0 = m->q0;
  }
  s.dx = view.center.x() - sim.center0.x();
  s.dy = view.center.y() - sim.center0.y();
  s.turned = view.angle - angle0;
  const Rot q = q0.inverseTimes(view.q);
  s.qc = q.c;
  s.qs = q.s;
}

}  // namespace impulse2d
