#include "weld_clusters.hpp"

#include <algorithm>
#include <cmath>

#include "joint.hpp"

namespace impulse2d {
namespace {

bool mergeable(const Body& body) { return body.type == BodyType::Dynamic && body.awake; }

// A weld opened further than this (m at the anchor, rad) is solved as a joint until it closes:
// a cluster keeps its members' poses as it finds them, and would hold the error for ever.
constexpr double kMaxClusterGap = 0.02;
constexpr double kMaxClusterTurn = 0.02;

bool closed(const Joint& joint, const Body& a, const Body& b) {
  const Vec2 gap = b.xf.apply(joint.localAnchorB) - a.xf.apply(joint.localAnchorA);
  const double turn = b.angle - a.angle - joint.referenceAngle;
  return gap.squaredNorm() <= kMaxClusterGap * kMaxClusterGap && std::abs(turn) <= kMaxClusterTurn;
}

bool merges(const Joint& joint, const std::vector<Body>& bodies) {
  const Body& a = bodies[joint.bodyA];
  const Body& b = bodies[joint.bodyB];
  return isRigidWeld(joint) && mergeable(a) && mergeable(b) && closed(joint, a, b);
}

}  // namespace

bool isRigidWeld(const Joint& joint) {
  return joint.params.type == JointType::Weld && joint.params.frequency <= 0.0;
}

int WeldClusters::findRoot(int slot) {
  while (parent_[slot] != slot) slot = parent_[slot] = parent_[parent_[slot]];
  return slot;
}

void WeldClusters::find(const std::vector<Body>& bodies, const std::vector<int>& movableSlots,
                        const std::vector<Joint>& joints, const std::vector<char>& jointAlive,
                        int rigidWelds) {
  roots_.clear();
  first_.clear();
  members_.clear();
  bool anyWeld = false;
  for (size_t j = 0; rigidWelds > 0 && j < joints.size() && !anyWeld; ++j) {
    const Joint& joint = joints[j];
    anyWeld = jointAlive[j] && merges(joint, bodies);
  }
  if (!anyWeld) return;

  // Only awake dynamic bodies merge (mergeable), so only movable slots take part.
  parent_.resize(bodies.size());
  for (const int i : movableSlots) parent_[i] = i;
  for (size_t j = 0; j < joints.size(); ++j) {
    const Joint& joint = joints[j];
    if (!jointAlive[j] || !merges(joint, bodies)) continue;
    const int a = findRoot(joint.bodyA), b = findRoot(joint.bodyB);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);  // the lowest slot stays the root
  }
  // Number the clusters by their roots (the lowest slot), in slot order; then list the members.
  clusterOfSlot_.assign(bodies.size(), -1);
  std::vector<int> size;
  for (const int i : movableSlots) {
    if (parent_[i] == i) continue;
    const int root = findRoot(i);
    if (clusterOfSlot_[root] < 0) {
      clusterOfSlot_[root] = static_cast<int>(roots_.size());
      roots_.push_back(root);
      size.push_back(1);
    }
    clusterOfSlot_[i] = clusterOfSlot_[root];
    ++size[clusterOfSlot_[root]];
  }
  first_.assign(roots_.size() + 1, 0);
  for (size_t c = 0; c < roots_.size(); ++c) first_[c + 1] = first_[c] + size[c];
  members_.resize(static_cast<size_t>(first_.back()));
  std::vector<int> next(first_.begin(), first_.end() - 1);
  for (const int i : movableSlots) {
    if (clusterOfSlot_[i] >= 0) members_[next[clusterOfSlot_[i]]++] = i;
  }
}

RigidCluster WeldClusters::combine(int cluster, const std::vector<Body>& bodies) const {
  RigidCluster r;
  Vec2 weighted = Vec2::Zero(), momentum = Vec2::Zero();
  for (const int* m = membersBegin(cluster); m != membersEnd(cluster); ++m) {
    const Body& b = bodies[*m];
    r.mass += b.mass;
    weighted += b.mass * b.center;
    momentum += b.mass * b.linearVelocity;
    r.force += b.force;
    r.linearDamping += b.mass * b.linearDamping;
  }
  r.center = weighted / r.mass;
  r.velocity = momentum / r.mass;
  r.linearDamping /= r.mass;
  double angularMomentum = 0.0, angularDampingSum = 0.0;
  for (const int* m = membersBegin(cluster); m != membersEnd(cluster); ++m) {
    const Body& b = bodies[*m];
    const Vec2 arm = b.center - r.center;
    r.inertia += b.inertia + b.mass * arm.squaredNorm();
    angularMomentum += b.inertia * b.angularVelocity + b.mass * cross(arm, b.linearVelocity);
    r.torque += b.torque + cross(arm, b.force);
    angularDampingSum += b.inertia * b.angularDamping;
  }
  r.angularVelocity = angularMomentum / r.inertia;
  double inertiaSum = 0.0;
  for (const int* m = membersBegin(cluster); m != membersEnd(cluster); ++m) {
    inertiaSum += bodies[*m].inertia;
  }
  r.angularDamping = angularDampingSum / inertiaSum;
  return r;
}

std::vector<int> rigidlyWeldedTo(int slot, const std::vector<Body>& bodies,
                                 const std::vector<Joint>& joints,
                                 const std::vector<std::vector<int>>& jointsOfBody) {
  std::vector<int> group{slot};
  if (bodies[slot].type != BodyType::Dynamic) return group;
  for (size_t k = 0; k < group.size(); ++k) {
    for (const int j : jointsOfBody[group[k]]) {
      const Joint& joint = joints[j];
      if (!isRigidWeld(joint)) continue;
      const int other = joint.bodyA == group[k] ? joint.bodyB : joint.bodyA;
      if (bodies[other].type != BodyType::Dynamic) continue;
      if (std::find(group.begin(), group.end(), other) == group.end()) group.push_back(other);
    }
  }
  std::sort(group.begin(), group.end());
  return group;
}

}  // namespace impulse2d
