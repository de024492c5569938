// The ray-cast ground truth on the GPU (metrics/gpu_raycast.h), timed from the host, and its CPU
// oracle on the same frame. The device is LODBENCH_BENCH_DEVICE (a name substring or index, as
// --device takes it; default lavapipe).
#include <cstdlib>

#include "bench.h"
#include "camera/camera_path.h"
#include "metrics/gpu_raycast.h"
#include "metrics/raycast.h"
#include "terrain/heightfield.h"
#include "vk/context.h"

namespace lb {

namespace {

// The committed real DEM crop (tests/dem_crop.h) and frame 80 of the flyover path over it.
struct Frame {
  Heightfield hf;
  CameraPose pose;
};

Frame demFrame() {
  TerrainSpec spec;
  spec.type = "hgt";
  spec.file = std::string(LODBENCH_SOURCE_DIR) + "/tests/data/N44W072_crop601.hgt";
  spec.extent = 54000;
  spec.heightScale = 5;
  Frame f{makeHeightfield(spec), {}};
  f.pose = samplePose(loadCameraPath(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/flyover.csv"), 30, 80, f.hf);
  return f;
}

}  // namespace

void benchGpuRaycast(benchmark::State& state, int width, int height) {
  const Frame frame = demFrame();
  Context ctx;
  const char* device = std::getenv("LODBENCH_BENCH_DEVICE");
  createContext(ctx, {device ? device : "", false});
  {
    GpuRaycast gpu(ctx, frame.hf);
    const VkDeviceSize bytes = VkDeviceSize(width) * VkDeviceSize(height) * 4;
    Buffer rgba = createBuffer(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);
    Buffer distance = createBuffer(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);
    double gpuMs = 0;
    for (auto _ : state) {
      gpu.run(frame.pose, width, height, rgba, &distance);
      gpuMs += gpu.lastGpuMs();
    }
    // Wall time per iteration includes the submit and the wait; gpu_ms is the dispatch alone.
    state.counters["gpu_ms"] = benchmark::Counter(gpuMs, benchmark::Counter::kAvgIterations);
    state.counters["double"] = gpu.usesDouble() ? 1 : 0;
    state.SetLabel(ctx.props.deviceName);
  }
  destroyContext(ctx);
}

void benchCpuRaycast(benchmark::State& state, int width, int height) {
  const Frame frame = demFrame();
  std::vector<float> distance;
  for (auto _ : state) benchmark::DoNotOptimize(raycastImage(frame.hf, frame.pose, width, height, &distance));
}

}  // namespace lb
