#pragma once
// Microbenchmarks of lodbench's CPU-side work and of the GPU ray cast (Google Benchmark).
// bench_main.cpp registers every function below from one table, and BM_SchemeUpdate once per
// entry of the scheme registry.
#include <benchmark/benchmark.h>
#include <vulkan/vulkan.h>

#include <string>

namespace lb {

class Scheme;
struct Context;

// The benchmarks' shared Vulkan context (LODBENCH_BENCH_DEVICE picks the device), made on first use.
Context& benchContext();

void benchSchemeUpdate(benchmark::State& state, const Scheme& scheme);  // Scheme::update, default params
void benchDensityMap(benchmark::State& state, int size);                // densityMap over a size^2 terrain
void benchPlaneFit(benchmark::State& state, int size, bool book);       // fitPlanes (book or least squares)
// errbound's deviation table over a size^2 terrain of fine relief ("detail": "resolution", ~1 m
// spacing like the large-terrain runs) with patches of 256 texels; reference: the oracle.
void benchTessDeviation(benchmark::State& state, int size, bool reference);
void benchSamplePose(benchmark::State& state, const std::string& path);  // samplePose over every frame
void benchSummarize(benchmark::State& state, int n);                     // summarize() of n frame times
void benchPercentile(benchmark::State& state, int n);                    // percentile() of n frame times
void benchCompareImages(benchmark::State& state, int width, int height);
void benchSsim(benchmark::State& state, int width, int height);
// A measured frame's image and error statistics: GpuReduce's compare + errorStats (wall time per
// iteration; counter gpu_ms: their GPU time) and the CPU's compareImages + summarize.
void benchGpuReduce(benchmark::State& state, int width, int height);
void benchCpuReduce(benchmark::State& state, int width, int height);
void benchWriteCase(benchmark::State& state, int frames);  // caseJson + writeFileAtomic
void benchMannWhitney(benchmark::State& state, int n);     // lodbench compare's test, n per side
void benchBootstrap(benchmark::State& state, int n);       // its ratio interval, n per side
// GpuRaycast::run at width x height over the DEM crop (its own Vulkan context; bench_gpu.cpp), and
// its CPU oracle raycastImage on every hardware thread, on the same frame.
void benchGpuRaycast(benchmark::State& state, int width, int height);
void benchCpuRaycast(benchmark::State& state, int width, int height);
// A stateful LOD's per-frame measurement work on cbt at depth 25, 1920x1080 (bench_settle.cpp): one
// update; its state set aside and put back on the device (keep, putBack) or through the host (read,
// load); an error map read back. And a memcpy out of a mapped buffer of `bytes`, made by createBuffer
// (host-visible storage) or by createReadBackBuffer.
void benchCbtUpdate(benchmark::State& state);
void benchCbtStateAside(benchmark::State& state, bool onDevice);
void benchCbtErrorMap(benchmark::State& state);
void benchHostRead(benchmark::State& state, VkDeviceSize bytes, bool readBack);

}  // namespace lb
