// The sub-stepping solvers' contacts, eight at a time. The contacts of one colour
// (constraint_coloring.hpp) are packed into bundles of kBundleLanes lanes, structure of arrays,
// so that a SIMD kernel (contact_kernels.cpp) solves a bundle's lanes at once: 2, 4 or 8 doubles
// a register, whatever the processor, on the same layout. A bundle holds only what every pass
// reads; what restitution, the relax totals and storing read is in BundleExtra.
//
// Each lane is one contact of up to two points. A point is held as an anchor on each body,
// measured from its centre of mass in the world's orientation when the step began:
//
//        aA  ->  * <-  aB         the manifold point, seen from both centres (aA = aB + cB - cA)
//   cA  o               o  cB
//
// Through the sub-steps the separation follows the anchors turned with their bodies,
//   s = baseSeparation + n . (dB - dA + qB aB - qA aA),
// while the rows act at one point of both bodies, the anchors moved by half their bodies'
// relative move, rA = aA + (dB - dA) / 2 and rB = aB - (dB - dA) / 2: equal and opposite impulses
// at one point keep angular momentum (with an anchor of its own on each body they would not).
// The shift is bounded (maxShift) where it would make the step-start masses overshoot.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "contact.hpp"
#include "crushed_bodies.hpp"
#include "feedback.hpp"
#include "step_colors.hpp"
#include "substep_bodies.hpp"

#include <impulse2d/defs.hpp>

namespace impulse2d {

constexpr int kBundleLanes = 8;

// ContactBundle::laneFlags: a two-point lane too ill-conditioned for the block (its points are
// solved in turn); a lane that may bounce; one whose other body cannot move (the soft step's
// spring is stiffer there); a lane of two points; one that presses a crushed body
// (crushed_bodies.hpp: the soft step's biased pass does not push it out).
enum : uint8_t {
  kSequentialLane = 1,
  kRestitutionLane = 2,
  kAgainstStaticLane = 4,
  kTwoPointLane = 8,
  kNoPushLane = 16
};

struct BundlePoint {
  double anchorAx[kBundleLanes], anchorAy[kBundleLanes];             // m, from A's centre of mass
  double anchorBx[kBundleLanes], anchorBy[kBundleLanes];             // m, from B's centre of mass
  double normalImpulse[kBundleLanes], tangentImpulse[kBundleLanes];  // N s, accumulated
};

// Effective masses and the like only set how fast the iterations converge, not what they
// conserve (impulses, masses, anchors and normals stay doubles: both bodies of a row take the
// same impulse at the same point), so they are kept as floats: the sweeps stream these bundles
// from memory, and a smaller bundle is a faster sweep.
struct ContactBundle {
  ContactBundle() {}  // fill() and finishFill() write every field of every lane: no zeroing
  // BodyState offsets (row * kStateDoubles) of each lane's bodies; a lane that must not write
  // its body back (static, kinematic, an empty lane) holds ~offset.
  alignas(64) int32_t offsetA[kBundleLanes];
  int32_t offsetB[kBundleLanes];
  double invMassA[kBundleLanes], invInertiaA[kBundleLanes];
  double invMassB[kBundleLanes], invInertiaB[kBundleLanes];
  double normalX[kBundleLanes], normalY[kBundleLanes];
  BundlePoint points[2];
  float friction[kBundleLanes];
  // The two normal rows' 2x2 block K: K12 and the inverse (the diagonal is the points' normal
  // masses' inverse). A one-point lane has K12 = 0 and inverse (1 / K11, 0, 0).
  float k12[kBundleLanes];
  float inverse11[kBundleLanes], inverse12[kBundleLanes], inverse22[kBundleLanes];
  float baseSeparation[2][kBundleLanes];  // m, the separation minus n . (aB - aA): see above
  float normalMass[2][kBundleLanes], tangentMass[2][kBundleLanes];  // kg; 0: an absent point
  alignas(64) int laneCount;
  bool anySequential;  // of the lanes, summed up by finishFill()
  bool anyRestitution;
  bool anyNoPush;
  uint8_t laneFlags[kBundleLanes];  // kSequentialLane, kRestitutionLane, ... (above)
  // m, the largest shift of the lever arms (half the relative move along n and along t) for
  // which no row's K grows by more than half: the masses above were computed at the step's start,
  // and a row whose K has doubled would overshoot at every iteration. Bodies that move apart fast
  // (a small body pinched and spun by a motor) reach it; resting and sliding ones never do.
  alignas(32) float maxShift[kBundleLanes];  // aligned for one 8-float load
};
static_assert(sizeof(ContactBundle) % 64 == 0 && alignof(ContactBundle) == 64, "whole lines");

// Only the totals are kept for every lane; restitution's fields only in bundles that bounce,
// the diagonal only for the soft step (the fill writes no more than the step reads).
struct alignas(64) BundleExtra {
  BundleExtra() {}  // as ContactBundle
  double restitution[kBundleLanes];
  double approach[2][kBundleLanes];  // m/s, the lowest normal speed before a warm start
  double maxNormalImpulse[2][kBundleLanes];
  double totalNormalImpulse[2][kBundleLanes], totalTangentImpulse[2][kBundleLanes];
  double k[2][kBundleLanes];  // K11, K22 (the soft step's springs scale with them)
};

/// One pass of a kernel over some bundles.
struct BundlePass {
  ContactBundle* bundles = nullptr;
  BundleExtra* extras = nullptr;
  double* states = nullptr;  // SubstepBodies::states(), as doubles
  int32_t sinkOffset = 0;    // this worker's sink row * kStateDoubles
  double h = 0.0, inverseH = 0.0;
  bool useBias = false;  // the soft step's push (springs of dynamicSoft and staticSoft)
  bool relax = false;    // add this pass's impulses to the step's totals
  double maxPushVelocity = 0.0;
  Feedback dynamicSoft, staticSoft;
  double restitutionThreshold = 0.0;
  // Position pass (NGS).
  double baumgarte = 0.0, linearSlop = 0.0, maxLinearCorrection = 0.0;
};

/// The colours' bundles of one step, built from the touching contacts of moving bodies.
class ContactBundles {
 public:
  /// Colours of fewer constraints than this, and fewer contacts than kMinColorContacts, join the
  /// overflow (StepColors::assign): two bundles' worth, and half a bundle.
  static constexpr int kMinColorSize = 2 * kBundleLanes;
  static constexpr int kMinColorContacts = kBundleLanes / 2;
  /// Gives each contact that `colors` solves its lane, colour after colour, then the overflow,
  /// whose bundles are solved one lane after the other. On one thread.
  void assign(const std::vector<Contact>& contacts, const StepColors& colors);
  /// Fills the lanes of the contacts [first, last) as the step begins, reading the contacts in
  /// order; impulses are the arbiters' whole-step ones divided among `substeps`. What follows
  /// from the lane alone (masses, block, shift) is left to finishFill. `crushed`, when given,
  /// marks the lanes that press a crushed body (kNoPushLane).
  void fill(std::vector<Contact>& contacts, size_t first, size_t last, const SubstepBodies& bodies,
            const std::vector<Body>& items, int substeps, const CrushedBodies* crushed);
  /// After fill(), for the bundles [begin, end): the lanes no contact took, then the masses of
  /// every lane (SIMD, prepareBundleMasses), then each bundle's summary flags.
  void finishFill(int begin, int end, const SubstepBodies& bodies, bool soft);
  /// After finishFill(): lists the bundles with a lane that may bounce (bouncing()).
  void collectBouncing();
  /// Writes the step's summed impulses of the contacts [first, last) back into them.
  void store(std::vector<Contact>& contacts, size_t first, size_t last) const;

  int colorCount() const { return static_cast<int>(colorStart_.size()) - 1; }
  int colorBegin(int color) const { return colorStart_[color]; }
  int colorEnd(int color) const { return colorStart_[color + 1]; }
  int overflowBegin() const { return colorStart_.back(); }
  int bundleCount() const { return static_cast<int>(bundles_.size()); }
  size_t contactCount() const { return contactCount_; }
  const std::vector<int>& bouncing() const { return bouncing_; }

  BundlePass pass(SubstepBodies& bodies) {
    BundlePass p;
    p.bundles = bundles_.data();
    p.extras = extras_.data();
    p.states = &bodies.states()->vx;
    return p;
  }

 private:
  std::vector<ContactBundle> bundles_;
  std::vector<BundleExtra> extras_;
  std::vector<int> colorStart_;  // bundles of colour c: [colorStart_[c], colorStart_[c + 1])
  std::vector<int> laneOf_;      // by contact: bundle * kBundleLanes + lane, or -1: not solved
  std::vector<int> rank_;        // by colour, scratch of assign(): its contacts placed so far
  std::vector<int> bouncing_;    // the bundles with anyRestitution, in order
  size_t contactCount_ = 0;
};

// --- the SIMD kernels (contact_kernels.cpp), over the bundles [begin, end) ---
// Colour bundles are solved lane-parallel, overflow bundles (`oneByOne`) one lane at a time.

void warmStartBundles(const BundlePass& pass, int begin, int end, bool oneByOne);
/// One iteration: friction, then both normal rows (rigid, or the soft step's push).
void solveBundles(const BundlePass& pass, int begin, int end, bool oneByOne);
/// Lowers each point's approach speed to its normal speed now, in the listed bundles: before
/// each sub-step's warm start (restitution reads it).
void noteBundleApproaches(const BundlePass& pass, const int* bundles, int count);
/// Bounces points that approached faster than the threshold, once, after the sub-steps.
void restituteBundles(const BundlePass& pass, int begin, int end, bool oneByOne);
/// One non-linear Gauss-Seidel pass on positions; returns the deepest separation measured.
double solveBundlePositions(const BundlePass& pass, int begin, int end, bool oneByOne);
/// Each lane's masses, block and largest shift (ContactBundles::finishFill).
void prepareBundleMasses(ContactBundle* bundles, BundleExtra* extras, int begin, int end,
                         bool soft);
// The kernels' instruction set is chosen through include/impulse2d/simd.hpp.

}  // namespace impulse2d
