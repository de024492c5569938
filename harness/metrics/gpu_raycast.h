#pragma once
// The ray-cast ground truth (metrics/raycast.h) as a compute pass, shaders/raycast.comp: the same
// rays (pixelRay), the same max-mipmap traversal and exact bilinear-cell intersection (castRay), the
// same shading (shadeTerrain), one thread per pixel. Where the device has shaderFloat64 the ray and
// the intersection run in double with the CPU's operation order and no fused multiply-add, so the
// image and distances are the CPU oracle's (tests/test_gpu_raycast.cpp counts what differs);
// elsewhere raycast_f32.comp runs the same in float (usesDouble() says which).
#include <vulkan/vulkan.h>

#include <vector>

#include "camera/camera_path.h"
#include "metrics/image_metrics.h"
#include "render/gpu_profiler.h"
#include "terrain/page_layout.h"
#include "vk/resources.h"

namespace lb {

struct Context;
struct Heightfield;

struct GpuRaycastOptions {
  bool allowDouble = true;  // false: the float shader even where the device has shaderFloat64
  int testDropLevels = 0;   // tests only: the pyramid built this many levels short of 1 x 1 (a planted defect)
};

// One per Context and Heightfield: uploads the heights, every max-mipmap level (one buffer) and the
// normal map once. Throws FeatureMissing when the terrain exceeds what the shader or the device's
// storage buffers take.
class GpuRaycast {
 public:
  GpuRaycast(Context& ctx, const Heightfield& hf, const GpuRaycastOptions& options = {});
  // Ray casts `pose` at width x height into `rgba` (width * height uint32, bytes R, G, B, A as the
  // renderer's RGBA8 read-back, kClearRgba on a miss) and `distance` (width * height float, eye-to-hit
  // distance, -1 on a miss; nullptr: not written). Both need STORAGE usage. Synchronous (records,
  // submits, waits), so the caller may read or reuse the buffers afterwards.
  void run(const CameraPose& pose, int width, int height, const Buffer& rgba, const Buffer* distance);
  // The same, read back into host memory: what tests and the CPU side use.
  RgbaImage image(const CameraPose& pose, int width, int height, std::vector<float>* distance = nullptr);
  double lastGpuMs() const { return lastGpuMs_; }  // GPU time of the last run's dispatch (timestamps)
  bool usesDouble() const { return double_; }

 private:
  Context& ctx_;
  bool double_ = false;
  int samplesX_ = 0, samplesZ_ = 0, cellsX_ = 0, cellsZ_ = 0, levels_ = 0;
  float extent_ = 0;
  std::vector<uint32_t> levelTable_;   // per level: offset, width, height, 0
  PageLayout pages_;                   // how heights_ holds the samples (the renderer's pages)
  std::vector<uint32_t> normalTable_;  // per normal map level: offset (uints), width, height, 0
  Buffer heights_, mip_, normals_, params_, unusedDistance_;
  Bindings bindings_;
  vk::Unique<VkPipeline> pipeline_;
  PassTimer timer_;
  double lastGpuMs_ = 0;
};

}  // namespace lb
