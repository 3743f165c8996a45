// The set of contact keys (contact.hpp's contactKey) that have an arbiter, so the broad phase
// finds each pair once. Every moved shape's query meets its old neighbours again, so most lookups
// are hits: in v3_tumbler, ten thousand a step. A node-based std::unordered_set spent two or
// three cache misses on each; this open-addressing table (linear probing, one flat array) spends
// about one.
//
//   slots:  [ 0 | k7 | k3 | k9 | 0 | 0 | k2 | ... ]     0 = empty (no key is 0: bodyB > bodyA)
//   a key lives at hash(k) or in the run of filled slots right after it
//
// Erasing shifts the rest of the run back into the gap (no tombstones), so a table that churns
// stays as fast as a fresh one, and its size is bounded by the most keys it ever held.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace impulse2d {

class ContactKeySet {
 public:
  bool contains(uint64_t key) const {
    if (slots_.empty()) return false;
    for (size_t i = home(key);; i = next(i)) {
      if (slots_[i] == key) return true;
      if (slots_[i] == 0) return false;
    }
  }

  /// Adds `key` (non-zero); false when it was there already.
  bool insert(uint64_t key) {
    if (2 * (size_ + 1) > slots_.size()) grow();
    size_t i = home(key);
    for (; slots_[i] != 0; i = next(i)) {
      if (slots_[i] == key) return false;
    }
    slots_[i] = key;
    ++size_;
    return true;
  }

  void erase(uint64_t key) {
    if (slots_.empty()) return;
    size_t gap = home(key);
    for (; slots_[gap] != key; gap = next(gap)) {
      if (slots_[gap] == 0) return;  // not there
    }
    // Move back every later key of the run that may sit in the gap: one whose home is not in
    // (gap, i] going round the table.
    for (size_t i = next(gap); slots_[i] != 0; i = next(i)) {
      const size_t h = home(slots_[i]);
      const bool homeAfterGap = gap <= i ? (gap < h && h <= i) : (gap < h || h <= i);
      if (homeAfterGap) continue;
      slots_[gap] = slots_[i];
      gap = i;
    }
    slots_[gap] = 0;
    --size_;
  }

  /// A hint: the slot where a lookup of `key` starts is about to be read.
  void prefetch(uint64_t key) const {
    if (!slots_.empty()) __builtin_prefetch(&slots_[home(key)]);
  }

  size_t size() const { return size_; }

  void clear() {
    slots_.assign(slots_.size(), 0);
    size_ = 0;
  }

 private:
  // Fibonacci hashing: the key's bits mixed by an odd constant near 2^64 / golden ratio, the
  // table index from the top bits (the low bits of a key are its shape indices, mostly 0).
  size_t home(uint64_t key) const {
    return static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
  }
  size_t next(size_t i) const { return (i + 1) & (slots_.size() - 1); }

  void grow() {
    std::vector<uint64_t> old;
    old.swap(slots_);
    const size_t capacity = old.empty() ? 64 : 2 * old.size();
    slots_.assign(capacity, 0);
    shift_ = 64;
    for (size_t c = capacity; c > 1; c >>= 1) --shift_;
    size_ = 0;
    for (const uint64_t key : old) {
      if (key != 0) insert(key);
    }
  }

  std::vector<uint64_t> slots_;  // a power of two long, at most half full
  size_t size_ = 0;
  int shift_ = 64;
};

}  // namespace impulse2d
