#include "step_colors.hpp"

#include "constraint_coloring.hpp"

#include <algorithm>

namespace impulse2d {
namespace {

// A constraint takes the first colour free for both its bodies at or after a colour picked by a
// hash of its key among the first kColorSpread. Plain first fit in key order gives every body its
// contacts in the same pattern (a box's left support before its right one, across the whole
// pile), and Gauss-Seidel in such a systematic order leans tall piles over: the 5050-box pyramid
// moved 1.9 m sideways in 300 steps; spread over 8 colours it moves 7 mm (12 colours in all).
constexpr int kColorSpread = 8;

int startColor(uint64_t key) {
  key ^= key >> 33;
  key *= 0xff51afd7ed558ccdull;
  key ^= key >> 33;
  return static_cast<int>(key % kColorSpread);
}

}  // namespace

void StepColors::assign(const std::vector<Contact>& contacts, const std::vector<int>& jointSlots,
                        const std::vector<std::pair<int, int>>& jointBodies,
                        const SubstepBodies& bodies, int minSize, int minContacts,
                        StepWorkers& workers) {
  ConstraintColoring& coloring = coloring_;  // kept: a step allocated it anew
  coloring.reset(bodies.dynamicCount());
  constexpr int kOverflowIndex = ConstraintColoring::kMaxColors;  // the overflow's, in `count`
  colorOfContact_.resize(contacts.size());
  jointColor_.resize(jointSlots.size());
  int count[kOverflowIndex + 1] = {};  // constraints, joints and contacts
  int contactCount[kOverflowIndex + 1] = {};
  auto dynamicEntry = [&](int slot) {
    const int entry = bodies.entryOf(slot);
    return bodies.isDynamicEntry(entry) ? entry : -1;
  };
  for (size_t k = 0; k < jointSlots.size(); ++k) {
    const int color =
        coloring.assign(dynamicEntry(jointBodies[k].first), dynamicEntry(jointBodies[k].second),
                        startColor(static_cast<uint64_t>(jointSlots[k]) << 32));
    jointColor_[k] = color == ConstraintColoring::kOverflow ? kOverflowIndex : color;
    ++count[jointColor_[k]];
  }
  // What the colouring needs of each contact, in parallel: reading a contact and its bodies'
  // entries waits on memory at each (two thirds of v3_many_pyramids' 1.2 ms colouring stage, on
  // one thread while the others waited). Then the colours, in contact order, on one thread.
  ends_.resize(contacts.size());
  workers.forRanges(
      static_cast<int>(contacts.size()), kContactsPerBlock, [&](int begin, int end, int) {
        for (size_t i = static_cast<size_t>(begin); i < static_cast<size_t>(end); ++i) {
          const Contact& contact = contacts[i];
          Ends& e = ends_[i];
          e.a = e.b = -1;  // not solved, unless:
          if (contact.manifold.pointCount == 0) continue;
          const int dynamicA = dynamicEntry(contact.bodyA), dynamicB = dynamicEntry(contact.bodyB);
          if (dynamicA < 0 && dynamicB < 0) continue;  // asleep, or between bodies no impulse moves
          if (dynamicA == dynamicB) continue;          // two members of one welded cluster
          e = {dynamicA, dynamicB, startColor(contact.key)};
        }
      });
  for (size_t i = 0; i < contacts.size(); ++i) {
    const Ends& e = ends_[i];
    colorOfContact_[i] = -1;
    if (e.a < 0 && e.b < 0) continue;
    const int color = coloring.assign(e.a, e.b, e.start);
    colorOfContact_[i] = color == ConstraintColoring::kOverflow ? kOverflowIndex : color;
    ++count[colorOfContact_[i]];
    ++contactCount[colorOfContact_[i]];
  }
  // The colours kept are numbered in order, the overflow last. A colour's contacts are solved
  // side by side from minContacts on: a chain of contacts one at a time (a stack: each waits for
  // the last) took longer than its colours' half-empty bundles. Its joints need minSize
  // constraints in the colour, or go one by one in the overflow, in their order: a chain of
  // joints (a bridge) converges along it that way, and opened twice as wide in colours.
  auto keepsJoints = [&](int color) { return color < kOverflowIndex && count[color] >= minSize; };
  int kept[kOverflowIndex + 1];  // each colour's number among the colours kept, or -1
  int keptCount = 0;
  for (int color = 0; color < kOverflowIndex; ++color) {
    kept[color] = keepsJoints(color) || contactCount[color] >= minContacts ? keptCount++ : -1;
  }
  kept[kOverflowIndex] = keptCount;
  auto numberOf = [&](int color) { return kept[color] < 0 ? keptCount : kept[color]; };
  jointsOfColor_.resize(static_cast<size_t>(keptCount) + 1);
  for (std::vector<int>& list : jointsOfColor_) list.clear();
  for (size_t k = 0; k < jointSlots.size(); ++k) {
    const int color = jointColor_[k];
    jointsOfColor_[keepsJoints(color) ? kept[color] : keptCount].push_back(jointSlots[k]);
  }
  contactCount_.assign(static_cast<size_t>(keptCount) + 1, 0);
  for (int& color : colorOfContact_) {
    if (color < 0) continue;
    color = numberOf(color);
    ++contactCount_[color];
  }
}

}  // namespace impulse2d
