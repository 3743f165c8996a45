// The world's internals: slot storage for bodies and joints, the broad phase and the arbiters.
// world.cpp holds the public API and bookkeeping; world_step.cpp the step pipeline.
#pragma once

#include "contact.hpp"
#include "contact_bundles.hpp"
#include "contact_key_set.hpp"
#include "contact_solver.hpp"
#include "distance.hpp"
#include "dynamic_tree.hpp"
#include "joint.hpp"
#include "joint_lanes.hpp"
#include "position_guard.hpp"
#include "solver_body.hpp"
#include "stage_clock.hpp"
#include "step_workers.hpp"
#include "substep_bodies.hpp"
#include "warm_start_guard.hpp"
#include "weld_clusters.hpp"

#include <impulse2d/world.hpp>

#include <algorithm>
#include <functional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace impulse2d {

/// Fat boxes are this much larger than their shapes, so a body that moves a little does not touch
/// the tree at all.
constexpr double kAabbMargin = 0.1;
/// Parallel stages take contacts, and bodies, in blocks of this many.
constexpr int kContactsPerBlock = 256;
constexpr int kBodiesPerBlock = 256;
/// The pair search takes moved proxies in blocks of this many: a query costs as much as
/// refitting a few dozen bodies.
constexpr int kProxiesPerBlock = 64;

/// Slot storage: stable indices, a generation per slot to reject stale handles, and a free list
/// so that create/destroy churn reuses memory instead of growing.
template <class T>
struct Slots {
  std::vector<T> items;
  std::vector<uint32_t> generation;
  std::vector<char> alive;
  std::vector<int> freeList;

  int acquire() {
    if (!freeList.empty()) {
      const int index = freeList.back();
      freeList.pop_back();
      alive[index] = 1;
      return index;
    }
    items.emplace_back();
    generation.push_back(1);
    alive.push_back(1);
    return static_cast<int>(items.size()) - 1;
  }
  void release(int index) {
    items[index] = T();
    alive[index] = 0;
    ++generation[index];
    freeList.push_back(index);
  }
  bool isAlive(int index, uint32_t gen) const {
    return index >= 0 && index < static_cast<int>(items.size()) && alive[index] &&
           generation[index] == gen;
  }
  size_t count() const { return items.size() - freeList.size(); }
};

/// A body the solver moves this step: dynamic and awake.
inline bool isActive(const Body& body) { return body.type == BodyType::Dynamic && body.awake; }
/// Keeps xf consistent with the centre of mass and angle after a body was moved.
inline void syncTransform(Body& body) {
  body.xf.q = Rot(body.angle);
  body.xf.p = body.center - body.xf.q.apply(body.localCenter);
}
/// A body whose motion can disturb others: awake and not static.
inline bool isMoving(const Body& body) {
  return body.type == BodyType::Dynamic
             ? body.awake
             : body.type == BodyType::Kinematic &&
                   (body.linearVelocity.squaredNorm() > 0.0 || body.angularVelocity != 0.0);
}

/// A broad-phase proxy's user data names its shape: body slot << 8 | shape index (the 8 bits hold
/// kMaxShapesPerBody, limits.hpp).
inline int64_t proxyData(int slot, int shape) {
  return (static_cast<int64_t>(slot) << 8) | static_cast<int64_t>(shape);
}
inline int proxySlot(int64_t userData) { return static_cast<int>(userData >> 8); }
inline int proxyShape(int64_t userData) { return static_cast<int>(userData & 0xff); }

/// What the pair search reads of a proxy of `tree` before it reads any body: its shape's filter,
/// and whether that shape is its body's only one. Two such proxies whose filters refuse each other
/// are a pair shouldCollide() refuses too (it keeps a pair of bodies when any two of their shapes
/// may touch), found without reading either body: v3_rain's ragdolls meet their own parts' fat
/// boxes 17,000 times a step, each refused by the ragdoll's group.
struct ProxyFilter {
  CollisionFilter filter;
  bool onlyShape = false;
};

/// What the world keeps of a body besides what users read of it (Body): the broad phase's
/// bookkeeping and whether it was reported lost.
struct BodyBookkeeping {
  std::vector<int> proxies;        // the broad-phase proxy of each shape
  std::vector<int> staticProxies;  // a static body's: each shape's proxy in staticTree too
  /// Where the body was when the fat boxes of all its shapes were last placed: while it has
  /// moved less than their margin since, no shape can have left its box.
  Transform proxyXf;
  bool lost = false;  // reported lost for good (World::takeLostBodies), not back since
};

/// A body deeper in a static one than it may be (keep_out_of_static.cpp).
struct DeepStatic {
  int slot, contact;
  Vec2 n;  // the contact's normal when the step began, out of the static body
};

/// Two shapes whose fat boxes began to overlap, and which may touch (world_step.cpp).
struct NewPair {
  uint64_t key;               // contactKey
  int slotA, shapeA, proxyA;  // slotA < slotB
  int slotB, shapeB, proxyB;
};

/// A value on a cache line of its own: what threads write at once, each its own (a vector's
/// header grows with every push), must not share a line, or each write takes the line from the
/// other threads (v3_spinner's pair search ran as long on two threads as on one).
template <class T>
struct alignas(64) OwnLine {
  T value{};
};

/// The buffers the step's stages reuse, so that a warm step allocates nothing: scratch, each
/// stage's own, meaningless between steps.
struct StepScratch {
  // Broad phase (world_step.cpp): by block, the proxies that left their fat boxes and the new
  // pairs their queries found; by worker, a tree query's stack; all new pairs, merged.
  std::vector<OwnLine<std::vector<std::pair<int, Aabb>>>> refits;
  std::vector<OwnLine<std::vector<NewPair>>> newPairs;
  std::vector<OwnLine<std::vector<int>>> queryStacks;
  std::vector<NewPair> freshPairs;
  // Sub-steps' colouring (world_substeps.cpp): the active joints' slots, colour after colour.
  std::vector<int> jointOrder;
  // Continuous collision (continuous.cpp): by fast body, the first impact of one that is not a
  // bullet (found in parallel); by dynamic entry, whether it may have moved fast (sub-steps).
  std::vector<double> fastImpacts;
  std::vector<uint8_t> mayBeFast;
  // Both solver paths: the joints the warm-start guard looks at.
  std::vector<Joint*> guardedJoints;
  // One-pass solvers (world_step.cpp): by dynamic entry, its centre and angle as the step began.
  std::vector<std::pair<Vec2, double>> onePassStarts;
  TurnCaps turnCaps;  // the one-pass solvers' (motion_limits.hpp)
  // Bodies of joints left far open by the position passes, with their start (noteHeldOpen).
  struct HeldOpen {
    int slot;
    Vec2 center0;
    double angle0;
  };
  std::vector<HeldOpen> heldOpen;
  // Sub-steps' NGS passes (world_substeps.cpp): by worker, its verdicts on the pass: whether
  // every joint it solved was within the slop, the widest joint error and the deepest overlap.
  struct PassVerdict {
    bool jointsOk = true;
    double widest = 0.0, deepest = 0.0;
  };
  std::vector<OwnLine<PassVerdict>> workerVerdicts;
  // Both NGS paths' guard (position_guard.hpp): the moving bodies' rows before the passes.
  std::vector<BodyState> guardedStates;
  std::vector<SolverBody> guardedBodies;
  // The far-reaching rows before the position passes (world_substeps.cpp, boundFarReach): the
  // sub-stepping solvers' states, the one-pass solvers' bodies.
  struct FarReach {
    int entry;
    double reach;
    BodyState before;
  };
  std::vector<FarReach> farReaching;
  struct OnePassFarReach {
    int entry;
    double reach;
    SolverBody before;
  };
  std::vector<OnePassFarReach> onePassFarReaching;
  // Baumgarte's split joints (world_step.cpp, splitStressedJoints): their slots.
  std::vector<int> splitJoints;
  // Keeping out of static bodies (keep_out_of_static.cpp): the deep bodies, and by block of
  // contacts those it found; by welded cluster, its first push out this step.
  std::vector<DeepStatic> deepStatic;
  std::vector<OwnLine<std::vector<DeepStatic>>> deepStaticOfBlock;
  std::vector<Vec2> clusterPush;
  // Sleeping (island_sleep.cpp). By movable place: the islands' union-find links, what a link to
  // the body does, whether a moving kinematic body holds the body; by island root: whether a body
  // is awake, how long all have been still. wakeStack: the bodies wakeJointedSleepers has still to
  // go on from.
  std::vector<int> islandParent, wakeStack;
  std::vector<uint8_t> islandKind, islandHeld, islandAwake;
  std::vector<double> islandStillFor;
  // By block of contacts, read in parallel: the bodies (slots) of the overlaps too deep to rest,
  // and the touching contacts' pairs of movable bodies (places), which the islands link.
  struct SleepContacts {
    std::vector<std::pair<int, int>> deep, links;
  };
  std::vector<OwnLine<SleepContacts>> sleepContactsOfBlock;
  // Lost bodies (world_bounds.cpp): by movable place, why a body leaves (null: it stays) and
  // how low it reaches; the candidates, their marks by body slot, a joined group.
  std::vector<std::pair<const char*, RemovalCause>> escapes;
  std::vector<double> lostTops, kinematicBottoms;  // by movable place, by block
  std::vector<int> lostCandidates, candidatesInComponent;
  std::vector<char> lostCandidateMark;
  std::vector<int> lostGroup;
};

/// The body at the other end of each of a body's joints, in jointsOfBody's order, for every body
/// in one array, and the bodies' jointed components (bodies that joints join, directly or not;
/// a body without joints is one alone): the lost-body search walks a hanging grid's joints every
/// step, and a list per body plus a jointBodies lookup per joint waited on memory at each
/// (v3_joint_grid: 3.5 % of its step). Rebuilt at the first use after the joints changed
/// (refresh(), in world_bounds.cpp with its one user).
class JointNeighbours {
 public:
  void invalidate() { valid_ = false; }
  void refresh(const std::vector<std::vector<int>>& jointsOfBody,
               const std::vector<std::pair<int, int>>& jointBodies);
  /// The other ends of the joints of the body in `slot` (after refresh()).
  const int* begin(int slot) const { return others_.data() + start_[static_cast<size_t>(slot)]; }
  const int* end(int slot) const { return others_.data() + start_[static_cast<size_t>(slot) + 1]; }
  /// The body's component, and how many bodies (slots, of any type) it has.
  int componentOf(int slot) const { return component_[static_cast<size_t>(slot)]; }
  int componentSize(int component) const { return componentSize_[static_cast<size_t>(component)]; }
  int componentCount() const { return static_cast<int>(componentSize_.size()); }

 private:
  bool valid_ = false;
  std::vector<int> start_;  // by body slot, and one past the last
  std::vector<int> others_;
  std::vector<int> component_, componentSize_, stack_;
};

struct WorldImpl {
  WorldDef def;
  bool profiling = false;
  StepProfile profile;  // the last profiled step's (World::profile)
  /// Where a stage's clock adds its time: a field of `profile`, or null while profiling is off.
  double* stage(double StepProfile::*field) { return profiling ? &(profile.*field) : nullptr; }
  StepProfile* profiled() { return profiling ? &profile : nullptr; }
  Slots<Body> bodies;
  std::vector<BodyBookkeeping> bookkeeping;  // by body slot
  /// The slots of living bodies that are not static (types never change), ascending, and each
  /// slot's place in that list (-1: static or free). The per-step scans go through this list, in
  /// slot order as before, so static bodies (a map's walls) cost a step nothing.
  std::vector<int> movableSlots;
  std::vector<int> movableIndex;
  void addMovable(int slot);
  void removeMovable(int slot);
  bool isMovable(int slot) const {
    return slot < static_cast<int>(movableIndex.size()) && movableIndex[slot] >= 0;
  }
  Slots<Joint> joints;
  std::vector<JointDef> jointDefs;  // by joint slot: as created (names), for World::jointDef
  std::vector<std::vector<int>> jointsOfBody;  // by body slot
  // By joint slot, its bodies' slots (A, B): the walks over joints that each step makes (which
  // are active, islands, lost bodies) read these 8 bytes instead of a 624-byte Joint's first
  // line (v3_joint_grid's 19,800 joints: a cache miss each, five walks a step).
  std::vector<std::pair<int, int>> jointBodies;
  JointNeighbours jointNeighbours;  // invalidated wherever jointsOfBody changes
  int rigidWelds = 0;               // living rigid welds (isRigidWeld): without any, no body merges
  std::unordered_map<std::string, int> bodyByName;
  std::unordered_map<std::string, int> jointByName;
  size_t shapeCount = 0;  // over all living bodies, against kMaxShapes

  DynamicTree tree;
  // The static shapes again, on their own: what continuous collision sweeps a body that is not a
  // bullet against. In the one tree, a fast box in a pile walked past every moving neighbour to
  // find none static (a quarter of v3_tumbler's step, which has no static shape at all).
  DynamicTree staticTree;
  std::vector<int> movedProxies;
  std::vector<char> proxyMoved;           // by proxy id
  std::vector<ProxyFilter> proxyFilters;  // by proxy id of `tree`
  /// Whether the shapes of two proxies of `tree` may never touch, told by their filters alone.
  bool filtersRefuse(int proxyA, int proxyB) const {
    const ProxyFilter& a = proxyFilters[static_cast<size_t>(proxyA)];
    const ProxyFilter& b = proxyFilters[static_cast<size_t>(proxyB)];
    return a.onlyShape && b.onlyShape && !filtersAllowContact(a.filter, b.filter);
  }

  std::vector<Contact> contacts;  // solved in this order
  ContactKeySet contactKeys;      // the keys of `contacts`: a pair is found once
  // Contacts of destroyed bodies (bodyA = bodyB = -1), still in `contacts` until the next step
  // or edit drops them: one compaction for a batch of deletions instead of one each (v3_rain
  // destroys dozens of bodies at a time among ten thousand contacts).
  size_t deadContacts = 0;
  static bool isDead(const Contact& c) { return c.bodyA < 0; }
  void dropDeadContacts() {
    if (deadContacts == 0) return;
    contacts.erase(std::remove_if(contacts.begin(), contacts.end(), isDead), contacts.end());
    deadContacts = 0;
  }

  // The one-pass solvers (baumgarte, ngs) work on these, not on `bodies`.
  SolverBodies solverBodies;
  ContactSolver contactSolver;
  // The sub-stepping solvers (world_substeps.cpp) on these, on the step's threads.
  SubstepBodies substepBodies;
  StepColors stepColors;
  ContactBundles contactBundles;
  CrushedBodies crushedBodies;  // the soft step's, this step
  StepWorkers stepWorkers;
  std::vector<std::pair<int, int>> activeJointBodies;  // by active joint: its bodies' slots
  // The sub-stepping solvers' active joints, colour after colour (copies). After a step they,
  // not joints.items, hold those joints' impulses and rows (heldJointOrder lists their slots):
  // the next step that colours the same joints in the same order, with no joint edited between,
  // solves them where they are, and neither the copy in nor the copy back runs (a tenth of
  // v3_joint_grid's step). What joints.items holds of a joint's definition (bodies, params,
  // anchors, reference angle) is always current; syncJoints() writes the rest back before
  // anything edits a joint or colours them in another order.
  std::vector<Joint> solverJoints;
  std::vector<int> heldJointOrder;  // solverJoints' slots while they hold the joints; else empty
  std::vector<int> jointStart;      // colour c's in solverJoints: [jointStart[c], [c + 1])
  // The revolute joints of the colours in SIMD lanes, under `substep` (joint_lanes.hpp):
  // filled as the sub-steps begin, written back into solverJoints after them.
  JointLanes jointLanes;
  bool jointLanesFilled = false;
  JointLaneArgs jointLaneArgs;
  std::vector<uint8_t> contactFates;  // the narrow phase's verdict, by contact
  // Continuous collision's bodies and clusters of this step (continuous.cpp).
  struct FastBody {  // moved farther than the speculative margin this step
    int slot;
    Vec2 startCenter;
    double startAngle;
    int cluster;  // into fastClusters when a member of a welded cluster, else -1
  };
  std::vector<FastBody> fastBodies;
  // A welded cluster's rigid motion this step: its members are swept together, and stopped
  // together at the first impact of any of them.
  struct FastCluster {
    Vec2 pivot0;    // its centre of mass when the step began
    Vec2 move;      // how far the centre moved
    double turn;    // rad
    double impact;  // the earliest impact of any member, as a fraction of the step (1: none)
  };
  std::vector<FastCluster> fastClusters;
  WeldClusters weldClusters;  // this step's (weld_clusters.hpp)
  WarmStartGuard warmStartGuard;
  PositionGuard positionGuard;       // of the NGS passes and soft's bias (position_guard.hpp)
  bool anyFeedbackWithheld = false;  // some joint's this step (Joint::feedbackWithheld)
  std::vector<int> activeJoints;     // joints with an awake dynamic body, this step
  StepScratch scratch;
  double time = 0.0;
  uint64_t steps = 0;

  // Broad phase bookkeeping (world.cpp).
  void createProxies(int slot);
  void destroyProxies(int slot);
  void markMoved(int proxy);
  bool movedThisStep(int proxy) const {
    return proxy < static_cast<int>(proxyMoved.size()) && proxyMoved[proxy];
  }
  /// Refits the fat boxes of a body whose shapes left them; forced = after a teleport.
  void updateProxies(int slot, bool forced);
  /// Marks the contacts of the body in `bodySlot` dead (the next step drops them, see
  /// deadContacts) and wakes the bodies they touched (v3_rain destroys a column of ragdolls
  /// every eighth step).
  void destroyContactsOf(int bodySlot);
  /// Removes the contacts `pred` selects, keeping the others in order (and dead ones with them).
  template <class Pred>
  void eraseContactsIf(Pred pred) {
    size_t write = 0;
    for (size_t read = 0; read < contacts.size(); ++read) {
      if (isDead(contacts[read])) continue;
      if (pred(contacts[read])) {
        contactKeys.erase(contacts[read].key);
        continue;
      }
      if (write != read) contacts[write] = contacts[read];
      ++write;
    }
    contacts.resize(write);
    deadContacts = 0;
  }
  bool shouldCollide(int bodyA, int bodyB) const;
  void wakeBody(Body& body);

  // The step pipeline (world_step.cpp).
  void gatherSolverBodies();  // one-pass solvers: welded clusters found, bodies copied
  void storeMotion();         // one-pass solvers: the solved motion written back
  void updateBroadPhase();
  void findNewContacts();
  void updateContacts();
  void prefetchPairAhead(size_t i, size_t last) const;
  void integrateVelocities(double dt);
  void solve(double dt);
  void solveSubsteps(double dt);
  // The sub-stepping solvers' passes (world_substeps.cpp): an operation on one joint (with
  // scalar views of its bodies) and one on a range of contact bundles, each told its worker.
  // An operation on one joint is any callable (Joint&, SolverBody&, SolverBody&, int worker),
  // passed as a template argument: with a std::function call and out-of-line body views per
  // joint visit, v3_joint_grid's relax pass took 14.0 ms a step instead of 10.2.
  using BundleOp =
      std::function<void(const BundlePass&, int begin, int end, bool oneByOne, int worker)>;
  /// What a pass's joint op reads and writes of the joint's bodies.
  enum class JointAccess {
    Velocities,  // reads and writes velocities only (velocityView)
    ReadPoses,   // reads the poses too, writes velocities
    WritePoses,  // reads and writes poses and velocities (the position passes)
  };
  /// Asks for the memory that the joints a few places after k (before end) will read; with
  /// `geometry`, their anchors too (the passes that prepare the rows).
  void prefetchJointAhead(int k, int end, bool geometry) const;
  /// Runs op on solverJoints[index] and writes back what it changed of its bodies.
  template <JointAccess access, class JointOp>
  void onJoint(int index, int worker, const JointOp& op);
  /// One pass over every colour's joints (none for a null op) and bundles, then the overflow's;
  /// bundleOp may be empty. While the joint lanes are filled (jointLanesFilled), a colour's
  /// joints in lanes run `lanePass` instead of jointOp.
  template <JointAccess access, class JointOp>
  void overColors(const JointOp& jointOp, const BundleOp& bundleOp, const BundlePass& pass,
                  JointLanePass lanePass = JointLanePass::Solve);
  /// One colour's joints in a pass while the lanes are filled: its bundles run `lanePass`, its
  /// other joints jointOp.
  template <JointAccess access, class JointOp>
  void overLaneColor(int color, const JointOp& jointOp, JointLanePass lanePass);
  /// A position pass over a colour's joint bundle: in the kernels, or jointOp on each lane's
  /// joint where the bundle has limits. The errors go to the worker's scratch.workerVerdicts, as
  /// correctSubstepPositions' jointOp does.
  template <class JointOp>
  void positionLanes(const JointLaneArgs& args, int bundle, int worker, const JointOp& jointOp);
  /// Runs a joint-lane position kernel (kernel(widest, within) returns how many joints it took)
  /// into the worker's verdict: the widest error, and jointsOk cleared where one was not within.
  template <class Kernel>
  int intoVerdict(int worker, const Kernel& kernel);
  /// The lanes of bundles [begin, end) whose warm start the kernels left to the scalar path.
  void warmStartScalarLanes(int begin, int end);
  // solveSubsteps' stages, in order.
  /// The active joints and the contacts coloured together, the joints copied colour by colour.
  void colorConstraints();
  /// Writes the joints that solverJoints holds back to their slots (heldJointOrder); a no-op
  /// when it holds none. Before a joint is edited, created or destroyed.
  void syncJoints();
  /// The bundles' pass parameters for sub-steps of h seconds.
  BundlePass bundlePass(double h);
  /// The warm-start guard, then the contacts into their lanes.
  void fillBundles(double dt, int substeps, bool soft);
  /// Before a sub-step's warm start: the bouncing bundles' approach speeds (noteBundleApproaches).
  /// False when no bundle bounces.
  bool noteApproaches(const BundlePass& pass);
  /// The step's summed impulses back into the contacts.
  void storeBundles();
  void correctSubstepPositions(const BundlePass& pass);
  /// Before the position passes: the rows whose farthest point a pass could swing further than
  /// it moves their centre (scratch.farReaching); after them (`passes` run), each such row's
  /// correction shrunk until no point of it moved further than 2 kMaxLinearCorrection a pass.
  void noteFarReach();
  void boundFarReach(int passes);
  /// The same for the one-pass solvers' position passes (world_step.cpp).
  void noteOnePassFarReach();
  void boundOnePassFarReach(int passes);
  /// How far the row's farthest shape point lies from its centre (m): a lone body's (in
  /// `loneSlot`) maxExtent, or a welded cluster's farthest member's.
  double reachOf(const ClusterRows& rows, int row, int loneSlot) const;
  // The position guard (position_guard.hpp, world_position_guard.cpp).
  using JointErrorNote = std::function<void(int entryA, int entryB, double squaredError)>;
  /// The solving joints in the order of this step's solver (colour order or slot order), each
  /// with its bodies' dynamic entries (-1 for a body not moved) and its squared error now.
  void visitJointErrors(const JointErrorNote& note);
  /// The same for the one-pass solvers' joints in these slots.
  void visitOnePassJointErrors(const std::vector<int>& slots, const JointErrorNote& note);
  /// The soft step, as its sub-steps begin and after them: a group whose joints opened wider
  /// solves its next step without bias.
  void measureSoftStepStart();
  void withholdFeedbackOfWorseGroups();
  /// Baumgarte: the joints of groups open wider than joints that can all hold (PositionGuard's
  /// judged groups) are solved without bias, their bodies' contacts without push, and the
  /// joints are closed by guarded NGS passes after the positions move (correctPositions).
  void splitStressedJoints();
  /// What the one-pass solvers' NGS passes do besides moving the joints they are given.
  struct PositionPasses {
    bool guarded = false;        // each pass's joint corrections kept only where they closed
    bool forgetImpulses = true;  // ... and the joint impulses of a group they opened forgotten
    bool contacts = true;        // each pass also pushes overlapping contacts apart
  };
  /// Up to positionIterations passes over the joints in `slots` (and the contacts); returns the
  /// widest joint error the last pass met.
  double runPositionPasses(const std::vector<int>& slots, const PositionPasses& passes);
  /// After the one-pass solvers' passes over `slots`: the dynamic bodies of the joints still
  /// open wider than `open` (m or rad; 0: every one), for dropMotionUndone (world_step.cpp).
  void noteHeldOpen(const std::vector<int>& slots, double open);
  /// Once nothing else moves them this step: those bodies keep no more velocity than the motion
  /// the step left them.
  void dropMotionUndone();
  /// noteHeldOpen on either path: viewOf(slot) is a joint's view of a body, note(slot) notes the
  /// body if it is one to note (dynamic, not in a welded cluster).
  template <class ViewOf, class Note>
  void noteHeldOpenBodies(const std::vector<int>& slots, double open, ViewOf viewOf, Note note) {
    for (const int j : slots) {
      const Joint& joint = joints.items[j];
      if (open > 0.0) {
        const PositionError error =
            jointPositionError(joint, viewOf(joint.bodyA), viewOf(joint.bodyB));
        if (!(std::max(error.linear, error.angular) > open)) continue;
      }
      note(joint.bodyA);
      note(joint.bodyB);
    }
  }
  /// The bodies that moved farther than the speculative margin, for continuous collision.
  void findFastSubstepBodies();
  /// Lists the joints the step solves (both solver paths): those with a body for which
  /// moves(slot) holds, except welds inside a welded cluster (one rigid body already); without
  /// warm starting their kept impulses are dropped.
  template <class Moves>
  void collectActiveJoints(Moves moves) {
    activeJoints.clear();
    for (size_t j = 0; j < joints.items.size(); ++j) {
      if (!joints.alive[j]) continue;
      const auto [bodyA, bodyB] = jointBodies[j];
      if (!moves(bodyA) && !moves(bodyB)) continue;
      if (weldClusters.joins(bodyA, bodyB)) continue;
      activeJoints.push_back(static_cast<int>(j));
      if (!def.warmStarting) {
        Joint& joint = joints.items[j];
        joint.pairImpulse.setZero();
        joint.motorImpulse = joint.lowerImpulse = joint.upperImpulse = 0.0;
      }
    }
  }
  /// The turn caps (motion_limits.hpp, TurnCaps) of the active joints' dynamic bodies:
  /// entryOf(slot) is a body's dynamic entry of `entries` (-1: none), centerOf(entry) its centre
  /// of mass as the step began.
  template <class EntryOf, class CenterOf>
  void capTurnsByJointReach(TurnCaps& caps, int entries, const MotionLimits& limits,
                            EntryOf entryOf, CenterOf centerOf) const {
    caps.clear();
    for (const int j : activeJoints) {
      const Joint& joint = joints.items[j];
      for (const auto& [slot, anchor] : {std::pair(joint.bodyA, joint.localAnchorA),
                                         std::pair(joint.bodyB, joint.localAnchorB)}) {
        const int entry = entryOf(slot);
        if (entry < 0) continue;
        const Vec2 arm = bodies.items[slot].xf.apply(anchor) - centerOf(entry);
        caps.note(entry, entries, arm.norm(), limits);
      }
    }
  }
  /// Prepares the active joints for a pass of time step dt with the given feedback.
  void prepareJoints(const Feedback& fb, double dt);
  void warmStartJoints();
  void solveJointVelocities(double dt);
  /// Runs op(joint, viewA, viewB) on each active joint of the one-pass solvers and writes back
  /// what it changed of its bodies (the poses too when `pose`).
  template <class Op>
  void onActiveJoints(Op op, bool pose);
  void integratePositions(double dt);
  void correctPositions();
  /// Whether a body that moved by `move` and turned by `turn` (about a point `arm` from its centre
  /// of mass) moved far enough to skip past something: continuous collision sweeps it.
  bool isFast(const Body& body, const Vec2& move, double turn, double arm) const;
  /// The one-pass solvers' fast bodies, from the whole step's motion of each dynamic entry.
  void findOnePassFastBodies();
  /// Continuous collision's candidates from one solver row's motion this step (both solver
  /// paths): the body in `slot` alone, or the welded cluster of the row (`rows`), swept whole
  /// when any member moved fast. center0 and angle0: the row's centre of mass and angle when the
  /// step began.
  void noteIfFast(const ClusterRows& rows, int row, int slot, const Vec2& center0, double angle0,
                  const Vec2& move, double turn);
  void keepOutOfStatic();  // keep_out_of_static.cpp, with the helpers below
  std::pair<const Shape*, const Shape*> staticPair(const Contact& contact) const;
  double staticDepth(const Contact& contact, const Vec2& n) const;
  double allowedDepth(const Contact& contact) const;
  void pushOut(int slot, const Vec2& push, const Vec2& n);
  bool escapeSeam(const DeepStatic* begin, const DeepStatic* end);
  void solveContinuous();
  /// The fast body's motion this step, from its start pose to where the solver left it.
  Sweep sweepOf(const FastBody& fast) const;
  /// The first time of impact (0-1) of that sweep with what the body must not pass through; a
  /// tree query on `stack`.
  double firstImpact(const FastBody& fast, std::vector<int>& stack) const;
  void wakeJointedSleepers();
  void updateSleep(double dt);
  void clearForces();
  // Bodies that left kWorldExtent or stopped being finite (world_bounds.cpp).
  std::vector<RemovedBody> removedBodies;  // since the last World::takeRemovedBodies()
  uint64_t removedBodyCount = 0;
  std::vector<int> overflowedBodies;  // slots whose velocity overflowed this step (step stage 4)
  // Lost bodies (world_bounds.cpp): the static bodies' bounding box, kept until they change.
  std::vector<LostBody> lostBodies;  // since the last World::takeLostBodies()
  uint64_t lostBodyCount = 0;
  bool staticBoundsStale = true;
  bool hasStaticBodies = false;
  Aabb staticBounds;
  void staticBodiesChanged() { staticBoundsStale = true; }
  void refreshStaticBounds();
  /// Reports the bodies lost for good, or adds them to `removeLost` with def.removeLostBodies.
  void findLostBodies(std::vector<RemovedBody>* removeLost);
};

}  // namespace impulse2d
