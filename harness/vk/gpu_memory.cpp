#include "vk/gpu_memory.h"

#include <atomic>

namespace lb {

static std::array<std::atomic<uint64_t>, kGpuResources>& processLive() {
  static std::array<std::atomic<uint64_t>, kGpuResources> live{};
  return live;
}

const char* gpuResourceName(GpuResource r) {
  switch (r) {
    case GpuResource::Heights:
      return "heights";
    case GpuResource::NormalMap:
      return "normal_map";
    case GpuResource::SchemeTables:
      return "scheme_tables";
    case GpuResource::Geometry:
      return "geometry";
    case GpuResource::Instances:
      return "instances";
    case GpuResource::LodState:
      return "lod_state";
    case GpuResource::Frame:
      return "frame";
    case GpuResource::Other:
      return "other";
    case GpuResource::Capture:
      return "capture";
    case GpuResource::Staging:
      return "staging";
    case GpuResource::Measure:
      return "measure";
    case GpuResource::Count:
      break;
  }
  return "?";
}

MemoryCharge::MemoryCharge(MemoryTag tag, uint64_t bytes) : tag_(tag), bytes_(bytes) {
  processLive()[size_t(tag_.resource)] += bytes_;
  if (tag_.account) tag_.account->live[size_t(tag_.resource)] += bytes_;
}

MemoryCharge& MemoryCharge::operator=(MemoryCharge&& o) noexcept {
  if (this != &o) {
    reset();
    tag_ = o.tag_;
    bytes_ = std::exchange(o.bytes_, 0);
  }
  return *this;
}

void MemoryCharge::reset() {
  if (bytes_ == 0) return;
  processLive()[size_t(tag_.resource)] -= bytes_;
  if (tag_.account) tag_.account->live[size_t(tag_.resource)] -= bytes_;
  bytes_ = 0;
}

uint64_t gpuBytesLive(GpuResource r) {
  return processLive()[size_t(r)];
}

}  // namespace lb
