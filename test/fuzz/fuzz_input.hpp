// Reads typed values off a fuzzer's byte string, front to back; past the end every read gives
// zero, so a harness never needs to check the length. (Clang 14 on Debian ships no
// FuzzedDataProvider header.)
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace impulse2d {
namespace fuzz {

class FuzzInput {
 public:
  FuzzInput(const uint8_t* data, size_t size) : data_(data), size_(size) {}

  bool empty() const { return offset_ >= size_; }

  uint8_t byte() { return offset_ < size_ ? data_[offset_++] : 0; }

  uint16_t u16() { return static_cast<uint16_t>(byte() | (byte() << 8)); }

  /// Any double, NaN and inf included: the raw bits of the next eight bytes.
  double rawDouble() {
    uint64_t bits = 0;
    for (int i = 0; i < 8; ++i) bits |= uint64_t(byte()) << (8 * i);
    double value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }

  /// A finite double in [lo, hi] on a grid of 65536 steps.
  double inRange(double lo, double hi) { return lo + (hi - lo) * (u16() / 65535.0); }

  /// Mostly ordinary values in [lo, hi]; one read in 16 is raw bits (NaN, inf, huge, tiny), so
  /// both the checks and the code behind them are exercised.
  double number(double lo, double hi) {
    return (byte() & 0x0f) == 0 ? rawDouble() : inRange(lo, hi);
  }

  /// Up to `maxLength` bytes as a string (any byte value).
  std::string text(size_t maxLength) {
    const size_t length = std::min<size_t>(byte(), maxLength);
    std::string out;
    for (size_t i = 0; i < length && !empty(); ++i) out += static_cast<char>(byte());
    return out;
  }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t offset_ = 0;
};

/// Stops the run with a message libFuzzer saves the input for (abort() is a crash to it).
[[noreturn]] inline void fail(const char* what) {
  std::fprintf(stderr, "fuzz property violated: %s\n", what);
  std::abort();
}

#define IMPULSE2D_FUZZ_CHECK(cond)               \
  do {                                           \
    if (!(cond)) ::impulse2d::fuzz::fail(#cond); \
  } while (0)

}  // namespace fuzz
}  // namespace impulse2d
