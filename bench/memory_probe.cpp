#include "memory_probe.hpp"

#include <malloc.h>

namespace impulse2d_bench {

size_t heapBytesInUse() {
  const struct mallinfo2 info = mallinfo2();
  return info.uordblks + info.hblkhd;
}

}  // namespace impulse2d_bench
