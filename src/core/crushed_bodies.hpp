// Bodies crushed between bodies the step does not move (crushed_bodies.cpp): their overlaps
// with them cannot all be pushed out, so those contacts get no push, only what stops them going
// deeper. Baumgarte's velocity bias (contact_solver.cpp) and the soft step's springs
// (contact_bundles.cpp) both read it.
#pragma once

#include "contact.hpp"

#include <impulse2d/math.hpp>

#include <vector>

namespace impulse2d {

class CrushedBodies {
 public:
  /// Marks (by slot) the bodies pressed into overlaps from opposite sides by bodies the step
  /// does not move, directly or through a row of moving bodies. `moves(slot)`: whether the step
  /// moves the body (dynamic and awake). Forgets the last call's marks.
  template <class Moves>
  void find(const std::vector<Contact>& contacts, const Moves& moves);
  /// Whether the contact presses a crushed body against a body the step does not move or
  /// against another crushed body. `moves` as find's.
  template <class Moves>
  bool pressesCrushed(const Contact& contact, const Moves& moves) const {
    if (crushed_.marked.empty()) return false;
    const bool crushedA = crushed_.has(contact.bodyA), crushedB = crushed_.has(contact.bodyB);
    return (crushedA && (crushedB || !moves(contact.bodyB))) || (crushedB && !moves(contact.bodyA));
  }
  bool any() const { return !crushed_.marked.empty(); }

  // Marks by slot for one step, with the slots marked listed so that clearing touches only them.
  struct SlotMarks {
    void mark(int slot) {
      const size_t k = static_cast<size_t>(slot);
      if (bySlot.size() <= k) bySlot.resize(k + 1, 0);
      if (!bySlot[k]) marked.push_back(slot);
      bySlot[k] = 1;
    }
    bool has(int slot) const {
      const size_t k = static_cast<size_t>(slot);
      return k < bySlot.size() && bySlot[k];
    }
    void clear() {
      for (const int slot : marked) bySlot[static_cast<size_t>(slot)] = 0;
      marked.clear();
    }
    std::vector<char> bySlot;
    std::vector<int> marked;
  };

 private:
  /// The first pass of find: one overlap, seen by whether the step moves its bodies.
  void meet(const Contact& contact, bool movesA, bool movesB);
  /// The rest of find, once every overlap has been met.
  void handOnPushes();
  static int sectorOf(const Vec2& direction);
  static bool mayOppose(unsigned sectors);

  // By slot, the first push from a still body a moving body meets, directly (from kStill) or
  // handed on by the moving body `from` (the still body's push).
  static constexpr int kStill = -1;
  static constexpr int kHandOnRounds = 8;  // the longest row of moving bodies handed a push
  struct Backing {
    Vec2 push = Vec2::Zero();
    int from = kStill;
    bool pushed = false;
  };
  std::vector<Backing> backing_;
  std::vector<int> backedSlots_;  // the slots set in it, to clear only them
  struct PressedPair {
    int a, b;
    Vec2 normal;  // from a to b
  };
  std::vector<PressedPair> pressedPairs_;  // overlaps between two moving bodies
  unsigned sectors_ = 0;                   // the twelfths of the circle still bodies push into
  SlotMarks crushed_;
};

template <class Moves>
void CrushedBodies::find(const std::vector<Contact>& contacts, const Moves& moves) {
  crushed_.clear();  // last step's
  pressedPairs_.clear();
  sectors_ = 0;
  for (const Contact& contact : contacts) {
    const Manifold& m = contact.manifold;
    bool overlapping = false;
    for (int i = 0; i < m.pointCount; ++i) overlapping |= m.points[i].separation < 0.0;
    if (overlapping) meet(contact, moves(contact.bodyA), moves(contact.bodyB));
  }
  handOnPushes();
}

}  // namespace impulse2d
