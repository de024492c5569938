// Statistics, image metrics and result writing: what a sweep and lodbench compare do per case.
#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "bench.h"
#include "compare/significance.h"
#include "config/config.h"
#include "metrics/image_metrics.h"
#include "results/write.h"
#include "stats.h"

namespace lb {

// Frame-time-like values: 1.0 ms plus a deterministic spread, no two equal.
static std::vector<double> frameTimes(int n, double scale = 1.0) {
  std::vector<double> v;
  for (int i = 0; i < n; ++i) v.push_back(scale * (1.0 + 0.1 * double((i * 7919) % n) / n));
  return v;
}

void benchSummarize(benchmark::State& state, int n) {
  auto v = frameTimes(n);
  for (auto _ : state) benchmark::DoNotOptimize(summarize(v));
  state.SetItemsProcessed(state.iterations() * n);
}

void benchPercentile(benchmark::State& state, int n) {
  auto v = frameTimes(n);
  for (auto _ : state) benchmark::DoNotOptimize(percentile(v, 95));
  state.SetItemsProcessed(state.iterations() * n);
}

void benchMannWhitney(benchmark::State& state, int n) {
  auto a = frameTimes(n), b = frameTimes(n, 1.05);
  for (auto _ : state) benchmark::DoNotOptimize(mannWhitneyU(a, b));
}

void benchBootstrap(benchmark::State& state, int n) {
  auto a = frameTimes(n), b = frameTimes(n, 1.05);
  for (auto _ : state) benchmark::DoNotOptimize(bootstrapMedianRatio(a, b, 0.99));
}

static RgbaImage pattern(int w, int h, int shift) {
  RgbaImage img{w, h, std::vector<uint8_t>(size_t(w) * h * 4)};
  for (size_t i = 0; i < img.px.size(); ++i) img.px[i] = uint8_t((i * 31 + size_t(shift) * (i % 7)) & 0xff);
  return img;
}

void benchCompareImages(benchmark::State& state, int w, int h) {
  RgbaImage a = pattern(w, h, 0), b = pattern(w, h, 3);
  for (auto _ : state) benchmark::DoNotOptimize(compareImages(a, b));
  state.SetItemsProcessed(state.iterations() * w * h);
}

void benchSsim(benchmark::State& state, int w, int h) {
  RgbaImage a = pattern(w, h, 0), b = pattern(w, h, 3);
  for (auto _ : state) benchmark::DoNotOptimize(ssim(a, b));
  state.SetItemsProcessed(state.iterations() * w * h);
}

void benchWriteCase(benchmark::State& state, int frames) {
  Case c;
  c.id = "uniform-level8_proc513s1_flyover_320x180";
  c.scheme = "uniform";
  c.params = {{"level", 8}};
  c.path = "configs/paths/flyover.csv";
  c.width = 320;
  c.height = 180;
  CaseResult r;
  for (int f = 0; f < frames; ++f) {
    FrameResult fr;
    fr.frame = f;
    fr.gpuMs = 1.0 + 0.001 * f;
    fr.cpuMs = 2.0;
    fr.stats.tcsPatches = 1024;
    fr.stats.clipInvocations = 100000 + uint64_t(f);
    r.frames.push_back(fr);
  }
  std::string file =
      (std::filesystem::temp_directory_path() / ("lodbench_bench_case_" + std::to_string(::getpid()) + ".json"))
          .string();
  for (auto _ : state) writeFileAtomic(file, caseJson(c, r).dump(1));
  std::filesystem::remove(file);
  state.SetItemsProcessed(state.iterations() * frames);
}

}  // namespace lb
