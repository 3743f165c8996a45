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

int JointLanes::addLane(Joint& joint, int k, const SubstepBodies& bodies, double h, int& lane) {
  if (lane == kJointLanes) {
    bundles_.emplace_back();
    bundles_.back().laneCount = 0;
    bundles_.back().anyMotor = bundles_.back().anyLimit = false;
    bundles_.back().scalarLanes = 0;
    lane = 0;
  }
  JointBundle& j = bundles_.back();
  const JointParams& params = joint.params;
  // What the scalar prepare sets, every pass, for a joint without a motor or limits.
  if (!params.enableMotor) joint.motorImpulse = 0.0;
  if (!params.enableLimit) joint.lowerImpulse = joint.upperImpulse = 0.0;
  j.joint[lane] = k;
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
  j.laneCount = lane + 1;
  return static_cast<int>(bundles_.size() - 1) * kJointLanes + lane++;
}

void JointLanes::fill(std::vector<Joint>& joints, const std::vector<int>& colorStart, int colors,
                      const SubstepBodies& bodies, double h) {
  const int32_t identityOffset = static_cast<int32_t>(bodies.identityRow() * kStateDoubles);
  bundles_.clear();
  bundleStart_.assign(1, 0);
  scalarJoints_.resize(static_cast<size_t>(colors));
  overflowLanes_.clear();
  for (int color = 0; color <= colors; ++color) {  // the overflow last
    const bool overflow = color == colors;
    int lane = kJointLanes;  // the last bundle is full: the next lane opens one
    if (!overflow) scalarJoints_[static_cast<size_t>(color)].clear();
    for (int k = colorStart[color]; k < colorStart[color + 1]; ++k) {
      Joint& joint = joints[static_cast<size_t>(k)];
      const bool lanes = fits(joint);
      if (overflow) {
        overflowLanes_.push_back(lanes ? addLane(joint, k, bodies, h, lane) : -1);
      } else if (lanes) {
        addLane(joint, k, bodies, h, lane);
      } else {
        scalarJoints_[static_cast<size_t>(color)].push_back(k);
      }
    }
    for (; lane < kJointLanes; ++lane) setEmptyLane(bundles_.back(), lane, identityOffset);
    bundleStart_.push_back(static_cast<int>(bundles_.size()));
  }
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

void JointLanes::writeBack(std::vector<Joint>& joints, const SubstepBodies& bodies) {
  for (const JointBundle& j : bundles_) {
    for (int lane = 0; lane < j.laneCount; ++lane) {
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
