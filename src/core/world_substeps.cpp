// Stages 4-6 and 8 of World::step for the sub-stepping solvers: n = velocity_iterations sub-steps
// of h = dt / n. The narrow phase ran once for the whole step; then
//
//   colour the contacts, prepare them (contact_bundles.hpp)
//   n times: integrate velocities (h) -> warm start -> solve once -> move (h) -> relax: solve
//            once more
//   restitution, store the impulses; SubstepNgs: NGS position passes
//
// where the first solve of the soft step has a soft position bias and every other is rigid
// without bias. A load crosses one contact or joint per iteration, and gravity adds only g h per
// sub-step, so small sub-steps carry it through a tall pile or a long chain where one big step
// with the same number of iterations cannot: the pile sags and rebounds instead. SubstepNgs adds
// no position bias at all (no energy, no momentum) and leaves the drift to the NGS passes;
// SoftStep pushes overlaps and joint gaps apart as stiff, heavily damped springs, and its relax
// pass takes back the velocity that push added.
//
// Contacts are solved a colour at a time, a colour's bundles in SIMD lanes and in blocks shared
// among the step's threads (step_workers.hpp); joints, and contacts of bodies with more
// constraints than colours (the overflow), one after the other on the stepping thread.
#include "world_impl.hpp"

#include <algorithm>
#include <cmath>

namespace impulse2d {
namespace {

// Joint springs stiffer than this fraction of the sub-step rate outrun their own integration.
constexpr double kMaxJointHertzPerSubstepRate = 0.25;
// Contact springs stiffer than this fraction of the sub-step rate were measured to shake the
// 5050-box pyramid apart (0.19 sways, 0.25 collapses; 0.15 holds it within 3 cm).
constexpr double kMaxContactHertzPerSubstepRate = 0.15;
// The largest position correction one NGS pass applies, so deep overlaps (spawned inside each
// other) separate over several steps instead of exploding apart.
constexpr double kMaxLinearCorrection = 0.2;
// Work shared among threads comes in blocks of this many bundles or bodies: big enough that
// claiming a block costs little, small enough that the threads finish a colour together.
constexpr int kBundlesPerBlock = 4;

int blocksOf(int count, int perBlock) { return (count + perBlock - 1) / perBlock; }

}  // namespace

void WorldImpl::forEachJoint(const std::function<void(Joint&, SolverBody&, SolverBody&)>& fn,
                             bool pose) {
  for (const int j : activeJoints) {
    Joint& joint = joints.items[j];
    SolverBody a = substepBodies.view(joint.bodyA), b = substepBodies.view(joint.bodyB);
    fn(joint, a, b);
    substepBodies.store(joint.bodyA, a, pose);
    substepBodies.store(joint.bodyB, b, pose);
  }
}

void WorldImpl::solveSubsteps(double dt) {
  const int substeps = std::max(1, def.velocityIterations);
  const double h = dt / substeps;
  const bool soft = def.solver == SolverType::SoftStep;
  SubstepBodies& sb = substepBodies;
  sb.gather(bodies.items, bodies.alive, def.gravity, h, substeps, stepWorkers);
  overflowedBodies.insert(overflowedBodies.end(), sb.overflowed().begin(), sb.overflowed().end());
  contactBundles.assign(contacts, sb);

  activeJoints.clear();
  for (size_t j = 0; j < joints.items.size(); ++j) {
    if (!joints.alive[j]) continue;
    Joint& joint = joints.items[j];
    const bool moves = sb.isDynamicEntry(sb.entryOf(joint.bodyA)) ||
                       sb.isDynamicEntry(sb.entryOf(joint.bodyB));
    if (!moves) continue;
    activeJoints.push_back(static_cast<int>(j));
    if (!def.warmStarting) {
      joint.pointImpulse.setZero();
      joint.motorImpulse = joint.lowerImpulse = joint.upperImpulse = 0.0;
    }
  }

  BundlePass pass = contactBundles.pass(sb);
  pass.h = h;
  pass.inverseH = 1.0 / h;
  pass.maxPushVelocity = def.maxPushVelocity;
  const double contactHertz = std::min(def.contactHertz, kMaxContactHertzPerSubstepRate / h);
  pass.dynamicSoft = springFeedback(contactHertz, def.contactDampingRatio, h);
  pass.staticSoft = springFeedback(2.0 * contactHertz, def.contactDampingRatio, h);
  pass.restitutionThreshold = def.restitutionThreshold;
  pass.baumgarte = def.baumgarte;
  pass.linearSlop = def.linearSlop;
  pass.maxLinearCorrection = kMaxLinearCorrection;

  const Feedback rigid;  // no bias
  const Feedback jointSpring = springFeedback(
      std::min(def.jointHertz, kMaxJointHertzPerSubstepRate / h), def.jointDampingRatio, h);
  const int bodyBlocks = blocksOf(sb.movingCount(), kBodiesPerBlock);
  const int dynamicBlocks = blocksOf(sb.dynamicCount(), kBodiesPerBlock);

  // A kernel over every colour, a colour at a time, then the overflow lane by lane.
  auto overColors = [&](auto kernel) {
    for (int color = 0; color < contactBundles.colorCount(); ++color) {
      const int first = contactBundles.colorBegin(color), end = contactBundles.colorEnd(color);
      stepWorkers.stage(blocksOf(end - first, kBundlesPerBlock), [&](int block, int worker) {
        BundlePass mine = pass;
        mine.sinkOffset = static_cast<int32_t>(sb.sinkRow(worker) * kStateDoubles);
        const int begin = first + block * kBundlesPerBlock;
        kernel(mine, begin, std::min(end, begin + kBundlesPerBlock), false);
      });
    }
    BundlePass mine = pass;
    mine.sinkOffset = static_cast<int32_t>(sb.sinkRow(0) * kStateDoubles);
    kernel(mine, contactBundles.overflowBegin(), contactBundles.bundleCount(), true);
  };

  {
    const int contactBlocks = blocksOf(static_cast<int>(contacts.size()), kContactsPerBlock);
    stepWorkers.stage(contactBlocks, [&](int block, int) {
      const size_t first = static_cast<size_t>(block) * kContactsPerBlock;
      contactBundles.fill(contacts, first, std::min(contacts.size(), first + kContactsPerBlock), sb,
                          bodies.items, substeps, soft);
    });
    stepWorkers.stage(blocksOf(contactBundles.bundleCount(), kBundlesPerBlock * 8),
                      [&](int block, int) {
                        const int begin = block * kBundlesPerBlock * 8;
                        contactBundles.finishFill(
                            begin, std::min(contactBundles.bundleCount(), begin + kBundlesPerBlock * 8),
                            sb);
                      });
    for (int substep = 0; substep < substeps; ++substep) {
      stepWorkers.stage(dynamicBlocks, [&](int block, int) {
        sb.integrateVelocities(block * kBodiesPerBlock, (block + 1) * kBodiesPerBlock);
      });
      forEachJoint([&](Joint& j, SolverBody& a, SolverBody& b) {
        prepareJoint(j, a, b, def, soft ? jointSpring : rigid, h);
        warmStartJoint(j, a, b);
      });
      overColors(warmStartBundles);
      forEachJoint([&](Joint& j, SolverBody& a, SolverBody& b) { solveJointVelocity(j, a, b, h); });
      pass.useBias = soft;
      pass.relax = false;
      overColors(solveBundles);

      stepWorkers.stage(bodyBlocks, [&](int block, int) {
        sb.integratePositions(block * kBodiesPerBlock,
                              std::min(sb.movingCount(), (block + 1) * kBodiesPerBlock), h);
      });

      // Relax: a second iteration at the new poses. For the soft step it takes back the push;
      // for both it is what keeps warm-started sub-steps stable (with one iteration per
      // sub-step the 5050-box pyramid holds at 8 sub-steps but shakes apart at 12).
      forEachJoint([&](Joint& j, SolverBody& a, SolverBody& b) {
        prepareJoint(j, a, b, def, rigid, h);
        solveJointVelocity(j, a, b, h);
      });
      pass.useBias = false;
      pass.relax = true;
      overColors(solveBundles);
    }
    pass.relax = false;
    overColors(restituteBundles);
    stepWorkers.stage(contactBlocks, [&](int block, int) {
      const size_t first = static_cast<size_t>(block) * kContactsPerBlock;
      contactBundles.store(contacts, first, std::min(contacts.size(), first + kContactsPerBlock));
    });
    if (def.solver == SolverType::SubstepNgs) correctSubstepPositions(pass);
  }
  stepWorkers.stage(bodyBlocks, [&](int block, int) {
    sb.finish(bodies.items, block * kBodiesPerBlock, (block + 1) * kBodiesPerBlock);
  });

  // Continuous collision looks at the whole step's motion, as after a one-pass solve.
  fastBodies.clear();
  for (int e = 0; e < sb.dynamicCount(); ++e) {
    const BodyState& s = sb.state(e);
    const BodyStart& start = sb.start(e);
    const Body& body = bodies.items[start.slot];
    const double reach = std::hypot(s.dx, s.dy) + std::abs(s.turned) * body.maxExtent;
    if (reach > std::max(def.speculativeDistance, 0.25 * body.minExtent)) {
      fastBodies.push_back({start.slot, sb.sim(e).center0, start.angle0});
    }
  }
}

// NGS passes after the sub-steps: push what still overlaps apart by moving the bodies (no
// velocity, so no energy added), until every overlap is within 3 slops.
void WorldImpl::correctSubstepPositions(BundlePass pass) {
  std::vector<double>& deepest = blockDeepest;
  for (int iteration = 0; iteration < def.positionIterations; ++iteration) {
    bool jointsOk = true;
    forEachJoint(
        [&](Joint& j, SolverBody& a, SolverBody& b) { jointsOk &= solveJointPosition(j, a, b, def); },
        true);
    double worst = 0.0;
    for (int color = 0; color < contactBundles.colorCount(); ++color) {
      const int first = contactBundles.colorBegin(color), end = contactBundles.colorEnd(color);
      const int blocks = blocksOf(end - first, kBundlesPerBlock);
      deepest.assign(static_cast<size_t>(blocks), 0.0);
      stepWorkers.stage(blocks, [&](int block, int worker) {
        BundlePass mine = pass;
        mine.sinkOffset = static_cast<int32_t>(substepBodies.sinkRow(worker) * kStateDoubles);
        const int begin = first + block * kBundlesPerBlock;
        deepest[block] =
            solveBundlePositions(mine, begin, std::min(end, begin + kBundlesPerBlock), false);
      });
      for (const double d : deepest) worst = std::min(worst, d);
    }
    pass.sinkOffset = static_cast<int32_t>(substepBodies.sinkRow(0) * kStateDoubles);
    worst = std::min(worst, solveBundlePositions(pass, contactBundles.overflowBegin(),
                                                 contactBundles.bundleCount(), true));
    if (jointsOk && worst >= -3.0 * def.linearSlop) break;
  }
}

}  // namespace impulse2d
