// Stages 4-7 of World::step for the sub-stepping solvers: n = velocity_iterations sub-steps
// of h = dt / n. The narrow phase ran once for the whole step; then
//
//   gather the moving bodies, colour the joints and contacts, fill the contact bundles
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
// Each pass goes over the joints a colour at a time (one by one, on scalar views of their bodies),
// then over the contact bundles a colour at a time (the SIMD kernels), each colour in blocks
// shared among the step's threads (step_workers.hpp); each overflow, one after the other, on the
// stepping thread.
#include "world_impl.hpp"

#include "position_pass.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <type_traits>

namespace impulse2d {
namespace {

// Joint springs stiffer than this fraction of the sub-step rate outrun their own integration.
constexpr double kMaxJointHertzPerSubstepRate = 0.25;
// Contact springs stiffer than this fraction of the sub-step rate were measured to shake the
// 5050-box pyramid apart (0.19 sways, 0.25 collapses; 0.15 holds it within 3 cm).
constexpr double kMaxContactHertzPerSubstepRate = 0.15;
// Work shared among threads comes in blocks of at most this many bundles or joints: big enough
// that claiming a block costs little, small enough that the threads finish a colour together.
// A small colour is cut finer (bundlesPerBlock), so that each thread gets at least
// kLeastBlocksPerThread blocks of it.
constexpr int kBundlesPerBlock = 4;
constexpr int kLeastBlocksPerThread = 4;
constexpr int kJointsPerBlock = 32;
constexpr int kJointBundlesPerBlock = 4;
// Joints copied to and from their colours' order per block, and the joint lanes' bundles filled
// and written back per block (the same 256 joints).
constexpr int kJointsPerCopyBlock = 256;
constexpr int kJointBundlesPerCopyBlock = kJointsPerCopyBlock / kJointLanes;

int blocksOf(int count, int perBlock) { return (count + perBlock - 1) / perBlock; }

// Whether a colour pass of this many bundles (of contacts or joints) is shared among the threads.
// Handing a stage to another thread passes a few lines between the cores (the stage, its blocks'
// counters, the bodies), measured at 2-3 us a stage on a VM whose cores pass a line in 250 ns,
// while a bundle takes 20-40 ns: shared, pyramid20's colours of 5-10 bundles made two threads
// 4.5x slower than one. Which thread runs a block never changes the result.
// On one thread nothing is shared.
constexpr int kLeastSharedBundles = 32;
bool worthSharing(int bundles, int threads) {
  return threads > 1 && bundles >= kLeastSharedBundles;
}

// A shared colour's bundles go in blocks of `most`, or finer (down to a bundle) where that would
// leave a thread fewer than kLeastBlocksPerThread blocks: in blocks of four, most of a colour of a
// few dozen bundles ran on one thread while the others waited (v3_compounds ends in small
// colours). Blocks never change what is computed.
int bundlesPerBlock(int bundles, int threads, int most) {
  return std::clamp(bundles / (kLeastBlocksPerThread * threads), 1, most);
}

// Asks for every line of a joint (the copies into and out of colour order read or write it all).
template <bool forWriting>
void prefetchWholeJoint(const Joint& joint) {
  const char* bytes = reinterpret_cast<const char*>(&joint);
  for (size_t line = 0; line < sizeof(Joint); line += 64)
    __builtin_prefetch(bytes + line, forWriting);
}

}  // namespace

// A pass waits on memory at each joint: 20,000 joints of 624 bytes (v3_joint_grid) do not stay
// in cache from pass to pass, and `perf` put a third of the pass loop's samples on the first
// load of each joint. So while it works on joint k, the rows every pass reads of joint k + 8
// (and, for a pass that prepares them, the anchors at its end) and the bodies' rows (what their
// views read) of joint k + 4 (whose lines arrived by then) are asked for; hints only, nothing
// computed changes.
void WorldImpl::prefetchJointAhead(int k, int end, bool geometry) const {
  constexpr int kJointsAhead = 8, kBodiesAhead = 4;
  if (k + kJointsAhead < end) {
    const Joint& ahead = solverJoints[k + kJointsAhead];
    const char* joint = reinterpret_cast<const char*>(&ahead);
    // Its first four lines: the rows every pass reads (a fifth, for the impulses after them, was
    // slower in three side-by-side runs).
    for (int line = 0; line < 4; ++line) __builtin_prefetch(joint + 64 * line);
    if (geometry) {
      __builtin_prefetch(&ahead.localAnchorA);
      __builtin_prefetch(&ahead.restLength);
    }
  }
  if (k + kBodiesAhead < end) {
    const Joint& joint = solverJoints[k + kBodiesAhead];
    substepBodies.prefetchView(joint.bodyA, geometry);
    substepBodies.prefetchView(joint.bodyB, geometry);
  }
}

template <WorldImpl::JointAccess access, class JointOp>
void WorldImpl::onJoint(int index, int worker, const JointOp& op) {
  Joint& joint = solverJoints[index];
  SubstepBodies& sb = substepBodies;
  if constexpr (access == JointAccess::Velocities) {
    BodyVelocity a = sb.velocityView(joint.bodyA), b = sb.velocityView(joint.bodyB);
    op(joint, a, b, worker);
    sb.store(joint.bodyA, a);
    sb.store(joint.bodyB, b);
  } else {
    SolverBody a = sb.view(joint.bodyA), b = sb.view(joint.bodyB);
    op(joint, a, b, worker);
    constexpr bool pose = access == JointAccess::WritePoses;
    sb.store(joint.bodyA, a, pose);
    sb.store(joint.bodyB, b, pose);
  }
}

void WorldImpl::warmStartScalarLanes(int begin, int end) {
  const MotionLimits& limits = jointLaneArgs.limits;
  for (int k = begin; k < end; ++k) {
    JointBundle& bundle = jointLanes.bundle(k);
    for (int lane = 0; bundle.scalarLanes != 0 && lane < kJointLanes; ++lane) {
      if (!(bundle.scalarLanes & (1u << lane))) continue;
      Joint& joint = solverJoints[static_cast<size_t>(bundle.joint[lane])];
      JointLanes::toJoint(bundle, lane, joint);
      onJoint<JointAccess::Velocities>(bundle.joint[lane], 0,
                                       [&](Joint& j, BodyVelocity& a, BodyVelocity& b, int) {
                                         warmStartJoint(j, a, b, limits);
                                       });
      JointLanes::fromJoint(joint, bundle, lane);
    }
    bundle.scalarLanes = 0;
  }
}

template <class Kernel>
int WorldImpl::intoVerdict(int worker, const Kernel& kernel) {
  StepScratch::PassVerdict& verdict = scratch.workerVerdicts[static_cast<size_t>(worker)].value;
  bool within = true;
  const int ran = kernel(&verdict.widest, &within);
  if (!within) verdict.jointsOk = false;
  return ran;
}

template <class JointOp>
void WorldImpl::positionLanes(const JointLaneArgs& args, int bundle, int worker,
                              const JointOp& jointOp) {
  const JointBundle& j = jointLanes.bundle(bundle);
  if (j.anyLimit) {  // the limits' position rows stay scalar
    for (int i = 0; i < j.laneCount; ++i) {
      onJoint<JointAccess::WritePoses>(j.joint[i], worker, jointOp);
    }
    return;
  }
  intoVerdict(worker, [&](double* widest, bool* within) {
    positionJointLanes(args, bundle, bundle + 1, def.linearSlop, widest, within);
    return 1;
  });
}

template <WorldImpl::JointAccess access, class JointOp>
void WorldImpl::overLaneColor(int color, const JointOp& jointOp, JointLanePass lanePass) {
  // The colour's bundles, then its joints that take no lane: all independent of each other.
  const int firstBundle = jointLanes.bundleStart(color);
  const int bundles = jointLanes.bundleStart(color + 1) - firstBundle;
  const std::vector<int>& scalar = jointLanes.scalarJoints(color);
  const int count = static_cast<int>(scalar.size());
  // Not shared, the colour's bundles go to the kernels in one call and its other joints in one
  // block, as overColors does with the contacts' colours: blocks only serve sharing.
  const bool shared = worthSharing(bundles + count / kJointLanes, stepWorkers.threads());
  const int perBlock = shared
                           ? bundlesPerBlock(bundles, stepWorkers.threads(), kJointBundlesPerBlock)
                           : std::max(1, bundles);
  const int jointsPerBlock = shared ? kJointsPerBlock : std::max(1, count);
  const int bundleBlocks = blocksOf(bundles, perBlock);
  const auto runBlock = [&](int block, int worker) {
    if (block < bundleBlocks) {
      JointLaneArgs args = jointLaneArgs;
      args.sinkOffset = static_cast<int32_t>(substepBodies.sinkRow(worker) * kStateDoubles);
      const int from = firstBundle + block * perBlock;
      const int to = std::min(firstBundle + bundles, from + perBlock);
      if constexpr (access == JointAccess::WritePoses) {
        for (int k = from; k < to; ++k) positionLanes(args, k, worker, jointOp);
      } else {
        runJointLanes(args, lanePass, from, to);
        if (warmsStart(lanePass)) warmStartScalarLanes(from, to);
      }
      return;
    }
    const int from = (block - bundleBlocks) * jointsPerBlock;
    const int to = std::min(count, from + jointsPerBlock);
    for (int i = from; i < to; ++i) onJoint<access>(scalar[i], worker, jointOp);
  };
  stepWorkers.stage(bundleBlocks + blocksOf(count, jointsPerBlock), runBlock, shared);
}

template <WorldImpl::JointAccess access, class JointOp>
void WorldImpl::overColors(const JointOp& jointOp, const BundleOp& bundleOp, const BundlePass& pass,
                           JointLanePass lanePass) {
  SubstepBodies& sb = substepBodies;
  const int colors = contactBundles.colorCount();
  // The joints first, colour after colour and then their overflow, and the contacts after them:
  // the contacts' last word keeps jointed bodies out of the ground. Interleaving a colour's
  // joints with its contacts instead let ragdolls landing at 28 m/s (v3_rain) open their joints
  // by up to 38 cm and sink 12 cm, where this order keeps them within a few centimetres.
  if constexpr (!std::is_same_v<JointOp, std::nullptr_t>) {
    if (!solverJoints.empty()) {  // no stage per colour for a world without joints
      for (int color = 0; color < colors; ++color) {
        if (jointLanesFilled) {
          overLaneColor<access>(color, jointOp, lanePass);
          continue;
        }
        const int firstJoint = jointStart[color], endJoint = jointStart[color + 1];
        stepWorkers.forRanges(endJoint - firstJoint, kJointsPerBlock,
                              [&](int begin, int last, int worker) {
                                const int from = firstJoint + begin, to = firstJoint + last;
                                for (int k = from; k < to; ++k) {
                                  prefetchJointAhead(k, to, access != JointAccess::Velocities);
                                  onJoint<access>(k, worker, jointOp);
                                }
                              });
      }
      // The overflow, one joint after the other: in a lane of its own where it has one. The
      // lanes of consecutive joints are consecutive: a run of them goes to the kernels at once.
      JointLaneArgs args = jointLaneArgs;
      args.sinkOffset = static_cast<int32_t>(substepBodies.sinkRow(0) * kStateDoubles);
      const int first = jointStart[colors], end = jointStart[colors + 1];
      // A lane's prepare reads only poses, which no joint of a velocity pass moves: all of the
      // overflow's lanes are prepared first, side by side, out of the chain of one joint after
      // the other (bridge20 spent a third of its joints' time there).
      JointLanePass overflowPass = lanePass;
      if (jointLanesFilled && prepares(lanePass)) {
        prepareJointLanes(args, jointLanes.bundleStart(colors), jointLanes.bundleStart(colors + 1));
        overflowPass = warmsStart(lanePass) ? JointLanePass::WarmStart : JointLanePass::Solve;
      }
      for (int k = first; k < end;) {
        const int lane = jointLanesFilled ? jointLanes.overflowLane(k - first) : -1;
        if (lane < 0) {
          onJoint<access>(k++, 0, jointOp);
          continue;
        }
        const int run = jointLanes.overflowRun(k - first);
        if constexpr (access == JointAccess::WritePoses) {
          const int ran = intoVerdict(0, [&](double* widest, bool* within) {
            return positionJointOverflow(args, lane, run, def.linearSlop, widest, within);
          });
          k += ran;
          if (ran == 0) onJoint<access>(k++, 0, jointOp);  // its bundle has limits: scalar
          continue;
        }
        const int ran = runJointOverflow(args, overflowPass, lane, run);
        k += ran;
        const int bundle = (lane + ran - 1) / kJointLanes;
        if (warmsStart(lanePass)) warmStartScalarLanes(bundle, bundle + 1);
      }
    }
  }
  if (!bundleOp) return;
  auto sink = [&](int worker) {
    BundlePass mine = pass;
    mine.sinkOffset = static_cast<int32_t>(sb.sinkRow(worker) * kStateDoubles);
    return mine;
  };
  // Colours not shared run on this thread, a run of them in one call: their bundles follow one
  // another, and one call solves them in the same order. Cut into blocks of a few bundles, each
  // block a call (a dispatch, a pass copied), pyramid20 spent a tenth of its step calling.
  int unshared = contactBundles.colorBegin(0);  // the first bundle of the run not yet solved
  for (int color = 0; color < colors; ++color) {
    const int first = contactBundles.colorBegin(color), end = contactBundles.colorEnd(color);
    if (!worthSharing(end - first, stepWorkers.threads())) continue;
    if (unshared < first) bundleOp(sink(0), unshared, first, false, 0);
    const int perBlock = bundlesPerBlock(end - first, stepWorkers.threads(), kBundlesPerBlock);
    const auto runRange = [&](int begin, int last, int worker) {
      bundleOp(sink(worker), first + begin, first + last, false, worker);
    };
    stepWorkers.forRanges(end - first, perBlock, runRange);
    unshared = end;
  }
  if (colors > 0 && unshared < contactBundles.colorEnd(colors - 1)) {
    bundleOp(sink(0), unshared, contactBundles.colorEnd(colors - 1), false, 0);
  }
  // The overflow: one after the other, on this thread.
  bundleOp(sink(0), contactBundles.overflowBegin(), contactBundles.bundleCount(), true, 0);
}

void WorldImpl::solveSubsteps(double dt) {
  const int substeps = std::max(1, def.velocityIterations);
  const double h = dt / substeps;
  const bool soft = def.solver == SolverType::SoftStep;
  SubstepBodies& sb = substepBodies;
  StageLaps laps(profiled());
  weldClusters.find(bodies.items, movableSlots, joints.items, joints.alive, rigidWelds);
  sb.gather(bodies.items, movableSlots, def.gravity, h, MotionLimits::of(def, h), weldClusters,
            stepWorkers);
  overflowedBodies.insert(overflowedBodies.end(), sb.overflowed().begin(), sb.overflowed().end());
  laps.lap(&StepProfile::prepare);
  colorConstraints();
  capTurnsByJointReach(
      sb.turnCaps(), sb.dynamicCount(), MotionLimits::of(def, h),
      [&](int slot) {
        const int entry = sb.entryOf(slot);
        return sb.isDynamicEntry(entry) ? entry : -1;
      },
      [&](int entry) { return sb.center0(entry); });
  laps.lap(&StepProfile::coloring);
  if (soft) measureSoftStepStart();
  BundlePass pass = bundlePass(h);
  if (soft) {  // its springs would turn a crushed body out of its overlaps (crushed_bodies.hpp)
    crushedBodies.find(contacts, [&](int slot) { return sb.dynamicEntryOf(slot); });
  }
  fillBundles(dt, substeps, soft);
  const bool preparedByRelax = !soft && def.warmStarting;
  jointLanesFilled = preparedByRelax;  // the lanes' rows are rigid and warm started
  // The joint lanes' bundles [begin, end) in blocks on the threads: each lane is its own joint's.
  const auto overLaneBundles = [&](const auto& op) {
    const int count = jointLanes.bundleCount();
    stepWorkers.forRanges(count, kJointBundlesPerCopyBlock,
                          [&](int begin, int end, int) { op(begin, end); });
  };
  if (jointLanesFilled) {
    jointLanes.layOut(solverJoints, jointStart, stepColors.colorCount());
    overLaneBundles([&](int begin, int end) { jointLanes.fill(begin, end, solverJoints, sb, h); });
    jointLaneArgs.bundles = jointLanes.bundles();
    jointLaneArgs.h = h;
    jointLaneArgs.states = reinterpret_cast<double*>(sb.states());
    jointLaneArgs.limits = MotionLimits::of(def, h);
  }
  laps.lap(&StepProfile::prepare);

  const Feedback rigid;  // no bias
  Feedback jointSpring = springFeedback(std::min(def.jointHertz, kMaxJointHertzPerSubstepRate / h),
                                        def.jointDampingRatio, h);
  jointSpring.maxPush = def.maxPushVelocity;
  const int bodyBlocks = blocksOf(sb.movingCount(), kBodiesPerBlock);
  const int dynamicBlocks = blocksOf(sb.dynamicCount(), kBodiesPerBlock);
  const MotionLimits motionLimits = MotionLimits::of(def, h);
  // Joints prepare their rows at the bodies' poses when a pass first reaches them. Without the
  // soft step's springs, the rows the last relax pass prepared are this sub-step's already: the
  // poses have not moved since, and rigid rows are all the same (13 % of v3_rain's step went to
  // preparing revolute joints twice a sub-step).
  const Feedback firstFeedback = soft ? jointSpring : rigid;
  int substep = 0;
  const auto prepareAndWarmStart = [&](Joint& j, SolverBody& a, SolverBody& b, int) {
    prepareJoint(j, a, b, def, j.feedbackWithheld ? rigid : firstFeedback, h);
    warmStartJoint(j, a, b, motionLimits);
  };
  const auto warmStart = [&](Joint& j, BodyVelocity& a, BodyVelocity& b, int) {
    warmStartJoint(j, a, b, motionLimits);
  };
  const auto solveJoints = [h](Joint& j, BodyVelocity& a, BodyVelocity& b, int) {
    solveJointVelocity(j, a, b, h);
  };
  const auto prepareAndRelax = [&](Joint& j, SolverBody& a, SolverBody& b, int) {
    prepareJoint(j, a, b, def, rigid, h);
    solveJointVelocity(j, a, b, h);
  };
  auto kernel = [](void (*run)(const BundlePass&, int, int, bool)) -> BundleOp {
    return [run](const BundlePass& p, int begin, int end, bool oneByOne, int) {
      run(p, begin, end, oneByOne);
    };
  };
  for (substep = 0; substep < substeps; ++substep) {
    stepWorkers.stage(dynamicBlocks, [&](int block, int) {
      sb.integrateVelocities(block * kBodiesPerBlock, (block + 1) * kBodiesPerBlock);
    });
    laps.lap(&StepProfile::integrate);
    if (noteApproaches(pass)) laps.lap(&StepProfile::restitution);
    if (substep == 0 || !preparedByRelax) {  // else the rows are the last relax pass's
      overColors<JointAccess::ReadPoses>(prepareAndWarmStart, kernel(warmStartBundles), pass,
                                         JointLanePass::PrepareAndWarmStart);
    } else {
      overColors<JointAccess::Velocities>(warmStart, kernel(warmStartBundles), pass,
                                          JointLanePass::WarmStart);
    }
    laps.lap(&StepProfile::warmStart);
    pass.useBias = soft;
    pass.relax = false;
    overColors<JointAccess::Velocities>(solveJoints, kernel(solveBundles), pass,
                                        JointLanePass::Solve);
    laps.lap(&StepProfile::solve);

    stepWorkers.stage(bodyBlocks, [&](int block, int) {
      sb.integratePositions(block * kBodiesPerBlock,
                            std::min(sb.movingCount(), (block + 1) * kBodiesPerBlock), h);
    });
    laps.lap(&StepProfile::integrate);

    // Relax: a second iteration at the new poses. For the soft step it takes back the push;
    // for both it is what keeps warm-started sub-steps stable (with one iteration per sub-step
    // the 5050-box pyramid holds at 8 sub-steps but shakes apart at 12).
    pass.useBias = false;
    pass.relax = true;
    overColors<JointAccess::ReadPoses>(prepareAndRelax, kernel(solveBundles), pass,
                                       JointLanePass::PrepareAndSolve);
    laps.lap(&StepProfile::relax);
  }
  if (jointLanesFilled) {  // the joints as the last relax pass left them
    overLaneBundles(
        [&](int begin, int end) { jointLanes.writeBack(begin, end, solverJoints, sb); });
    laps.lap(&StepProfile::relax);
  }
  pass.relax = false;
  overColors<JointAccess::Velocities>(nullptr, kernel(restituteBundles), pass);
  storeBundles();
  laps.lap(&StepProfile::restitution);
  if (soft) {
    withholdFeedbackOfWorseGroups();
  } else {
    correctSubstepPositions(pass);  // with the joint lanes' position pass
  }
  jointLanesFilled = false;
  laps.lap(&StepProfile::positions);
  stepWorkers.stage(bodyBlocks, [&](int block, int) {
    sb.finish(bodies.items, block * kBodiesPerBlock, (block + 1) * kBodiesPerBlock);
  });
  laps.lap(&StepProfile::integrate);
  findFastSubstepBodies();
  laps.lap(&StepProfile::continuous);
}

void WorldImpl::colorConstraints() {
  SubstepBodies& sb = substepBodies;
  // Without warm starting, collectActiveJoints drops the kept impulses in the joints' slots.
  if (!def.warmStarting) syncJoints();
  collectActiveJoints([&](int slot) { return sb.isDynamicSlot(slot); });
  activeJointBodies.clear();  // what the colouring needs of them
  for (const int j : activeJoints) activeJointBodies.push_back(jointBodies[j]);
  stepColors.assign(contacts, activeJoints, activeJointBodies, sb, ContactBundles::kMinColorSize,
                    ContactBundles::kMinColorContacts, stepWorkers);
  contactBundles.assign(contacts, stepColors);
  // The joints, colour after colour and the overflow last, copied side by side: a colour's
  // joints are every few in slot order, and a pass over them there waited on memory at each.
  // The copies (600 bytes a joint) in parallel blocks, each joint to its place; none when the
  // last step left these joints there in this order (world_impl.hpp, heldJointOrder).
  scratch.jointOrder.clear();
  jointStart.assign(1, 0);
  for (int color = 0; color <= stepColors.colorCount(); ++color) {
    const std::vector<int>& slots = stepColors.jointsOf(color);
    scratch.jointOrder.insert(scratch.jointOrder.end(), slots.begin(), slots.end());
    jointStart.push_back(static_cast<int>(scratch.jointOrder.size()));
  }
  if (!heldJointOrder.empty() && scratch.jointOrder == heldJointOrder) return;
  syncJoints();
  std::swap(heldJointOrder, scratch.jointOrder);  // solverJoints hold these joints from now on
  const std::vector<int>& order = heldJointOrder;
  const int count = static_cast<int>(order.size());
  solverJoints.resize(static_cast<size_t>(count));
  stepWorkers.forRanges(count, kJointsPerCopyBlock, [&](int begin, int end, int) {
    for (int k = begin; k < end; ++k) {
      if (k + 4 < end) {  // a colour's joints lie every few slots apart
        prefetchWholeJoint<false>(joints.items[order[k + 4]]);
      }
      solverJoints[static_cast<size_t>(k)] = joints.items[order[k]];
    }
  });
}

void WorldImpl::syncJoints() {
  if (heldJointOrder.empty()) return;
  heldJointOrder.clear();
  const int count = static_cast<int>(solverJoints.size());
  stepWorkers.forRanges(count, kJointsPerCopyBlock, [&](int begin, int end, int) {
    for (int k = begin; k < end; ++k) {
      if (k + 4 < end) {  // the slot written four joints on
        prefetchWholeJoint<true>(joints.items[solverJoints[static_cast<size_t>(k + 4)].id.index]);
      }
      const Joint& joint = solverJoints[static_cast<size_t>(k)];
      joints.items[joint.id.index] = joint;
    }
  });
}

BundlePass WorldImpl::bundlePass(double h) {
  BundlePass pass = contactBundles.pass(substepBodies);
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
  return pass;
}

void WorldImpl::fillBundles(double dt, int substeps, bool soft) {
  SubstepBodies& sb = substepBodies;
  // What the last step kept, before the bundles take the contacts' (warm_start_guard.hpp).
  scratch.guardedJoints.clear();
  for (Joint& joint : solverJoints) scratch.guardedJoints.push_back(&joint);
  warmStartGuard.run(
      scratch.guardedJoints, contacts, sb.dynamicCount(),
      [&](int slot) { return static_cast<int>(sb.writeRow(slot)); },
      [&](int slot) { return sb.view(slot); }, [&](int slot) { sb.prefetchView(slot, true); },
      &jointStart, &stepWorkers, def.gravity.norm() * dt, def.maxLinearSpeed, !soft);
  stepWorkers.forRanges(
      static_cast<int>(contacts.size()), kContactsPerBlock, [&](int begin, int end, int) {
        contactBundles.fill(contacts, static_cast<size_t>(begin), static_cast<size_t>(end), sb,
                            bodies.items, substeps, soft ? &crushedBodies : nullptr);
      });
  stepWorkers.forRanges(
      contactBundles.bundleCount(), 8 * kBundlesPerBlock,
      [&](int begin, int end, int) { contactBundles.finishFill(begin, end, sb, soft); });
  contactBundles.collectBouncing();
}

bool WorldImpl::noteApproaches(const BundlePass& pass) {
  const std::vector<int>& bouncing = contactBundles.bouncing();
  if (bouncing.empty()) return false;
  stepWorkers.forRanges(static_cast<int>(bouncing.size()), 8 * kBundlesPerBlock,
                        [&](int begin, int end, int) {
                          noteBundleApproaches(pass, bouncing.data() + begin, end - begin);
                        });
  return true;
}

void WorldImpl::storeBundles() {
  stepWorkers.forRanges(
      static_cast<int>(contacts.size()), kContactsPerBlock, [&](int begin, int end, int) {
        contactBundles.store(contacts, static_cast<size_t>(begin), static_cast<size_t>(end));
      });
}

void WorldImpl::findFastSubstepBodies() {
  // Continuous collision looks at the whole step's motion, as after a one-pass solve.
  SubstepBodies& sb = substepBodies;
  fastBodies.clear();
  fastClusters.clear();
  // In parallel, which lone bodies moved fast (each test reads its body, anywhere in memory;
  // a welded cluster's members are left to noteIfFast); then in order, the list.
  const int count = sb.dynamicCount();
  std::vector<uint8_t>& mayBeFast = scratch.mayBeFast;
  mayBeFast.resize(static_cast<size_t>(count));
  stepWorkers.forRanges(count, kBodiesPerBlock, [&](int begin, int end, int) {
    for (int e = begin; e < end; ++e) {
      const auto [first, last] = sb.clusterRows().ofRow(e);
      const BodyState& s = sb.state(e);
      mayBeFast[static_cast<size_t>(e)] =
          first != last || isFast(bodies.items[sb.start(e).slot], Vec2(s.dx, s.dy), s.turned, 0.0);
    }
  });
  for (int e = 0; e < count; ++e) {
    if (!mayBeFast[static_cast<size_t>(e)]) continue;
    const BodyState& s = sb.state(e);
    const BodyStart& start = sb.start(e);
    noteIfFast(sb.clusterRows(), e, start.slot, sb.sim(e).center0, start.angle0, Vec2(s.dx, s.dy),
               s.turned);
  }
}

// NGS passes after the sub-steps: push what still overlaps apart by moving the bodies (no
// velocity, so no energy added), until every joint is within its slop and every overlap within
// 3 slops. Each thread keeps its own verdicts: AND and min do not depend on the order.
void WorldImpl::correctSubstepPositions(const BundlePass& pass) {
  const size_t workers = static_cast<size_t>(stepWorkers.threads());
  SubstepBodies& sb = substepBodies;
  const auto visitJoints = [&](const auto& note) { visitJointErrors(note); };
  const bool guarded = positionGuard.armed();  // position_guard.hpp
  double widest = 0.0;                         // the widest joint error the last pass met
  noteFarReach();
  int passes = 0;
  for (int iteration = 0; iteration < def.positionIterations; ++iteration) {
    ++passes;
    scratch.workerVerdicts.assign(workers, {});
    auto verdictOf = [&](int worker) -> StepScratch::PassVerdict& {
      return scratch.workerVerdicts[static_cast<size_t>(worker)].value;
    };
    const auto jointPositions = [&](Joint& j, SolverBody& a, SolverBody& b, int worker) {
      const PositionError error = solveJointPosition(j, a, b);
      StepScratch::PassVerdict& verdict = verdictOf(worker);
      verdict.widest = std::max({verdict.widest, error.linear, error.angular});
      if (!error.within(def.linearSlop)) verdict.jointsOk = false;
    };
    const BundleOp contactPositions = [&](const BundlePass& p, int begin, int end, bool oneByOne,
                                          int worker) {
      double& deepest = verdictOf(worker).deepest;
      deepest = std::min(deepest, solveBundlePositions(p, begin, end, oneByOne));
    };
    if (guarded) {  // the joints' part of the pass is kept only where it closed them
      positionGuard.guardPass(
          sb.dynamicCount(), visitJoints, iteration == 0,
          [&] { scratch.guardedStates.assign(sb.states(), sb.states() + sb.dynamicCount()); },
          [&] { overColors<JointAccess::WritePoses>(jointPositions, BundleOp(), pass); },
          [&](int entry) { sb.state(entry) = scratch.guardedStates[entry]; },
          [&](size_t j) { scaleJointImpulses(solverJoints[j], 0.0); });
      overColors<JointAccess::WritePoses>(nullptr, contactPositions, pass);
    } else {
      overColors<JointAccess::WritePoses>(jointPositions, contactPositions, pass);
    }
    bool jointsOk = true;
    double deepest = 0.0;
    widest = 0.0;
    for (const OwnLine<StepScratch::PassVerdict>& verdict : scratch.workerVerdicts) {
      jointsOk = jointsOk && verdict.value.jointsOk;
      widest = std::max(widest, verdict.value.widest);
      deepest = std::min(deepest, verdict.value.deepest);
    }
    if (jointsOk && overlapsResolved(deepest, def.linearSlop)) break;
  }
  boundFarReach(passes);
  if (widest > PositionGuard::kJudgedError) {  // world_step.cpp, noteHeldOpen
    noteHeldOpenBodies(
        activeJoints, PositionGuard::kJudgedError, [&](int slot) { return sb.view(slot); },
        [&](int slot) {
          const int e = sb.entryOf(slot);
          if (!sb.isDynamicEntry(e)) return;
          const auto [first, last] = sb.clusterRows().ofRow(e);
          if (first != last) return;  // a welded cluster: its start is not a member's
          scratch.heldOpen.push_back({slot, sb.sim(e).center0, sb.start(e).angle0});
        });
  }
  positionGuard.settle(widest);
}

// A pass corrects a body by at most kMaxLinearCorrection at its centre and kMaxAngularCorrection
// of turn, and moves it without velocity; continuous collision then sweeps each member of a welded
// cluster along the chord from where it began. A cluster whose members lie metres from its centre
// swung them metres a step (soak seed 1146, substep: a 9 g body welded 11 m from its partner,
// their cluster pulled round by a prismatic joint that a teleport had opened 34 m, went 5.6-7.3 m
// a step, into the ceiling and out of the arena). So no point of a row moves further than
// 2 kMaxLinearCorrection a pass, as no point of a body reaching kLongestFreeReach (1.4 m) does
// under one constraint's caps; the move and the turn are shrunk alike:
//
//                                  o'   a pass's 8 degrees at 11 m: 1.5 m
//                              _.-'
//     [c]---------------------o         the far member
//                              `-o''    bounded: 0.4 m
//
// Only rows reaching further than kLongestFreeReach are noted: their turn can carry a point
// further than the pass moves their centre.
void WorldImpl::noteFarReach() {
  SubstepBodies& sb = substepBodies;
  scratch.farReaching.clear();
  for (int e = 0; e < sb.dynamicCount() && def.positionIterations > 0; ++e) {
    const double reach = reachOf(sb.clusterRows(), e, sb.start(e).slot);
    if (reach > kLongestFreeReach) scratch.farReaching.push_back({e, reach, sb.state(e)});
  }
}

void WorldImpl::boundFarReach(int passes) {
  for (const StepScratch::FarReach& far : scratch.farReaching) {
    BodyState& s = substepBodies.state(far.entry);
    const BodyState& before = far.before;
    const double moveX = s.dx - before.dx, moveY = s.dy - before.dy;
    const double turn = s.turned - before.turned;
    const double share = farReachShare(std::hypot(moveX, moveY), turn, far.reach, passes);
    if (share >= 1.0) continue;
    s.dx = before.dx + share * moveX;
    s.dy = before.dy + share * moveY;
    s.turned = before.turned + share * turn;
    const Rot q = Rot::fromCosSin(before.qc, before.qs) * Rot(share * turn);
    s.qc = q.c;
    s.qs = q.s;
  }
}

double WorldImpl::reachOf(const ClusterRows& rows, int row, int loneSlot) const {
  const auto [first, last] = rows.ofRow(row);
  if (first == last) return bodies.items[loneSlot].maxExtent;
  double reach = 0.0;
  for (int k = first; k < last; ++k) {
    const MemberStart& m = rows.member(k);
    reach = std::max(reach, m.offset.norm() + bodies.items[m.slot].maxExtent);
  }
  return reach;
}

}  // namespace impulse2d
