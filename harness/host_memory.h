#pragma once
// The process's peak host memory (Linux: the resident set's high-water mark, VmHWM), which a case
// resets at its start so its figure is its own peak, not the sweep's.
#include <cstdint>
#include <string>

namespace lb {

struct HostPeak {
  int64_t bytes = -1;       // -1: unknown, `reason` says why
  bool sinceReset = false;  // true: since the last resetHostPeak(); false: since the process started
  std::string reason;
};

// Sets the high-water mark to the resident set now (/proc/self/clear_refs "5"). False where the
// kernel does not allow it (the next hostPeak() then covers the whole process).
bool resetHostPeak();
HostPeak hostPeak(bool sinceReset);

}  // namespace lb
