// The sub-stepping solver's revolute joints in SIMD lanes, as contact_bundles.hpp lays out the
// contacts: a colour's joints share no moving body, so eight of them can be solved at once. The
// revolute joints of `substep` take lanes (rigid rows: no bias, no spring; warm started), with
// their motors and limits; the overflow's too, each solved on its own in the overflow's order.
// Every other joint stays on the scalar path (joint_*.cpp).
//
// Each lane repeats the scalar rows' IEEE operations in their order (prepareRevolute,
// warmStartJoint, solveRevoluteVelocity), so a joint gives the same bits in a lane as on the
// scalar path, on every instruction set. A lane whose warm start would break the motion limits
// (warmStartJoint's rescaling, rare) is left untouched and handed back to the scalar path.
//
//   per step:       layOut (which lane each joint takes), then fill (the bodies' rows, start
//                   poses, anchors, kept impulses)
//   per sub-step:   [prepare +] warm start, solve, prepare + relax (solve at the new poses)
//   after them:     writeBack (the impulses, and the rows as the last relax prepared them),
//                   then the NGS position passes (joints without limits; limits stay scalar)
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "joint.hpp"
#include "motion_limits.hpp"
#include "substep_bodies.hpp"

namespace impulse2d {

constexpr int kJointLanes = 8;

// Each array of doubles fills a whole line (the kernels' aligned loads).
struct alignas(64) JointBundle {
  JointBundle() {}  // fill() writes every field of every lane: no zeroing
  double invMassA[kJointLanes], invInertiaA[kJointLanes];
  double invMassB[kJointLanes], invInertiaB[kJointLanes];
  // Each view's rotation as the step began (SubstepBodies::viewStart) and whether the body turns
  // this step (1) or is read as it stands (0: q is q0 itself, not q0 times the identity).
  double q0cA[kJointLanes], q0sA[kJointLanes], q0cB[kJointLanes], q0sB[kJointLanes];
  double turnsA[kJointLanes], turnsB[kJointLanes];
  // m, the anchor from each body's centre of mass in the body's frame (localAnchor - localCenter).
  double anchorAx[kJointLanes], anchorAy[kJointLanes];
  double anchorBx[kJointLanes], anchorBy[kJointLanes];
  // The rows as the last prepare left them: the arms at the poses then and K^-1 (symmetric).
  double rAx[kJointLanes], rAy[kJointLanes], rBx[kJointLanes], rBy[kJointLanes];
  double mass00[kJointLanes], mass01[kJointLanes], mass11[kJointLanes];
  double impulseX[kJointLanes], impulseY[kJointLanes];  // N s, accumulated (Joint::pairImpulse)
  // The motor and the limits, in bundles that have any (anyMotor, anyLimit): 1 where the lane's
  // joint has one, its parameters, the relative angle's parts, and the rows' state.
  double hasMotor[kJointLanes], hasLimit[kJointLanes];
  double motorSpeed[kJointLanes], maxMotorImpulse[kJointLanes];  // rad/s; N m s a sub-step
  double lower[kJointLanes], upper[kJointLanes], referenceAngle[kJointLanes];  // rad
  double angle0A[kJointLanes], angle0B[kJointLanes];      // each view's angle as the step began
  double axialMass[kJointLanes];                          // kg m^2
  double lowerBias[kJointLanes], upperBias[kJointLanes];  // rad/s, as the last prepare left them
  double motorImpulse[kJointLanes], lowerImpulse[kJointLanes], upperImpulse[kJointLanes];
  // m, each view's centre of mass as the step began (the position passes').
  double center0Ax[kJointLanes], center0Ay[kJointLanes];
  double center0Bx[kJointLanes], center0By[kJointLanes];
  // BodyState offsets (row * kStateDoubles); ~offset for a body the lane must not write (static,
  // kinematic, an empty lane), as ContactBundle.
  int32_t offsetA[kJointLanes];
  int32_t offsetB[kJointLanes];
  int32_t joint[kJointLanes];  // index in the solver's joints
  int laneCount;
  bool anyMotor, anyLimit;
  uint8_t scalarLanes;  // bit i: lane i's warm start was left to the scalar path (above)
};
static_assert(offsetof(JointBundle, center0By) % 64 == 0, "the doubles in whole lines");

/// What the joint kernels do in one pass over some bundles.
enum class JointLanePass { PrepareAndWarmStart, WarmStart, Solve, PrepareAndSolve };
inline bool warmsStart(JointLanePass pass) {
  return pass == JointLanePass::PrepareAndWarmStart || pass == JointLanePass::WarmStart;
}
inline bool prepares(JointLanePass pass) {
  return pass == JointLanePass::PrepareAndWarmStart || pass == JointLanePass::PrepareAndSolve;
}

struct JointLaneArgs {
  JointBundle* bundles = nullptr;
  double* states = nullptr;  // SubstepBodies::states(), as doubles
  int32_t sinkOffset = 0;    // this worker's sink row * kStateDoubles
  double h = 0.0;            // s, the sub-step
  MotionLimits limits;       // of a sub-step, for the warm start
};

/// The kernels (joint_kernels.cpp) over the bundles [begin, end), whose lanes share no body.
void runJointLanes(const JointLaneArgs& args, JointLanePass pass, int begin, int end);
/// prepareRevolute (the arms, K^-1, the limits' targets) for every lane of the bundles [begin,
/// end), whose lanes may share bodies: a prepare reads only the poses, which a velocity pass does
/// not change.
void prepareJointLanes(const JointLaneArgs& args, int begin, int end);
/// The same as runJointLanes for `count` consecutive lanes from firstLane (bundle * kJointLanes +
/// lane), one at a time in order, as the overflow's joints are solved. A warm start stops after a
/// lane it left to the scalar path (JointBundle::scalarLanes), whose turn comes before the next
/// joint's. Returns how many lanes it ran.
int runJointOverflow(const JointLaneArgs& args, JointLanePass pass, int firstLane, int count);
/// One NGS position pass (solveRevolutePosition) over the bundles [begin, end), none with limits.
/// Raises *widest to the largest joint error met (m), and clears *within where one exceeds
/// `linearSlop`.
void positionJointLanes(const JointLaneArgs& args, int begin, int end, double linearSlop,
                        double* widest, bool* within);
/// The same for `count` consecutive overflow lanes from firstLane, one at a time in order; stops
/// before a lane whose bundle has limits (the scalar path's). Returns how many lanes it ran.
int positionJointOverflow(const JointLaneArgs& args, int firstLane, int count, double linearSlop,
                          double* widest, bool* within);

class JointLanes {
 public:
  /// Whether a joint takes a lane: revolute.
  static bool fits(const Joint& joint);
  /// Lays the fitting joints of each colour ([colorStart[c], colorStart[c + 1]) of `joints`, the
  /// overflow (colour `colors`) last) into bundles, a lane each; the others of each colour are
  /// listed in scalarJoints. On one thread; fill() then fills the lanes.
  void layOut(const std::vector<Joint>& joints, const std::vector<int>& colorStart, int colors);
  /// Fills the lanes of bundles [begin, end) for sub-steps of h: each touches only its own lanes
  /// and joints, so blocks of bundles may be filled on several threads at once.
  void fill(int begin, int end, std::vector<Joint>& joints, const SubstepBodies& bodies, double h);
  int bundleCount() const { return static_cast<int>(bundles_.size()); }
  /// Colour c's bundles are [bundleStart(c), bundleStart(c + 1)).
  int bundleStart(int color) const { return bundleStart_[color]; }
  /// Colour c's joints that take no lane (indices in the solver's joints).
  const std::vector<int>& scalarJoints(int color) const { return scalarJoints_[color]; }
  /// The i-th overflow joint's lane (bundle * kJointLanes + lane), or -1: it takes none. The
  /// overflow's lanes are solved one at a time, in the overflow's order.
  int overflowLane(int i) const { return overflowLanes_[static_cast<size_t>(i)]; }
  /// How many overflow joints from the i-th on take consecutive lanes (0 where it takes none): a
  /// run the kernels take in one call.
  int overflowRun(int i) const { return overflowRuns_[static_cast<size_t>(i)]; }
  JointBundle* bundles() { return bundles_.data(); }
  JointBundle& bundle(int k) { return bundles_[k]; }
  /// Copies a lane's rows and impulse into its joint (for the scalar path), and back.
  static void toJoint(const JointBundle& bundle, int lane, Joint& joint);
  static void fromJoint(const Joint& joint, JointBundle& bundle, int lane);
  /// After the sub-steps: the impulses and rows of the lanes of bundles [begin, end) into their
  /// joints, as the scalar path's last relax pass left them (blocks on several threads at once).
  void writeBack(int begin, int end, std::vector<Joint>& joints, const SubstepBodies& bodies) const;

 private:
  /// Asks for the rows and start poses of the bodies of the lane a few after (k, lane), among
  /// bundles < end.
  void prefetchBodiesAhead(int k, int lane, int end, const std::vector<Joint>& joints,
                           const SubstepBodies& bodies) const;
  /// Fills a lane with its joint.
  static void fillLane(Joint& joint, JointBundle& j, int lane, const SubstepBodies& bodies,
                       double h);

  std::vector<JointBundle> bundles_;
  std::vector<int> bundleStart_;                // by colour, one past the last
  std::vector<std::vector<int>> scalarJoints_;  // by colour
  std::vector<int> overflowLanes_;              // by overflow joint
  std::vector<int> overflowRuns_;               // by overflow joint
};

}  // namespace impulse2d
