// Stages 4-6 of World::step for the sub-stepping solvers: n = velocity_iterations sub-steps of
// h = dt / n. The narrow phase ran once for the whole step; each sub-step then does
//
//   integrate velocities (h) -> warm start -> solve once -> move (h) -> relax: solve once more
//
// where the first solve of the soft step has a soft position bias and every other is rigid
// without bias, and restitution is applied once after the last sub-step. A load crosses one
// contact or joint per iteration, and gravity adds only g h per sub-step, so small sub-steps carry
// it through a tall pile or a long chain where one big step with the same number of iterations
// cannot: the pile sags and rebounds instead. SubstepNgs adds no position bias at all (no energy,
// no momentum) and leaves the drift to the NGS position pass after the step; SoftStep pushes
// overlaps and joint gaps apart as stiff, heavily damped springs, and its relax pass takes back the
// velocity that push added.
#include "world_impl.hpp"

#include <algorithm>
#include <cmath>

namespace impulse2d {
namespace {

// Joint springs stiffer than this fraction of the sub-step rate outrun their own integration.
constexpr double kMaxJointHertzPerSubstepRate = 0.25;

}  // namespace

void WorldImpl::moveBodies(double h) {
  solverBodies.holdKinematicVelocities();
  for (int e = 0; e < solverBodies.movingCount(); ++e) {
    SolverBody& body = solverBodies[e];
    body.center += h * body.linearVelocity;
    turnBy(body, h * body.angularVelocity);
  }
}

void WorldImpl::solveSubsteps(double dt) {
  const int substeps = std::max(1, def.velocityIterations);
  const double h = dt / substeps;
  const bool soft = def.solver == SolverType::SoftStep;

  stepStart.clear();
  for (int e = 0; e < solverBodies.dynamicCount(); ++e) {
    stepStart.push_back({solverBodies.slotOf(e), solverBodies[e].center, solverBodies[e].angle});
  }

  collectActiveJoints();
  contactSolver.prepare(contacts, solverBodies, def, dt);
  contactSolver.prepareSubsteps(def, substeps, h);
  const Feedback rigid;  // no bias
  const Feedback jointSpring = springFeedback(
      std::min(def.jointHertz, kMaxJointHertzPerSubstepRate / h), def.jointDampingRatio, h);

  for (int substep = 0; substep < substeps; ++substep) {
    integrateVelocities(h);
    prepareJoints(soft ? jointSpring : rigid, h);
    warmStartJoints();
    contactSolver.warmStart();
    solveJointVelocities(h);
    contactSolver.solveSubstep(h, soft, false, def.maxPushVelocity);

    moveBodies(h);

    // Relax: a second iteration at the new poses. For the soft step it takes back the push;
    // for both it is what keeps warm-started sub-steps stable (with one iteration per sub-step
    // the 5050-box pyramid holds at 8 sub-steps but shakes apart at 12).
    prepareJoints(rigid, h);
    solveJointVelocities(h);
    contactSolver.solveSubstep(h, false, true, def.maxPushVelocity);
  }
  contactSolver.applyRestitution(def.restitutionThreshold);
  contactSolver.storeImpulses();

  // Continuous collision looks at the whole step's motion, as after a one-pass solve.
  fastBodies.clear();
  for (int e = 0; e < solverBodies.dynamicCount(); ++e) {
    const FastBody& start = stepStart[e];
    const SolverBody& body = solverBodies[e];
    const Body& shape = bodies.items[start.slot];
    const double reach = (body.center - start.startCenter).norm() +
                         std::abs(body.angle - start.startAngle) * shape.maxExtent;
    if (reach > std::max(def.speculativeDistance, 0.25 * shape.minExtent)) {
      fastBodies.push_back(start);
    }
  }
}

}  // namespace impulse2d
