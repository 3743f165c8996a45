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
  /// Marks (by solver row) the bodies pressed into overlaps from opposite sides by bodies the
  /// step does not move, directly or through a row of moving bodies. `rowOf(slot)`: the solver
  /// row of a body the step moves (dynamic and awake), which the members of a welded cluster
  /// share (they are one rigid body: pushes on two members oppose as on one body), or -1.
  /// Forgets the last call's marks.
  template <class RowOf>
  void find(const std::vector<Contact>& contacts, const RowOf& rowOf);
  /// Whether the contact presses a crushed body against a body the step does not move or
  /// against another crushed body. `rowOf` as find's.
  template <class RowOf>
  bool pressesCrushed(const Contact& contact, const RowOf& rowOf) const {
    if (crushed_.marked.empty()) return false;
    const int rowA = rowOf(contact.bodyA), rowB = rowOf(contact.bodyB);
    const bool crushedA = rowA >= 0 && crushed_.has(rowA);
    const bool crushedB = rowB >= 0 && crushed_.has(rowB);
    return (crushedA && (crushedB || rowB < 0)) || (crushedB && rowA < 0);
  }
  bool any() const { return !crushed_.marked.empty(); }

  // Marks by slot (or row) for one step, with those marked listed so that clearing touches only
  // them.
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
  /// The first pass of find: one overlap, seen by the rows of its bodies (-1: still).
  void meet(const Contact& contact, int rowA, int rowB);
  /// The rest of find, once every overlap has been met.
  void handOnPushes();
  struct Backing;
  static bool pressedBack(const Vec2& push, const Backing& other, const Vec2& normal);
  static int sectorOf(const Vec2& direction);
  static bool mayOppose(unsigned sectors);

  // By row, the pushes from still bodies a moving body meets, up to kKeptPushes of them in the
  // order met: directly (from kStill), or the one handed on by the moving body `from`. Each new
  // push is weighed against every one kept (crushed_bodies.cpp, seed 1586); the first is the one
  // handed on.
  static constexpr int kStill = -1;
  static constexpr int kHandOnRounds = 8;  // the longest row of moving bodies handed a push
  static constexpr int kKeptPushes = 4;
  struct Backing {
    Vec2 pushes[kKeptPushes];
    int count = 0;
    int from = kStill;
    bool pushed() const { return count > 0; }
    const Vec2& first() const { return pushes[0]; }
  };
  static Backing backed(const Vec2& push, int from) {
    Backing backing;
    backing.pushes[0] = push;
    backing.count = 1;
    backing.from = from;
    return backing;
  }
  std::vector<Backing> backing_;
  std::vector<int> backedRows_;  // the rows set in it, to clear only them
  struct PressedPair {
    int a, b;
    Vec2 normal;  // from a to b
  };
  std::vector<PressedPair> pressedPairs_;  // overlaps between two moving bodies (rows)
  unsigned sectors_ = 0;                   // the twelfths of the circle still bodies push into
  SlotMarks crushed_;
};

template <class RowOf>
void CrushedBodies::find(const std::vector<Contact>& contacts, const RowOf& rowOf) {
  crushed_.clear();  // last step's
  pressedPairs_.clear();
  sectors_ = 0;
  for (const Contact& contact : contacts) {
    const Manifold& m = contact.manifold;
    bool overlapping = false;
    for (int i = 0; i < m.pointCount; ++i) overlapping |= m.points[i].separation < 0.0;
    if (overlapping) meet(contact, rowOf(contact.bodyA), rowOf(contact.bodyB));
  }
  handOnPushes();
}

}  // namespace impulse2d
