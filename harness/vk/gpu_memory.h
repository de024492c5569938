#pragma once
// Device memory as a result: every allocation the create helpers (vk/resources.h) make is charged,
// at creation, to a resource kind and to the account of its owner (a renderer), for exactly the
// bytes the device asked for (VkMemoryRequirements::size); the charge is given back when the
// buffer or image is released. Driver-internal memory (pipelines, pools, command buffers) is not
// seen here.
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>

namespace lb {

// What an allocation holds (docs/results-format.md, "memory"). Capture, staging and measurement
// are counted apart from what a scheme's frames need.
enum class GpuResource : uint8_t {
  Heights,       // the height image(s)
  NormalMap,     // the shading normal map with its mips
  SchemeTables,  // a scheme's own tables: scheme texture, scheme buffer, mesh strip table
  Geometry,      // patch grid and footprint meshes, patch bounds and records
  Instances,     // instance records
  LodState,      // GPU LOD state kept across frames and its indirect arguments
  Frame,         // render targets, uniforms, placeholder buffers
  Other,         // allocated without a tag
  Capture,       // measurement capture and read-back buffers of a renderer
  Staging,       // transient upload and download buffers
  Measure,       // measurement passes' own buffers (ray cast, reductions)
  Count
};
constexpr int kGpuResources = int(GpuResource::Count);
// The field name of a kind: "heights", "normal_map", "scheme_tables", ...
const char* gpuResourceName(GpuResource r);

// Live bytes by kind of one owner's allocations.
struct GpuMemoryAccount {
  std::array<uint64_t, kGpuResources> live{};
  uint64_t bytes(GpuResource r) const { return live[size_t(r)]; }
};

// Which kind an allocation is and whose: the last argument of every create helper.
struct MemoryTag {
  GpuResource resource = GpuResource::Other;
  GpuMemoryAccount* account = nullptr;  // null: counted process-wide only
};

// Bytes charged to a tag while this lives (move-only, like the objects it accompanies).
class MemoryCharge {
 public:
  MemoryCharge() = default;
  MemoryCharge(MemoryTag tag, uint64_t bytes);
  ~MemoryCharge() { reset(); }
  MemoryCharge(MemoryCharge&& o) noexcept : tag_(o.tag_), bytes_(std::exchange(o.bytes_, 0)) {}
  MemoryCharge& operator=(MemoryCharge&& o) noexcept;
  MemoryCharge(const MemoryCharge&) = delete;
  MemoryCharge& operator=(const MemoryCharge&) = delete;
  void reset();
  uint64_t bytes() const { return bytes_; }
  GpuResource resource() const { return tag_.resource; }

 private:
  MemoryTag tag_;
  uint64_t bytes_ = 0;
};

// Live bytes of a kind over every owner in the process: a test releases everything and checks
// that this comes back to where it started.
uint64_t gpuBytesLive(GpuResource r);

}  // namespace lb
