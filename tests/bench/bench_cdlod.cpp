// cdlod and cdlod-sse: the CPU selection per frame (InstancedLod::select) over a 4097^2 procedural
// terrain at 1920x1080, along a low flight, and cdlod-sse's load-time node errors. Registered here
// rather than in bench_main.cpp's table because the schemes' factories are all it needs.
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "bench.h"
#include "camera/camera_matrices.h"
#include "render/instanced.h"
#include "render/renderer.h"
#include "render/scheme.h"
#include "shaders/shared.h"
#include "terrain/heightfield.h"

namespace lb {

const Scheme& cdlodScheme();
const Scheme& cdlodSseScheme();

namespace {

Heightfield benchTerrain(int size) {
  TerrainSpec spec;
  spec.size = size;
  spec.seed = 1;
  spec.detailToSpacing = true;
  spec.extent = float((size - 1) / 1024 * 1000);
  spec.heightScale = spec.extent * 0.12f;
  return makeHeightfield(spec);
}

// A low flight across the terrain, looking ahead and slightly down (as Renderer::fillUniforms
// builds the uniforms).
std::vector<FrameUniforms> flight(const Heightfield& hf, const Scheme& scheme, const ParamValues& v, int frames) {
  std::vector<FrameUniforms> out;
  const float e = hf.extent;
  for (int f = 0; f < frames; ++f) {
    const float t = 0.1f + 0.8f * float(f) / float(frames);
    glm::vec3 eye(t * e, 0, (0.2f + 0.3f * t) * e);
    eye.y = hf.sample(eye.x, eye.z) + 0.01f * e;
    glm::vec3 target = eye + glm::vec3(0.2f * e, -0.02f * e, 0.1f * e);
    glm::mat4 view = glm::lookAt(eye, target, glm::vec3(0, 1, 0));
    glm::mat4 proj = glm::perspective(glm::radians(60.0f), 1920.0f / 1080.0f, e * 1e-4f, e * 4.0f);
    proj[1][1] *= -1.0f;
    FrameUniforms u{};
    u.viewProj = proj * view;
    u.lodView = view;
    u.lodProj = proj;
    u.lodEye = glm::vec4(eye, 1.0f);
    frustumPlanes(u.viewProj, u.frustum);
    u.viewport = glm::vec4(1920.0f, 1080.0f, 1.0f / 1920.0f, 1.0f / 1080.0f);
    u.terrain = glm::vec4(e, 32.0f, float(hf.width), float(hf.height));
    scheme.update(u, v);
    out.push_back(u);
  }
  return out;
}

// A timed frame's selection (the renderer asks for the scheme's counters on measured frames only);
// `counters` true adds them, as a measured frame pays.
void benchSelect(benchmark::State& state, const Scheme& scheme, bool counters = false) {
  static const Heightfield hf = benchTerrain(4097);
  const ParamValues v = resolveParams(scheme.info(), {});
  auto lod = scheme.instancedLod(hf, v);
  const std::vector<FrameUniforms> frames = flight(hf, scheme, v, 64);
  Selection sel;
  sel.countersWanted = counters;
  size_t f = 0, instances = 0;
  for (auto _ : state) {
    lod->select(frames[f], sel);
    instances += sel.instanceCount();
    f = (f + 1) % frames.size();
    benchmark::DoNotOptimize(sel);
  }
  state.counters["instances"] = double(instances) / double(state.iterations());
  state.SetItemsProcessed(state.iterations());  // frames
}

// cdlod-sse's node-error scan at load, on a terrain its cache has not seen (a new seed each time).
void benchSseLoad(benchmark::State& state, int size) {
  const ParamValues v = resolveParams(cdlodSseScheme().info(), {});
  uint32_t seed = 100;
  for (auto _ : state) {
    state.PauseTiming();
    TerrainSpec spec;
    spec.size = size;
    spec.seed = seed++;
    Heightfield hf = makeHeightfield(spec);
    state.ResumeTiming();
    benchmark::DoNotOptimize(cdlodSseScheme().instancedLod(hf, v));
  }
  state.SetItemsProcessed(state.iterations() * int64_t(size) * size);
}

const bool kRegistered = [] {
  benchmark::RegisterBenchmark("BM_CdlodSelect/4097/1080p", [](benchmark::State& s) { benchSelect(s, cdlodScheme()); });
  benchmark::RegisterBenchmark("BM_CdlodSelectMeasured/4097/1080p",
                               [](benchmark::State& s) { benchSelect(s, cdlodScheme(), true); });
  benchmark::RegisterBenchmark("BM_CdlodSseSelect/4097/1080p",
                               [](benchmark::State& s) { benchSelect(s, cdlodSseScheme()); });
  benchmark::RegisterBenchmark("BM_CdlodSseLoad/1025", [](benchmark::State& s) {
    benchSseLoad(s, 1025);
  })->Unit(benchmark::kMillisecond);
  return true;
}();

}  // namespace
}  // namespace lb
