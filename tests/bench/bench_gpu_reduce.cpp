// Image and error statistics of a measured frame, reduced on the GPU (metrics/gpu_reduce.h) and on
// the CPU (compareImages, summarize), on the same synthetic frame. The device is lavapipe unless
// LODBENCH_BENCH_DEVICE names another (a name substring or an index, as `lodbench run --device`).
#include <cstdlib>

#include "bench.h"
#include "metrics/gpu_reduce.h"
#include "stats.h"
#include "vk/context.h"

namespace lb {

Context& benchContext() {
  static Context* ctx = [] {
    auto* c = new Context();
    const char* dev = std::getenv("LODBENCH_BENCH_DEVICE");
    createContext(*c, {dev ? dev : "", false});
    std::atexit([] { destroyContext(benchContext()); });
    return c;
  }();
  return *ctx;
}

namespace {

// A frame-like pair: the top fifth clear (magenta sky) in both, terrain below that differs by a
// few levels in some pixels; an error map of small values with -1 under the sky.
struct Frame {
  RgbaImage a, b;
  std::vector<float> error;
};
Frame frame(int w, int h) {
  Frame f{{w, h, std::vector<uint8_t>(size_t(w) * size_t(h) * 4, 255)}, {}, std::vector<float>(size_t(w) * size_t(h))};
  for (size_t i = 0; i < f.error.size(); ++i) {
    const bool sky = i < f.error.size() / 5;
    uint8_t* p = &f.a.px[i * 4];
    p[0] = sky ? 255 : uint8_t(60 + i * 7 % 50);
    p[1] = sky ? 0 : uint8_t(90 + i * 13 % 40);
    p[2] = sky ? 255 : uint8_t(40 + i * 3 % 30);
    f.error[i] = sky ? -1.0f : 0.01f * float(i * 2654435761u % 300);
  }
  f.b = f.a;
  for (size_t i = f.error.size() / 5; i < f.error.size(); i += 3) f.b.px[i * 4 + i % 3] += uint8_t(i % 9);
  return f;
}

}  // namespace

void benchGpuReduce(benchmark::State& state, int width, int height) {
  Context& ctx = benchContext();
  Frame f = frame(width, height);
  GpuReduce reduce(ctx, width, height);
  Buffer a = reduce.upload(f.a), b = reduce.upload(f.b), error = reduce.upload(f.error);
  double gpuMs = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(reduce.compare(a, b));
    gpuMs += reduce.lastGpuMs();
    benchmark::DoNotOptimize(reduce.errorStats(error));
    gpuMs += reduce.lastGpuMs();
  }
  state.counters["gpu_ms"] = benchmark::Counter(gpuMs, benchmark::Counter::kAvgIterations);
  state.SetLabel(ctx.props.deviceName + std::string(reduce.float64() ? ", SSIM in double" : ", SSIM in float"));
}

void benchCpuReduce(benchmark::State& state, int width, int height) {
  Frame f = frame(width, height);
  for (auto _ : state) {
    benchmark::DoNotOptimize(compareImages(f.a, f.b));
    std::vector<double> e;  // as measure.cpp summarises the error map
    for (float v : f.error)
      if (v >= 0) e.push_back(v);
    benchmark::DoNotOptimize(summarize(e));
  }
}

}  // namespace lb
