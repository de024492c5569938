// CPU work per frame and at load time: scheme updates, terrain preprocessing, camera sampling.
#include "bench.h"
#include "camera/camera_path.h"
#include "render/scheme.h"
#include "schemes/preprocess/density_map.h"
#include "schemes/preprocess/plane_fit.h"
#include "schemes/preprocess/tess_deviation.h"
#include "shaders/shared.h"
#include "terrain/heightfield.h"

namespace lb {

static Heightfield terrain(int size) {
  TerrainSpec spec;
  spec.size = size;
  spec.seed = 1;
  spec.extent = 1000;
  spec.heightScale = 120;
  return makeHeightfield(spec);
}

void benchSchemeUpdate(benchmark::State& state, const Scheme& scheme) {
  ParamValues values = resolveParams(scheme.info(), {});
  FrameUniforms u{};
  for (auto _ : state) {
    scheme.update(u, values);
    benchmark::DoNotOptimize(u);
    benchmark::ClobberMemory();
  }
}

void benchDensityMap(benchmark::State& state, int size) {
  Heightfield hf = terrain(size);
  for (auto _ : state) benchmark::DoNotOptimize(densityMap(hf, 0.0f, 40.0f));  // the density scheme's defaults
  state.SetItemsProcessed(state.iterations() * int64_t(size) * size);
}

void benchPlaneFit(benchmark::State& state, int size, bool book) {
  Heightfield hf = terrain(size);
  for (auto _ : state) benchmark::DoNotOptimize(fitPlanes(hf, book ? PlaneFit::Book : PlaneFit::LeastSquares));
  state.SetItemsProcessed(state.iterations() * int64_t(size) * size);
}

void benchTessDeviation(benchmark::State& state, int size, bool reference) {
  TerrainSpec spec;
  spec.size = size;
  spec.seed = 1;
  spec.detailToSpacing = true;
  spec.extent = float((size - 1) / 1024 * 1000);
  spec.heightScale = 1500;
  Heightfield hf = makeHeightfield(spec);
  const int grid = (size - 1) / 256;
  for (auto _ : state) benchmark::DoNotOptimize(reference ? tessDeviationReference(hf, grid) : tessDeviation(hf, grid));
  state.SetItemsProcessed(state.iterations() * int64_t(grid) * grid);  // patches
}

void benchSamplePose(benchmark::State& state, const std::string& file) {
  Heightfield hf = terrain(129);
  CameraPath path = loadCameraPath(file);
  const int frames = frameCount(path, 30);
  for (auto _ : state)
    for (int f = 0; f < frames; ++f) benchmark::DoNotOptimize(samplePose(path, 30, f, hf));
  state.SetItemsProcessed(state.iterations() * frames);
}

}  // namespace lb
