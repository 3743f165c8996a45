// Rigid welds make one rigid body. Bodies joined by rigid welds (frequency 0), dynamic and awake,
// form a cluster that the solvers move as one body: one row, with the members' summed mass,
// inertia about the common centre of mass, momentum and loads. Each member keeps its pose
// relative to the cluster exactly, so a welded assembly never opens, whatever hits it.
//
//     a o========[ b ]          three bodies, two welds:   one row   (M, I about c, v, w)
//               //                                          members   a, b, c at fixed offsets
//          c  ( )                                                     from the centre of mass
//
// As sequential joints, welds with long arms and large mass ratios (a 0.8 g circle welded 5 m
// from a 0.8 kg box) traded errors until the soft step threw the light body 456 km and the
// one-pass solvers carried the loop through the ground (issue 26). Contacts and joints between
// two members of one cluster have nothing to do and are left out of the step.
#pragma once

#include <impulse2d/body.hpp>

#include <utility>
#include <vector>

namespace impulse2d {

struct Joint;  // joint.hpp, which includes solver_body.hpp, which needs this header

/// A cluster's rigid body at the start of a step.
struct RigidCluster {
  double mass = 0.0, inertia = 0.0;  // kg, kg m^2 about `center`
  Vec2 center = Vec2::Zero();        // common centre of mass
  Vec2 velocity = Vec2::Zero();      // of the centre: total momentum / mass
  double angularVelocity = 0.0;      // angular momentum about the centre / inertia
  Vec2 force = Vec2::Zero();         // N, the members' forces
  double torque = 0.0;               // N m about the centre
  double linearDamping = 0.0;        // 1/s, mass-weighted
  double angularDamping = 0.0;       // 1/s, inertia-weighted
};

/// A member of a cluster where the step began: it has no solver row of its own, and moves
/// rigidly with its cluster's, whose frame starts at the common centre of mass with angle 0.
struct MemberStart {
  int slot = -1;
  Vec2 offset = Vec2::Zero();  // its centre of mass from the cluster's, world axes
  double angle0 = 0.0;
  Rot q0;
  // The local centre that a joint's view of the member uses, so that the joint measures its arms
  // from the cluster's centre of mass: q (localAnchor - viewLocalCenter) = anchor - cluster
  // centre, at any turn of the cluster.
  Vec2 viewLocalCenter = Vec2::Zero();
};

/// The start of the member in `slot` of a cluster whose centre of mass is `center`.
inline MemberStart memberStart(const Body& body, int slot, const Vec2& center) {
  MemberStart m;
  m.slot = slot;
  m.offset = body.center - center;
  m.angle0 = body.angle;
  m.q0 = body.xf.q;
  m.viewLocalCenter = body.localCenter - body.xf.q.applyInverse(m.offset);
  return m;
}

/// Whether a joint welds its bodies rigidly (the kind a cluster merges).
bool isRigidWeld(const Joint& joint);

class WeldClusters {
 public:
  /// Finds this step's clusters: awake dynamic bodies joined by rigid welds. Costs nothing when
  /// the world has no rigid weld (`rigidWelds`, its count), one pass over the joints when none
  /// joins two such bodies; else passes over the movable slots (WorldImpl::movableSlots,
  /// ascending: static bodies are never members).
  void find(const std::vector<Body>& bodies, const std::vector<int>& movableSlots,
            const std::vector<Joint>& joints, const std::vector<char>& jointAlive, int rigidWelds);
  bool any() const { return !roots_.empty(); }
  int count() const { return static_cast<int>(roots_.size()); }
  /// The cluster of the body in `slot`, or -1 when it moves alone.
  int clusterOf(int slot) const { return any() ? clusterOfSlot_[slot] : -1; }
  /// Whether both bodies are members of one cluster.
  bool joins(int slotA, int slotB) const {
    const int c = clusterOf(slotA);
    return c >= 0 && c == clusterOf(slotB);
  }
  /// The cluster's lowest slot: the body whose solver row stands for the cluster.
  int root(int cluster) const { return roots_[cluster]; }
  /// The members' slots, in slot order, root first.
  const int* membersBegin(int cluster) const { return members_.data() + first_[cluster]; }
  const int* membersEnd(int cluster) const { return members_.data() + first_[cluster + 1]; }
  /// The cluster as one rigid body, from its members now.
  RigidCluster combine(int cluster, const std::vector<Body>& bodies) const;

 private:
  int findRoot(int slot);
  std::vector<int> parent_;         // union-find over body slots, this step
  std::vector<int> clusterOfSlot_;  // by body slot
  std::vector<int> roots_;          // by cluster
  std::vector<int> first_;          // by cluster, into members_ (one past the last at the end)
  std::vector<int> members_;
};

/// Where a step's solver rows put the welded clusters' members: shared by the one-pass solvers'
/// SolverBodies and the sub-stepping solvers' SubstepBodies, which both give each cluster one
/// row (its root's) that every member's slot maps to. Empty when there are no clusters.
class ClusterRows {
 public:
  /// Starts a step for `slots` bodies and `rows` solver rows.
  void reset(const WeldClusters& clusters, size_t slots, size_t rows) {
    members_.clear();
    first_.assign(1, 0);
    memberOfSlot_.clear();
    clusterOfRow_.clear();
    if (!clusters.any()) return;
    memberOfSlot_.assign(slots, -1);
    clusterOfRow_.assign(rows, -1);
  }
  /// Records the members of `cluster`, whose centre of mass is `center`, as moving with `row`,
  /// and points their slots in `rowOfSlot` at it.
  void add(const WeldClusters& clusters, int cluster, const std::vector<Body>& bodies,
           const Vec2& center, int row, std::vector<int>& rowOfSlot) {
    clusterOfRow_[static_cast<size_t>(row)] = static_cast<int>(first_.size()) - 1;
    for (const int* m = clusters.membersBegin(cluster); m != clusters.membersEnd(cluster); ++m) {
      memberOfSlot_[static_cast<size_t>(*m)] = static_cast<int>(members_.size());
      rowOfSlot[static_cast<size_t>(*m)] = row;
      members_.push_back(memberStart(bodies[static_cast<size_t>(*m)], *m, center));
    }
    first_.push_back(static_cast<int>(members_.size()));
  }
  /// The member in `slot`, or null for a body alone.
  const MemberStart* ofSlot(int slot) const {
    if (memberOfSlot_.empty() || memberOfSlot_[static_cast<size_t>(slot)] < 0) return nullptr;
    return &members_[static_cast<size_t>(memberOfSlot_[static_cast<size_t>(slot)])];
  }
  /// The members moving with `row` ([first, last) of member()), or an empty range.
  std::pair<int, int> ofRow(int row) const {
    if (clusterOfRow_.empty() || row >= static_cast<int>(clusterOfRow_.size())) return {0, 0};
    const int c = clusterOfRow_[static_cast<size_t>(row)];
    return c < 0 ? std::pair<int, int>(0, 0) : std::pair<int, int>(first_[c], first_[c + 1]);
  }
  const MemberStart& member(int index) const { return members_[static_cast<size_t>(index)]; }

 private:
  std::vector<MemberStart> members_;
  std::vector<int> first_;  // by cluster recorded, into members_ (one past the last at the end)
  std::vector<int> memberOfSlot_;  // by body slot, into members_, or -1
  std::vector<int> clusterOfRow_;  // by row, or -1
};

/// The bodies rigidly welded to the body in `slot` (dynamic bodies joined by rigid welds,
/// asleep or awake), itself included, in slot order: what World moves as one when a user
/// teleports or sets the velocity of one of them.
std::vector<int> rigidlyWeldedTo(int slot, const std::vector<Body>& bodies,
                                 const std::vector<Joint>& joints,
                                 const std::vector<std::vector<int>>& jointsOfBody);

}  // namespace impulse2d
