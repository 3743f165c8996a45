// Heap bytes in use, from glibc's allocator statistics (mallinfo2): everything the process holds
// through malloc, calloc and operator new, which is how all three engines allocate.
#pragma once

#include <cstddef>

namespace impulse2d_bench {

/// Bytes currently allocated from the heap (arena blocks in use plus mmap-ed blocks).
size_t heapBytesInUse();

}  // namespace impulse2d_bench
