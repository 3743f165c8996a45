// Colours for the step's constraints: no two constraints of one colour share a body the solver
// moves, so a colour's constraints can be solved at once (in SIMD lanes, on several threads) with
// the result of solving them one after the other in any order. Static and kinematic bodies do not
// count: no impulse changes them, and nothing writes them back.
//
// First fit from a start colour, in the order the constraints come (sorted contact keys), so the
// colouring depends only on which constraints exist, never on threads or timing. Each body keeps
// a mask of the colours its constraints took; a constraint takes the lowest colour free in both
// masks at or after its start colour (or, when none is, the lowest free one):
//
//   box 7 used 0b0101, box 9 used 0b0011  ->  free: ~(0b0111)  ->  start 0: colour 3
//
// The caller picks the start (step_colors.cpp: by a hash of the constraint's key, which keeps
// Gauss-Seidel from a systematic order; plain first fit is start 0).
// A body with more constraints than colours sends the rest to the overflow, solved one by one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace impulse2d {

class ConstraintColoring {
 public:
  static constexpr int kMaxColors = 24;
  static constexpr int kOverflow = -1;

  /// Forgets every colour; bodies are numbered [0, bodyCount).
  void reset(int bodyCount) { used_.assign(static_cast<size_t>(bodyCount), 0u); }

  /// The colour of a constraint between bodies a and b (-1: a body that does not count).
  int assign(int a, int b, int start = 0) {
    const uint32_t taken = (a >= 0 ? used_[a] : 0u) | (b >= 0 ? used_[b] : 0u);
    const uint32_t all = (1u << kMaxColors) - 1u;
    const uint32_t free = ~taken & all;
    if (free == 0u) return kOverflow;
    // The first free colour at or after `start`, else the first free one.
    const uint32_t after = free & (all << start);
    const int color = __builtin_ctz(after != 0u ? after : free);
    if (a >= 0) used_[a] |= 1u << color;
    if (b >= 0) used_[b] |= 1u << color;
    return color;
  }

 private:
  std::vector<uint32_t> used_;  // by body
};

}  // namespace impulse2d
