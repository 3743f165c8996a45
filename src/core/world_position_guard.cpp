// The position guard's view of the world (position_guard.hpp): the joints each solver path
// solves, with their bodies' entries, and the soft step's measurements around the step.
#include "world_impl.hpp"

namespace impulse2d {

void WorldImpl::visitJointErrors(const JointErrorNote& note) {
  if (usesSubsteps(def.solver)) {
    SubstepBodies& sb = substepBodies;
    for (const Joint& j : solverJoints) {
      const int a = sb.entryOf(j.bodyA), b = sb.entryOf(j.bodyB);
      note(sb.isDynamicEntry(a) ? a : -1, sb.isDynamicEntry(b) ? b : -1,
           jointPositionError(j, sb.view(j.bodyA), sb.view(j.bodyB)).squared());
    }
    return;
  }
  visitOnePassJointErrors(activeJoints, note);
}

void WorldImpl::visitOnePassJointErrors(const std::vector<int>& slots, const JointErrorNote& note) {
  const auto dynamicEntry = [&](int slot) {
    const int entry = solverBodies.movingEntryOf(slot);
    return entry >= 0 && solverBodies.isDynamic(entry) ? entry : -1;
  };
  for (const int j : slots) {
    const Joint& joint = joints.items[j];
    note(dynamicEntry(joint.bodyA), dynamicEntry(joint.bodyB),
         jointPositionError(joint, solverBodies.view(joint.bodyA), solverBodies.view(joint.bodyB))
             .squared());
  }
}

void WorldImpl::measureSoftStepStart() {
  positionGuard.measureStepStart(substepBodies.dynamicCount(),
                                 [&](const auto& note) { visitJointErrors(note); });
}

void WorldImpl::withholdFeedbackOfWorseGroups() {
  // Last step's verdicts are spent: this step's joints were prepared with them.
  if (anyFeedbackWithheld) {
    for (Joint& joint : solverJoints) joint.feedbackWithheld = false;
  }
  anyFeedbackWithheld = false;
  if (!positionGuard.armed()) return;
  positionGuard.keepOrRestore([&](const auto& note) { visitJointErrors(note); }, [](int) {},
                              [&](size_t j) {
                                solverJoints[j].feedbackWithheld = true;
                                anyFeedbackWithheld = true;
                              });
}

}  // namespace impulse2d
