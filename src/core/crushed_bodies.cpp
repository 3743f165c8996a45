#include "crushed_bodies.hpp"

#include <algorithm>
#include <cmath>

namespace impulse2d {

// A body pressed into overlaps from opposite sides by bodies the step does not move (static,
// kinematic, asleep) cannot leave them. Baumgarte's pushes out of each overlap cannot all be met,
// so the iterations and the warm starts grow their impulses without bound, step after step (the
// core soak saw 4,400 N s on a 1 kg rod wedged between two stopped kinematic bodies), until
// one of the contacts drops and the others fling the body out (157 m/s). Such a body's contacts
// with them get no push, only what stops it going deeper: that set can be met. The soft step's
// springs (contact_kernels.cpp) do the same by turning the body: where its contact points
// let it turn out of both overlaps at once, the pushes from both sides are a couple, and the
// warm starts handed it on sub-step after sub-step (soak seed 469 under `soft`: a body 0.54 m
// thick, 21 cm deep, 0.2 -> 123 rad/s in one step).
//
//      ///// still /////           the pushes into the body from the
//         n1 |  v                 bodies that do not move oppose
//        +---------+              (more than 120 degrees apart):
//        |  body   |              crushed
//        +---------+
//         n2 ^  |
//      ///// still /////
//
// The same holds for a row of moving bodies pressed into each other between two still ones (seed
// 526: a thin box 0.25 m inside another, the pair wedged between two still bodies, 2,300 N s
// each way):
//
//      ///// still /////
//         +---------+
//         |  moving |  <- the still body's push, handed on
//         +--+---+--+     through the overlap below
//            | moving |
//      ///// still /////
//
// Bodies are weighed by solver row: the members of a welded cluster are one rigid body, and
// pushes on two of its members oppose as pushes on one (seed 1752: a welded pair between the
// ground and a body asleep, 3,000 N s). Each push on a body is weighed against every earlier one
// kept, not only the first: a bar held by three still bodies from 24, 143 and 229 degrees
// (seed 1586) has one opposed pair, and the push met first need not be in it. So is a push
// handed on by a row of moving bodies (seed 2327, below: pressedBack).
//
// A still body's push is handed on, body to body, through overlaps that press
// onward (within 60 degrees of it); where two pushes from opposite sides (more than 120 degrees
// apart) meet, every body along both rows is crushed, and the contacts between them get no push
// either.
void CrushedBodies::meet(const Contact& contact, int rowA, int rowB) {
  // Sized for every row handOnPushes reads, so that no reference into it moves there.
  auto ensureBacking = [&](int row) {
    const size_t needed = static_cast<size_t>(row) + 1;
    if (backing_.size() < needed) backing_.resize(needed);
  };
  const Vec2& normal = contact.manifold.normal;
  if (rowA >= 0 && rowB >= 0) {
    if (rowA == rowB) return;  // two members of one welded cluster
    ensureBacking(std::max(rowA, rowB));
    pressedPairs_.push_back({rowA, rowB, normal});
    return;
  }
  if (rowA < 0 && rowB < 0) return;
  // Pushes from still bodies, those met on each body (pushes are unit vectors), and the
  // twelfths of the circle they point into.
  const int row = rowA >= 0 ? rowA : rowB;
  const Vec2 push = rowA >= 0 ? Vec2(-normal) : normal;  // into the body that moves
  sectors_ |= 1u << sectorOf(push);
  ensureBacking(row);
  Backing& backing = backing_[static_cast<size_t>(row)];
  if (!backing.pushed()) backedRows_.push_back(row);
  bool opposes = false;
  for (int i = 0; i < backing.count; ++i) opposes |= backing.pushes[i].dot(push) < -0.5;
  if (opposes) crushed_.mark(row);
  // Kept either way: a row of moving bodies may press against it (pressedBack).
  if (backing.count < kKeptPushes) backing.pushes[backing.count++] = push;
}

void CrushedBodies::handOnPushes() {
  // Handed on through the moving pairs, one body further each round (deterministic: contact
  // order), until nothing changes; a row longer than the rounds is left alone. Only where two
  // still bodies push from opposite sides can a row be crushed (a pile on the ground is not:
  // its pushes all point up, and the rounds would cost a large pyramid a quarter of its step).
  if (mayOppose(sectors_)) {
    // Marks the body in `row` and those that handed it its push, back to the still body.
    auto crushAlong = [&](int row) {
      for (int hops = 0; row != kStill && hops <= kHandOnRounds; ++hops) {
        crushed_.mark(row);
        row = backing_[static_cast<size_t>(row)].from;
      }
    };
    for (int round = 0; round < kHandOnRounds && !pressedPairs_.empty(); ++round) {
      bool handedOn = false;
      for (const PressedPair& pair : pressedPairs_) {
        Backing& backedA = backing_[static_cast<size_t>(pair.a)];
        Backing& backedB = backing_[static_cast<size_t>(pair.b)];
        const bool aPressesB = backedA.pushed() && backedA.first().dot(pair.normal) > 0.5;
        const bool bPressesA = backedB.pushed() && backedB.first().dot(pair.normal) < -0.5;
        if ((aPressesB && pressedBack(backedA.first(), backedB, pair.normal)) ||
            (bPressesA && pressedBack(backedB.first(), backedA, Vec2(-pair.normal)))) {
          crushAlong(pair.a);
          crushAlong(pair.b);
        } else if (aPressesB && !backedB.pushed()) {
          backedB = backed(backedA.first(), pair.a);
          backedRows_.push_back(pair.b);
          handedOn = true;
        } else if (bPressesA && !backedA.pushed()) {
          backedA = backed(backedB.first(), pair.b);
          backedRows_.push_back(pair.a);
          handedOn = true;
        }
      }
      if (!handedOn) break;
    }
  }
  for (const int row : backedRows_) backing_[static_cast<size_t>(row)] = Backing();
  backedRows_.clear();
}

// Whether a push pressing across an overlap (along `normal`, into `other`) meets one kept on the
// other body that presses back, more than 120 degrees from it: any of them, not only the first
// (seed 2327: a bar crushed between two still bodies, pressed by a third body's row against one
// of them, 0.16 m deep, at 250 N s).
bool CrushedBodies::pressedBack(const Vec2& push, const Backing& other, const Vec2& normal) {
  bool found = false;
  for (int i = 0; i < other.count; ++i) {
    const Vec2& q = other.pushes[i];
    found |= q.dot(normal) < -0.5 && q.dot(push) < -0.5;
  }
  return found;
}

// Which twelfth of the circle a unit vector points into: 0 from -pi (and 0 for one not finite).
int CrushedBodies::sectorOf(const Vec2& direction) {
  const double twelfths = (std::atan2(direction.y(), direction.x()) + kPi) / (kPi / 6.0);
  if (!(twelfths > 0.0)) return 0;  // before the cast: a NaN or negative int is undefined
  return std::min(static_cast<int>(twelfths), 11);
}

// Whether two pushes in the marked twelfths may be more than 120 degrees apart (dot < -0.5):
// twelfths four or more apart around the circle hold such pairs (their far edges 150 degrees);
// three apart at most 120.
bool CrushedBodies::mayOppose(unsigned sectors) {
  for (int i = 0; i < 12; ++i) {
    if (!(sectors & (1u << i))) continue;
    for (int j = i + 4; j <= i + 8; ++j) {
      if (sectors & (1u << (j % 12))) return true;
    }
  }
  return false;
}

}  // namespace impulse2d
