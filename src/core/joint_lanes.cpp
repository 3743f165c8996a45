// Laying the sub-stepping solver's revolute joints into SIMD lanes (joint_lanes.hpp).
#include "joint_lanes.hpp"

namespace impulse2d {
namespace {

void setBody(const SubstepBodies& bodies, int slot, const Vec2& localAnchor, int32_t& offset,
             double& invMass, double& invInertia, double& q0c, double& q0s, double& turns,
             double& angle0, double& anchorX, double& anchorY, double& center0X, double& center0Y) {
  const int64_t read = bodies.readRow(slot) * kStateDoubles;
  offset = bodies.writeRow(slot) >= 0 ? static_cast<int32_t>(read) : ~static_cast<int32_t>(read);
  const BodyVelocity v = bodies.velocityView(slot);
  invMass = v.invMass;
  invInertia = v.invInertia;
  const SubstepBodies::ViewStart start = bodies.viewStart(slot);
  q0c = start.q0.c;
  q0s = start.q0.s;
  turns = start.moves ? 1.0 : 0.0;
  angle0 = start.angle0;
  center0X = start.center0.x();
  center0Y = start.center0.y();
  const Vec2 anchor = localAnchor - start.localCenter;  // as anchorGap (joint_revolute.cpp)
  anchorX = anchor.x();
  anchorY = anchor.y();
}

void setEmptyLane(JointBundle& j, int lane, int32_t identityOffset) {
  j.offsetA[lane] = j.offsetB[lane] = ~identityOffset;
  j.joint[lane] = -1;
  j.invMassA[lane] = j.invInertiaA[lane] = j.invMassB[lane] = j.invInertiaB[lane] = 0.0;
  j.q0cA[lane] = j.q0cB[lane] = 1.0;
  j.q0sA[lane] = j.q0sB[lane] = j.turnsA[lane] = j.turnsB[lane] = 0.0;
  j.anchorAx[lane] = j.anchorAy[lane] = j.anchorBx[lane] = j.anchorBy[lane] = 0.0;
  j.rAx[lane] = j.rAy[lane] = j.rBx[lane] = j.rBy[lane] = 0.0;
  j.mass00[lane] = j.mass01[lane] = j.mass11[lane] = 0.0;
  j.impulseX[lane] = j.impulseY[lane] = 0.0;
  j.hasMotor[lane] = j.hasLimit[lane] = j.motorSpeed[lane] = j.maxMotorImpulse[lane] = 0.0;
  j.lower[lane] = j.upper[lane] = j.referenceAngle[lane] = j.angle0A[lane] = j.angle0B[lane] = 0.0;
  j.axialMass[lane] = j.lowerBias[lane] = j.upperBias[lane] = 0.0;
  j.motorImpulse[lane] = j.lowerImpulse[lane] = j.upperImpulse[lane] = 0.0;
  j.center0Ax[lane] = j.center0Ay[lane] = j.center0Bx[lane] = j.center0By[lane] = 0.0;
}

}  // namespace

bool JointLanes::fits(const Joint& joint) { return joint.params.type == JointType::Revolute; }

void JointLanes::layOut(const std::vector<Joint>& joints, const std::vector<int>& colorStart,
                        int colors) {
  bundles_.clear();
  bundleStart_.assign(1, 0);
  scalarJoints_.resize(static_cast<size_t>(colors));
  overflowLanes_.clear();
  for (int color = 0; color <= colors; ++color) {  // the overflow last
    const bool overflow = color == colors;
    int lane = kJointLanes;  // the last bundle is full: the next lane opens one
    if (!overflow) scalarJoints_[static_cast<size_t>(color)].clear();
    for (int k = colorStart[color]; k < colorStart[color + 1]; ++k) {
      const bool lanes = fits(joints[static_cast<size_t>(k)]);
      int place = -1;
      if (lanes) {
        if (lane == kJointLanes) {
          bundles_.emplace_back();
          lane = 0;
        }
        JointBundle& j = bundles_.back();
        j.joint[lane] = k;
        j.laneCount = lane + 1;
        place = static_cast<int>(bundles_.size() - 1) * kJointLanes + lane++;
      }
      if (overflow) {
        overflowLanes_.push_back(place);
      } else if (!lanes) {
        scalarJoints_[static_cast<size_t>(color)].push_back(k);
      }
    }
    bundleStart_.push_back(static_cast<int>(bundles_.size()));
  }
  // The overflow's lanes follow one another: a run ends only at a joint that takes none.
  overflowRuns_.assign(overflowLanes_.size(), 0);
  for (size_t i = overflowLanes_.size(); i-- > 0;) {
    if (overflowLanes_[i] < 0) continue;
    overflowRuns_[i] = i + 1 < overflowLanes_.size() ? overflowRuns_[i + 1] + 1 : 1;
  }
}

void JointLanes::prefetchBodiesAhead(int k, int lane, int end, const std::vector<Joint>& joints,
                                     const SubstepBodies& bodies) const {
  // A colour's joints share no body, so each lane's two bodies are anywhere in the rows: each
  // lane waited on memory for them (v3_joint_grid: a tenth of its step filling and writing back).
  constexpr int kLanesAhead = 4;
  lane += kLanesAhead;
  const int used = bundles_[static_cast<size_t>(k)].laneCount;
  if (lane >= used) {  // on into the next bundle, whose lanes count from 0
    lane -= used;
    if (++k >= end) return;
  }
  const JointBundle& j = bundles_[static_cast<size_t>(k)];
  if (lane >= j.laneCount) return;
  const Joint& joint = joints[static_cast<size_t>(j.joint[lane])];
  bodies.prefetchView(joint.bodyA, true);
  bodies.prefetchView(joint.bodyB, true);
}

void JointLanes::fill(int begin, int end, std::vector<Joint>& joints, const SubstepBodies& bodies,
                      double h) {
  const int32_t identityOffset = static_cast<int32_t>(bodies.identityRow() * kStateDoubles);
  for (int k = begin; k < end; ++k) {
    JointBundle& j = bundles_[static_cast<size_t>(k)];
    j.anyMotor = j.anyLimit = false;
    j.scalarLanes = 0;
    for (int lane = 0; lane < j.laneCount; ++lane) {
      prefetchBodiesAhead(k, lane, end, joints, bodies);
      fillLane(joints[static_cast<size_t>(j.joint[lane])], j, lane, bodies, h);
    }
    for (int lane = j.laneCount; lane < kJointLanes; ++lane) setEmptyLane(j, lane, identityOffset);
  }
}

void JointLanes::fillLane(Joint& joint, JointBundle& j, int lane, const SubstepBodies& bodies,
                          double h) {
  const JointParams& params = joint.params;
  // What the scalar prepare sets, every pass, for a joint without a motor or limits.
  if (!params.enableMotor) joint.motorImpulse = 0.0;
  if (!params.enableLimit) joint.lowerImpulse = joint.upperImpulse = 0.0;
  setBody(bodies, joint.bodyA, joint.localAnchorA, j.offsetA[lane], j.invMassA[lane],
          j.invInertiaA[lane], j.q0cA[lane], j.q0sA[lane], j.turnsA[lane], j.angle0A[lane],
          j.anchorAx[lane], j.anchorAy[lane], j.center0Ax[lane], j.center0Ay[lane]);
  setBody(bodies, joint.bodyB, joint.localAnchorB, j.offsetB[lane], j.invMassB[lane],
          j.invInertiaB[lane], j.q0cB[lane], j.q0sB[lane], j.turnsB[lane], j.angle0B[lane],
          j.anchorBx[lane], j.anchorBy[lane], j.center0Bx[lane], j.center0By[lane]);
  j.hasMotor[lane] = params.enableMotor ? 1.0 : 0.0;
  j.hasLimit[lane] = params.enableLimit ? 1.0 : 0.0;
  j.anyMotor = j.anyMotor || params.enableMotor;
  j.anyLimit = j.anyLimit || params.enableLimit;
  j.motorSpeed[lane] = params.motorSpeed;
  j.maxMotorImpulse[lane] = params.maxMotorTorque * h;  // as solveRevoluteVelocity
  j.lower[lane] = params.lower;
  j.upper[lane] = params.upper;
  j.referenceAngle[lane] = joint.referenceAngle;
  const double inertiaSum = j.invInertiaA[lane] + j.invInertiaB[lane];  // as prepareRevolute
  j.axialMass[lane] = inertiaSum > 0.0 ? 1.0 / inertiaSum : 0.0;
  j.lowerBias[lane] = j.upperBias[lane] = 0.0;
  fromJoint(joint, j, lane);
}

void JointLanes::toJoint(const JointBundle& j, int lane, Joint& joint) {
  joint.rA.x() = j.rAx[lane];
  joint.rA.y() = j.rAy[lane];
  joint.rB.x() = j.rBx[lane];
  joint.rB.y() = j.rBy[lane];
  joint.pairMass << j.mass00[lane], j.mass01[lane], j.mass01[lane], j.mass11[lane];
  joint.pairImpulse.x() = j.impulseX[lane];
  joint.pairImpulse.y() = j.impulseY[lane];
  joint.motorImpulse = j.motorImpulse[lane];
  joint.lowerImpulse = j.lowerImpulse[lane];
  joint.upperImpulse = j.upperImpulse[lane];
}

void JointLanes::fromJoint(const Joint& joint, JointBundle& j, int lane) {
  j.rAx[lane] = joint.rA.x();
  j.rAy[lane] = joint.rA.y();
  j.rBx[lane] = joint.rB.x();
  j.rBy[lane] = joint.rB.y();
  j.mass00[lane] = joint.pairMass(0, 0);
  j.mass01[lane] = joint.pairMass(0, 1);
  j.mass11[lane] = joint.pairMass(1, 1);
  j.impulseX[lane] = joint.pairImpulse.x();
  j.impulseY[lane] = joint.pairImpulse.y();
  j.motorImpulse[lane] = joint.motorImpulse;
  j.lowerImpulse[lane] = joint.lowerImpulse;
  j.upperImpulse[lane] = joint.upperImpulse;
}

void JointLanes::writeBack(int begin, int end, std::vector<Joint>& joints,
                           const SubstepBodies& bodies) const {
  for (int k = begin; k < end; ++k) {
    const JointBundle& j = bundles_[static_cast<size_t>(k)];
    for (int lane = 0; lane < j.laneCount; ++lane) {
      prefetchBodiesAhead(k, lane, end, joints, bodies);
      Joint& joint = joints[static_cast<size_t>(j.joint[lane])];
      toJoint(j, lane, joint);
      // The rest of what prepareRevolute set in the last relax pass (rigid feedback).
      joint.feedback = Feedback();
      joint.axialMass = j.axialMass[lane];
      joint.angle =
          bodies.viewAngle(joint.bodyB) - bodies.viewAngle(joint.bodyA) - joint.referenceAngle;
      joint.pairBias.x() = joint.pairBias.y() = 0.0;
      if (joint.params.enableLimit) {
        joint.lowerBias = j.lowerBias[lane];
        joint.upperBias = j.upperBias[lane];
        joint.lowerFeedback = joint.upperFeedback = Feedback();
      }
    }
  }
}

}  // namespace impulse2d
