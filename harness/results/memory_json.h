#pragma once
// A case's memory (docs/results-format.md, "memory"): the device memory its renderer held by
// resource, the capture buffers apart, and the process's peak host memory. Unknown values are
// null with the reason beside them, never 0.
#include <nlohmann/json.hpp>
#include <string>

#include "host_memory.h"

namespace lb {

struct GpuMemoryAccount;

// gpu null: gpuReason says why there is no device figure.
nlohmann::json memoryJson(const GpuMemoryAccount* gpu, const std::string& gpuReason, const HostPeak& host);
// The record of a case that ended before its memory was taken (failed, skipped).
nlohmann::json memoryUnknownJson(const std::string& why);

}  // namespace lb
