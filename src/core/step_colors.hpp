// The sub-stepping solvers' colours of one step: the active joints and the touching contacts
// coloured together (constraint_coloring.hpp), so that a colour's joints and contacts can all be
// solved at once, then the colours of few constraints folded into the overflow (assign), which is
// solved one constraint after the other. ContactBundles lays each colour's contacts into lanes; the
// joints are solved colour by colour from jointsOf().
#pragma once

#include <utility>
#include <vector>

#include "constraint_coloring.hpp"
#include "contact.hpp"
#include "step_workers.hpp"
#include "substep_bodies.hpp"

namespace impulse2d {

class StepColors {
 public:
  /// Colours the joints (slots, in the order given, with their bodies' slots) first and then the
  /// contacts (in their order). A colour's joints join the overflow when it has fewer than
  /// `minSize` constraints, its contacts when it has fewer than that and fewer than `minContacts`
  /// contacts. What each contact needs is read in parallel blocks on `workers`; the colours are
  /// given on one thread, in order.
  void assign(const std::vector<Contact>& contacts, const std::vector<int>& jointSlots,
              const std::vector<std::pair<int, int>>& jointBodies, const SubstepBodies& bodies,
              int minSize, int minContacts, StepWorkers& workers);

  /// The colours kept; the overflow is colour colorCount().
  int colorCount() const { return static_cast<int>(jointsOfColor_.size()) - 1; }
  /// The joints (slots) of a colour, in the order given; of the overflow for colorCount().
  const std::vector<int>& jointsOf(int color) const { return jointsOfColor_[color]; }
  /// A contact's colour (colorCount() for the overflow), or -1: not solved (no dynamic body
  /// it could move, no point, or inside one welded cluster).
  int colorOfContact(size_t contact) const { return colorOfContact_[contact]; }
  /// How many contacts a colour has (the overflow's for colorCount()).
  int contactsOf(int color) const { return contactCount_[color]; }

 private:
  static constexpr int kContactsPerBlock = 1024;
  struct Ends {
    int a, b;   // the dynamic entries a contact's impulses move (-1: none); both -1: not solved
    int start;  // the colour its search starts at
  };
  std::vector<Ends> ends_;                       // by contact, scratch
  std::vector<int> colorOfContact_;              // by contact
  std::vector<int> jointColor_;                  // by joint given to assign(), scratch
  std::vector<std::vector<int>> jointsOfColor_;  // by colour kept, the overflow last
  std::vector<int> contactCount_;                // by colour kept, the overflow last
  ConstraintColoring coloring_;                  // scratch
};

}  // namespace impulse2d
