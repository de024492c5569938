// Linked into the camera_path and config fuzz targets (and their replay drivers). The CSV reader
// (fccp's io::LineReader, harness/camera/camera_path.cpp) allocates a fixed 48 MiB buffer
// (3 x 2^24) per parse, whatever the input's size. Under ASan each such allocation maps fresh
// memory and its shadow and poisons 6 MiB of shadow on free: ~40 ms per execution, 771
// executions in 30 s. This keeps one such block for the process and hands it out again:
//  - while handed out, only the prefix the reader can touch is unpoisoned: LineReader copies the
//    input (n bytes, < 2^25) to the buffer's start and reads one byte past it (next_line() tests
//    buffer[data_end] before line_end != data_end), so [0, n] suffices (at least kPrefix is
//    opened; where n is unknown, the whole block). Any access beyond stays poisoned and is
//    reported, which is stricter than plain ASan (no report for reading uninitialised memory);
//  - once released the block is poisoned again, so a use after free is still reported (as
//    use-after-poison), and the redzone after the malloc'd block still catches overflows.
// Other array allocations go to the scalar operator new/delete: lost is only ASan's report of a
// new[] freed with scalar delete, which no parser code does (they use std containers).
// Without ASan it only defines lbFuzzInputSize.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define LB_FCCP_POOL 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define LB_FCCP_POOL 1
#endif

#ifdef LB_FCCP_POOL
#include <sanitizer/asan_interface.h>

namespace {
constexpr size_t kFccpBuffer = size_t(3) << 24;  // io::LineReader: new char[3 * block_len], block_len = 2^24
constexpr size_t kPrefix = size_t(1) << 20;
void* block = nullptr;
bool inUse = false;
size_t openBytes = 0;  // bytes unpoisoned while handed out
}  // namespace

// The size of the CSV a target is about to parse (bytes); the prefix is at least one past it.
// Unknown (the config target, whose configs load CSV files): the whole block is opened.
size_t lbFuzzInputSize = SIZE_MAX;

void* operator new[](size_t n) {
  if (n == kFccpBuffer && !inUse) {
    if (!block) {
      if (!(block = std::calloc(1, kFccpBuffer))) throw std::bad_alloc();
      ASAN_POISON_MEMORY_REGION(block, kFccpBuffer);
    }
    inUse = true;
    openBytes = lbFuzzInputSize >= kFccpBuffer  ? kFccpBuffer
                : lbFuzzInputSize + 1 > kPrefix ? lbFuzzInputSize + 1
                                                : kPrefix;
    ASAN_UNPOISON_MEMORY_REGION(block, openBytes);
    return block;
  }
  return ::operator new(n);
}

void operator delete[](void* p) noexcept {
  if (p && p == block) {
    // Back to zeros, as the fresh mapping a 48 MiB allocation gets everywhere else: the reader
    // tests buffer[data_end], one past the input, before it checks the end, and a '\n' left there
    // by an earlier input sent it scanning past the end (found by the long fuzz run; harmless
    // outside this pool, where that byte is always 0).
    std::memset(block, 0, openBytes);
    ASAN_POISON_MEMORY_REGION(block, openBytes);
    inUse = false;
    return;
  }
  ::operator delete(p);
}

void operator delete[](void* p, size_t) noexcept {
  operator delete[](p);
}
#else
size_t lbFuzzInputSize = SIZE_MAX;
#endif
