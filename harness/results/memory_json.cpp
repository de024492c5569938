#include "results/memory_json.h"

#include "vk/gpu_memory.h"

namespace lb {

using nlohmann::json;

// What a scheme's frames hold; Capture, Staging and Measure are counted apart.
static constexpr GpuResource kHeld[] = {GpuResource::Heights,  GpuResource::NormalMap, GpuResource::SchemeTables,
                                        GpuResource::Geometry, GpuResource::Instances, GpuResource::LodState,
                                        GpuResource::Frame,    GpuResource::Other};
// What the LOD scheme adds over the terrain and the frame every scheme shares.
static constexpr GpuResource kLod[] = {GpuResource::SchemeTables, GpuResource::Geometry, GpuResource::Instances,
                                       GpuResource::LodState};

static json hostFields(json out, const HostPeak& host) {
  out["host_peak_bytes"] = host.bytes >= 0 ? json(host.bytes) : json(nullptr);
  out["host_peak_scope"] = host.bytes >= 0 ? json(host.sinceReset ? "case" : "process") : json(nullptr);
  out["host_reason"] = host.bytes >= 0 ? json(nullptr) : json(host.reason);
  return out;
}

json memoryJson(const GpuMemoryAccount* gpu, const std::string& gpuReason, const HostPeak& host) {
  json out = json::object();
  if (gpu) {
    json bytes = json::object();
    uint64_t total = 0, lod = 0;
    for (GpuResource r : kHeld) {
      bytes[gpuResourceName(r)] = gpu->bytes(r);
      total += gpu->bytes(r);
    }
    for (GpuResource r : kLod) lod += gpu->bytes(r);
    out["gpu_bytes"] = bytes;
    out["gpu_total_bytes"] = total;
    out["gpu_lod_bytes"] = lod;
    out["gpu_capture_bytes"] = gpu->bytes(GpuResource::Capture);
    out["gpu_reason"] = nullptr;
  } else {
    for (const char* k : {"gpu_bytes", "gpu_total_bytes", "gpu_lod_bytes", "gpu_capture_bytes"}) out[k] = nullptr;
    out["gpu_reason"] = gpuReason;
  }
  return hostFields(out, host);
}

json memoryUnknownJson(const std::string& why) {
  HostPeak host;
  host.reason = why;
  return memoryJson(nullptr, why, host);
}

}  // namespace lb
